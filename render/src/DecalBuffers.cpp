#include "DecalBuffers.hpp"

#include "GlStateGuard.hpp"

namespace spatter::render_detail {

namespace {

constexpr GLenum kFormats[DecalBuffers::kTargets] = {GL_SRGB8_ALPHA8, GL_RGBA16F, GL_RGBA8};

} // namespace

void DecalBuffers::prepare(GLuint depthTexture, bool restoreGlState) {
    GlStateGuard guard(restoreGlState);
    GLint w = 0, h = 0;
    glGetTextureLevelParameteriv(depthTexture, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(depthTexture, 0, GL_TEXTURE_HEIGHT, &h);
    if (!textures_[0] || w != width_ || h != height_) {
        for (int i = 0; i < kTargets; ++i) {
            textures_[i] = createTexture(GL_TEXTURE_2D);
            glTextureStorage2D(textures_[i].get(), 1, kFormats[i], w, h);
        }
        width_ = w;
        height_ = h;
        written_ = true; // new storage holds nothing defined
    }
    if (!written_) return;
    const float none[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    for (const GlTexture& t : textures_)
        glClearTexImage(t.get(), 0, GL_RGBA, GL_FLOAT, none);
    written_ = false;
}

void DecalBuffers::attach(GLuint fbo) {
    GLenum buffers[kTargets];
    for (int i = 0; i < kTargets; ++i) {
        const GLuint b = GLuint(i);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0 + b, textures_[i].get(), 0);
        buffers[i] = GL_COLOR_ATTACHMENT0 + b;
        glEnablei(GL_BLEND, b);
        glBlendEquationi(b, GL_FUNC_ADD);
        glBlendFuncSeparatei(b, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
        glColorMaski(b, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    }
    glNamedFramebufferDrawBuffers(fbo, kTargets, buffers);
    written_ = true;
}

} // namespace spatter::render_detail
