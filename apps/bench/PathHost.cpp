#include "PathHost.hpp"

#include "GlHelpers.hpp"

#include <epoxy/gl.h>
#include <glm/gtc/matrix_transform.hpp>

#include "BenchSupport.hpp"

#include <array>
#include <cstring>
#include <string>
#include <vector>

namespace spatter::bench {

namespace {

const char* kGeometryVert = R"(#version 450 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 0) uniform mat4 u_modelViewProj;
layout(location = 4) uniform mat4 u_model; // object -> camera-relative world
layout(location = 8) uniform mat3 u_normalMatrix;
out vec3 v_normal;
out vec3 v_position;
void main() {
    gl_Position = u_modelViewProj * vec4(a_position, 1.0);
    v_normal = u_normalMatrix * a_normal;
    v_position = (u_model * vec4(a_position, 1.0)).xyz;
}
)";

const char* kGeometryFrag = R"(#version 450 core
in vec3 v_normal;
layout(location = 11) uniform uint u_id;
layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out uint o_id;
void main() {
    o_albedo = vec4(0.5, 0.5, 0.5, 0.8);
    o_normal = vec4(normalize(v_normal) * 0.5 + 0.5, 1.0);
    o_id = u_id;
}
)";

const char* kShade = R"(
vec3 shade(vec3 albedo, vec3 n, float roughness) {
    vec3 l = normalize(vec3(0.3, 1.0, 0.2));
    return albedo * (0.2 + 0.8 * max(dot(n, l), 0.0)) + vec3(0.04 * (1.0 - roughness));
}
)";

const char* kForwardFrag = R"(
in vec3 v_normal;
in vec3 v_position;
layout(location = 11) uniform uint u_id;
layout(location = 0) out vec4 o_color;
void main() {
    SpatterSurface s = SpatterSurface(vec3(0.5), normalize(v_normal), 0.8);
    spatterApplyForwardDecals(gl_FragCoord.xy, v_position, u_id, s);
    o_color = vec4(shade(s.albedo, s.normal, s.roughness), 1.0);
}
)";

const char* kPlainForwardFrag = R"(
in vec3 v_normal;
layout(location = 0) out vec4 o_color;
void main() {
    o_color = vec4(shade(vec3(0.5), normalize(v_normal), 0.8), 1.0);
}
)";

const char* kFullscreenVert = R"(#version 450 core
void main() {
    gl_Position = vec4((gl_VertexID & 1) != 0 ? 3.0 : -1.0, (gl_VertexID & 2) != 0 ? 3.0 : -1.0, 0.0, 1.0);
}
)";

const char* kLightingFrag = R"(
layout(binding = 0) uniform sampler2D s_albedo;
layout(binding = 1) uniform sampler2D s_normal;
layout(binding = 2) uniform sampler2D s_dbufferAlbedo;
layout(binding = 3) uniform sampler2D s_dbufferNormal;
layout(binding = 4) uniform sampler2D s_dbufferMaterial;
layout(location = 0) out vec4 o_color;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 albedo = texelFetch(s_albedo, p, 0);
    vec3 n = normalize(texelFetch(s_normal, p, 0).xyz * 2.0 - 1.0);
    float roughness = albedo.a;
#ifdef DBUFFER
    albedo.rgb = spatterDBufferAlbedo(s_dbufferAlbedo, p, albedo.rgb);
    n = spatterDBufferNormal(s_dbufferNormal, p, n);
    roughness = spatterDBufferRoughness(s_dbufferMaterial, p, roughness);
#endif
    o_color = vec4(shade(albedo.rgb, n, roughness), 1.0);
}
)";

GLuint framebuffer(const std::vector<GLuint>& colours, GLuint depth) {
    GLuint fbo = 0;
    glCreateFramebuffers(1, &fbo);
    std::vector<GLenum> buffers;
    for (size_t i = 0; i < colours.size(); ++i) {
        glNamedFramebufferTexture(fbo, GLenum(GL_COLOR_ATTACHMENT0 + i), colours[i], 0);
        buffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + i));
    }
    glNamedFramebufferDrawBuffers(fbo, GLsizei(buffers.size()), buffers.data());
    if (depth) glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth, 0);
    return fbo;
}

struct HostMesh {
    GLuint vao = 0, buffers[3] = {0, 0, 0};
    GLsizei indices = 0;
    glm::dmat4 transform{1.0};
    uint32_t id = 0;
};

// GPU time of the commands between begin() and end(), waited for: a GL_TIME_ELAPSED query, or on a
// software rasteriser (llvmpipe, whose queries report a fraction of a pass that follows another
// timed pass) the wall time between two glFinish calls.
class PassTimer {
public:
    PassTimer() {
        glCreateQueries(GL_TIME_ELAPSED, 1, &query_);
        const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        software_ = renderer && (std::strstr(renderer, "llvmpipe") || std::strstr(renderer, "softpipe"));
    }
    ~PassTimer() { glDeleteQueries(1, &query_); }
    PassTimer(const PassTimer&) = delete;
    PassTimer& operator=(const PassTimer&) = delete;
    bool software() const { return software_; }
    void begin() {
        if (software_) {
            glFinish();
            start_ = now();
        } else {
            glBeginQuery(GL_TIME_ELAPSED, query_);
        }
    }
    double end() const {
        if (software_) {
            glFinish();
            return (now() - start_) * 1e3;
        }
        glEndQuery(GL_TIME_ELAPSED);
        GLuint64 ns = 0;
        glGetQueryObjectui64v(query_, GL_QUERY_RESULT, &ns);
        return double(ns) * 1e-6;
    }

private:
    GLuint query_ = 0;
    bool software_ = false;
    double start_ = 0.0;
};

} // namespace

struct PathHost::Impl {
    int width = 0, height = 0;
    GLuint geometry = 0, forward = 0, plainForward = 0, lighting = 0, dbufferLighting = 0;
    GLuint depth = 0, albedo = 0, normal = 0, ids = 0, color = 0;
    GLuint gbufferFbo = 0, colorFbo = 0, emptyVao = 0;
    std::vector<HostMesh> meshes;
    PassTimer timer;

    ~Impl() {
        clearMeshes();
        for (GLuint p : {geometry, forward, plainForward, lighting, dbufferLighting})
            glDeleteProgram(p);
        const GLuint textures[5] = {depth, albedo, normal, ids, color};
        glDeleteTextures(5, textures);
        const GLuint fbos[2] = {gbufferFbo, colorFbo};
        glDeleteFramebuffers(2, fbos);
        glDeleteVertexArrays(1, &emptyVao);
    }

    void clearMeshes() {
        for (HostMesh& m : meshes) {
            glDeleteVertexArrays(1, &m.vao);
            glDeleteBuffers(3, m.buffers);
        }
        meshes.clear();
    }

    glm::dmat4 projection(const Camera& c) const {
        return glm::perspective(glm::radians(c.fovYDeg), double(width) / double(height), c.nearPlane, 1000.0);
    }

    void setState(GLuint fbo) const {
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glViewport(0, 0, width, height);
        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glDisable(GL_FRAMEBUFFER_SRGB);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    }

    // Draws the meshes with `program` into `fbo` (cleared first), depth-tested; returns its GPU time.
    double drawMeshes(GLuint fbo, GLuint program, const Camera& camera) {
        setState(fbo);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        timer.begin();
        const GLfloat zero[4] = {0, 0, 0, 0};
        const GLuint zeroId[4] = {0, 0, 0, 0};
        glClearBufferfv(GL_COLOR, 0, zero);
        if (fbo == gbufferFbo) {
            glClearBufferfv(GL_COLOR, 1, zero);
            glClearBufferuiv(GL_COLOR, 2, zeroId);
        }
        glClearBufferfv(GL_DEPTH, 0, std::array<GLfloat, 1>{1.0f}.data());
        glUseProgram(program);
        const glm::dmat4 viewProj = projection(camera) * viewRotation(camera);
        for (const HostMesh& m : meshes) {
            glm::dmat4 rel = m.transform;
            rel[3] -= glm::dvec4(camera.eye, 0.0);
            const glm::mat4 mvp(viewProj * rel), model(rel);
            const glm::mat3 normalMatrix(glm::transpose(glm::inverse(glm::dmat3(m.transform))));
            glUniformMatrix4fv(0, 1, GL_FALSE, &mvp[0][0]);
            glUniformMatrix4fv(4, 1, GL_FALSE, &model[0][0]);
            glUniformMatrix3fv(8, 1, GL_FALSE, &normalMatrix[0][0]);
            glUniform1ui(11, m.id);
            glBindVertexArray(m.vao);
            glDrawElements(GL_TRIANGLES, m.indices, GL_UNSIGNED_INT, nullptr);
        }
        return timer.end();
    }

    double light(GLuint program, const ProjectorResources& r) {
        setState(colorFbo);
        glDisable(GL_DEPTH_TEST);
        timer.begin();
        const GLuint inputs[5] = {albedo, normal, r.dbufferAlbedo, r.dbufferNormal, r.dbufferMaterial};
        glBindTextures(0, program == dbufferLighting ? 5 : 2, inputs);
        glUseProgram(program);
        glBindVertexArray(emptyVao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        return timer.end();
    }

    // Runs a projector call and sets `ms` to its GPU time: the projector's own timer query (it times
    // its pass with ProjectorSettings::waitForTimers), or on a software rasteriser wall time.
    template <typename Call> Result<ProjectorStats> timed(Call call, double& ms) {
        if (!timer.software()) {
            Result<ProjectorStats> s = call();
            ms = s ? s->gpuMs : 0.0;
            return s;
        }
        timer.begin();
        Result<ProjectorStats> s = call();
        ms = timer.end();
        return s;
    }

    HostFrame frame(const Camera& camera) const {
        HostFrame f;
        f.width = width;
        f.height = height;
        f.view = viewRotation(camera) * glm::translate(glm::dmat4(1.0), -camera.eye);
        f.projection = projection(camera);
        f.eye = camera.eye;
        f.depth = {depth, DepthEncoding::Window, ClipDepth::MinusOneToOne, false};
        f.normals = {normal, NormalEncoding::WorldUnorm};
        f.albedoTexture = albedo;
        f.roughness = {albedo, 3};
        f.objectIdTexture = ids;
        return f;
    }
};

PathHost::PathHost(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
PathHost::PathHost(PathHost&&) noexcept = default;
PathHost& PathHost::operator=(PathHost&&) noexcept = default;
PathHost::~PathHost() = default;

Result<PathHost> PathHost::create(int width, int height) {
    auto m = std::make_unique<Impl>();
    m->width = width;
    m->height = height;
    Result<std::string> forward = DecalProjector::hostShader("forward.glsl");
    Result<std::string> dbuffer = DecalProjector::hostShader("dbuffer.glsl");
    if (!forward) return fail(forward.error());
    if (!dbuffer) return fail(dbuffer.error());
    const std::string head = "#version 450 core\n";
    Result<GLuint> geometry = example::linkProgram(kGeometryVert, kGeometryFrag);
    Result<GLuint> forwardProgram =
        example::linkProgram(kGeometryVert, head + forward.value() + kShade + kForwardFrag);
    Result<GLuint> plainForward = example::linkProgram(kGeometryVert, head + kShade + kPlainForwardFrag);
    Result<GLuint> lighting =
        example::linkProgram(kFullscreenVert, head + dbuffer.value() + kShade + kLightingFrag);
    Result<GLuint> dbufferLighting = example::linkProgram(
        kFullscreenVert, head + "#define DBUFFER 1\n" + dbuffer.value() + kShade + kLightingFrag);
    for (const Result<GLuint>* p : {&geometry, &forwardProgram, &plainForward, &lighting, &dbufferLighting})
        if (!*p) return fail(p->error());
    m->geometry = geometry.value();
    m->forward = forwardProgram.value();
    m->plainForward = plainForward.value();
    m->lighting = lighting.value();
    m->dbufferLighting = dbufferLighting.value();
    m->depth = example::texture(GL_DEPTH_COMPONENT24, width, height);
    m->albedo = example::texture(GL_RGBA8, width, height);
    m->normal = example::texture(GL_RGB10_A2, width, height);
    m->ids = example::texture(GL_R8UI, width, height);
    m->color = example::texture(GL_RGBA8, width, height);
    m->gbufferFbo = framebuffer({m->albedo, m->normal, m->ids}, m->depth);
    m->colorFbo = framebuffer({m->color}, m->depth);
    glCreateVertexArrays(1, &m->emptyVao);
    return PathHost(std::move(m));
}

void PathHost::setScene(const Scene& scene) {
    Impl& m = *impl_;
    m.clearMeshes();
    for (const SceneObject& o : scene.objects) {
        HostMesh g;
        g.vao = example::meshVertexArray(*o.mesh, g.buffers);
        g.indices = GLsizei(o.mesh->indices.size());
        g.transform = o.transform;
        m.meshes.push_back(g);
    }
}

Result<PathTimes> PathHost::frame(HostPath path, DecalProjector& projector, const Camera& camera) {
    Impl& m = *impl_;
    const HostFrame f = m.frame(camera);
    PathTimes t;
    if (path == HostPath::Forward) {
        ForwardFrame ff;
        ff.width = f.width;
        ff.height = f.height;
        ff.view = f.view;
        ff.projection = f.projection;
        ff.eye = f.eye;
        ff.clip = ClipDepth::MinusOneToOne;
        Result<ProjectorStats> s = m.timed([&] { return projector.bin(ff); }, t.projectorMs);
        if (!s) return fail(s.error());
        t.stats = s.value();
        if (Status bound = projector.bindForward(); !bound) return fail(bound.error());
        t.hostPassMs = m.drawMeshes(m.colorFbo, m.forward, camera);
        t.baselineMs = m.drawMeshes(m.colorFbo, m.plainForward, camera);
    } else {
        m.drawMeshes(m.gbufferFbo, m.geometry, camera);
        ProjectorDraw options;
        if (path == HostPath::DBuffer) options.path = ProjectorPath::DBuffer;
        Result<ProjectorStats> s = m.timed([&] { return projector.draw(f, options); }, t.projectorMs);
        if (!s) return fail(s.error());
        t.stats = s.value();
        if (path == HostPath::DBuffer) {
            t.hostPassMs = m.light(m.dbufferLighting, projector.resources());
            t.baselineMs = m.light(m.lighting, projector.resources());
        } else {
            m.light(m.lighting, projector.resources());
        }
    }
    return t;
}

} // namespace spatter::bench
