#pragma once
// DecalBatch: the CPU side of the decal store. The decals live on the GPU as 44-byte records
// (DecalRecord.hpp, DecalRecordBuffers.hpp); the batch builds the records of the decals that changed (all of
// them on setDecals, those a DecalChanges names on applyChanges) and stages them for upload, keeps the draw
// order (DrawOrder.hpp) and a validity bit per decal. It keeps a CPU copy of the records and of the draw
// order's entries only while it holds fewer decals than its mirror limit, for culling them on the CPU, in
// draw order, into the visible list; above it no per-decal data but each decal's place in the order and the
// validity bit stays on the CPU, and the GPU culls (GpuCulling).

#include "DecalRecord.hpp"
#include "DrawOrder.hpp"

#include "spatter/core/Decal.hpp"
#include "spatter/core/DecalChanges.hpp"
#include "spatter/core/DecalType.hpp"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace spatter::render_detail {

struct DecalVisibility {
    std::vector<uint32_t> visible; // decal indices in draw order
    size_t inside = 0;             // of those, boxes that may contain the eye or cross the near plane
    uint32_t flags = 0;            // union of the DecalFlag bits of the visible decals
    size_t culled = 0;             // valid decals outside the view or on a singular object
    size_t invalid = 0;            // decals that cannot be drawn (box, object or type)
    size_t hostDrawn = 0;          // valid decals the host draws itself (setHostDrawn)
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

// Records waiting for upload: `records` go to [begin, begin + records.size()).
struct StagedRecords {
    size_t begin = 0;
    std::vector<DecalRecordGpu> records;
};

class DecalBatch {
public:
    // Settings that shape the type records: the wrap-around angle and the texture layers' cutouts
    // (DecalCutout.hpp, one per layer).
    void configure(float wrapMaxAngleDeg, std::vector<glm::vec4> cutouts);
    void setTypes(std::vector<DecalType> types);
    // Types and objects (nonzero entries) whose decals the host draws itself: kept, not drawn. Their
    // type records say so (info.z 2); objects are told to the shaders by the host (ProjectorObjectGpu).
    void setHostDrawn(std::vector<uint8_t> types, std::vector<uint8_t> objects);
    // Decals naming an object at or past `objectCount` are not drawn.
    void setObjectCount(size_t objectCount) { objectCount_ = objectCount; }
    // The CPU copy of the records is kept while fewer decals than this are held.
    void setMirrorLimit(size_t limit);

    // Every decal afresh.
    void setDecals(const std::vector<Decal>& decals);
    // The decals after `changes` (DecalChanges.hpp); takes them whole when the changes are not
    // complete, do not fit the decals held, or the types' priorities changed since the last call.
    void applyChanges(const std::vector<Decal>& decals, const DecalChanges& changes);

    size_t size() const { return order_.decalCount(); }
    // Decals whose box cannot be drawn (degenerate or not finite); with the CPU copy also those naming a
    // missing object or type.
    size_t invalidCount() const;
    // Whether every type is drawn by the projector (none the host's, none that cannot be drawn) and
    // every decal staged since setDecals names one of them: then a decal's type need not be read to
    // know whether it is drawn.
    bool typesPlain() const;
    // The DecalFlag bits of the valid decals (without the CPU copy: of every type that can be drawn).
    uint32_t flagsUnion() const;
    const DrawOrder& order() const { return order_; }
    // The order's changes since the last call (DrawOrder::takeChanged); every entry when `all`.
    DrawOrder::Changes takeOrderChanges(bool all = false) { return order_.takeChanged(all); }
    // The GPU's copy of the order has taken them (DrawOrder::uploaded).
    void orderUploaded() { order_.uploaded(); }
    bool mirrored() const { return mirror_; }
    // The CPU copy of the records (mirrored() only) and whether record i can be drawn.
    const std::vector<DecalRecordGpu>& instances() const { return records_; }
    bool valid(size_t i) const;
    // Whether the host draws the decal of a record itself (it counts its invalid ones too).
    bool hostDrawn(const DecalRecordGpu& r) const;
    bool hostDrawnObject(size_t object) const { return object < hostObjects_.size() && hostObjects_[object]; }
    // The types as the shaders read them (one entry per type given to setTypes).
    const std::vector<DecalTypeGpu>& typeRecords() const { return typeRecords_; }
    // The DecalFlag bits of a record: its type's and its own.
    uint32_t flags(const DecalRecordGpu& r) const {
        return typeRecords_[recordType(r)].info.y | recordFlags(r);
    }

    // Bytes of its own allocations: the draw order, the validity bits, the CPU copy and the staged records.
    size_t cpuBytes() const;

    // Records changed since markUploaded(), in runs.
    const std::vector<StagedRecords>& staged() const { return staged_; }
    void markUploaded();

    // Frustum culling of the valid decals (mirrored() only) under the current object transforms
    // (world space, double) against `view`, in draw order.
    DecalVisibility cull(const std::vector<glm::dmat4>& objectTransforms, const CullView& view) const;

private:
    void rebuildTypes();
    bool replay(const std::vector<Decal>& decals, const DecalChanges& changes, std::vector<uint32_t>& stale);
    void stage(const std::vector<Decal>& decals, std::vector<uint32_t> stale);
    void setValid(size_t i, bool valid);
    void updateMirror(const std::vector<Decal>& decals);

    float wrapMaxAngleDeg_ = 120.0f;
    std::vector<glm::vec4> cutouts_;
    size_t objectCount_ = 0;
    size_t mirrorLimit_ = std::numeric_limits<size_t>::max();
    std::vector<DecalType> types_;
    std::vector<DecalTypeGpu> typeRecords_;
    std::vector<uint8_t> hostTypes_, hostObjects_;
    std::vector<uint32_t> typeRank_;
    size_t typeBound_ = 0; // above every type index staged since setDecals
    bool ranksChanged_ = false;
    DrawOrder order_;
    std::vector<bool> sound_; // per decal: its box can be drawn
    size_t unsound_ = 0;
    bool mirror_ = true;
    std::vector<DecalRecordGpu> records_;
    std::vector<StagedRecords> staged_;
};

} // namespace spatter::render_detail
