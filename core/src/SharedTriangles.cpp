#include "SharedTriangles.hpp"

#include <algorithm>
#include <cstring>

namespace spatter::detail {

namespace {

bool lexicographicLess(const glm::dvec3& a, const glm::dvec3& b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
}

} // namespace

std::array<glm::dvec3, 3> TriangleCorners::sortedCorners(std::array<glm::dvec3, 3> p) {
    if (lexicographicLess(p[1], p[0])) std::swap(p[0], p[1]);
    if (lexicographicLess(p[2], p[1])) std::swap(p[1], p[2]);
    if (lexicographicLess(p[1], p[0])) std::swap(p[0], p[1]);
    return p;
}

uint64_t TriangleCorners::hashCorners(const std::array<glm::dvec3, 3>& sorted) {
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (const glm::dvec3& c : sorted)
        for (int k = 0; k < 3; ++k) {
            const double v = c[k] + 0.0; // -0 becomes +0
            uint64_t bits;
            std::memcpy(&bits, &v, sizeof bits);
            h = (h ^ bits) * 0xff51afd7ed558ccdull;
            h ^= h >> 33;
        }
    return h;
}

TriangleCorners::TriangleCorners(const std::vector<glm::dvec3>& positions, const Triangles& triangles) {
    if (triangles.empty()) return;
    size_t size = 2;
    while (size < 2 * triangles.size())
        size *= 2;
    slots_.assign(size, Slot{});
    mask_ = size - 1;
    for (size_t t = 0; t < triangles.size(); ++t) {
        const std::array<uint32_t, 3>& c = triangles[t];
        const uint64_t h = hashCorners(sortedCorners({positions[c[0]], positions[c[1]], positions[c[2]]}));
        size_t i = h & mask_;
        while (slots_[i].triangle != kEmpty)
            i = (i + 1) & mask_;
        slots_[i] = {h, uint32_t(t)};
    }
}

} // namespace spatter::detail
