#include "spatter/core/DecalRefit.hpp"

#include "spatter/core/Frame.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>

namespace spatter {

namespace {

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Frame `f` turned about its normal as far as `turned` is turned from `base` (two frames on one
// normal).
Frame turnedLike(const Frame& f, const Frame& base, const Frame& turned) {
    return rotateAboutNormal(
        f, std::atan2(glm::dot(turned.tangent, base.bitangent), glm::dot(turned.tangent, base.tangent)));
}

// Frame `f` turned by the least rotation that takes its normal to unit `n`.
Frame leastTurn(const Frame& f, const glm::vec3& n) {
    const glm::quat turn(f.normal, n);
    return Frame{turn * f.tangent, turn * f.bitangent, n};
}

// The frame `f` of decal `d` laid on `normal` (object space, facing the decal's normal), in world
// space where placement builds frames (normals by the transpose of `toObject`, directions by
// `toWorld`); nothing for a normal 89 degrees or more from the decal's.
std::optional<Frame> laidWorldFrame(const Decal& d, const Frame& f, const glm::dmat3& toWorld,
                                    const glm::dmat3& toObject, const glm::vec3& normal) {
    const glm::dmat3 normalToWorld = glm::transpose(toObject);
    const glm::vec3 oldNormal = glm::normalize(glm::vec3(normalToWorld * glm::dvec3(f.normal)));
    const glm::vec3 newNormal = glm::normalize(
        glm::vec3(normalToWorld * glm::dvec3(glm::dot(normal, f.normal) < 0.0f ? -normal : normal)));
    constexpr float kCosMaxTurn = 0.0174524f; // cos 89 degrees: an edge-on surface takes no decal
    if (!(glm::dot(newNormal, oldNormal) > kCosMaxTurn)) return std::nullopt;
    const glm::vec3 tangent = glm::normalize(glm::vec3(toWorld * glm::dvec3(f.tangent)));
    const Frame old{tangent, glm::cross(oldNormal, tangent), oldNormal};
    if (d.slant == 0) return leastTurn(old, newNormal);
    const glm::vec3 hint = -glm::vec3(toWorld * glm::dvec3(d.projectionAxis())); // the shot
    return turnedLike(frameFromNormalAndHint(newNormal, hint), frameFromNormalAndHint(oldNormal, hint), old);
}

} // namespace

std::optional<Decal> relaidDecal(const Decal& d, const glm::dmat3& toWorld, const glm::vec3& point,
                                 const glm::vec3& normal, float halfDepth) {
    const Frame f = d.frame();
    const double det = glm::determinant(toWorld);
    if (f.normal == glm::vec3(0.0f) || !finite(point) || !finite(normal) || !std::isfinite(halfDepth) ||
        halfDepth < 0.0f || !std::isfinite(det) || det == 0.0)
        return std::nullopt;
    const glm::dmat3 toObject = glm::inverse(toWorld);
    const std::optional<Frame> laid = laidWorldFrame(d, f, toWorld, toObject, normal);
    if (!laid) return std::nullopt;
    // Back to object space as placement takes its frames there, the decal's world size kept.
    const glm::dvec3 n = glm::normalize(glm::transpose(toWorld) * glm::dvec3(laid->normal));
    glm::dvec3 t = toObject * glm::dvec3(laid->tangent);
    t = glm::normalize(t - n * glm::dot(n, t));
    const glm::dvec3 b = glm::cross(n, t);
    const glm::dvec2 worldSize(double(d.size.x) * glm::length(toWorld * glm::dvec3(f.tangent)),
                               double(d.size.y) * glm::length(toWorld * glm::dvec3(f.bitangent)));
    Decal out = d;
    out.center = point;
    if (!out.setFrame(Frame{glm::vec3(t), glm::vec3(d.mirrored() ? -b : b), glm::vec3(n)}))
        return std::nullopt;
    out.size = glm::vec2(worldSize / glm::dvec2(glm::length(toWorld * t), glm::length(toWorld * b)));
    if (d.slant != 0) out.setProjectionAxis(d.projectionAxis()); // along its normal: the new one
    out.halfDepth = halfDepth;
    return out;
}

std::optional<double> laidShotAngleDeg(const Decal& d, const Decal& laid, const glm::dmat3& toWorld) {
    if (d.slant == 0) return std::nullopt;
    const glm::dvec3 shot = glm::normalize(toWorld * glm::dvec3(d.projectionAxis()));
    const glm::dvec3 n =
        glm::normalize(glm::transpose(glm::inverse(toWorld)) * glm::dvec3(laid.frame().normal));
    constexpr double kDegrees = 57.295779513082320876798;
    return std::acos(std::clamp(glm::dot(shot, n), -1.0, 1.0)) * kDegrees;
}

} // namespace spatter
