#include "spatter/core/Decal.hpp"

#include <algorithm>
#include <cmath>

namespace spatter {

namespace {

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Below this length an axis is rounding noise, not a direction.
constexpr double kMinAxis = 1e-12;

} // namespace

Frame Decal::frame() const {
    const glm::dquat q(orientation);
    const double length = glm::length(q);
    if (!(length > kMinAxis) || !std::isfinite(length))
        return Frame{glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};
    const glm::dmat3 m = glm::mat3_cast(q / length);
    return Frame{glm::vec3(m[0]), glm::vec3(mirrored ? -m[1] : m[1]), glm::vec3(m[2])};
}

bool Decal::setFrame(const Frame& f) {
    const glm::dvec3 n0(f.normal), t0(f.tangent), b0(f.bitangent);
    const double nl = glm::length(n0);
    orientation = glm::quat(0.0f, 0.0f, 0.0f, 0.0f);
    mirrored = false;
    if (!finite(n0) || !finite(t0) || !finite(b0) || !(nl > kMinAxis)) return false;
    const glm::dvec3 n = n0 / nl;
    const glm::dvec3 tp = t0 - n * glm::dot(n, t0);
    const double tl = glm::length(tp);
    if (!(tl > kMinAxis * std::max(1.0, glm::length(t0)))) return false;
    const glm::dvec3 t = tp / tl;
    const glm::dvec3 b = glm::cross(n, t);
    glm::dquat q = glm::quat_cast(glm::dmat3(t, b, n));
    if (q.w < 0.0) q = -q; // q and -q are the same rotation; one sign keeps packing deterministic
    orientation = glm::quat(q);
    mirrored = glm::dot(b0, b) < 0.0;
    return true;
}

glm::mat4 Decal::boxToObject() const {
    const Frame f = frame();
    return glm::mat4(glm::vec4(f.tangent * (size.x * 0.5f), 0.0f),
                     glm::vec4(f.bitangent * (size.y * 0.5f), 0.0f), glm::vec4(f.normal * halfDepth, 0.0f),
                     glm::vec4(center, 1.0f));
}

} // namespace spatter
