#pragma once
// NormalCopy: the G-buffer blend's copy of the host's normals. Decals that blend normal maps into the
// host's normal texture must read the surface as it was before any decal, so the projector reads a
// copy. Where the visible boxes cover little of the viewport the copy is taken under them only: the
// screen rectangle of each of a few boxes, or a draw of the boxes with shaders/normal_copy.frag (at
// the cost of the pixels they cover); where they cover much of it, the whole viewport at once. The
// copy is as large as the host's normal texture; the projector frees it when its draws have stopped
// reading it (ProjectorMemory::kNormalCopyIdleDraws).

#include "DecalBatch.hpp"
#include "GlObjects.hpp"

#include "spatter/core/Result.hpp"
#include "spatter/render/DecalProjector.hpp"

#include <string>

namespace spatter::render_detail {

enum class NormalCopyMode { None, InPlace, Rects, Boxes, Viewport };

// When the screen rectangles of the visible boxes add up to at most a quarter of the viewport (a box
// that may hold the eye counts as the whole viewport): Rects (a copy of each rectangle; on an H200
// about 1 microsecond each) for up to kRectCopyDecals boxes, else Boxes (a draw of the boxes, about
// 30 microseconds whatever their number). Otherwise Viewport.
// InPlace, no copy at all, where up to kInPlaceDecals boxes' screen rectangles, widened by a pixel, overlap
// nowhere and `inPlace` allows it: each pixel is then drawn by one box at most, whose fragment reads the
// host's normal and writes it (GL's one defined feedback loop, after a texture barrier); the caller
// allows it when no visible decal wraps (a wrapped decal's texture derivatives read the neighbours'
// normals) and no second draw reads the normals after the first wrote them.
NormalCopyMode normalCopyMode(const DecalVisibility& vis, int width, int height, bool inPlace);
// The same choice for a visible list built on the GPU, from its length (that of an earlier draw):
// Boxes while at most kBoxCopyDecals decals are in view.
NormalCopyMode normalCopyMode(uint32_t gpuVisible);
constexpr unsigned kBoxCopyDecals = 1024;
constexpr size_t kRectCopyDecals = 24;
constexpr size_t kInPlaceDecals = 64;

const char* normalCopyName(NormalCopyMode mode);

class NormalCopy {
public:
    // Builds the copy program on first use.
    Status prepare();
    // Gives the copy the host normal texture's format and size.
    void allocate(GLuint hostNormals);
    // Frees the copy's texels (allocate() makes them again).
    void release();
    // Copies the frame's viewport of the host's normals.
    void copyViewport(const HostFrame& f) const;
    // Copies the screen rectangles (normalised device x, y bounds) of `vis`'s boxes.
    void copyRects(const HostFrame& f, const DecalVisibility& vis) const;

    GLuint texture() const { return texture_.get(); }
    GLuint program() const { return program_.get(); }
    // Bytes of the copy's texels (0 before the first allocate).
    size_t gpuBytes() const { return bytes_; }

private:
    GlProgram program_;
    GlTexture texture_;
    GLenum format_ = 0;
    int width_ = 0, height_ = 0;
    size_t bytes_ = 0;
};

} // namespace spatter::render_detail
