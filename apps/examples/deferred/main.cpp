// spatter-example-deferred: a small deferred renderer of its own that hosts spatter's decal
// projector, read from top to bottom. It uses spatter's installed headers only: core and placement
// for the scene and its decals, the projector, and spatter's headless GL context and camera.
//
// Its frame is laid out unlike spatter's own renderer:
//   depth     DEPTH_COMPONENT24, standard Z (near 0, far 1), GL's default [-1, 1] clip depth
//   normals   RGB10_A2, world space as n * 0.5 + 0.5
//   albedo    RGBA8, linear base colour, roughness in alpha
//   ids       R8UI, the objects' 8-bit decal IDs (those that take no decals: an ID no decal has)
//   coverage  R8, where decals change a pixel (the coverage view)
// A frame: the geometry pass fills the G-buffer; the decal pass projects the decals; the lighting
// pass (or the albedo or coverage view) writes the image. The decals take one of two paths:
//   G-buffer blend (the default): the projector blends them into the G-buffer's albedo, normals and
//                  roughness before the lighting;
//   DBuffer (--dbuffer): the projector renders them into its own decal buffers, reading the
//                  G-buffer only, and the lighting pass applies them (spatter's dbuffer.glsl).
// Materials are their base colour and roughness factors.

#include "CommandLine.hpp"
#include "GlHelpers.hpp"
#include "SceneGpu.hpp"

#include <spatter/render/DecalProjector.hpp>
#include <spatter/render/GlContext.hpp>

#include <cstdio>
#include <string>

namespace {

const char* kProgram = "spatter-example-deferred";

// ---- Shaders --------------------------------------------------------------------------------------

// The geometry pass, after the scene's vertex stage (SceneGpu.hpp).
const char* kGeometryFrag = R"(#version 450 core
in vec3 v_normal;
layout(location = 11) uniform vec4 u_material; // linear base colour, roughness
layout(location = 12) uniform uint u_decalId;
layout(location = 13) uniform bool u_mirrored;
layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out uint o_id;
void main() {
    vec3 n = normalize(v_normal);
    if (gl_FrontFacing == u_mirrored) n = -n; // two-sided: a back face shows the reversed normal
    o_albedo = u_material;
    o_normal = vec4(n * 0.5 + 0.5, 1.0);
    o_id = u_decalId;
}
)";

const char* kFullscreenVert = R"(#version 450 core
void main() {
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

// The lighting pass: one sun and an ambient term (Blinn-Phong, glossier for lower roughness), or a
// view of the albedo or the coverage. It follows spatter's dbuffer.glsl, pasted after its #version
// line, and applies the decal buffers in DBuffer mode.
const char* kOutputFrag = R"(
layout(binding = 0) uniform sampler2D s_depth;
layout(binding = 1) uniform sampler2D s_albedo;
layout(binding = 2) uniform sampler2D s_normal;
layout(binding = 3) uniform sampler2D s_coverage;
layout(binding = 4) uniform sampler2D s_dbufferAlbedo;
layout(binding = 5) uniform sampler2D s_dbufferNormal;
layout(binding = 6) uniform sampler2D s_dbufferMaterial;
layout(location = 0) uniform int u_view;            // 0 final, 1 albedo, 2 coverage
layout(location = 1) uniform mat4 u_clipToDirection; // inverse(projection * view rotation)
layout(location = 5) uniform vec3 u_toSun;
layout(location = 6) uniform bool u_dbuffer;         // apply the decal buffers
layout(location = 0) out vec4 o_color;

vec3 toSrgb(vec3 c) {
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

struct Surface {
    vec3 albedo;
    vec3 normal;
    float roughness;
};

// What the G-buffer holds at `p`, with the decals: blended in already, or applied here from the
// decal buffers.
Surface surfaceAt(ivec2 p) {
    vec4 a = texelFetch(s_albedo, p, 0);
    Surface s = Surface(a.rgb, normalize(texelFetch(s_normal, p, 0).xyz * 2.0 - 1.0), a.a);
    if (u_dbuffer) {
        s.albedo = spatterDBufferAlbedo(s_dbufferAlbedo, p, s.albedo);
        s.normal = spatterDBufferNormal(s_dbufferNormal, p, s.normal);
        s.roughness = spatterDBufferRoughness(s_dbufferMaterial, p, s.roughness);
    }
    return s;
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
    if (u_view == 1) c = background ? vec3(0.0) : surfaceAt(p).albedo;
    if (u_view == 2) c = vec3(texelFetch(s_coverage, p, 0).r > 0.5 ? 1.0 : 0.0);
    if (u_view == 0 && !background) c = min(shade(surfaceAt(p), toEye), vec3(1.0));
    o_color = vec4(u_view == 2 ? c : toSrgb(c), 1.0);
}
)";

// ---- The G-buffer ---------------------------------------------------------------------------------

struct GBuffer {
    int width = 0, height = 0;
    GLuint depth = 0, albedo = 0, normal = 0, ids = 0, coverage = 0, output = 0;
    GLuint framebuffer = 0, outputFramebuffer = 0;
};

spatter::Result<GBuffer> createGBuffer(int width, int height) {
    GBuffer g;
    g.width = width;
    g.height = height;
    g.depth = example::texture(GL_DEPTH_COMPONENT24, width, height);
    g.albedo = example::texture(GL_RGBA8, width, height);
    g.normal = example::texture(GL_RGB10_A2, width, height);
    g.ids = example::texture(GL_R8UI, width, height);
    g.coverage = example::texture(GL_R8, width, height);
    g.output = example::texture(GL_RGBA8, width, height);
    glCreateFramebuffers(1, &g.framebuffer);
    const GLuint targets[3] = {g.albedo, g.normal, g.ids};
    const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    for (int k = 0; k < 3; ++k)
        glNamedFramebufferTexture(g.framebuffer, buffers[k], targets[k], 0);
    glNamedFramebufferTexture(g.framebuffer, GL_DEPTH_ATTACHMENT, g.depth, 0);
    glNamedFramebufferDrawBuffers(g.framebuffer, 3, buffers);
    glCreateFramebuffers(1, &g.outputFramebuffer);
    glNamedFramebufferTexture(g.outputFramebuffer, GL_COLOR_ATTACHMENT0, g.output, 0);
    if (glCheckNamedFramebufferStatus(g.framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE ||
        glCheckNamedFramebufferStatus(g.outputFramebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return spatter::fail("the G-buffer is incomplete");
    return g;
}

// ---- The passes -----------------------------------------------------------------------------------

// Clears the G-buffer and the coverage and draws the scene into the G-buffer.
void geometryPass(const GBuffer& g, const example::SceneGpu& scene, const example::Inputs& in,
                  GLuint program) {
    glBindFramebuffer(GL_FRAMEBUFFER, g.framebuffer);
    glViewport(0, 0, g.width, g.height);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    const GLfloat zero[4] = {0, 0, 0, 0}, far = 1.0f;
    const GLuint noId[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, zero);
    glClearBufferfv(GL_COLOR, 1, zero);
    glClearBufferuiv(GL_COLOR, 2, noId);
    glClearBufferfv(GL_DEPTH, 0, &far);
    glClearTexImage(g.coverage, 0, GL_RED, GL_FLOAT, zero);
    glUseProgram(program);
    example::drawScene(scene, in);
}

// The G-buffer as the projector's host frame: the DBuffer path reads its depth, normals and IDs only.
spatter::HostFrame hostFrame(const GBuffer& g, const example::Inputs& in, spatter::ProjectorPath path) {
    spatter::HostFrame h;
    h.width = g.width;
    h.height = g.height;
    h.view = in.view;
    h.projection = in.projection;
    h.eye = in.camera.eye;
    h.depth = {g.depth, spatter::DepthEncoding::Window, spatter::ClipDepth::MinusOneToOne, false};
    h.normals = {g.normal, spatter::NormalEncoding::WorldUnorm};
    if (path == spatter::ProjectorPath::GBufferBlend) {
        h.albedoTexture = g.albedo;
        h.roughness = {g.albedo, 3};
    }
    h.objectIdTexture = g.ids;
    return h;
}

// The decals: the projector blends their albedo, normals and roughness into the G-buffer or renders
// them into its decal buffers (or, for the coverage view, marks the pixels they change). Only decals
// that changed since the last frame are uploaded.
spatter::Result<spatter::ProjectorStats> decalPass(spatter::DecalProjector& projector,
                                                   const example::SceneGpu& scene, const example::Inputs& in,
                                                   const GBuffer& g, spatter::ProjectorPath path,
                                                   example::View view) {
    if (spatter::Status s = projector.setObjects(scene.transforms, scene.decalIds); !s)
        return spatter::fail(s.error());
    projector.setDecals(in.decals.decals);
    spatter::ProjectorDraw draw;
    draw.path = path;
    if (view == example::View::Coverage) draw.coverageTexture = g.coverage;
    return projector.draw(hostFrame(g, in, path), draw);
}

// Lighting, or the albedo or coverage view, into the output image; with `decalBuffers`, the DBuffer
// path's buffers applied.
void outputPass(const GBuffer& g, const example::Inputs& in, GLuint program, GLuint emptyVertexArray,
                example::View view, const spatter::ProjectorResources* decalBuffers) {
    glBindFramebuffer(GL_FRAMEBUFFER, g.outputFramebuffer);
    glViewport(0, 0, g.width, g.height);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(program);
    const GLuint inputs[7] = {g.depth,
                              g.albedo,
                              g.normal,
                              g.coverage,
                              decalBuffers ? decalBuffers->dbufferAlbedo : 0,
                              decalBuffers ? decalBuffers->dbufferNormal : 0,
                              decalBuffers ? decalBuffers->dbufferMaterial : 0};
    glBindTextures(0, 7, inputs);
    const glm::mat4 clipToDirection(glm::inverse(in.projection * spatter::viewRotation(in.camera)));
    glUniform1i(0, int(view));
    glUniformMatrix4fv(1, 1, GL_FALSE, &clipToDirection[0][0]);
    glUniform3f(5, 0.4f, 0.8f, 0.45f);
    glUniform1i(6, decalBuffers ? 1 : 0);
    glBindVertexArray(emptyVertexArray);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

} // namespace

int main(int argc, char** argv) {
    // What to draw: spatter-render's command line, scene and decals, and the decals' path.
    const std::vector<example::Switch> own = {
        {"--dbuffer", "the DBuffer path: the decals go into the projector's decal buffers, which\n"
                      "the lighting pass applies (default: blended into the G-buffer)"}};
    spatter::Result<example::Options> options = example::parseCommandLine(argc, argv, own);
    if (!options) return example::usageError(kProgram, options.error());
    if (options->help) {
        std::fputs(
            example::usage(kProgram,
                           "Renders SCENE with its decals in a deferred renderer of its own that hosts "
                           "spatter's decal\nprojector, headless, and writes one view as a PNG.",
                           own)
                .c_str(),
            stdout);
        return 0;
    }
    const spatter::ProjectorPath path = options->switches.count("--dbuffer")
                                            ? spatter::ProjectorPath::DBuffer
                                            : spatter::ProjectorPath::GBufferBlend;
    spatter::Result<example::Inputs> in = example::loadInputs(options.value());
    if (!in) return example::failure(kProgram, in.error());
    for (const std::string& warning : in->decals.warnings)
        std::fprintf(stderr, "%s: warning: %s\n", kProgram, warning.c_str());

    // The host: a GL 4.5 context, its G-buffer, programs and scene. The lighting pass takes
    // spatter's GLSL for the decal buffers.
    spatter::Result<spatter::GlContext> gl = spatter::GlContext::createHeadless();
    if (!gl) return example::failure(kProgram, gl.error());
    spatter::Result<std::string> dbufferGlsl = spatter::DecalProjector::hostShader("dbuffer.glsl");
    if (!dbufferGlsl) return example::failure(kProgram, dbufferGlsl.error());
    spatter::Result<GBuffer> gbuffer = createGBuffer(options->width, options->height);
    spatter::Result<GLuint> geometry = example::linkProgram(example::kSceneVertex, kGeometryFrag);
    spatter::Result<GLuint> output =
        example::linkProgram(kFullscreenVert, "#version 450 core\n" + dbufferGlsl.value() + kOutputFrag);
    spatter::Result<example::SceneGpu> scene = example::uploadScene(in.value());
    for (const std::string& error : {gbuffer.error(), geometry.error(), output.error(), scene.error()})
        if (!error.empty()) return example::failure(kProgram, error);
    GLuint emptyVertexArray = 0;
    glCreateVertexArrays(1, &emptyVertexArray);

    // The projector: created once on the host's context and told the decal types. Each of its calls
    // leaves the GL state as it found it; a host whose passes bind what they use turns that off
    // (ProjectorSettings::restoreGlState) and saves the calls' queries.
    spatter::Result<spatter::DecalProjector> projector = spatter::DecalProjector::create();
    if (!projector) return example::failure(kProgram, projector.error());
    projector->setDecalTypes(in->decals.types);

    // One frame: geometry, decals, lighting.
    geometryPass(gbuffer.value(), scene.value(), in.value(), geometry.value());
    spatter::Result<spatter::ProjectorStats> stats =
        decalPass(projector.value(), scene.value(), in.value(), gbuffer.value(), path, options->view);
    if (!stats) return example::failure(kProgram, stats.error());
    const spatter::ProjectorResources decalBuffers = projector->resources();
    outputPass(gbuffer.value(), in.value(), output.value(), emptyVertexArray, options->view,
               path == spatter::ProjectorPath::DBuffer ? &decalBuffers : nullptr);

    const spatter::Image image = example::readImage(gbuffer->output, options->width, options->height);
    if (spatter::Status s = spatter::writePng(options->out, image); !s)
        return example::failure(kProgram, s.error());
    return 0;
}
