#pragma once
// DecalBatch: the CPU side of the decal pass. It turns Decals and DecalTypes into per-instance GPU
// data (object space, so that it changes only when a decal or its type changes), keeps track of
// which instances changed since the last upload, keeps the draw order (DecalType::priority, then
// spawn time, then index), and per frame culls the boxes against the view into the visible list,
// in draw order, noting the boxes that may hold the eye.

#include "DecalRecord.hpp"

#include "spatter/core/Decal.hpp"
#include "spatter/core/DecalType.hpp"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace spatter::render_detail {

struct DecalVisibility {
    std::vector<uint32_t> visible; // decal indices in draw order
    size_t inside = 0;             // of those, boxes that may contain the eye or cross the near plane
    uint32_t flags = 0;            // union of the DecalFlag bits of the visible decals
    size_t culled = 0;             // valid decals outside the view
    // With CullView::rects: for each of `visible`, the normalised device x, y bounds of its box
    // (min x, min y, max x, max y) clamped to [-1, 1]; the whole view where the box reaches behind
    // the eye or may hold it.
    std::vector<glm::vec4> rects;
};

// The view the decals are culled against, in the host's clip conventions.
struct CullView {
    glm::dmat4 viewProj{1.0};  // camera-relative world -> clip
    glm::dvec3 eye{0.0};       // world
    bool reversedZ = true;     // near at clip depth w, far at the low end
    bool clipMinusOne = false; // clip depth range [-w, w] (GL's default), else [0, w]
    double nearRadius = 0.0;   // radius of a sphere around the eye holding the near plane's rectangle
    bool rects = false;        // also the screen rectangles of the boxes (DecalVisibility::rects)
};

class DecalBatch {
public:
    // Settings that shape the instance data; a change rebuilds every instance.
    void configure(float wrapMaxAngleDeg, int layerCount);
    void setTypes(std::vector<DecalType> types);
    void setDecals(const std::vector<Decal>& decals, size_t objectCount);
    // Decals naming an object at or past `objectCount` are invalid.
    void setObjectCount(size_t objectCount);

    size_t size() const { return gpu_.size(); }
    size_t invalidCount() const { return invalid_; }
    // The union of the DecalFlag bits of the valid instances.
    uint32_t flagsUnion() const { return flagsUnion_; }
    // The decal indices in draw order: by DecalType::priority, then Decal::spawnTime, then index.
    const std::vector<uint32_t>& drawOrder() const { return order_; }
    // Whether drawOrder() is 0, 1, 2...
    bool indexOrder() const { return indexOrder_; }
    // Whether the draw order changed since the last call.
    bool takeOrderChange() { return std::exchange(orderChanged_, false); }
    // Whether instance i can be drawn (invalid instances are zero).
    bool valid(size_t i) const { return i < valid_.size() && valid_[i] != 0; }
    const std::vector<DecalRecordGpu>& instances() const { return gpu_; }
    // The types as the shaders read them (one entry per type given to setTypes).
    const std::vector<DecalTypeGpu>& typeRecords() const { return typeRecords_; }
    // The DecalFlag bits of a valid record: its type's and its own.
    uint32_t flags(const DecalRecordGpu& r) const {
        return typeRecords_[recordType(r)].info.y | recordFlags(r);
    }
    // Ranges [begin, end) of instances() changed since markUploaded().
    const std::vector<std::pair<size_t, size_t>>& dirty() const { return dirty_; }
    void markUploaded() { dirty_.clear(); }

    // Frustum culling of the valid decals under the current object transforms (world space,
    // double) against `view`, in draw order.
    DecalVisibility cull(const std::vector<glm::dmat4>& objectTransforms, const CullView& view) const;

private:
    void rebuild();
    void sortDrawOrder();
    // The instance of decal i, or nothing (zero, invalid) when it cannot be drawn.
    bool build(const Decal& d, DecalRecordGpu& out) const;

    float wrapMaxAngleDeg_ = 120.0f;
    int layerCount_ = 0;
    size_t objectCount_ = 0;
    std::vector<DecalType> types_;
    std::vector<Decal> decals_;
    std::vector<uint8_t> valid_;
    std::vector<DecalRecordGpu> gpu_;
    std::vector<DecalTypeGpu> typeRecords_;
    std::vector<std::pair<size_t, size_t>> dirty_;
    size_t invalid_ = 0;
    uint32_t flagsUnion_ = 0;
    std::vector<uint32_t> order_;
    bool indexOrder_ = true;
    bool orderChanged_ = true;
};

} // namespace spatter::render_detail
