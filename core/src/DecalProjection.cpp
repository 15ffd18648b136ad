#include "spatter/core/DecalProjection.hpp"

#include <cmath>
#include <glm/gtc/packing.hpp>

namespace spatter {

namespace {

const double kMaxSlope = std::tan(kMaxSlantDeg * 3.14159265358979323846 / 180.0);

} // namespace

uint32_t packSlant(const glm::vec2& slopes) {
    glm::dvec2 s(slopes);
    if (!std::isfinite(s.x) || !std::isfinite(s.y)) return 0;
    const double length = glm::length(s);
    if (length > kMaxSlope) s *= kMaxSlope / length;
    return glm::packHalf2x16(glm::vec2(s));
}

glm::vec2 unpackSlant(uint32_t bits) {
    return glm::unpackHalf2x16(bits);
}

bool validSlant(uint32_t bits) {
    const glm::dvec2 s(unpackSlant(bits));
    // Each half rounds by at most 2^-11 of itself: a clamped slope may come out that much longer.
    return std::isfinite(s.x) && std::isfinite(s.y) && glm::length(s) <= kMaxSlope * (1.0 + 1.0 / 1024.0);
}

uint32_t slantOf(const glm::dvec3& t, const glm::dvec3& b, const glm::dvec3& n, const glm::dvec3& axis) {
    const double along = glm::dot(axis, n);
    if (!(along > 0.0) || !std::isfinite(glm::dot(axis, axis))) return 0;
    const glm::dvec2 across(glm::dot(axis, t), glm::dot(axis, b));
    // Beyond kMaxSlope the division would lose what packSlant keeps: clamp before dividing.
    const double length = glm::length(across);
    if (length > kMaxSlope * along) return packSlant(glm::vec2(across * (kMaxSlope / length)));
    return packSlant(glm::vec2(across / along));
}

} // namespace spatter
