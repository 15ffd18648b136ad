// libFuzzer target: the ray-line parser of spatter-place (parseRayLine). Each input is split into
// lines like the tool does; every line must give a consistent RayLine, and a parsed ray printed with
// 17 significant digits must parse back to the same bits.

#include "spatter/placement/RayParser.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

bool sameBits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b));
}

void check(const std::string& line, size_t number) {
    const spatter::RayLine p = spatter::parseRayLine(line, number);
    if (!p.isRay && (p.ok || !p.error.empty())) std::abort();
    if (p.isRay && p.ok != p.error.empty()) std::abort();
    if (p.isRay && !p.ok && p.error.rfind("line " + std::to_string(number) + ": ", 0) != 0) std::abort();
    if (!p.ok) return;
    if (p.ray.tnear != 0.0 || !std::isinf(p.ray.tfar)) std::abort();
    const double v[6] = {p.ray.origin.x,    p.ray.origin.y,    p.ray.origin.z,
                         p.ray.direction.x, p.ray.direction.y, p.ray.direction.z};
    char text[256];
    std::snprintf(text, sizeof text, "%.17g %.17g %.17g %.17g %.17g %.17g # again", v[0], v[1], v[2], v[3],
                  v[4], v[5]);
    const spatter::RayLine q = spatter::parseRayLine(text, number);
    if (!q.ok) std::abort();
    const double w[6] = {q.ray.origin.x,    q.ray.origin.y,    q.ray.origin.z,
                         q.ray.direction.x, q.ray.direction.y, q.ray.direction.z};
    for (int i = 0; i < 6; ++i)
        if (!sameBits(v[i], w[i])) std::abort();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    size_t start = 0, number = 0;
    while (start <= text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        check(text.substr(start, end - start), ++number);
        start = end + 1;
    }
    return 0;
}
