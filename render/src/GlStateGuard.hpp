#pragma once
// GlStateGuard: saves, on construction, the GL state the projector may change and restores it on
// destruction (the list in spatter/render/DecalProjector.hpp), as Dear ImGui's OpenGL 3 backend
// does, so that a host can call the projector between its own passes; or, for a host that binds what
// its passes use (ProjectorSettings::restoreGlState off), neither queries nor restores anything. neutralise()
// then switches off what a host may have left on that would change the projector's draws (polygon mode,
// rasterizer discard, logic op, depth clamp, clip distances).

#include <epoxy/gl.h>

#include <array>

namespace spatter::render_detail {

class GlStateGuard {
public:
    static constexpr int kTextureUnits = 8;
    static constexpr int kDrawBuffers = 4;
    static constexpr int kUniformBindings = 2;
    static constexpr int kStorageBindings = 11;
    static constexpr int kImageUnits = 3;

    // Saves the state where `save`; otherwise the guard does nothing.
    explicit GlStateGuard(bool save);
    ~GlStateGuard();
    // Fills polygons, with rasterizer discard, colour logic op, depth clamp and clip distances 0-7 off.
    static void neutralise();
    GlStateGuard(const GlStateGuard&) = delete;
    GlStateGuard& operator=(const GlStateGuard&) = delete;

private:
    struct IndexedBuffer {
        GLint buffer = 0;
        GLint64 start = 0, size = 0;
    };
    struct ImageUnit {
        GLint texture = 0, level = 0, layered = GL_FALSE, layer = 0, access = GL_READ_ONLY, format = GL_R8;
    };
    struct Blend {
        GLboolean enabled = GL_FALSE;
        GLint srcRgb = 0, dstRgb = 0, srcAlpha = 0, dstAlpha = 0, equationRgb = 0, equationAlpha = 0;
        GLboolean mask[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
    };

    bool saved_ = false;
    GLint drawFramebuffer_ = 0, readFramebuffer_ = 0, program_ = 0, vertexArray_ = 0, activeTexture_ = 0;
    GLint viewport_[4] = {0, 0, 0, 0};
    std::array<GLint, kTextureUnits> texture2d_{}, textureArray_{}, sampler_{};
    std::array<IndexedBuffer, kUniformBindings> uniform_{};
    std::array<IndexedBuffer, kStorageBindings> storage_{};
    std::array<ImageUnit, kImageUnits> image_{};
    GLint uniformBuffer_ = 0, storageBuffer_ = 0, arrayBuffer_ = 0, unpackBuffer_ = 0, indirectBuffer_ = 0,
          dispatchBuffer_ = 0;
    std::array<Blend, kDrawBuffers> blend_{};
    GLboolean depthTest_ = GL_FALSE, depthMask_ = GL_TRUE, stencilTest_ = GL_FALSE, scissorTest_ = GL_FALSE;
    GLboolean cullFace_ = GL_FALSE, framebufferSrgb_ = GL_FALSE, rasterizerDiscard_ = GL_FALSE;
    GLboolean colorLogicOp_ = GL_FALSE, depthClamp_ = GL_FALSE;
    std::array<GLboolean, 8> clipDistance_{};
    GLint polygonMode_[2] = {GL_FILL, GL_FILL};
    GLint depthFunc_ = 0, cullMode_ = 0, frontFace_ = 0, clipOrigin_ = 0, clipDepth_ = 0,
          unpackAlignment_ = 4;
};

} // namespace spatter::render_detail
