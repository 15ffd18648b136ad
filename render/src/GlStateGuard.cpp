#include "GlStateGuard.hpp"

namespace spatter::render_detail {

namespace {

void enable(GLenum cap, GLboolean on) {
    if (on)
        glEnable(cap);
    else
        glDisable(cap);
}

} // namespace

GlStateGuard::GlStateGuard(bool save) : saved_(save) {
    if (!save) return;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer_);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFramebuffer_);
    glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertexArray_);
    glGetIntegerv(GL_VIEWPORT, viewport_);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture_);
    for (int i = 0; i < kTextureUnits; ++i) {
        glActiveTexture(GLenum(GL_TEXTURE0 + i));
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture2d_[size_t(i)]);
        glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &textureArray_[size_t(i)]);
        glGetIntegerv(GL_SAMPLER_BINDING, &sampler_[size_t(i)]);
    }
    glActiveTexture(GLenum(activeTexture_));
    for (int i = 0; i < kUniformBindings; ++i) {
        IndexedBuffer& b = uniform_[size_t(i)];
        glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, GLuint(i), &b.buffer);
        glGetInteger64i_v(GL_UNIFORM_BUFFER_START, GLuint(i), &b.start);
        glGetInteger64i_v(GL_UNIFORM_BUFFER_SIZE, GLuint(i), &b.size);
    }
    for (int i = 0; i < kStorageBindings; ++i) {
        IndexedBuffer& b = storage_[size_t(i)];
        glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, GLuint(i), &b.buffer);
        glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, GLuint(i), &b.start);
        glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, GLuint(i), &b.size);
    }
    for (int i = 0; i < kImageUnits; ++i) {
        ImageUnit& u = image_[size_t(i)];
        glGetIntegeri_v(GL_IMAGE_BINDING_NAME, GLuint(i), &u.texture);
        glGetIntegeri_v(GL_IMAGE_BINDING_LEVEL, GLuint(i), &u.level);
        glGetIntegeri_v(GL_IMAGE_BINDING_LAYERED, GLuint(i), &u.layered);
        glGetIntegeri_v(GL_IMAGE_BINDING_LAYER, GLuint(i), &u.layer);
        glGetIntegeri_v(GL_IMAGE_BINDING_ACCESS, GLuint(i), &u.access);
        glGetIntegeri_v(GL_IMAGE_BINDING_FORMAT, GLuint(i), &u.format);
    }
    glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &uniformBuffer_);
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &storageBuffer_);
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &arrayBuffer_);
    glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpackBuffer_);
    glGetIntegerv(GL_DRAW_INDIRECT_BUFFER_BINDING, &indirectBuffer_);
    glGetIntegerv(GL_DISPATCH_INDIRECT_BUFFER_BINDING, &dispatchBuffer_);
    for (int i = 0; i < kDrawBuffers; ++i) {
        Blend& b = blend_[size_t(i)];
        const auto index = GLuint(i);
        b.enabled = glIsEnabledi(GL_BLEND, index);
        glGetIntegeri_v(GL_BLEND_SRC_RGB, index, &b.srcRgb);
        glGetIntegeri_v(GL_BLEND_DST_RGB, index, &b.dstRgb);
        glGetIntegeri_v(GL_BLEND_SRC_ALPHA, index, &b.srcAlpha);
        glGetIntegeri_v(GL_BLEND_DST_ALPHA, index, &b.dstAlpha);
        glGetIntegeri_v(GL_BLEND_EQUATION_RGB, index, &b.equationRgb);
        glGetIntegeri_v(GL_BLEND_EQUATION_ALPHA, index, &b.equationAlpha);
        glGetBooleani_v(GL_COLOR_WRITEMASK, index, b.mask);
    }
    depthTest_ = glIsEnabled(GL_DEPTH_TEST);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask_);
    glGetIntegerv(GL_DEPTH_FUNC, &depthFunc_);
    stencilTest_ = glIsEnabled(GL_STENCIL_TEST);
    scissorTest_ = glIsEnabled(GL_SCISSOR_TEST);
    cullFace_ = glIsEnabled(GL_CULL_FACE);
    glGetIntegerv(GL_CULL_FACE_MODE, &cullMode_);
    glGetIntegerv(GL_FRONT_FACE, &frontFace_);
    glGetIntegerv(GL_CLIP_ORIGIN, &clipOrigin_);
    glGetIntegerv(GL_CLIP_DEPTH_MODE, &clipDepth_);
    framebufferSrgb_ = glIsEnabled(GL_FRAMEBUFFER_SRGB);
    rasterizerDiscard_ = glIsEnabled(GL_RASTERIZER_DISCARD);
    colorLogicOp_ = glIsEnabled(GL_COLOR_LOGIC_OP);
    depthClamp_ = glIsEnabled(GL_DEPTH_CLAMP);
    for (int i = 0; i < 8; ++i)
        clipDistance_[size_t(i)] = glIsEnabled(GLenum(GL_CLIP_DISTANCE0 + i));
    glGetIntegerv(GL_POLYGON_MODE, polygonMode_);
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &unpackAlignment_);
}

GlStateGuard::~GlStateGuard() {
    if (!saved_) return;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(drawFramebuffer_));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(readFramebuffer_));
    glUseProgram(GLuint(program_));
    glBindVertexArray(GLuint(vertexArray_));
    glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
    for (int i = 0; i < kTextureUnits; ++i) {
        glActiveTexture(GLenum(GL_TEXTURE0 + i));
        glBindTexture(GL_TEXTURE_2D, GLuint(texture2d_[size_t(i)]));
        glBindTexture(GL_TEXTURE_2D_ARRAY, GLuint(textureArray_[size_t(i)]));
        glBindSampler(GLuint(i), GLuint(sampler_[size_t(i)]));
    }
    for (int i = 0; i < kImageUnits; ++i) {
        const ImageUnit& u = image_[size_t(i)];
        const GLuint texture = u.texture != 0 && glIsTexture(GLuint(u.texture)) ? GLuint(u.texture) : 0u;
        glBindImageTexture(GLuint(i), texture, u.level, GLboolean(u.layered), u.layer, GLenum(u.access),
                           GLenum(u.format));
    }
    glActiveTexture(GLenum(activeTexture_));
    // A buffer deleted meanwhile (one of the projector's, which the host had bound, and which grew) is
    // unbound, as GL itself unbinds a buffer deleted while bound.
    auto alive = [](GLint name) { return name != 0 && glIsBuffer(GLuint(name)) ? GLuint(name) : 0u; };
    auto rebind = [&](GLenum target, GLuint index, const IndexedBuffer& b) {
        const GLuint name = alive(b.buffer);
        if (name != 0 && b.size > 0)
            glBindBufferRange(target, index, name, GLintptr(b.start), GLsizeiptr(b.size));
        else
            glBindBufferBase(target, index, name);
    };
    for (int i = 0; i < kUniformBindings; ++i)
        rebind(GL_UNIFORM_BUFFER, GLuint(i), uniform_[size_t(i)]);
    for (int i = 0; i < kStorageBindings; ++i)
        rebind(GL_SHADER_STORAGE_BUFFER, GLuint(i), storage_[size_t(i)]);
    // The generic bindings last: binding a range also sets them.
    glBindBuffer(GL_UNIFORM_BUFFER, alive(uniformBuffer_));
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, alive(storageBuffer_));
    glBindBuffer(GL_ARRAY_BUFFER, alive(arrayBuffer_));
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, alive(unpackBuffer_));
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, alive(indirectBuffer_));
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, alive(dispatchBuffer_));
    for (int i = 0; i < kDrawBuffers; ++i) {
        const Blend& b = blend_[size_t(i)];
        const auto index = GLuint(i);
        if (b.enabled)
            glEnablei(GL_BLEND, index);
        else
            glDisablei(GL_BLEND, index);
        glBlendFuncSeparatei(index, GLenum(b.srcRgb), GLenum(b.dstRgb), GLenum(b.srcAlpha),
                             GLenum(b.dstAlpha));
        glBlendEquationSeparatei(index, GLenum(b.equationRgb), GLenum(b.equationAlpha));
        glColorMaski(index, b.mask[0], b.mask[1], b.mask[2], b.mask[3]);
    }
    enable(GL_DEPTH_TEST, depthTest_);
    glDepthMask(depthMask_);
    glDepthFunc(GLenum(depthFunc_));
    enable(GL_STENCIL_TEST, stencilTest_);
    enable(GL_SCISSOR_TEST, scissorTest_);
    enable(GL_CULL_FACE, cullFace_);
    glCullFace(GLenum(cullMode_));
    glFrontFace(GLenum(frontFace_));
    glClipControl(GLenum(clipOrigin_), GLenum(clipDepth_));
    enable(GL_FRAMEBUFFER_SRGB, framebufferSrgb_);
    enable(GL_RASTERIZER_DISCARD, rasterizerDiscard_);
    enable(GL_COLOR_LOGIC_OP, colorLogicOp_);
    enable(GL_DEPTH_CLAMP, depthClamp_);
    for (int i = 0; i < 8; ++i)
        enable(GLenum(GL_CLIP_DISTANCE0 + i), clipDistance_[size_t(i)]);
    glPolygonMode(GL_FRONT_AND_BACK, GLenum(polygonMode_[0]));
    glPixelStorei(GL_UNPACK_ALIGNMENT, unpackAlignment_);
}

void GlStateGuard::neutralise() {
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDisable(GL_RASTERIZER_DISCARD);
    glDisable(GL_COLOR_LOGIC_OP);
    glDisable(GL_DEPTH_CLAMP);
    for (int i = 0; i < 8; ++i)
        glDisable(GLenum(GL_CLIP_DISTANCE0 + i));
}

} // namespace spatter::render_detail
