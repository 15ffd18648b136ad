#include "SkinAnchors.hpp"

#include "spatter/core/Frame.hpp"

#include <algorithm>
#include <cmath>

namespace spatter {

void moveOntoDrawnSurface(Decal& d, const glm::dmat4& frame, const glm::dvec3& shot, const DecalType& type,
                          float depthMargin, const glm::dmat4& objectTransform) {
    constexpr double kMinDepth = 0.01; // of the size: a box that still holds the surface under it
    const glm::dmat3 m(objectTransform);
    const glm::dmat3 inv = glm::inverse(m);
    const glm::dmat3 normalMatrix = glm::transpose(inv);
    const Frame f = d.frame();
    // The render triangle's normal, unless the shot grazed a silhouette and met it from behind.
    const glm::dvec3 surfaceNormal =
        glm::dot(glm::dvec3(frame[2]), inv * shot) < 0.0 ? glm::dvec3(frame[2]) : glm::dvec3(f.normal);
    // The frame rebuilt in world space as placement builds it, from that normal and the shot, turned
    // about it as the decal was turned: projecting the proxy's tangent instead would swing it where
    // the shot meets the surface nearly face-on.
    const glm::vec3 proxyNormal(glm::normalize(normalMatrix * glm::dvec3(f.normal)));
    const glm::vec3 tangent(glm::normalize(m * glm::dvec3(f.tangent)));
    const Frame base = frameFromNormalAndHint(proxyNormal, glm::vec3(shot));
    const float turn = std::atan2(glm::dot(tangent, base.bitangent), glm::dot(tangent, base.tangent));
    const Frame w = rotateAboutNormal(
        frameFromNormalAndHint(glm::vec3(glm::normalize(normalMatrix * surfaceNormal)), glm::vec3(shot)),
        turn);
    // To object space as placement does: normals by the transpose, tangents by the inverse.
    const glm::dvec3 n = glm::normalize(glm::transpose(m) * glm::dvec3(w.normal));
    glm::dvec3 tan = inv * glm::dvec3(w.tangent);
    tan = tan - n * glm::dot(n, tan);
    if (!(glm::length(tan) > 1e-6)) return; // no frame can be made of it: leave the decal as placed
    tan = glm::normalize(tan);
    const glm::dvec3 bit = glm::cross(n, tan);
    d.center = glm::vec3(frame[3]);
    d.packedFrame = packFrame(tan, bit, n, d.mirrored());
    if (type.projection == Projection::Shot) d.slant = slantOf(tan, bit, n, -(inv * shot));
    const double worldSize =
        std::max(double(d.size.x) * glm::length(m * tan), double(d.size.y) * glm::length(m * bit));
    const double halfDepth = std::max(double(depthMargin), kMinDepth) * worldSize;
    d.halfDepth = float(halfDepth * glm::length(glm::transpose(inv) * n));
}

std::optional<SkinAnchors::Location> SkinAnchors::locate(const Decal& decal, uint32_t primitive,
                                                         const glm::dvec3& direction,
                                                         const CollisionWorld& world) {
    const std::optional<SurfaceAnchor> surface =
        world.anchorAt(decal.object, primitive, glm::dvec3(decal.center), direction);
    if (!surface) return std::nullopt;
    const std::optional<glm::dmat4> frame = world.anchorFrame(decal.object, *surface);
    if (!frame) return std::nullopt;
    return Location{*surface, *frame};
}

void SkinAnchors::add(uint32_t slot, const Decal& decal, const Location& location) {
    // The frame is orthonormal: its inverse rotation is its transpose.
    const glm::dmat3 toLocal = glm::transpose(glm::dmat3(location.frame));
    const Frame f = decal.frame();
    Anchor a;
    a.surface = location.surface;
    a.center = toLocal * (glm::dvec3(decal.center) - glm::dvec3(location.frame[3]));
    a.tangent = toLocal * glm::dvec3(f.tangent);
    a.normal = toLocal * glm::dvec3(f.normal);
    byObject_[decal.object][slot] = a;
}

std::vector<SavedAnchor> SkinAnchors::saved() const {
    std::vector<SavedAnchor> out;
    for (const auto& [object, anchors] : byObject_)
        for (const auto& [slot, a] : anchors)
            out.push_back({slot, a.surface, a.center, a.tangent, a.normal});
    std::sort(out.begin(), out.end(),
              [](const SavedAnchor& a, const SavedAnchor& b) { return a.slot < b.slot; });
    return out;
}

void SkinAnchors::place(const Anchor& anchor, const glm::dmat4& frame, Decal& decal) {
    const glm::dmat3 rotation(frame);
    const glm::dvec3 n = glm::normalize(rotation * anchor.normal);
    glm::dvec3 t = rotation * anchor.tangent;
    t = glm::normalize(t - n * glm::dot(n, t));
    decal.center = glm::vec3(glm::dvec3(frame[3]) + rotation * anchor.center);
    decal.packedFrame = packFrame(t, glm::cross(n, t), n, decal.mirrored());
}

} // namespace spatter
