// Depth reconstruction: planes at 0.1 m to 10 km from the eye are drawn into a 32-bit float depth
// buffer with the renderer's reversed-Z projection (Camera.hpp: projection, viewRotation,
// pixelDirection), and every pixel's camera-relative position is rebuilt from that depth on the GPU by
// the renderer's own worldPositionFromDepth (shaders/common.glsl, embedded at build time). The
// relative error |rebuilt - true| / distance must stay at most 1e-5. The same is done with a
// standard-Z projection (depth 0 at the near plane, 1 at a far plane of 20 km) for comparison, and
// both are also emulated on the CPU in float (projection, perspective divide, float32 or 24-bit
// storage, the shader's reconstruction).

#include "StressCase.hpp"
#include "StressSupport.hpp"

#include "RendererShaders.hpp"
#include "ShaderProgram.hpp"
#include "spatter/render/Camera.hpp"

#include <epoxy/gl.h>

#include <cmath>
#include <cstring>
#include <memory>

namespace spatter::stress {

namespace {

constexpr double kFarStandard = 2e4; // far plane of the standard-Z comparison
constexpr double kMinDistance = 0.1, kMaxDistance = 1e4;

// The renderer's per-frame block (std140), as shaders/common.glsl declares it.
struct FrameBlock {
    glm::mat4 viewProj;
    glm::mat4 view;
    glm::mat4 invView;
    glm::vec4 projection; // P[0][0], P[1][1], A, B: depth = (A z + B) / -z
    glm::vec4 viewport;
    glm::vec4 lightDirection;
    glm::vec4 lightColor;
    glm::vec4 skyAmbient;
    glm::vec4 groundAmbient;
    glm::vec4 depthRange;
};
static_assert(sizeof(FrameBlock) == 3 * 64 + 7 * 16, "std140 layout of FrameBlock");

// depth = (A z + B) / -z with depth 0 at the near plane and 1 at the far plane.
glm::dmat4 standardProjection(const Camera& c, double aspect, double farPlane) {
    glm::dmat4 p = projection(c, aspect);
    const double n = c.nearPlane, f = farPlane;
    p[2][2] = -f / (f - n);
    p[3][2] = -n * f / (f - n);
    return p;
}

// A plane: a point on it and its unit normal (camera-relative world space).
struct Plane {
    glm::dvec3 point, normal;
};

// Largest relative errors by decade of distance, [0.1, 1), [1, 10), ..., [1e3, 1e4].
struct ErrorBands {
    double band[5] = {0, 0, 0, 0, 0};
    size_t count[5] = {0, 0, 0, 0, 0};
    size_t samples = 0;

    void add(double distance, double err) {
        if (distance < kMinDistance || distance > kMaxDistance) return;
        const int b = std::min(4, std::max(0, int(std::floor(std::log10(distance))) + 1));
        band[b] = worse(band[b], err);
        count[b]++;
        samples++;
    }
    double worst() const {
        double w = 0.0;
        for (double b : band)
            w = worse(w, b);
        return w;
    }
};

GLuint compile(GLenum stage, const std::string& source, std::string& log) {
    const GLuint s = glCreateShader(stage);
    const char* text = source.c_str();
    glShaderSource(s, 1, &text, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char buf[4096];
        glGetShaderInfoLog(s, sizeof buf, nullptr, buf);
        log += buf;
        glDeleteShader(s);
        return 0;
    }
    return s;
}

GLuint link(const std::string& vert, const std::string& frag, std::string& log) {
    using namespace render_detail;
    const Result<std::string> common = expandShader(shaderLibrary(kRendererShaders), "common.glsl", {});
    if (!common) {
        log += common.error();
        return 0;
    }
    const std::string header = common.value() + "\n";
    const GLuint vs = compile(GL_VERTEX_SHADER, header + vert, log);
    const GLuint fs = compile(GL_FRAGMENT_SHADER, header + frag, log);
    if (!vs || !fs) {
        glDeleteShader(vs);
        glDeleteShader(fs);
        return 0;
    }
    const GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    glLinkProgram(p);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char buf[4096];
        glGetProgramInfoLog(p, sizeof buf, nullptr, buf);
        log += buf;
        glDeleteProgram(p);
        return 0;
    }
    return p;
}

const char* kPlaneVert = R"glsl(
layout(location = 0) in vec3 a_position; // camera-relative world space
void main() { gl_Position = u_viewProj * vec4(a_position, 1.0); }
)glsl";
const char* kPlaneFrag = R"glsl(
void main() {}
)glsl";
const char* kFullscreenVert = R"glsl(
void main() {
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    gl_Position = vec4(p, 0.0, 1.0);
}
)glsl";
const char* kRebuildFrag = R"glsl(
layout(binding = 0) uniform sampler2D s_stressDepth;
layout(location = 0) out vec4 o_position;
void main() {
    float depth = texelFetch(s_stressDepth, ivec2(gl_FragCoord.xy), 0).r;
    o_position = vec4(worldPositionFromDepth(gl_FragCoord.xy, depth), depth);
}
)glsl";

// GL objects of the probe; everything is deleted on destruction.
class DepthProbe {
public:
    DepthProbe(int width, int height) : width_(width), height_(height) {}
    ~DepthProbe() {
        glDeleteProgram(planeProgram_);
        glDeleteProgram(rebuildProgram_);
        glDeleteFramebuffers(1, &depthFbo_);
        glDeleteFramebuffers(1, &outFbo_);
        glDeleteTextures(1, &depth_);
        glDeleteTextures(1, &out_);
        glDeleteBuffers(1, &ubo_);
        glDeleteBuffers(1, &vbo_);
        glDeleteVertexArrays(1, &vao_);
    }

    bool init(std::string& log) {
        planeProgram_ = link(kPlaneVert, kPlaneFrag, log);
        rebuildProgram_ = link(kFullscreenVert, kRebuildFrag, log);
        if (!planeProgram_ || !rebuildProgram_) return false;
        glCreateTextures(GL_TEXTURE_2D, 1, &depth_);
        glTextureStorage2D(depth_, 1, GL_DEPTH_COMPONENT32F, width_, height_);
        glTextureParameteri(depth_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(depth_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glCreateTextures(GL_TEXTURE_2D, 1, &out_);
        glTextureStorage2D(out_, 1, GL_RGBA32F, width_, height_);
        glCreateFramebuffers(1, &depthFbo_);
        glNamedFramebufferTexture(depthFbo_, GL_DEPTH_ATTACHMENT, depth_, 0);
        glNamedFramebufferDrawBuffer(depthFbo_, GL_NONE);
        glCreateFramebuffers(1, &outFbo_);
        glNamedFramebufferTexture(outFbo_, GL_COLOR_ATTACHMENT0, out_, 0);
        glNamedFramebufferDrawBuffer(outFbo_, GL_COLOR_ATTACHMENT0);
        glNamedFramebufferReadBuffer(outFbo_, GL_COLOR_ATTACHMENT0);
        if (glCheckNamedFramebufferStatus(depthFbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE ||
            glCheckNamedFramebufferStatus(outFbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            log += "depth probe framebuffers are incomplete";
            return false;
        }
        glCreateBuffers(1, &ubo_);
        glNamedBufferStorage(ubo_, sizeof(FrameBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
        glCreateBuffers(1, &vbo_);
        glNamedBufferStorage(vbo_, 6 * sizeof(glm::vec3), nullptr, GL_DYNAMIC_STORAGE_BIT);
        glCreateVertexArrays(1, &vao_);
        glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, sizeof(glm::vec3));
        glEnableVertexArrayAttrib(vao_, 0);
        glVertexArrayAttribFormat(vao_, 0, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(vao_, 0, 0);
        return true;
    }

    // Draws the quad (two triangles, camera-relative) with `block` and `reversed` depth, rebuilds every
    // pixel's position and returns width x height RGBA floats (xyz position, w depth), row 0 at the bottom.
    std::vector<float> run(const FrameBlock& block, const glm::vec3 quad[6], bool reversed) {
        glNamedBufferSubData(ubo_, 0, sizeof(FrameBlock), &block);
        glNamedBufferSubData(vbo_, 0, 6 * sizeof(glm::vec3), quad);
        glBindBufferBase(GL_UNIFORM_BUFFER, 0, ubo_);
        glViewport(0, 0, width_, height_);
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_STENCIL_TEST);
        glDisable(GL_FRAMEBUFFER_SRGB);

        glBindFramebuffer(GL_FRAMEBUFFER, depthFbo_);
        glEnable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
        glDepthFunc(reversed ? GL_GREATER : GL_LESS);
        glClearBufferfv(GL_DEPTH, 0, reversed ? &kZero : &kOne);
        glUseProgram(planeProgram_);
        glBindVertexArray(vao_);
        glDrawArrays(GL_TRIANGLES, 0, 6);

        glBindFramebuffer(GL_FRAMEBUFFER, outFbo_);
        glDisable(GL_DEPTH_TEST);
        glDepthMask(GL_FALSE);
        const float clear[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glClearBufferfv(GL_COLOR, 0, clear);
        glUseProgram(rebuildProgram_);
        glBindTextureUnit(0, depth_);
        glDrawArrays(GL_TRIANGLES, 0, 3);

        std::vector<float> pixels(size_t(width_) * size_t(height_) * 4);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, outFbo_);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, pixels.data());
        glBindVertexArray(0);
        glUseProgram(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glBindTextureUnit(0, 0);
        return pixels;
    }

private:
    static constexpr float kZero = 0.0f, kOne = 1.0f;
    int width_, height_;
    GLuint planeProgram_ = 0, rebuildProgram_ = 0, depth_ = 0, out_ = 0, depthFbo_ = 0, outFbo_ = 0;
    GLuint ubo_ = 0, vbo_ = 0, vao_ = 0;
};

FrameBlock frameBlock(const glm::dmat4& proj, const glm::dmat4& view, int width, int height) {
    FrameBlock f{};
    f.viewProj = glm::mat4(proj * view);
    f.view = glm::mat4(view);
    f.invView = glm::mat4(glm::transpose(view));
    f.projection = glm::vec4(float(proj[0][0]), float(proj[1][1]), float(proj[2][2]), float(proj[3][2]));
    f.viewport = glm::vec4(float(width), float(height), 1.0f / float(width), 1.0f / float(height));
    return f;
}

// The CPU emulation of one pixel: the true point through the float view-projection, the float
// perspective divide, storage (float32 or 24-bit unorm), and the shader's float reconstruction.
glm::dvec3 emulate(const FrameBlock& f, const glm::dvec3& truePoint, int i, int jBottom, bool unorm24) {
    const glm::vec4 clip = f.viewProj * glm::vec4(glm::vec3(truePoint), 1.0f);
    float depth = clip.z / clip.w;
    if (unorm24) {
        const double levels = 16777215.0;
        depth = float(std::round(std::clamp(double(depth), 0.0, 1.0) * levels) / levels);
    }
    const glm::vec2 frag(float(i) + 0.5f, float(jBottom) + 0.5f);
    const glm::vec2 ndc = frag * glm::vec2(f.viewport.z, f.viewport.w) * 2.0f - 1.0f;
    const float z = -f.projection.w / (depth + f.projection.z);
    const glm::vec3 viewPos(ndc.x * -z / f.projection.x, ndc.y * -z / f.projection.y, z);
    return glm::dvec3(glm::mat3(f.invView) * viewPos);
}

// The planes drawn at distance d along the view axis: facing the eye, and turned 60 degrees about
// the camera's right axis.
std::vector<Plane> planesAt(const CameraBasis& b, double d) {
    const glm::dvec3 p = -b.back * d;
    const double a = 60.0 * kPi / 180.0;
    return {{p, b.back}, {p, glm::normalize(b.back * std::cos(a) + b.up * std::sin(a))}};
}

// A quad on `plane` big enough to cover the view at its distance.
void quadOn(const Plane& plane, const CameraBasis& b, double d, glm::vec3 out[6]) {
    glm::dvec3 u = glm::cross(plane.normal, b.up);
    if (glm::length(u) < 1e-6) u = glm::cross(plane.normal, b.right);
    u = glm::normalize(u);
    const glm::dvec3 v = glm::cross(plane.normal, u);
    const double s = 4.0 * d;
    const glm::dvec3 c[4] = {plane.point - u * s - v * s, plane.point + u * s - v * s,
                             plane.point + u * s + v * s, plane.point - u * s + v * s};
    const int order[6] = {0, 1, 2, 0, 2, 3};
    for (int k = 0; k < 6; ++k)
        out[k] = glm::vec3(c[order[k]]);
}

void bandRows(StressResult& r, const std::string& what, const ErrorBands& e, bool informational) {
    const char* names[5] = {"0.1..1 m", "1..10 m", "10..100 m", "100 m..1 km", "1..10 km"};
    for (int k = 0; k < 5; ++k) {
        StressRow& row = r.row(what + ", " + names[k], e.band[k], 1e-5, e.count[k]);
        row.informational = informational;
    }
}

} // namespace

StressResult runDepth(const StressConfig& cfg) {
    StressResult r;
    r.technique = "reversed-Z (depth 1 at the near plane, 0 at infinity) in a 32-bit float buffer: float's "
                  "exponent follows 1/distance, so the relative error is about float epsilon at every "
                  "distance; reconstruction -B / (depth + A) in the shader";
    const int width = cfg.full ? 256 : 64, height = cfg.full ? 192 : 48;
    Camera cam;
    cam.eye = glm::dvec3(0.0);
    cam.target = glm::dvec3(0.3, -0.2, -1.0);
    const double aspect = double(width) / double(height);
    const CameraBasis basis = cameraBasis(cam);
    const glm::dmat4 view = viewRotation(cam);
    const FrameBlock reversedBlock = frameBlock(projection(cam, aspect), view, width, height);
    const FrameBlock standardBlock =
        frameBlock(standardProjection(cam, aspect, kFarStandard), view, width, height);

    std::unique_ptr<DepthProbe> probe;
    if (cfg.gl) {
        probe = std::make_unique<DepthProbe>(width, height);
        std::string log;
        if (!probe->init(log)) {
            r.failure("GPU depth probe: " + log);
            probe.reset();
            r.row("GPU depth probe builds", INFINITY, 0.0, 0);
        }
    }

    // [0]: planes facing the eye, whose depth is the same at every pixel, so that only the depth
    // format and the reconstruction count; [1]: planes at 60 degrees, where the rasterizer's
    // subpixel snapping of the vertices adds its own error (the drawn plane moves, whatever the format).
    ErrorBands gpuReversed[2], gpuStandard[2], cpuReversed, cpuStandard, cpuStandard24;
    size_t gpuMissing = 0;
    const int steps = cfg.full ? 100 : 25;
    for (int s = 0; s <= steps; ++s) {
        const double d = kMinDistance * std::pow(kMaxDistance / kMinDistance, double(s) / steps);
        const std::vector<Plane> planes = planesAt(basis, d);
        for (size_t kind = 0; kind < planes.size(); ++kind) {
            const Plane& plane = planes[kind];
            glm::vec3 quad[6];
            quadOn(plane, basis, d, quad);
            std::vector<float> rev, standard;
            if (probe) {
                rev = probe->run(reversedBlock, quad, true);
                standard = probe->run(standardBlock, quad, false);
            }
            for (int jb = 0; jb < height; ++jb) {
                for (int i = 0; i < width; ++i) {
                    const glm::dvec3 dir = pixelDirection(cam, width, height, i, height - 1 - jb);
                    const double denom = glm::dot(dir, plane.normal);
                    if (!(std::fabs(denom) > 1e-9)) continue;
                    const double t = glm::dot(plane.point, plane.normal) / denom;
                    if (!(t > 0.0)) continue;
                    const glm::dvec3 truth = dir * t;
                    const double distance = glm::length(truth);
                    // Pixels near the quad's rim or outside it are not part of the plane's image.
                    const glm::dvec3 local = truth - plane.point;
                    if (glm::length(local) > 3.5 * d) continue;
                    cpuReversed.add(distance,
                                    glm::length(emulate(reversedBlock, truth, i, jb, false) - truth) /
                                        distance);
                    if (distance < kFarStandard) {
                        cpuStandard.add(distance,
                                        glm::length(emulate(standardBlock, truth, i, jb, false) - truth) /
                                            distance);
                        cpuStandard24.add(distance,
                                          glm::length(emulate(standardBlock, truth, i, jb, true) - truth) /
                                              distance);
                    }
                    if (!probe || distance < kMinDistance || distance > kMaxDistance) continue;
                    const size_t px = (size_t(jb) * size_t(width) + size_t(i)) * 4;
                    if (!(rev[px + 3] > 0.0f)) {
                        gpuMissing++;
                        r.failure("GPU reversed-Z: no depth at pixel " + std::to_string(i) + "," +
                                  std::to_string(jb) + " for a plane at " + num(d));
                        continue;
                    }
                    const glm::dvec3 gpu(rev[px], rev[px + 1], rev[px + 2]);
                    const double err = glm::length(gpu - truth) / distance;
                    gpuReversed[kind].add(distance, err);
                    if (kind == 0 && !(err <= 1e-5))
                        r.failure("GPU reversed-Z at " + num(distance) + " m: relative error " + num(err));
                    if (standard[px + 3] < 1.0f)
                        gpuStandard[kind].add(distance, glm::length(glm::dvec3(standard[px], standard[px + 1],
                                                                               standard[px + 2]) -
                                                                    truth) /
                                                            distance);
                }
            }
        }
    }
    if (probe) {
        r.row("GPU, reversed-Z float32, planes facing the eye: |rebuilt - true| / distance, 0.1 m..10 km",
              gpuReversed[0].worst(), 1e-5, gpuReversed[0].samples, cfg.gl->info().renderer);
        r.row("GPU, reversed-Z: plane pixels without depth (count)", double(gpuMissing), 0.0,
              gpuReversed[0].samples + gpuReversed[1].samples);
        bandRows(r, "GPU, reversed-Z float32, facing", gpuReversed[0], false);
        bandRows(r, "GPU, standard-Z float32 (far 20 km), facing", gpuStandard[0], true);
        r.row("GPU, reversed-Z float32, planes at 60 deg (with the rasterizer's subpixel snapping)",
              gpuReversed[1].worst(), 1e-5, gpuReversed[1].samples)
            .informational = true;
        r.row("GPU, standard-Z float32, planes at 60 deg (with the rasterizer's subpixel snapping)",
              gpuStandard[1].worst(), 1e-5, gpuStandard[1].samples)
            .informational = true;
    } else if (r.rows.empty()) {
        StressRow& row = r.row("GPU depth probe: no OpenGL context", 0.0, 0.0, 0, cfg.glError);
        row.informational = true;
    }
    r.row("CPU float emulation, reversed-Z float32, both planes", cpuReversed.worst(), 1e-5,
          cpuReversed.samples);
    bandRows(r, "CPU, standard-Z float32 (far 20 km)", cpuStandard, true);
    bandRows(r, "CPU, standard-Z 24-bit unorm (far 20 km)", cpuStandard24, true);
    return r;
}

} // namespace spatter::stress
