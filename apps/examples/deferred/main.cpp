// spatter-example-deferred: a small deferred renderer of its own that hosts spatter's decal
// projector, read from top to bottom. It uses spatter's installed headers only: core and placement
// for the scene and its decals, the projector, and spatter's headless GL context and camera.
//
// Its frame is laid out unlike spatter's own renderer:
//   depth     DEPTH_COMPONENT24, standard Z (near 0, far 1), GL's default [-1, 1] clip depth
//   normals   RGB10_A2, world space as n * 0.5 + 0.5
//   albedo    RGBA8, linear base colour, roughness in alpha
//   ids       R8UI, the objects' 8-bit decal IDs
//   coverage  R8, where decals change a pixel (the coverage view)
// A frame: the geometry pass draws the objects that take decals; the projector blends the decals
// into the G-buffer; the objects that take no decals are drawn over them; the lighting pass (or the
// albedo or coverage view) writes the image. Materials are their base colour and roughness factors.

#include "CommandLine.hpp"

#include <spatter/core/Image.hpp>
#include <spatter/render/DecalProjector.hpp>
#include <spatter/render/GlContext.hpp>

#include <epoxy/gl.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace {

const char* kProgram = "spatter-example-deferred";

// ---- Shaders --------------------------------------------------------------------------------------

const char* kGeometryVert = R"(#version 450 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 0) uniform mat4 u_modelViewProj; // the model relative to the eye
layout(location = 4) uniform mat3 u_normalMatrix;  // object to world (locations 4 to 6)
out vec3 v_normal;
void main() {
    gl_Position = u_modelViewProj * vec4(a_position, 1.0);
    v_normal = u_normalMatrix * a_normal;
}
)";

const char* kGeometryFrag = R"(#version 450 core
in vec3 v_normal;
layout(location = 7) uniform vec4 u_material; // linear base colour, roughness
layout(location = 8) uniform uint u_id;
layout(location = 9) uniform bool u_mirrored; // the object's transform flips the winding
layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out uint o_id;
layout(location = 3) out vec4 o_coverage;
void main() {
    vec3 n = normalize(v_normal);
    if (gl_FrontFacing == u_mirrored) n = -n; // two-sided: a back face shows the reversed normal
    o_albedo = u_material;
    o_normal = vec4(n * 0.5 + 0.5, 1.0);
    o_id = u_id;
    o_coverage = vec4(0.0); // an object drawn after the decals hides their coverage
}
)";

const char* kFullscreenVert = R"(#version 450 core
void main() {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

// The lighting pass: one sun and an ambient term (Blinn-Phong, glossier for lower roughness), or a
// view of the albedo or the coverage.
const char* kOutputFrag = R"(#version 450 core
layout(binding = 0) uniform sampler2D s_depth;
layout(binding = 1) uniform sampler2D s_albedo;
layout(binding = 2) uniform sampler2D s_normal;
layout(binding = 3) uniform sampler2D s_coverage;
layout(location = 0) uniform int u_view;            // 0 final, 1 albedo, 2 coverage
layout(location = 1) uniform mat4 u_clipToDirection; // inverse(projection * view rotation)
layout(location = 5) uniform vec3 u_toSun;
layout(location = 0) out vec4 o_color;

vec3 toSrgb(vec3 c) {
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

struct Surface {
    vec3 albedo;
    vec3 normal;
    float roughness;
};

// What the G-buffer holds at `p`, decals included.
Surface surfaceAt(ivec2 p) {
    vec4 a = texelFetch(s_albedo, p, 0);
    return Surface(a.rgb, normalize(texelFetch(s_normal, p, 0).xyz * 2.0 - 1.0), a.a);
}

vec3 shade(Surface s, vec3 toEye) {
    vec3 l = normalize(u_toSun);
    float shininess = 2.0 / max(pow(s.roughness, 4.0), 1e-4) - 2.0;
    float nl = max(dot(s.normal, l), 0.0), nh = max(dot(s.normal, normalize(l + toEye)), 0.0);
    float specular = 0.04 * (shininess + 8.0) / 25.13 * pow(nh, shininess);
    return s.albedo * (0.25 + 0.85 * nl) + vec3(specular * nl);
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec2 ndc = gl_FragCoord.xy / vec2(textureSize(s_depth, 0)) * 2.0 - 1.0;
    vec4 far = u_clipToDirection * vec4(ndc, 1.0, 1.0);
    vec3 toEye = -normalize(far.xyz / far.w);
    bool background = texelFetch(s_depth, p, 0).r == 1.0;
    vec3 c = mix(vec3(0.62, 0.66, 0.7), vec3(0.3, 0.42, 0.6), clamp(-toEye.y, 0.0, 1.0));
    if (u_view == 1) c = texelFetch(s_albedo, p, 0).rgb;
    if (u_view == 2) c = vec3(texelFetch(s_coverage, p, 0).r > 0.5 ? 1.0 : 0.0);
    if (u_view == 0 && !background) c = min(shade(surfaceAt(p), toEye), vec3(1.0));
    o_color = vec4(u_view == 2 ? c : toSrgb(c), 1.0);
}
)";

GLuint compile(GLenum stage, const char* source) {
    const GLuint s = glCreateShader(stage);
    glShaderSource(s, 1, &source, nullptr);
    glCompileShader(s);
    return s;
}

spatter::Result<GLuint> linkProgram(const char* vertex, const char* fragment) {
    const GLuint vs = compile(GL_VERTEX_SHADER, vertex), fs = compile(GL_FRAGMENT_SHADER, fragment);
    const GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    glLinkProgram(p);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint linked = GL_FALSE;
    glGetProgramiv(p, GL_LINK_STATUS, &linked);
    if (linked) return p;
    char log[2048] = "";
    glGetProgramInfoLog(p, sizeof log, nullptr, log);
    return spatter::fail(std::string("a program does not link: ") + log);
}

// ---- The G-buffer ---------------------------------------------------------------------------------

struct GBuffer {
    int width = 0, height = 0;
    GLuint depth = 0, albedo = 0, normal = 0, ids = 0, coverage = 0, output = 0;
    GLuint framebuffer = 0, outputFramebuffer = 0;
};

GLuint texture(GLenum format, int width, int height) {
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, format, width, height);
    return t;
}

spatter::Result<GBuffer> createGBuffer(int width, int height) {
    GBuffer g;
    g.width = width;
    g.height = height;
    g.depth = texture(GL_DEPTH_COMPONENT24, width, height);
    g.albedo = texture(GL_RGBA8, width, height);
    g.normal = texture(GL_RGB10_A2, width, height);
    g.ids = texture(GL_R8UI, width, height);
    g.coverage = texture(GL_R8, width, height);
    g.output = texture(GL_RGBA8, width, height);
    glCreateFramebuffers(1, &g.framebuffer);
    const GLuint targets[4] = {g.albedo, g.normal, g.ids, g.coverage};
    const GLenum buffers[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                               GL_COLOR_ATTACHMENT3};
    for (int k = 0; k < 4; ++k)
        glNamedFramebufferTexture(g.framebuffer, buffers[k], targets[k], 0);
    glNamedFramebufferTexture(g.framebuffer, GL_DEPTH_ATTACHMENT, g.depth, 0);
    glNamedFramebufferDrawBuffers(g.framebuffer, 4, buffers);
    glCreateFramebuffers(1, &g.outputFramebuffer);
    glNamedFramebufferTexture(g.outputFramebuffer, GL_COLOR_ATTACHMENT0, g.output, 0);
    if (glCheckNamedFramebufferStatus(g.framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE ||
        glCheckNamedFramebufferStatus(g.outputFramebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return spatter::fail("the G-buffer is incomplete");
    return g;
}

// ---- The scene on the GPU -------------------------------------------------------------------------

struct DrawRange {
    GLsizei first = 0, count = 0;
    glm::vec4 material{1.0f}; // linear base colour, roughness
};

struct MeshGpu {
    GLuint vertexArray = 0;
    std::vector<DrawRange> ranges;
};

glm::vec4 materialOf(const spatter::Scene& scene, int index) {
    const spatter::Material m = index >= 0 ? scene.materials[size_t(index)] : spatter::Material{};
    return glm::vec4(glm::vec3(m.baseColorFactor), glm::clamp(m.roughness, 0.02f, 1.0f));
}

MeshGpu upload(const spatter::Scene& scene, const spatter::Mesh& mesh) {
    MeshGpu g;
    if (mesh.indices.empty()) return g;
    GLuint buffers[3] = {0, 0, 0};
    glCreateBuffers(3, buffers);
    glNamedBufferStorage(buffers[0], GLsizeiptr(mesh.positions.size() * sizeof(glm::vec3)),
                         mesh.positions.data(), 0);
    glNamedBufferStorage(buffers[1], GLsizeiptr(mesh.normals.size() * sizeof(glm::vec3)), mesh.normals.data(),
                         0);
    glNamedBufferStorage(buffers[2], GLsizeiptr(mesh.indices.size() * sizeof(uint32_t)), mesh.indices.data(),
                         0);
    glCreateVertexArrays(1, &g.vertexArray);
    for (GLuint a = 0; a < 2; ++a) {
        glVertexArrayVertexBuffer(g.vertexArray, a, buffers[a], 0, sizeof(glm::vec3));
        glVertexArrayAttribFormat(g.vertexArray, a, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(g.vertexArray, a, a);
        glEnableVertexArrayAttrib(g.vertexArray, a);
    }
    glVertexArrayElementBuffer(g.vertexArray, buffers[2]);
    if (mesh.submeshes.empty()) g.ranges.push_back({0, GLsizei(mesh.indices.size()), materialOf(scene, -1)});
    for (const spatter::Submesh& s : mesh.submeshes)
        g.ranges.push_back({GLsizei(s.firstIndex), GLsizei(s.indexCount), materialOf(scene, s.material)});
    return g;
}

// ---- The camera -----------------------------------------------------------------------------------

// Standard Z with GL's default clip depth; the far plane well beyond the scene, so that a decal box
// that holds the eye keeps its far faces.
glm::dmat4 projectionFor(const spatter::Camera& camera, const spatter::Scene& scene, double aspect) {
    const spatter::DBounds b = scene.worldBounds();
    double farthest = 0.0;
    for (int k = 0; k < 8 && !b.empty(); ++k) {
        const glm::dvec3 corner((k & 1) ? b.max.x : b.min.x, (k & 2) ? b.max.y : b.min.y,
                                (k & 4) ? b.max.z : b.min.z);
        farthest = std::max(farthest, glm::length(corner - camera.eye));
    }
    const double farPlane = std::max(2.0 * farthest, 2.0 * camera.nearPlane);
    return glm::perspective(glm::radians(camera.fovYDeg), aspect, camera.nearPlane, farPlane);
}

// ---- The passes -----------------------------------------------------------------------------------

struct Frame {
    const spatter::Scene* scene = nullptr;
    std::vector<MeshGpu> meshes;
    std::vector<glm::dmat4> transforms; // object to world, double
    std::vector<uint8_t> ids;           // the objects' decal IDs
    spatter::Camera camera;
    glm::dmat4 projection{1.0};
};

// The scene uploaded, its transforms and decal IDs, and the camera.
Frame frameOf(const example::Inputs& in, double aspect) {
    Frame f;
    f.scene = &in.scene;
    for (const spatter::SceneObject& o : in.scene.objects) {
        f.meshes.push_back(upload(in.scene, o.mesh));
        f.transforms.push_back(o.transform);
    }
    f.ids = in.decals.objectIds;
    f.ids.resize(in.scene.objects.size(), 0);
    f.camera = in.camera;
    f.projection = projectionFor(in.camera, in.scene, aspect);
    return f;
}

// Draws the objects that take decals (`receivers`) or the others into the G-buffer; the first clears it.
void geometryPass(const GBuffer& g, const Frame& f, GLuint program, bool receivers) {
    glBindFramebuffer(GL_FRAMEBUFFER, g.framebuffer);
    glViewport(0, 0, g.width, g.height);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    if (receivers) {
        const GLfloat zero[4] = {0, 0, 0, 0}, far = 1.0f;
        const GLuint noId[4] = {0, 0, 0, 0};
        for (GLint b : {0, 1, 3})
            glClearBufferfv(GL_COLOR, b, zero);
        glClearBufferuiv(GL_COLOR, 2, noId);
        glClearBufferfv(GL_DEPTH, 0, &far);
    }
    glUseProgram(program);
    const glm::dmat4 viewProjection = f.projection * spatter::viewRotation(f.camera);
    for (size_t i = 0; i < f.meshes.size(); ++i) {
        if (f.scene->objects[i].receivesDecals != receivers) continue;
        glm::dmat4 model = f.transforms[i];
        model[3] -= glm::dvec4(f.camera.eye, 0.0); // relative to the eye, in double
        const glm::mat4 mvp(viewProjection * model);
        const glm::mat3 normalMatrix(glm::transpose(glm::inverse(glm::dmat3(f.transforms[i]))));
        glUniformMatrix4fv(0, 1, GL_FALSE, &mvp[0][0]);
        glUniformMatrix3fv(4, 1, GL_FALSE, &normalMatrix[0][0]);
        glUniform1ui(8, f.ids[i]);
        glUniform1i(9, glm::determinant(glm::dmat3(f.transforms[i])) < 0.0 ? 1 : 0);
        glBindVertexArray(f.meshes[i].vertexArray);
        for (const DrawRange& r : f.meshes[i].ranges) {
            glUniform4fv(7, 1, &r.material[0]);
            glDrawElements(GL_TRIANGLES, r.count, GL_UNSIGNED_INT,
                           reinterpret_cast<const void*>(size_t(r.first) * sizeof(uint32_t)));
        }
    }
}

// The G-buffer as the projector's host frame.
spatter::HostFrame hostFrame(const GBuffer& g, const Frame& f) {
    spatter::HostFrame h;
    h.width = g.width;
    h.height = g.height;
    h.view = spatter::viewRotation(f.camera) * glm::translate(glm::dmat4(1.0), -f.camera.eye);
    h.projection = f.projection;
    h.eye = f.camera.eye;
    h.depth = {g.depth, spatter::DepthEncoding::Window, spatter::ClipDepth::MinusOneToOne, false};
    h.normals = {g.normal, spatter::NormalEncoding::WorldUnorm};
    h.albedoTexture = g.albedo;
    h.roughness = {g.albedo, 3};
    h.objectIdTexture = g.ids;
    return h;
}

// The decals, by G-buffer blend: the projector blends their albedo, normals and roughness into the
// G-buffer after the geometry pass and before the lighting (or, for the coverage view, marks the
// pixels they change). Only decals that changed since the last frame are uploaded.
spatter::Result<spatter::ProjectorStats> decalPass(spatter::DecalProjector& projector,
                                                   const std::vector<spatter::Decal>& decals,
                                                   const GBuffer& g, const Frame& f, example::View view) {
    if (spatter::Status s = projector.setObjects(f.transforms, f.ids); !s) return spatter::fail(s.error());
    projector.setDecals(decals);
    spatter::ProjectorDraw draw;
    if (view == example::View::Coverage) draw.coverageTexture = g.coverage;
    return projector.draw(hostFrame(g, f), draw);
}

// Lighting, or the albedo or coverage view, into the output image.
void outputPass(const GBuffer& g, const Frame& f, GLuint program, GLuint emptyVertexArray,
                example::View view) {
    glBindFramebuffer(GL_FRAMEBUFFER, g.outputFramebuffer);
    glViewport(0, 0, g.width, g.height);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(program);
    const GLuint inputs[4] = {g.depth, g.albedo, g.normal, g.coverage};
    glBindTextures(0, 4, inputs);
    const glm::mat4 clipToDirection(glm::inverse(f.projection * spatter::viewRotation(f.camera)));
    glUniform1i(0, int(view));
    glUniformMatrix4fv(1, 1, GL_FALSE, &clipToDirection[0][0]);
    glUniform3f(5, 0.4f, 0.8f, 0.45f);
    glBindVertexArray(emptyVertexArray);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

// The output image, row 0 at the top.
spatter::Image readOutput(const GBuffer& g) {
    spatter::Image image;
    image.width = g.width;
    image.height = g.height;
    const size_t row = size_t(g.width) * 4;
    std::vector<uint8_t> pixels(row * size_t(g.height));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(g.output, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()), pixels.data());
    image.rgba.resize(pixels.size());
    for (int y = 0; y < g.height; ++y)
        std::copy_n(&pixels[size_t(g.height - 1 - y) * row], row, &image.rgba[size_t(y) * row]);
    return image;
}

int usageError(const std::string& message) {
    std::fprintf(stderr, "%s: %s\n(see %s --help)\n", kProgram, message.c_str(), kProgram);
    return 2;
}

int failure(const std::string& message) {
    std::fprintf(stderr, "%s: %s\n", kProgram, message.c_str());
    return 1;
}

} // namespace

int main(int argc, char** argv) {
    // What to draw: spatter-render's command line, scene and decals.
    spatter::Result<example::Options> options = example::parseCommandLine(argc, argv);
    if (!options) return usageError(options.error());
    if (options->help) {
        std::fputs(example::usage(
                       kProgram, "Renders SCENE with its decals in a deferred renderer of its own that hosts "
                                 "spatter's decal\nprojector (G-buffer blend), headless, and writes one "
                                 "view as a PNG.")
                       .c_str(),
                   stdout);
        return 0;
    }
    spatter::Result<example::Inputs> in = example::loadInputs(options.value());
    if (!in) return failure(in.error());
    for (const std::string& warning : in->decals.warnings)
        std::fprintf(stderr, "%s: warning: %s\n", kProgram, warning.c_str());

    // The host: a GL 4.5 context, its G-buffer, programs and meshes.
    spatter::Result<spatter::GlContext> gl = spatter::GlContext::createHeadless();
    if (!gl) return failure(gl.error());
    spatter::Result<GBuffer> gbuffer = createGBuffer(options->width, options->height);
    spatter::Result<GLuint> geometry = linkProgram(kGeometryVert, kGeometryFrag);
    spatter::Result<GLuint> output = linkProgram(kFullscreenVert, kOutputFrag);
    if (!gbuffer || !geometry || !output)
        return failure(!gbuffer ? gbuffer.error() : !geometry ? geometry.error() : output.error());
    GLuint emptyVertexArray = 0;
    glCreateVertexArrays(1, &emptyVertexArray);
    const Frame frame = frameOf(in.value(), double(options->width) / double(options->height));

    // The projector: created once on the host's context and told the decal types.
    spatter::Result<spatter::DecalProjector> projector = spatter::DecalProjector::create();
    if (!projector) return failure(projector.error());
    projector->setDecalTypes(in->decals.types);

    // One frame: geometry, decals, the objects that take none, lighting.
    geometryPass(gbuffer.value(), frame, geometry.value(), true);
    spatter::Result<spatter::ProjectorStats> stats =
        decalPass(projector.value(), in->decals.decals, gbuffer.value(), frame, options->view);
    if (!stats) return failure(stats.error());
    geometryPass(gbuffer.value(), frame, geometry.value(), false);
    outputPass(gbuffer.value(), frame, output.value(), emptyVertexArray, options->view);

    if (spatter::Status s = spatter::writePng(options->out, readOutput(gbuffer.value())); !s)
        return failure(s.error());
    return 0;
}
