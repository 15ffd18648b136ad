#include "ForeignHost.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <string>

namespace spatter::test {

namespace {

const char* kVert = R"(#version 450 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 0) uniform mat4 u_modelViewProj;
layout(location = 4) uniform mat3 u_normalMatrix; // u_modelViewProj takes locations 0 to 3
out vec3 v_normal;
void main() {
    gl_Position = u_modelViewProj * vec4(a_position, 1.0);
    v_normal = u_normalMatrix * a_normal;
}
)";

const char* kFrag = R"(#version 450 core
in vec3 v_normal;
layout(location = 7) uniform uint u_id; // u_normalMatrix takes locations 4 to 6
layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_material;
layout(location = 3) out uint o_id;
void main() {
    vec3 n = normalize(v_normal); // the meshes are closed: their back faces are never seen
    o_albedo = vec4(0.5, 0.5, 0.5, 1.0);
    o_normal = vec4(n * 0.5 + 0.5, 1.0);
    o_material = vec4(0.0, 0.8, 0.0, 0.0);
    o_id = u_id;
}
)";

// The forward mode: the same meshes, their surface changed by the projector's forward path
// (forward.glsl, pasted after the #version line) before it is written, with coverage at location 4.
const char* kForwardVert = R"(#version 450 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 0) uniform mat4 u_modelViewProj;
layout(location = 4) uniform mat3 u_normalMatrix;
layout(location = 8) uniform mat4 u_model; // object -> camera-relative world
out vec3 v_normal;
out vec3 v_position;
void main() {
    gl_Position = u_modelViewProj * vec4(a_position, 1.0);
    v_normal = u_normalMatrix * a_normal;
    v_position = (u_model * vec4(a_position, 1.0)).xyz;
}
)";

const char* kForwardFrag = R"(
in vec3 v_normal;
in vec3 v_position;
layout(location = 7) uniform uint u_id;
layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_material;
layout(location = 3) out uint o_id;
layout(location = 4) out vec4 o_coverage;
void main() {
    SpatterSurface s = SpatterSurface(vec3(0.5), normalize(v_normal), 0.8);
    int decals = spatterApplyForwardDecals(gl_FragCoord.xy, v_position, u_id, s);
    o_albedo = vec4(s.albedo, 1.0);
    o_normal = vec4(s.normal * 0.5 + 0.5, 1.0);
    o_material = vec4(0.0, s.roughness, 0.0, 0.0);
    o_id = u_id;
    o_coverage = vec4(decals > 0 ? 1.0 : 0.0);
}
)";

GLuint compile(GLenum stage, const char* text) {
    const GLuint s = glCreateShader(stage);
    glShaderSource(s, 1, &text, nullptr);
    glCompileShader(s);
    return s;
}

GLuint link(const char* vert, const std::string& frag) {
    const GLuint vs = compile(GL_VERTEX_SHADER, vert), fs = compile(GL_FRAGMENT_SHADER, frag.c_str());
    const GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint linked = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    if (linked) return program;
    glDeleteProgram(program);
    return 0;
}

GLuint texture(GLenum format, int w, int h) {
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, format, w, h);
    return t;
}

struct MeshGpu {
    GLuint vao = 0, buffers[3] = {0, 0, 0};
    GLsizei indices = 0;
    bool receiver = true;
};

} // namespace

struct ForeignHost::Impl {
    int width = 0, height = 0;
    GLuint program = 0, forwardProgram = 0, fbo = 0, forwardFbo = 0, coverageFbo = 0;
    GLuint depth = 0, albedo = 0, normal = 0, material = 0, ids = 0, coverage = 0;
    std::vector<MeshGpu> meshes;

    ~Impl() {
        clearMeshes();
        const GLuint textures[6] = {depth, albedo, normal, material, ids, coverage};
        glDeleteTextures(6, textures);
        const GLuint fbos[3] = {fbo, forwardFbo, coverageFbo};
        glDeleteFramebuffers(3, fbos);
        glDeleteProgram(program);
        glDeleteProgram(forwardProgram);
    }

    void clearMeshes() {
        for (MeshGpu& m : meshes) {
            glDeleteVertexArrays(1, &m.vao);
            glDeleteBuffers(3, m.buffers);
        }
        meshes.clear();
    }
};

ForeignHost::ForeignHost(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ForeignHost::ForeignHost(ForeignHost&&) noexcept = default;
ForeignHost& ForeignHost::operator=(ForeignHost&&) noexcept = default;
ForeignHost::~ForeignHost() = default;

Result<ForeignHost> ForeignHost::create(int width, int height) {
    auto m = std::make_unique<Impl>();
    m->width = width;
    m->height = height;
    m->program = link(kVert, kFrag);
    Result<std::string> forward = DecalProjector::hostShader("forward.glsl");
    if (!forward) return fail(forward.error());
    m->forwardProgram = link(kForwardVert, "#version 450 core\n" + forward.value() + kForwardFrag);
    if (!m->program || !m->forwardProgram) return fail("foreign host: a program does not link");
    m->depth = texture(GL_DEPTH_COMPONENT24, width, height);
    m->albedo = texture(GL_RGBA8, width, height);
    m->normal = texture(GL_RGB10_A2, width, height);
    m->material = texture(GL_RG8, width, height);
    m->ids = texture(GL_R8UI, width, height);
    m->coverage = texture(GL_R8, width, height);
    glCreateFramebuffers(1, &m->fbo);
    glNamedFramebufferTexture(m->fbo, GL_COLOR_ATTACHMENT0, m->albedo, 0);
    glNamedFramebufferTexture(m->fbo, GL_COLOR_ATTACHMENT1, m->normal, 0);
    glNamedFramebufferTexture(m->fbo, GL_COLOR_ATTACHMENT2, m->material, 0);
    glNamedFramebufferTexture(m->fbo, GL_COLOR_ATTACHMENT3, m->ids, 0);
    glNamedFramebufferTexture(m->fbo, GL_DEPTH_ATTACHMENT, m->depth, 0);
    const GLenum buffers[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                               GL_COLOR_ATTACHMENT3};
    glNamedFramebufferDrawBuffers(m->fbo, 4, buffers);
    glCreateFramebuffers(1, &m->forwardFbo);
    const GLuint forwardTargets[5] = {m->albedo, m->normal, m->material, m->ids, m->coverage};
    GLenum forwardBuffers[5];
    for (GLuint i = 0; i < 5; ++i) {
        glNamedFramebufferTexture(m->forwardFbo, GL_COLOR_ATTACHMENT0 + i, forwardTargets[i], 0);
        forwardBuffers[i] = GL_COLOR_ATTACHMENT0 + i;
    }
    glNamedFramebufferDrawBuffers(m->forwardFbo, 5, forwardBuffers);
    glNamedFramebufferTexture(m->forwardFbo, GL_DEPTH_ATTACHMENT, m->depth, 0);
    glCreateFramebuffers(1, &m->coverageFbo);
    glNamedFramebufferTexture(m->coverageFbo, GL_COLOR_ATTACHMENT0, m->coverage, 0);
    if (glCheckNamedFramebufferStatus(m->fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return fail("foreign host: the G-buffer is incomplete");
    return ForeignHost(std::move(m));
}

void ForeignHost::setScene(const Scene& scene) {
    Impl& m = *impl_;
    m.clearMeshes();
    for (const SceneObject& o : scene.objects) {
        MeshGpu g;
        glCreateVertexArrays(1, &g.vao);
        glCreateBuffers(3, g.buffers);
        glNamedBufferStorage(g.buffers[0], GLsizeiptr(o.mesh->positions.size() * sizeof(glm::vec3)),
                             o.mesh->positions.data(), 0);
        glNamedBufferStorage(g.buffers[1], GLsizeiptr(o.mesh->normals.size() * sizeof(glm::vec3)),
                             o.mesh->normals.data(), 0);
        glNamedBufferStorage(g.buffers[2], GLsizeiptr(o.mesh->indices.size() * sizeof(uint32_t)),
                             o.mesh->indices.data(), 0);
        for (GLuint a = 0; a < 2; ++a) {
            glVertexArrayVertexBuffer(g.vao, a, g.buffers[a], 0, sizeof(glm::vec3));
            glVertexArrayAttribFormat(g.vao, a, 3, GL_FLOAT, GL_FALSE, 0);
            glVertexArrayAttribBinding(g.vao, a, a);
            glEnableVertexArrayAttrib(g.vao, a);
        }
        glVertexArrayElementBuffer(g.vao, g.buffers[2]);
        g.indices = GLsizei(o.mesh->indices.size());
        g.receiver = o.receivesDecals;
        m.meshes.push_back(g);
    }
}

glm::dmat4 ForeignHost::projection(const Camera& camera) const {
    return glm::perspective(glm::radians(camera.fovYDeg), double(impl_->width) / double(impl_->height),
                            camera.nearPlane, 1000.0);
}

void ForeignHost::draw(const std::vector<glm::dmat4>& transforms, const std::vector<uint8_t>& ids,
                       const Camera& camera) {
    drawMeshes(impl_->fbo, impl_->program, transforms, ids, camera);
}

Result<ProjectorStats> ForeignHost::drawForward(const std::vector<glm::dmat4>& transforms,
                                                const std::vector<uint8_t>& ids, const Camera& camera,
                                                DecalProjector& projector) {
    Result<ProjectorStats> stats = projector.bin(forwardFrame(camera));
    if (!stats) return stats;
    const ForwardBindings bindings;
    if (Status bound = projector.bindForward(bindings); !bound) return fail(bound.error());
    drawMeshes(impl_->forwardFbo, impl_->forwardProgram, transforms, ids, camera);
    for (const GLuint b : {bindings.decals, bindings.tiles, bindings.items})
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
    glBindTextureUnit(bindings.albedoUnit, 0);
    glBindTextureUnit(bindings.normalUnit, 0);
    return stats;
}

ForwardFrame ForeignHost::forwardFrame(const Camera& camera) const {
    const HostFrame f = frame(camera, false);
    ForwardFrame forward;
    forward.width = f.width;
    forward.height = f.height;
    forward.view = f.view;
    forward.projection = f.projection;
    forward.eye = f.eye;
    forward.clip = ClipDepth::MinusOneToOne;
    return forward;
}

void ForeignHost::drawMeshes(GLuint fbo, GLuint program, const std::vector<glm::dmat4>& transforms,
                             const std::vector<uint8_t>& ids, const Camera& camera) {
    Impl& m = *impl_;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, m.width, m.height);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glFrontFace(GL_CCW);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    const GLfloat zero[4] = {0, 0, 0, 0};
    const GLuint zeroId[4] = {0, 0, 0, 0};
    for (GLint b = 0; b < 3; ++b)
        glClearBufferfv(GL_COLOR, b, zero);
    glClearBufferuiv(GL_COLOR, 3, zeroId);
    if (program == m.forwardProgram) glClearBufferfv(GL_COLOR, 4, zero);
    glClearBufferfv(GL_DEPTH, 0, std::array<GLfloat, 1>{1.0f}.data());
    glUseProgram(program);
    const glm::dmat4 viewProj = projection(camera) * viewRotation(camera);
    for (size_t i = 0; i < m.meshes.size() && i < transforms.size(); ++i) {
        if (!m.meshes[i].receiver) continue;
        glm::dmat4 rel = transforms[i];
        rel[3] -= glm::dvec4(camera.eye, 0.0);
        const glm::mat4 mvp(viewProj * rel);
        const glm::mat3 normal(glm::transpose(glm::inverse(glm::dmat3(transforms[i]))));
        glUniformMatrix4fv(0, 1, GL_FALSE, &mvp[0][0]);
        glUniformMatrix3fv(4, 1, GL_FALSE, &normal[0][0]);
        if (program == m.forwardProgram) glUniformMatrix4fv(8, 1, GL_FALSE, &glm::mat4(rel)[0][0]);
        glUniform1ui(7, i < ids.size() ? ids[i] : 0u);
        glBindVertexArray(m.meshes[i].vao);
        glDrawElements(GL_TRIANGLES, m.meshes[i].indices, GL_UNSIGNED_INT, nullptr);
    }
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

HostFrame ForeignHost::frame(const Camera& camera, bool withIds) const {
    const Impl& m = *impl_;
    HostFrame f;
    f.width = m.width;
    f.height = m.height;
    f.view = viewRotation(camera) * glm::translate(glm::dmat4(1.0), -camera.eye);
    f.projection = projection(camera);
    f.eye = camera.eye;
    f.depth = {m.depth, DepthEncoding::Window, ClipDepth::MinusOneToOne, false};
    f.normals = {m.normal, NormalEncoding::WorldUnorm};
    f.albedoTexture = m.albedo;
    f.roughness = {m.material, 1};
    f.objectIdTexture = withIds ? m.ids : 0;
    return f;
}

void ForeignHost::clearCoverage() {
    const GLfloat zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(impl_->coverageFbo, GL_COLOR, 0, zero);
}

uint32_t ForeignHost::coverageTexture() const {
    return impl_->coverage;
}

uint32_t ForeignHost::albedoTexture() const {
    return impl_->albedo;
}

Image ForeignHost::read(uint32_t texture) const {
    const int w = impl_->width, h = impl_->height;
    std::vector<uint8_t> pixels(size_t(w) * size_t(h) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(texture, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()), pixels.data());
    Image image;
    image.width = w;
    image.height = h;
    image.rgba.resize(pixels.size());
    const size_t row = size_t(w) * 4;
    for (int y = 0; y < h; ++y)
        std::copy_n(&pixels[size_t(h - 1 - y) * row], row, &image.rgba[size_t(y) * row]);
    return image;
}

} // namespace spatter::test
