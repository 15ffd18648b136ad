#pragma once
// ProjectorBuffers: the GPU buffers every decal pass of the projector reads (the frame block, the
// objects, the decal records, the decal types and the visible list) and what sends to them only what
// changed: the records a change list staged (DecalBatch), the types when they change, the draw
// order's changed runs for the GPU culling.

#include "DecalBatch.hpp"
#include "DecalRecordBuffers.hpp"
#include "GlObjects.hpp"
#include "GpuCulling.hpp"

#include "spatter/render/DecalProjector.hpp"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace spatter::render_detail {

class ProjectorBuffers {
public:
    // Creates the frame block.
    void create();

    // The frame block (camera and viewport of `f`; `view` and `viewProj` camera-relative) and the
    // objects relative to the frame's eye (those whose decals the host draws itself flagged from
    // `batch`), sent every draw.
    void uploadFrame(const HostFrame& f, const glm::dmat4& view, const glm::dmat4& viewProj, float fadeStart,
                     const std::vector<glm::dmat4>& transforms, const std::vector<uint8_t>& ids,
                     const DecalBatch& batch);
    // Sends the decal records (and types) `batch` staged, marking the groups of the draw order whose
    // bounds they change in `groups`; returns the bytes sent and counts the uploads.
    size_t uploadRecords(DecalBatch& batch, size_t& uploads, GroupBounds& groups);
    // Sends a visible list culled on the CPU; returns the bytes sent.
    size_t uploadVisible(const std::vector<uint32_t>& visible);
    // Sends the draw order's changes to `culling` (all of it when the CPU culled since); returns the
    // bytes sent.
    size_t uploadDrawOrder(DecalBatch& batch, GpuCulling& culling);
    // The GPU's draw order falls behind (the CPU culls): sent whole when the GPU culls again.
    void orderLeftBehind() { orderOnGpu_ = false; }
    void typesChanged() { typesChanged_ = true; }

    // The frame block, objects, decal records, types and visible list at their binding points.
    void bind() const;

    GlBuffer& visible() { return visible_; }
    size_t& visibleCapacity() { return visibleCapacity_; }
    size_t visibleCount() const { return visibleCount_; }
    void setVisibleCount(size_t n) { visibleCount_ = n; }
    // For ProjectorResources.
    const DecalRecordBuffers& records() const { return records_; }
    GLuint types() const { return types_.get(); }
    GLuint visibleBuffer() const { return visible_.get(); }
    GLuint objects() const { return objects_.get(); }
    // Bytes of the buffers it holds.
    size_t gpuBytes() const { return records_.bytes() + visibleCapacity_ + objectCapacity_ + typeBytes_; }

private:
    size_t uploadTypes(const DecalBatch& batch);

    GlBuffer frame_, objects_, visible_, types_;
    DecalRecordBuffers records_;
    bool typesChanged_ = true;
    size_t objectCapacity_ = 0, visibleCapacity_ = 0, visibleCount_ = 0, typeBytes_ = 0;
    size_t recordsOnGpu_ = 0; // records the decal buffers hold (past the batch's size they are stale)
    bool orderOnGpu_ = false; // the GPU culling's draw order is the batch's
};

} // namespace spatter::render_detail
