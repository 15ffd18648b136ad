#include "spatter/core/Decal.hpp"

#include <algorithm>
#include <cmath>

namespace spatter {

namespace {

// Below this length an axis is rounding noise, not a direction.
constexpr double kMinAxis = 1e-12;

} // namespace

Frame Decal::frame() const {
    if (!hasOrientation(packedFrame)) return Frame{glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
    const glm::dmat3 m = glm::mat3_cast(orientation());
    return Frame{glm::vec3(m[0]), glm::vec3(mirrored() ? -m[1] : m[1]), glm::vec3(m[2])};
}

bool Decal::setFrame(const Frame& f) {
    const glm::dvec3 n0(f.normal), t0(f.tangent), b0(f.bitangent);
    packedFrame = kNoOrientation;
    const double nn = glm::dot(n0, n0), t0t0 = glm::dot(t0, t0);
    // Squares of floats stay finite in double: the sum is finite exactly when every component is.
    if (!std::isfinite(nn + t0t0 + glm::dot(b0, b0)) || !(nn > kMinAxis * kMinAxis)) return false;
    const glm::dvec3 n = n0 * (1.0 / std::sqrt(nn));
    const glm::dvec3 tp = t0 - n * glm::dot(n, t0);
    const double tt = glm::dot(tp, tp);
    if (!(tt > kMinAxis * kMinAxis * std::max(1.0, t0t0))) return false;
    const glm::dvec3 t = tp * (1.0 / std::sqrt(tt));
    const glm::dvec3 b = glm::cross(n, t);
    packedFrame = packFrame(t, b, n, glm::dot(b0, b) < 0.0);
    return true;
}

glm::vec3 Decal::projectionAxis() const {
    const Frame f = frame();
    const glm::vec2 s = unpackSlant(slant);
    const glm::vec3 axis = f.normal + s.x * f.tangent + s.y * f.bitangent;
    const float length = glm::length(axis);
    return length > 0.0f ? axis / length : axis;
}

void Decal::setProjectionAxis(const glm::vec3& axis) {
    const Frame f = frame();
    slant = slantOf(glm::dvec3(f.tangent), glm::dvec3(f.bitangent), glm::dvec3(f.normal), glm::dvec3(axis));
}

glm::mat4 Decal::boxToObject() const {
    const Frame f = frame();
    const glm::vec2 s = unpackSlant(slant);
    return glm::mat4(glm::vec4(f.tangent * (size.x * 0.5f), 0.0f),
                     glm::vec4(f.bitangent * (size.y * 0.5f), 0.0f),
                     glm::vec4((f.normal + s.x * f.tangent + s.y * f.bitangent) * halfDepth, 0.0f),
                     glm::vec4(center, 1.0f));
}

} // namespace spatter
