#pragma once
// NormalCopy: the G-buffer blend's copy of the host's normals. Decals that blend normal maps into the
// host's normal texture must read the surface as it was before any decal, so the projector reads a
// copy. Where the visible boxes cover little of the viewport the copy is taken under the boxes only
// (a draw of the boxes with shaders/normal_copy.frag, at the cost of the pixels they cover); where
// they cover much of it, the whole viewport is copied at once.

#include "DecalBatch.hpp"
#include "GlObjects.hpp"

#include "spatter/core/Result.hpp"
#include "spatter/render/DecalProjector.hpp"

#include <string>

namespace spatter::render_detail {

enum class NormalCopyMode { None, Boxes, Viewport };

// Boxes when the screen rectangles of the visible boxes add up to at most a quarter of the viewport
// (a box that may hold the eye counts as the whole viewport), else Viewport.
NormalCopyMode normalCopyMode(const DecalVisibility& vis);
// The same choice for a visible list built on the GPU, from its outside and inside counts (those of
// an earlier draw): boxes while at most kBoxCopyDecals decals are in view and none may hold the eye.
NormalCopyMode normalCopyMode(glm::uvec2 gpuTotals);
constexpr unsigned kBoxCopyDecals = 1024;

const char* normalCopyName(NormalCopyMode mode);

class NormalCopy {
public:
    // Builds the copy program on first use.
    Status prepare();
    // Gives the copy the host normal texture's format and size.
    void allocate(GLuint hostNormals);
    // Copies the frame's viewport of the host's normals.
    void copyViewport(const HostFrame& f) const;

    GLuint texture() const { return texture_.get(); }
    GLuint program() const { return program_.get(); }

private:
    GlProgram program_;
    GlTexture texture_;
    GLenum format_ = 0;
    int width_ = 0, height_ = 0;
};

} // namespace spatter::render_detail
