#pragma once
// DepthPyramid: the host's depth as a mip chain of farthest depths (shaders/depth_pyramid.comp), for
// the GPU culling's occlusion test: a box whose nearest point lies beyond every texel of the level
// where its screen rectangle spans at most two texels a side cannot show a pixel (or, past the top
// level, beyond every texel of the top level under it). Level 0 is half the viewport, rounded up to a
// multiple of 64 texels a side so that seven levels halve exactly (2.9 MB at 1080p with the levels
// above it, where a power of two a side took 5.6 MB).

#include "GlObjects.hpp"
#include "GpuCulling.hpp"

#include "spatter/core/Result.hpp"
#include "spatter/render/DecalProjector.hpp"

#include <glm/glm.hpp>

namespace spatter::render_detail {

class DepthPyramid {
public:
    // Builds the program for `frame`'s depth convention on first use.
    Status prepare(const HostFrame& frame);
    // Builds the pyramid of `frame`'s depth, read through `sampler`, and returns it for the culling.
    // Needs prepare() to have succeeded for the frame's convention.
    Occlusion build(const HostFrame& frame, GLuint sampler);

    // Bytes of the texture.
    size_t gpuBytes() const;

private:
    void allocate(glm::ivec2 size, int levels);

    GlProgram programs_[3]; // window standard Z, window reversed Z, linear view distance
    GlTexture texture_;
    glm::ivec2 size_{0};
    int levels_ = 0;
};

} // namespace spatter::render_detail
