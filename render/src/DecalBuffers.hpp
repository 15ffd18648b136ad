#pragma once
// DecalBuffers: the DBuffer path's three textures (ProjectorResources::dbuffer*): albedo
// (SRGB8_ALPHA8), world normal (RGBA16F) and material (RGBA8, roughness in R), the size of the host's
// depth texture. Each holds the decals premultiplied by their alpha in RGB and, in A, how much of the
// surface shows through; "no decal" is RGB 0, A 1 (shaders/dbuffer.glsl applies them).

#include "GlObjects.hpp"

namespace spatter::render_detail {

class DecalBuffers {
public:
    static constexpr int kTargets = 3;

    // Gives the buffers the size of `depthTexture` and clears them when a draw wrote into them since
    // the last clear. Leaves the GL state as it was where `restoreGlState` (ProjectorSettings).
    void prepare(GLuint depthTexture, bool restoreGlState);
    // Attaches them to `fbo` as colour attachments 0 to 2, each blending src * a + dst * (1 - a) in
    // RGB and dst * (1 - a) in A; they count as written from here on.
    void attach(GLuint fbo);
    // They count as written from here on: a compute pass stores into them (ComputeResolve).
    void markWritten() { written_ = true; }

    GLuint albedo() const { return textures_[0].get(); }
    GLuint normal() const { return textures_[1].get(); }
    GLuint material() const { return textures_[2].get(); }

private:
    GlTexture textures_[kTargets];
    int width_ = 0, height_ = 0;
    bool written_ = false;
};

} // namespace spatter::render_detail
