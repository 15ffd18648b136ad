#pragma once
// DepthPyramid: the host's depth as a mip chain of farthest depths (shaders/depth_pyramid.comp), for
// the GPU culling's occlusion test: a box whose nearest point lies beyond every texel of the level
// where its screen rectangle spans at most two texels a side cannot show a pixel (or, past the top
// level, beyond every texel of the top level under it). A level-0 texel holds 4 x 4 pixels: level 0
// is a quarter of the viewport a side, rounded up to a multiple of 64 texels so that seven levels
// halve exactly (0.87 MB at 1080p with the levels above it; 2.9 MB at 2 x 2 pixels, which tests
// only boxes under about 8 pixels against finer texels, and 5.6 MB at a power of two a side).

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
