#include "TextureSpaceDecals.hpp"

#include "DecalRecordBuffers.hpp"
#include "GlState.hpp"
#include "RendererShaders.hpp"
#include "ShaderProgram.hpp"

namespace spatter::render_detail {

namespace {

GlTexture makeTexture(GLenum format, int size) {
    GlTexture t = createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(t.get(), 1, format, size, size);
    glTextureParameteri(t.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(t.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

GlFramebuffer makeFramebuffer(GLuint colour0, GLuint colour1) {
    GlFramebuffer f = createFramebuffer();
    glNamedFramebufferTexture(f.get(), GL_COLOR_ATTACHMENT0, colour0, 0);
    if (colour1 != 0) glNamedFramebufferTexture(f.get(), GL_COLOR_ATTACHMENT1, colour1, 0);
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(f.get(), colour1 != 0 ? 2 : 1, buffers);
    return f;
}

// State every texture-space pass starts from: the whole square of `size` texels, nothing tested,
// sRGB-encoded writes.
void baseState(GLuint framebuffer, int size) {
    resetPassState(framebuffer, size, size, true);
}

void drawMesh(const GpuMesh& mesh, GLsizei instances) {
    glBindVertexArray(mesh.vao.get());
    glDrawElementsInstanced(GL_TRIANGLES, GLsizei(mesh.triangles * 3), GL_UNSIGNED_INT, nullptr, instances);
}

} // namespace

void TextureSpaceDecals::reset(size_t objectCount) {
    objects_.clear();
    objects_.resize(objectCount);
    scratch_.clear();
}

Status TextureSpaceDecals::buildPrograms() {
    if (maskProgram_) return {};
    Result<GlProgram> mask =
        buildProgram(shaderLibrary(kRendererShaders),
                     {{GL_VERTEX_SHADER, "splat.vert"}, {GL_FRAGMENT_SHADER, "splat.frag"}}, {"MASK"});
    if (!mask) return fail("texture-space decals: " + mask.error());
    Result<GlProgram> splat =
        buildProgram(shaderLibrary(kRendererShaders),
                     {{GL_VERTEX_SHADER, "splat.vert"}, {GL_FRAGMENT_SHADER, "splat.frag"}}, {});
    if (!splat) return fail("texture-space decals: " + splat.error());
    Result<GlProgram> dilate =
        buildProgram(shaderLibrary(kRendererShaders),
                     {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "dilate.frag"}}, {});
    if (!dilate) return fail("texture-space decals: " + dilate.error());
    maskProgram_ = std::move(mask.value());
    splatProgram_ = std::move(splat.value());
    dilateProgram_ = std::move(dilate.value());
    emptyVao_ = createVertexArray();
    return {};
}

Status TextureSpaceDecals::enable(size_t object, int size, const GpuMesh& mesh) {
    if (object >= objects_.size())
        return fail("texture-space decals: object " + std::to_string(object) + " out of range");
    if (Status s = buildPrograms(); !s) return s;
    auto layer = std::make_unique<Layer>();
    layer->size = size;
    layer->albedo = makeTexture(GL_SRGB8_ALPHA8, size);
    layer->normal = makeTexture(GL_RGBA8, size);
    layer->mask = makeTexture(GL_R8, size);
    layer->framebuffer = makeFramebuffer(layer->albedo.get(), layer->normal.get());
    layer->maskFramebuffer = makeFramebuffer(layer->mask.get(), 0);
    const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(layer->framebuffer.get(), GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(layer->framebuffer.get(), GL_COLOR, 1, zero);

    baseState(layer->maskFramebuffer.get(), size);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glClearBufferfv(GL_COLOR, 0, zero);
    glUseProgram(maskProgram_.get());
    if (mesh.triangles > 0) drawMesh(mesh, 1);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    objects_[object] = std::move(layer);
    scratch(size);
    return {};
}

void TextureSpaceDecals::disable(size_t object) {
    if (object < objects_.size()) objects_[object].reset();
}

void TextureSpaceDecals::clear(size_t object) {
    if (!enabled(object)) return;
    const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(objects_[object]->framebuffer.get(), GL_COLOR, 0, zero);
    glClearNamedFramebufferfv(objects_[object]->framebuffer.get(), GL_COLOR, 1, zero);
}

size_t TextureSpaceDecals::objectCount() const {
    size_t n = 0;
    for (const auto& o : objects_)
        n += o ? 1 : 0;
    return n;
}

size_t TextureSpaceDecals::bytes() const {
    size_t b = 0;
    for (const auto& o : objects_)
        if (o) b += size_t(o->size) * size_t(o->size) * (4 + 4 + 1);
    for (const auto& s : scratch_)
        b += size_t(s.first) * size_t(s.first) * (4 + 4);
    return b;
}

TextureSpaceDecals::Scratch& TextureSpaceDecals::scratch(int size) {
    auto it = scratch_.find(size);
    if (it != scratch_.end()) return it->second;
    Scratch s;
    s.albedo = makeTexture(GL_SRGB8_ALPHA8, size);
    s.normal = makeTexture(GL_RGBA8, size);
    s.framebuffer = makeFramebuffer(s.albedo.get(), s.normal.get());
    return scratch_.emplace(size, std::move(s)).first->second;
}

void TextureSpaceDecals::dilate(Layer& layer, size_t& drawCalls) {
    Scratch& s = scratch(layer.size);
    baseState(s.framebuffer.get(), layer.size);
    glUseProgram(dilateProgram_.get());
    glBindTextureUnit(0, layer.albedo.get());
    glBindTextureUnit(1, layer.normal.get());
    glBindTextureUnit(2, layer.mask.get());
    glBindVertexArray(emptyVao_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    ++drawCalls;
    glCopyImageSubData(s.albedo.get(), GL_TEXTURE_2D, 0, 0, 0, 0, layer.albedo.get(), GL_TEXTURE_2D, 0, 0, 0,
                       0, layer.size, layer.size, 1);
    glCopyImageSubData(s.normal.get(), GL_TEXTURE_2D, 0, 0, 0, 0, layer.normal.get(), GL_TEXTURE_2D, 0, 0, 0,
                       0, layer.size, layer.size, 1);
}

Result<size_t> TextureSpaceDecals::splat(const std::vector<std::vector<uint32_t>>& perObject,
                                         const SceneGpu& scene, const SplatInputs& in, float fadeStart,
                                         size_t& drawCalls) {
    if (Status s = buildPrograms(); !s) return fail(s.error());
    size_t splatted = 0;
    uint32_t first = 0;
    for (size_t o = 0; o < perObject.size(); ++o) {
        const uint32_t count = uint32_t(perObject[o].size());
        if (count == 0) continue;
        const uint32_t begin = first;
        first += count;
        if (!enabled(o) || o >= scene.objectCount() || scene.mesh(o).triangles == 0) continue;
        Layer& layer = *objects_[o];
        baseState(layer.framebuffer.get(), layer.size);
        glEnable(GL_BLEND);
        glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
        bindDecalRecords(in.bounds, in.bodies);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDecalTypeBuffer, in.types);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVisibleBuffer, in.lists);
        glBindTextureUnit(3, in.decalAlbedo);
        glBindTextureUnit(4, in.decalNormal);
        glUseProgram(splatProgram_.get());
        glUniform1ui(0, begin);
        glUniform1f(1, fadeStart);
        glUniform1ui(2, GLuint(o));
        glUniform1ui(3, in.posed ? 1u : 0u);
        const glm::mat4 toObject = o < in.worldToObject.size() ? in.worldToObject[o] : glm::mat4(1.0f);
        glUniformMatrix4fv(4, 1, GL_FALSE, &toObject[0][0]);
        drawMesh(scene.mesh(o), GLsizei(count));
        ++drawCalls;
        glDisable(GL_BLEND);
        dilate(layer, drawCalls);
        splatted += count;
    }
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return splatted;
}

} // namespace spatter::render_detail
