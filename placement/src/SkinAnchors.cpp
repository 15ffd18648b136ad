#include "SkinAnchors.hpp"

#include "spatter/core/PackedFrame.hpp"

#include <algorithm>
#include <cmath>

namespace spatter {

void SkinAnchors::add(uint32_t slot, const Decal& decal, const glm::dmat3& frame,
                      const SurfaceLocation& location) {
    // The frame is orthonormal: its inverse rotation is its transpose.
    const glm::dmat3 toLocal = glm::transpose(glm::dmat3(location.frame));
    Anchor a;
    a.surface = location.surface;
    a.center = toLocal * (glm::dvec3(decal.center) - glm::dvec3(location.frame[3]));
    a.tangent = toLocal * frame[0];
    a.normal = toLocal * frame[2];
    insert(decal.object, slot, a);
}

void SkinAnchors::insert(uint32_t object, uint32_t slot, const Anchor& anchor) {
    std::vector<Entry>& list = byObject_[object];
    if (indexOf_.size() <= slot) indexOf_.resize(size_t(slot) + 1, kNone);
    indexOf_[slot] = uint32_t(list.size());
    list.push_back({slot, anchor});
}

void SkinAnchors::erase(uint32_t slot, uint32_t object) {
    if (slot >= indexOf_.size() || indexOf_[slot] == kNone) return;
    const auto on = byObject_.find(object);
    if (on == byObject_.end()) return;
    std::vector<Entry>& list = on->second;
    const uint32_t index = indexOf_[slot];
    indexOf_[slot] = kNone;
    list[index] = list.back();
    list.pop_back();
    if (index < list.size()) indexOf_[list[index].slot] = index;
    if (list.empty()) byObject_.erase(on);
}

std::vector<SavedAnchor> SkinAnchors::saved() const {
    std::vector<SavedAnchor> out;
    for (const auto& [object, list] : byObject_)
        for (const Entry& e : list)
            out.push_back({e.slot, e.anchor.surface, e.anchor.center, e.anchor.tangent, e.anchor.normal});
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
