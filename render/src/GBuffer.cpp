#include "GBuffer.hpp"

#include <string>

namespace spatter::render_detail {

namespace {

GlTexture makeTarget(GLenum format, int width, int height) {
    GlTexture t = createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(t.get(), 1, format, width, height);
    glTextureParameteri(t.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(t.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

Status checkComplete(GLuint fbo, const char* what) {
    const GLenum status = glCheckNamedFramebufferStatus(fbo, GL_DRAW_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return fail(std::string("G-buffer: ") + what + " framebuffer is incomplete (status " +
                    std::to_string(status) + ")");
    return {};
}

} // namespace

Status GBuffer::create(int width, int height, bool withIds, bool withFaces) {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
    if (width <= 0 || height <= 0 || width > maxSize || height > maxSize)
        return fail("G-buffer: size " + std::to_string(width) + "x" + std::to_string(height) +
                    " is outside 1.." + std::to_string(maxSize));
    width_ = width;
    height_ = height;
    albedo_ = makeTarget(GL_SRGB8_ALPHA8, width, height);
    normal_ = makeTarget(GL_RG16F, width, height);
    normalCopy_ = makeTarget(GL_RG16F, width, height);
    material_ = makeTarget(GL_RG8, width, height);
    ids_ = withIds ? makeTarget(GL_R8UI, width, height) : GlTexture();
    coverage_ = makeTarget(GL_R8, width, height);
    faces_ = withFaces ? makeTarget(GL_RG16F, width, height) : GlTexture();
    depth_ = makeTarget(GL_DEPTH32F_STENCIL8, width, height);
    output_ = makeTarget(GL_RGBA8, width, height);

    fbo_ = createFramebuffer();
    glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT0, albedo_.get(), 0);
    glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT1, normal_.get(), 0);
    glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT2, material_.get(), 0);
    if (ids_) glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT3, ids_.get(), 0);
    glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT4, coverage_.get(), 0);
    if (faces_) glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT5, faces_.get(), 0);
    glNamedFramebufferTexture(fbo_.get(), GL_DEPTH_STENCIL_ATTACHMENT, depth_.get(), 0);
    if (Status s = checkComplete(fbo_.get(), "G-buffer"); !s) return s;

    outputFbo_ = createFramebuffer();
    glNamedFramebufferTexture(outputFbo_.get(), GL_COLOR_ATTACHMENT0, output_.get(), 0);
    glNamedFramebufferDrawBuffer(outputFbo_.get(), GL_COLOR_ATTACHMENT0);
    glNamedFramebufferReadBuffer(outputFbo_.get(), GL_COLOR_ATTACHMENT0);
    if (Status s = checkComplete(outputFbo_.get(), "output"); !s) return s;

    overlayFbo_ = createFramebuffer();
    glNamedFramebufferTexture(overlayFbo_.get(), GL_COLOR_ATTACHMENT0, output_.get(), 0);
    glNamedFramebufferTexture(overlayFbo_.get(), GL_DEPTH_STENCIL_ATTACHMENT, depth_.get(), 0);
    glNamedFramebufferDrawBuffer(overlayFbo_.get(), GL_COLOR_ATTACHMENT0);
    return checkComplete(overlayFbo_.get(), "overlay");
}

} // namespace spatter::render_detail
