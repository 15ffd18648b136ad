#include "SkinAnchors.hpp"

#include <algorithm>

namespace spatter {

std::optional<SkinAnchors::Location> SkinAnchors::locate(const Decal& decal, uint32_t primitive,
                                                         const CollisionWorld& world) {
    const std::optional<SurfaceAnchor> surface =
        world.anchorAt(decal.object, primitive, glm::dvec3(decal.center));
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
    a.object = decal.object;
    a.surface = location.surface;
    a.center = toLocal * (glm::dvec3(decal.center) - glm::dvec3(location.frame[3]));
    a.tangent = toLocal * glm::dvec3(f.tangent);
    a.normal = toLocal * glm::dvec3(f.normal);
    anchors_[slot] = a;
}

std::vector<SavedAnchor> SkinAnchors::saved() const {
    std::vector<SavedAnchor> out;
    out.reserve(anchors_.size());
    for (const auto& [slot, a] : anchors_)
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
