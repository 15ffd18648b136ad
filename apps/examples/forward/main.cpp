// spatter-example-forward: a small forward renderer of its own that hosts spatter's decal projector
// through its forward path, read from top to bottom. It uses spatter's installed headers only: core
// and placement for the scene and its decals, the projector, and spatter's headless GL context and
// camera.
//
// It has no G-buffer; its frame is
//   colour  RGBA8, sRGB-encoded by its shader
//   depth   DEPTH_COMPONENT24, standard Z (near 0, far 1), GL's default [-1, 1] clip depth
// A frame: the projector sorts the decals in view into screen tiles on the GPU (bin) and binds them
// for the host's shaders (bindForward); one pass draws the scene, and its fragment shader applies the
// decals of its pixel to the surface it shades (spatter's forward.glsl) before lighting it (or
// writing its albedo, or its coverage: how many decals changed it). Materials are their base colour
// and roughness factors; the objects that take no decals carry an object ID no decal has.

#include "CommandLine.hpp"
#include "GlHelpers.hpp"
#include "SceneGpu.hpp"

#include <spatter/render/DecalProjector.hpp>
#include <spatter/render/GlContext.hpp>

#include <cstdio>
#include <string>

namespace {

const char* kProgram = "spatter-example-forward";

// The forward pass, after the scene's vertex stage (SceneGpu.hpp): it follows spatter's forward.glsl,
// pasted after its #version line. One sun and an ambient term (Blinn-Phong, glossier for lower
// roughness), or a view of the albedo or the coverage.
const char* kForwardFrag = R"(
in vec3 v_normal;
in vec3 v_position; // relative to the eye, world space
layout(location = 11) uniform vec4 u_material; // linear base colour, roughness
layout(location = 12) uniform uint u_decalId;
layout(location = 13) uniform bool u_mirrored;
layout(location = 14) uniform int u_view; // 0 final, 1 albedo, 2 coverage
layout(location = 15) uniform vec3 u_toSun;
layout(location = 0) out vec4 o_color;

vec3 toSrgb(vec3 c) {
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

vec3 shade(SpatterSurface s, vec3 toEye) {
    vec3 l = normalize(u_toSun);
    float shininess = 2.0 / max(pow(s.roughness, 4.0), 1e-4) - 2.0;
    float nl = max(dot(s.normal, l), 0.0), nh = max(dot(s.normal, normalize(l + toEye)), 0.0);
    float specular = 0.04 * (shininess + 8.0) / 25.13 * pow(nh, shininess);
    return s.albedo * (0.25 + 0.85 * nl) + vec3(specular * nl);
}

void main() {
    vec3 n = normalize(v_normal);
    if (gl_FrontFacing == u_mirrored) n = -n; // two-sided: a back face shows the reversed normal
    SpatterSurface s = SpatterSurface(u_material.rgb, n, u_material.a);
    int decals = spatterApplyForwardDecals(gl_FragCoord.xy, v_position, u_decalId, s);
    vec3 c = u_view == 0 ? min(shade(s, -normalize(v_position)), vec3(1.0)) : s.albedo;
    o_color = vec4(u_view == 2 ? vec3(decals > 0 ? 1.0 : 0.0) : toSrgb(c), 1.0);
}
)";

// ---- The frame ------------------------------------------------------------------------------------

struct Target {
    int width = 0, height = 0;
    GLuint colour = 0, depth = 0, framebuffer = 0;
};

spatter::Result<Target> createTarget(int width, int height) {
    Target t;
    t.width = width;
    t.height = height;
    t.colour = example::texture(GL_RGBA8, width, height);
    t.depth = example::texture(GL_DEPTH_COMPONENT24, width, height);
    glCreateFramebuffers(1, &t.framebuffer);
    glNamedFramebufferTexture(t.framebuffer, GL_COLOR_ATTACHMENT0, t.colour, 0);
    glNamedFramebufferTexture(t.framebuffer, GL_DEPTH_ATTACHMENT, t.depth, 0);
    if (glCheckNamedFramebufferStatus(t.framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return spatter::fail("the frame's framebuffer is incomplete");
    return t;
}

// ---- The passes -----------------------------------------------------------------------------------

// The decals: the projector culls them against the camera and sorts those in view into the screen's
// tiles on the GPU, then binds its buffers and decal textures for the forward pass (ForwardBindings'
// defaults: shader storage bindings 5 to 7, texture units 14 and 15). Only decals that changed since
// the last frame are uploaded.
spatter::Result<spatter::ProjectorStats> binDecals(spatter::DecalProjector& projector,
                                                   const example::SceneGpu& scene, const example::Inputs& in,
                                                   const Target& t) {
    if (spatter::Status s = projector.setObjects(scene.transforms, scene.decalIds); !s)
        return spatter::fail(s.error());
    projector.setDecals(in.decals.decals);
    spatter::ForwardFrame f;
    f.width = t.width;
    f.height = t.height;
    f.view = in.view;
    f.projection = in.projection;
    f.eye = in.camera.eye;
    f.clip = spatter::ClipDepth::MinusOneToOne;
    f.reversedZ = false;
    spatter::Result<spatter::ProjectorStats> stats = projector.bin(f);
    if (!stats) return stats;
    if (spatter::Status bound = projector.bindForward(); !bound) return spatter::fail(bound.error());
    return stats;
}

// Clears the frame (to the sky's colour in the final view, black in the others) and draws the scene,
// shaded with its decals.
void forwardPass(const Target& t, const example::SceneGpu& scene, const example::Inputs& in, GLuint program,
                 example::View view) {
    glBindFramebuffer(GL_FRAMEBUFFER, t.framebuffer);
    glViewport(0, 0, t.width, t.height);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    const GLfloat sky[4] = {0.74f, 0.79f, 0.84f, 1.0f}, black[4] = {0, 0, 0, 1}, far = 1.0f;
    glClearBufferfv(GL_COLOR, 0, view == example::View::Final ? sky : black);
    glClearBufferfv(GL_DEPTH, 0, &far);
    glUseProgram(program);
    glUniform1i(14, int(view));
    glUniform3f(15, 0.4f, 0.8f, 0.45f);
    example::drawScene(scene, in);
}

} // namespace

int main(int argc, char** argv) {
    // What to draw: spatter-render's command line, scene and decals.
    spatter::Result<example::Options> options = example::parseCommandLine(argc, argv);
    if (!options) return example::usageError(kProgram, options.error());
    if (options->help) {
        std::fputs(example::usage(kProgram,
                                  "Renders SCENE with its decals in a forward renderer of its own that "
                                  "hosts spatter's decal\nprojector (its forward path), headless, and "
                                  "writes one view as a PNG.")
                       .c_str(),
                   stdout);
        return 0;
    }
    spatter::Result<example::Inputs> in = example::loadInputs(options.value());
    if (!in) return example::failure(kProgram, in.error());
    for (const std::string& warning : in->decals.warnings)
        std::fprintf(stderr, "%s: warning: %s\n", kProgram, warning.c_str());

    // The host: a GL 4.5 context, its frame, its forward program (with spatter's GLSL for the
    // forward path) and the scene.
    spatter::Result<spatter::GlContext> gl = spatter::GlContext::createHeadless();
    if (!gl) return example::failure(kProgram, gl.error());
    spatter::Result<std::string> forwardGlsl = spatter::DecalProjector::hostShader("forward.glsl");
    if (!forwardGlsl) return example::failure(kProgram, forwardGlsl.error());
    spatter::Result<Target> target = createTarget(options->width, options->height);
    spatter::Result<GLuint> forward = example::linkProgram(
        example::kSceneVertex, "#version 450 core\n" + forwardGlsl.value() + kForwardFrag);
    spatter::Result<example::SceneGpu> scene = example::uploadScene(in.value());
    for (const std::string& error : {target.error(), forward.error(), scene.error()})
        if (!error.empty()) return example::failure(kProgram, error);

    // The projector: created once on the host's context and told the decal types. Each of its calls
    // leaves the GL state as it found it; a host whose passes bind what they use turns that off
    // (ProjectorSettings::restoreGlState) and saves the calls' queries.
    spatter::Result<spatter::DecalProjector> projector = spatter::DecalProjector::create();
    if (!projector) return example::failure(kProgram, projector.error());
    projector->setDecalTypes(in->decals.types);

    // One frame: the decals binned, the scene drawn with them.
    spatter::Result<spatter::ProjectorStats> stats =
        binDecals(projector.value(), scene.value(), in.value(), target.value());
    if (!stats) return example::failure(kProgram, stats.error());
    forwardPass(target.value(), scene.value(), in.value(), forward.value(), options->view);

    const spatter::Image image = example::readImage(target->colour, options->width, options->height);
    if (spatter::Status s = spatter::writePng(options->out, image); !s)
        return example::failure(kProgram, s.error());
    return 0;
}
