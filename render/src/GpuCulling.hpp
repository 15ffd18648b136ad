#pragma once
// GpuCulling: the visible list of a draw built on the GPU, for decal counts where culling every box
// on the CPU each frame would cost more than the draw (ProjectorSettings::gpuCullingFrom). Three
// compute passes over the projector's decal instances and objects (bound at their binding points,
// objects relative to this frame's eye): classify each decal as DecalBatch::cull does (culled, drawn
// from outside, may hold the eye), scan the work groups' counts, and scatter the indices into the
// visible list in decal order, outside decals first and inside decals after them, with the two
// draws' instance counts written into an indirect draw buffer (the inside draw's first place, the
// outside count, is read by decal.vert from the same buffer, bound as CullTotals).

#include "GlObjects.hpp"

#include "spatter/core/Result.hpp"

#include <cstdint>
#include <glm/glm.hpp>

namespace spatter::render_detail {

class GpuCulling {
public:
    GpuCulling() = default;
    GpuCulling(const GpuCulling&) = delete;
    GpuCulling& operator=(const GpuCulling&) = delete;
    ~GpuCulling();

    // Builds the compute programs on first use.
    Status prepare();
    // Culls `count` decals against the frame block's camera; `nearRadius` is the radius of the
    // sphere around the eye holding the near plane's rectangle. The visible list goes into `visible`
    // (grown to hold `count` indices; `visibleCapacity` in bytes).
    void run(uint32_t count, double nearRadius, bool reversedZ, bool clipMinusOne, GlBuffer& visible,
             size_t& visibleCapacity);
    // Two DrawArraysIndirectCommand (outside, inside), then uvec4 totals (x: outside, y: inside).
    GLuint draws() const { return draws_.get(); }
    // The outside and inside counts of the last run when `wait` (waiting for the GPU), else those of
    // the latest run the GPU has finished (0, 0 before the first).
    glm::uvec2 totals(bool wait);

private:
    GlProgram classify_, scan_, scatter_;
    GlBuffer classes_, groups_, draws_, readback_;
    GLsync fence_ = nullptr; // signalled when the last run's totals are in readback_
    glm::uvec2 latest_{0u};
    size_t classesCapacity_ = 0, groupsCapacity_ = 0;
};

} // namespace spatter::render_detail
