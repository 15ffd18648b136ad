#include "spatter/core/DecalRefit.hpp"

#include "spatter/core/Frame.hpp"

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

} // namespace

std::optional<Decal> relaidDecal(const Decal& d, const glm::dmat3& toWorld, const glm::vec3& point,
                                 const glm::vec3& normal, float halfDepth) {
    const Frame f = d.frame();
    const double det = glm::determinant(toWorld);
    if (f.normal == glm::vec3(0.0f) || !finite(point) || !finite(normal) || !std::isfinite(halfDepth) ||
        halfDepth < 0.0f || !std::isfinite(det) || det == 0.0)
        return std::nullopt;
    const glm::dmat3 toObject = glm::inverse(toWorld);
    // The decal's frame and shot in world space, where placement builds frames: normals by the
    // inverse transpose, directions by the matrix itself.
    auto normalToWorld = [&](const glm::vec3& n) {
        return glm::vec3(glm::transpose(toObject) * glm::dvec3(n));
    };
    const glm::vec3 oldNormal = glm::normalize(normalToWorld(f.normal));
    glm::vec3 newNormal = normalToWorld(glm::dot(normal, f.normal) < 0.0f ? -normal : normal);
    constexpr float kCosMaxTurn = 0.0174524f; // cos 89 degrees: an edge-on surface takes no decal
    if (!(glm::dot(glm::normalize(newNormal), oldNormal) > kCosMaxTurn)) return std::nullopt;
    newNormal = glm::normalize(newNormal);
    const glm::vec3 axis = d.projectionAxis();
    const glm::vec3 hint = -glm::vec3(toWorld * glm::dvec3(axis));
    const glm::vec3 tangent = glm::vec3(toWorld * glm::dvec3(f.tangent));
    const Frame old{glm::normalize(tangent), glm::cross(oldNormal, glm::normalize(tangent)), oldNormal};
    const Frame laid = d.slant == 0 ? leastTurn(old, newNormal)
                                    : turnedLike(frameFromNormalAndHint(newNormal, hint),
                                                 frameFromNormalAndHint(oldNormal, hint), old);
    // Back to object space as placement takes its frames there, the decal's world size kept.
    const glm::dvec3 n = glm::normalize(glm::transpose(toWorld) * glm::dvec3(laid.normal));
    glm::dvec3 t = toObject * glm::dvec3(laid.tangent);
    t = glm::normalize(t - n * glm::dot(n, t));
    const glm::dvec3 b = glm::cross(n, t);
    const double worldWidth = double(d.size.x) * glm::length(toWorld * glm::dvec3(f.tangent));
    const double worldHeight = double(d.size.y) * glm::length(toWorld * glm::dvec3(f.bitangent));
    Decal out = d;
    out.center = point;
    if (!out.setFrame(Frame{glm::vec3(t), glm::vec3(d.mirrored() ? -b : b), glm::vec3(n)}))
        return std::nullopt;
    out.size = glm::vec2(float(worldWidth / glm::length(toWorld * t)),
                         float(worldHeight / glm::length(toWorld * b)));
    if (d.slant != 0) out.setProjectionAxis(axis); // a decal along its normal follows the new one
    out.halfDepth = halfDepth;
    return out;
}

} // namespace spatter
