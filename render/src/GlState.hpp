#pragma once
// The fixed-function state every pass starts from.

#include "GlStateGuard.hpp"

#include <epoxy/gl.h>

namespace spatter::render_detail {

// Binds `framebuffer` with a viewport of `width` x `height` and resets what a pass may have changed
// (the renderer's projector leaves its state as its passes set it: ProjectorSettings::restoreGlState):
// clip control (lower left, depth 0..1), no scissor, stencil, blending, culling, depth test or depth
// clamp, depth writes off, all colour channels written, counter-clockwise front faces, no sampler
// objects on units 0-7 (each texture samples with its own parameters); sRGB encoding on writes as
// `srgb` says.
inline void resetPassState(GLuint framebuffer, int width, int height, bool srgb) {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, width, height);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_DEPTH_CLAMP);
    glDepthMask(GL_FALSE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glFrontFace(GL_CCW);
    glBindSamplers(0, GlStateGuard::kTextureUnits, nullptr); // the units the projector may change
    if (srgb)
        glEnable(GL_FRAMEBUFFER_SRGB);
    else
        glDisable(GL_FRAMEBUFFER_SRGB);
}

} // namespace spatter::render_detail
