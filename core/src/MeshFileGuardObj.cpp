// MeshFileGuard for OBJ: OpenMesh's reader adds the "v" lines with three numbers as vertices, then
// reads each face corner "v[/vt[/vn]]" and stores its texture coordinate and normal at vertex v
// without checking v (an unparsable v leaves it an uninitialised int).

#include "MeshFileGuardFormats.hpp"

#include <cctype>
#include <cstdint>
#include <fstream>
#include <sstream>

namespace spatter::detail {

namespace {

std::string trimObjLine(const std::string& line) {
    const size_t first = line.find_first_not_of(" \t\r\n"), last = line.find_last_not_of(" \t\r\n");
    return first == std::string::npos ? std::string() : line.substr(first, last - first + 1);
}

bool objSkips(const std::string& line) {
    return line.empty() || line[0] == '#' || std::isspace(static_cast<unsigned char>(line[0]));
}

} // namespace

Status checkObjForOpenMesh(std::ifstream& in) {
    int64_t positions = 0;
    for (std::string raw; std::getline(in, raw);) {
        const std::string line = trimObjLine(raw);
        if (objSkips(line)) continue;
        std::istringstream words(line);
        std::string keyword;
        float x, y, z;
        if (words >> keyword && keyword == "v" && words >> x >> y >> z) positions++;
    }
    in.clear();
    in.seekg(0);
    int64_t vLines = 0; // negative indices count back from the "v" lines so far
    size_t lineNumber = 0;
    for (std::string raw; std::getline(in, raw);) {
        ++lineNumber;
        const std::string line = trimObjLine(raw);
        if (objSkips(line)) continue;
        std::istringstream words(line);
        std::string keyword;
        words >> keyword;
        if (keyword == "v") vLines++;
        if (keyword != "f") continue;
        const std::string where = "line " + std::to_string(lineNumber) + ": ";
        unsigned corners = 0;
        for (std::string corner; words >> corner;) {
            const size_t slash = corner.find('/');
            std::istringstream first(corner.substr(0, slash));
            int value = 0;
            if (!(first >> value)) {
                if (slash == std::string::npos) continue; // a lone word the reader skips
                return fail(where + "face corner '" + corner + "' has no vertex index");
            }
            const int64_t index = value < 0 ? vLines + value + 1 : value;
            if (index < 1 || index > positions)
                return fail(where + "face corner '" + corner + "' refers to vertex " + std::to_string(index) +
                            " of " + std::to_string(positions));
            if (++corners > kMaxFaceCorners)
                return fail(where + "face has more than " + std::to_string(kMaxFaceCorners) + " corners");
        }
    }
    return {};
}

} // namespace spatter::detail
