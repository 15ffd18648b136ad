#pragma once
// The G-buffer and the output image, as textures and framebuffers.
//
//   attachment 0  albedo    GL_SRGB8_ALPHA8  base colour (linear in the shaders), alpha
//   attachment 1  normal    GL_RG16F         world normal, octahedral
//   attachment 2  material  GL_RG8           roughness, metallic
//   attachment 3  ids       GL_R8UI          object decal IDs (only when the scene has dynamic objects)
//   attachment 4  coverage  GL_R8            decal coverage (coverage view)
//   attachment 5  faces     GL_RG16F         each pixel's triangle face normal, world, octahedral
//                                            (only with RendererSettings::faceNormals)
//   depth                   GL_DEPTH32F_STENCIL8, reversed-Z (cleared to 0); the stencil marks
//                           the holes of volumetric decals
// plus `normalCopy` (GL_RG16F), the normals the decal pass reads while it writes `normal`, and the
// output image (GL_RGBA8, sRGB-encoded by the shaders) in its own framebuffer, and the overlay
// framebuffer: the output image with the G-buffer depth, for lines depth-tested against the scene.

#include "GlObjects.hpp"

#include "spatter/core/Result.hpp"

namespace spatter::render_detail {

class GBuffer {
public:
    // (Re)creates every target at width x height; `withIds` adds the ID target, `withFaces` the face
    // normal target.
    Status create(int width, int height, bool withIds, bool withFaces);

    int width() const { return width_; }
    int height() const { return height_; }
    bool hasIds() const { return static_cast<bool>(ids_); }
    bool hasFaceNormals() const { return static_cast<bool>(faces_); }

    GLuint framebuffer() const { return fbo_.get(); }
    GLuint outputFramebuffer() const { return outputFbo_.get(); }
    GLuint overlayFramebuffer() const { return overlayFbo_.get(); }
    GLuint albedo() const { return albedo_.get(); }
    GLuint normal() const { return normal_.get(); }
    GLuint normalCopy() const { return normalCopy_.get(); }
    GLuint material() const { return material_.get(); }
    GLuint ids() const { return ids_.get(); }
    GLuint coverage() const { return coverage_.get(); }
    GLuint faceNormals() const { return faces_.get(); }
    GLuint depth() const { return depth_.get(); }
    GLuint output() const { return output_.get(); }

private:
    int width_ = 0;
    int height_ = 0;
    GlTexture albedo_, normal_, normalCopy_, material_, ids_, coverage_, faces_, depth_, output_;
    GlFramebuffer fbo_, outputFbo_, overlayFbo_;
};

} // namespace spatter::render_detail
