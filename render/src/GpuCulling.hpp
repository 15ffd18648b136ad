#pragma once
// GpuCulling: the visible list of a draw built on the GPU, for decal counts where culling every box on the
// CPU each frame would cost more than the draw (ProjectorSettings::gpuCullingFrom). Four compute passes (or
// three) over the projector's decal instances and objects (bound at their binding points, objects relative to
// this frame's eye): every group of 256 places of the draw order (DrawOrder.hpp) through a test of its box
// (GroupBounds: a group out of view is culled whole, none of its decals read; where most groups were left in
// the latest count, the next pass tests each group's boxes itself instead); the places of the other groups
// through a bounding-sphere test that needs no unpacked frame (cull.comp); the few left through the corner
// test DecalBatch::cull makes and the occlusion test (cull_exact.comp); then, for each group with a visible
// place, its visible indices into the visible list in draw order (cull_scatter.comp). The draw's instance
// count goes into an indirect draw buffer; the boxes are then drawn by their far faces (the GPU does not tell
// which may hold the eye). What a large world costs is its groups, and the places of the groups in view or
// spread over it; the test by place reads no more of a record than its box's centre, size and object.

#include "DrawOrder.hpp"
#include "GlObjects.hpp"
#include "GpuReadback.hpp"
#include "GroupBounds.hpp"

#include "spatter/core/Result.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <utility>
#include <vector>

namespace spatter::render_detail {

// The depth pyramid the culling tests boxes against (DepthPyramid); no texture: no occlusion test.
struct Occlusion {
    GLuint texture = 0;
    int levels = 0;
    int convention = 0; // 0 window depth with standard Z, 1 reversed Z, 2 view distance
    glm::ivec2 size{0}; // of level 0
};

// What a run culls: the decals held, the view's clip depth conventions, and whether the first pass
// reads each decal's type (DecalBatch::typesPlain() false).
struct CullRun {
    size_t decals = 0;
    bool reversedZ = true, clipMinusOne = false;
    bool checkTypes = true;
};

class GpuCulling {
public:
    GpuCulling() = default;
    GpuCulling(const GpuCulling&) = delete;
    GpuCulling& operator=(const GpuCulling&) = delete;

    // Builds the compute programs on first use.
    Status prepare();
    // Sends `order`'s `changes` (DrawOrder::takeChanged): every entry, runs of its entries, or writes
    // applied by a compute pass (order_write.comp); returns the bytes sent.
    size_t updateDrawOrder(const DrawOrder& order, const DrawOrder::Changes& changes);
    // Culls the decals of the draw order (`what.decals` of them) against the frame block's camera, and
    // against `occlusion`'s pyramid when it has one. The visible list goes into `visible` (grown to hold that
    // many indices; `visibleCapacity` in bytes). Binds its own buffers over shader storage bindings 0-2 and
    // 5-7 (the projector's objects at 1 among them, then the read-back buffer for the last pass).
    void run(const CullRun& what, const Occlusion& occlusion, GlBuffer& visible, size_t& visibleCapacity);
    // Marks the last run's counts, which its last pass writes into the read-back buffer, as ready to
    // read (visibleCount and the others read them), once a run: at the end of the pass, where the
    // mark holds up no pass after the culling.
    void readBack();
    // One DrawElementsIndirectCommand: the cube's 36 indices, the visible count as instances (followed by the
    // occluded, invalid and host-drawn counts).
    GLuint draws() const { return counters_.get(); }
    // The visible count of the last run when `wait` (read back now if readBack() has not been, and
    // waiting for the GPU), else that of the latest run the GPU has finished (0 before the first).
    uint32_t visibleCount(bool wait);
    // Whether the GPU has given a count yet (visibleCount reads it).
    bool hasCounted() const { return counts_.hasRead(); }
    // In the run visibleCount last read: the boxes in the frustum the occlusion test culled, the
    // decals that cannot be drawn (their box, type or object) and those the host draws itself
    // (DecalProjector::setHostDrawn).
    uint32_t occludedCount() const { return counts_.values()[1]; }
    uint32_t invalidCount() const { return counts_.values()[2]; }
    uint32_t hostDrawnCount() const { return counts_.values()[3]; }
    // The groups of 256 places whose decals were tested one by one, the others culled whole.
    uint32_t testedGroupCount() const { return counts_.values()[4]; }
    // The groups' bounds, to mark those whose decals change (ProjectorBuffers::uploadRecords).
    GroupBounds& groupBounds() { return groupBounds_; }

    // Bytes of its own allocations (the groups' marks), and of the GPU buffers it holds.
    size_t cpuBytes() const { return groupBounds_.cpuBytes(); }
    size_t gpuBytes() const {
        return classesCapacity_ + groupsCapacity_ + orderCapacity_ + writesCapacity_ +
               groupBounds_.gpuBytes();
    }

private:
    // Grows the buffers for this run and `visible` for `decals` indices; returns the groups of 256
    // places of the draw order.
    uint32_t reserve(size_t decals, GlBuffer& visible, size_t& visibleCapacity);
    void bind(const GlBuffer& visible) const;
    // Whether the test by place takes every group (most were listed in the latest count read back).
    bool testsEveryGroup(uint32_t groups) const;
    // The work groups of the corner test and of the scatter, sized by the latest counts read back.
    uint32_t exactGroups() const;
    uint32_t scatterGroups(uint32_t groups) const;

    // Applies `writes` to the draw order's buffer (order_write.comp).
    size_t writeDrawOrder(const std::vector<glm::uvec2>& writes);

    GlProgram classify_, exact_, scatter_, write_;
    GlBuffer classes_, groups_, counters_, order_, writes_;
    size_t classesCapacity_ = 0, groupsCapacity_ = 0, orderCapacity_ = 0, writesCapacity_ = 0;
    uint32_t entries_ = 0; // of the draw order
    GroupBounds groupBounds_;
    // The visible, occluded, invalid and host-drawn counts of a run, and the groups tested by place.
    GpuReadback counts_{5};
};

} // namespace spatter::render_detail
