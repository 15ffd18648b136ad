#include "spatter/placement/RayParser.hpp"

#include "spatter/core/TextFields.hpp"

#include <sstream>
#include <vector>

namespace spatter {

RayLine parseRayLine(const std::string& raw, size_t lineNumber) {
    RayLine p;
    const std::string line = raw.substr(0, raw.find('#'));
    std::istringstream in(line);
    std::vector<std::string> tokens;
    for (std::string tok; in >> tok;)
        tokens.push_back(tok);
    if (tokens.empty()) return p;
    p.isRay = true;
    double v[6];
    bool good = tokens.size() == 6;
    for (size_t i = 0; good && i < 6; ++i)
        good = parseDecimal(tokens[i], v[i]);
    if (!good) {
        p.error = "line " + std::to_string(lineNumber) + ": expected 6 decimal numbers \"ox oy oz dx dy dz\"";
        return p;
    }
    p.ok = true;
    p.ray.origin = glm::dvec3(v[0], v[1], v[2]);
    p.ray.direction = glm::dvec3(v[3], v[4], v[5]);
    return p;
}

} // namespace spatter
