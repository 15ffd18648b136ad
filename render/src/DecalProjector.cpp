#include "spatter/render/DecalProjector.hpp"

#include "ComputeResolve.hpp"
#include "DecalBatch.hpp"
#include "DecalBuffers.hpp"
#include "DecalTextureArray.hpp"
#include "DepthPyramid.hpp"
#include "ForwardBins.hpp"
#include "GlObjects.hpp"
#include "GlStateGuard.hpp"
#include "GpuCulling.hpp"
#include "GpuLayouts.hpp"
#include "GpuTimers.hpp"
#include "HostFrameCheck.hpp"
#include "NormalCopy.hpp"
#include "NormalMatrix.hpp"
#include "ProjectorBuffers.hpp"
#include "ProjectorLayouts.hpp"
#include "ProjectorShaders.hpp"
#include "ProjectorVariants.hpp"
#include "ShaderProgram.hpp"
#include "StageTimers.hpp"
#include "SurfaceProbe.hpp"

#include "spatter/core/Scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <map>

namespace spatter {

using namespace render_detail;

namespace {

// The smallest power of two at or above `v` (1 for 0): the screen tiles' runs are sized so.
uint64_t nextPowerOfTwo(uint64_t v) {
    uint64_t p = 1;
    while (p < v)
        p *= 2;
    return p;
}

std::string join(const std::vector<std::string>& parts) {
    std::string s;
    for (const std::string& p : parts)
        s += (s.empty() ? "" : " ") + p;
    return s;
}

// Whether the context's renderer is Mesa's software rasteriser.
bool softwareRasteriser() {
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    return renderer && (std::strstr(renderer, "llvmpipe") || std::strstr(renderer, "softpipe"));
}

// The context's shader storage bindings against the projector's (GlStateGuard::kStorageBindings: its
// buffers use bindings 0-10; OpenGL 4.5 promises 8).
Status checkStorageBindings(const ContextLimits& limits) {
    const GLint bindings = limits.storageBindings;
    if (bindings >= GlStateGuard::kStorageBindings) return {};
    return fail(
        "projector: the context has " + std::to_string(bindings) +
        " shader storage buffer bindings (GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS); the projector needs " +
        std::to_string(GlStateGuard::kStorageBindings));
}

Status validateSettings(const ProjectorSettings& s) {
    if (!std::isfinite(s.wrapMaxAngleDeg) || s.wrapMaxAngleDeg < 0.0f || s.wrapMaxAngleDeg > 180.0f)
        return fail("projector: wrapMaxAngleDeg must be in [0, 180]");
    if (!std::isfinite(s.fadeStart) || s.fadeStart < 0.0f || s.fadeStart >= 1.0f)
        return fail("projector: fadeStart must be in [0, 1)");
    const int t = s.forwardTileSize;
    if (t < 8 || t > 64 || (t & (t - 1)) != 0)
        return fail("projector: forwardTileSize must be a power of two in [8, 64], not " + std::to_string(t));
    if (s.forwardTileCapacity < 16 || s.forwardTileCapacity > 4096)
        return fail("projector: forwardTileCapacity must be in [16, 4096], not " +
                    std::to_string(s.forwardTileCapacity));
    if (s.normalFrame != DecalNormalFrame::DecalAxes && s.normalFrame != DecalNormalFrame::DepthDerivatives)
        return fail("projector: normalFrame " + std::to_string(int(s.normalFrame)) +
                    " names no DecalNormalFrame");
    if (s.deferredResolve != DeferredResolve::Auto && s.deferredResolve != DeferredResolve::Boxes &&
        s.deferredResolve != DeferredResolve::Compute)
        return fail("projector: deferredResolve " + std::to_string(int(s.deferredResolve)) +
                    " names no DeferredResolve");
    return {};
}

// Whether the draw blends into the host's G-buffer (not coverage, not the DBuffer).
bool blendsIntoHost(const ProjectorDraw& o) {
    return o.path == ProjectorPath::GBufferBlend && o.coverageTexture == 0;
}

// Whether the draw fills the projector's decal buffers.
bool fillsDBuffer(const ProjectorDraw& o) {
    return o.path == ProjectorPath::DBuffer && o.coverageTexture == 0;
}

// Whether the frame keeps roughness in an alpha channel: a pass of its own after the blend.
bool roughnessInAlpha(const HostFrame& f, const ProjectorDraw& o) {
    return f.roughness.texture != 0 && f.roughness.channel == 3 && blendsIntoHost(o);
}

// The programs of a draw: the main pass, the roughness pass into an alpha channel (0: none), and
// whether the main pass writes the host's normals.
struct Passes {
    GLuint main = 0, roughness = 0;
    bool writesNormals = false;
};

// The instanced draw of the visible boxes, in draw order, by their far faces (they cover a box's pixels
// also where the eye is inside it or the near plane cuts it, and culling on the CPU and on the GPU then
// draw the very same fragments). The count is known on the CPU, or read by the GPU from `indirect`
// (GpuCulling).
// The unit cube drawn per decal: corner i has x from bit 0, y from bit 1 and z from bit 2
// (decal.vert), triangles wound counter-clockwise seen from outside. Indexed, so that each box runs
// the vertex shader for its eight corners rather than for 36 vertices.
constexpr uint16_t kCubeIndices[36] = {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4,
                                       2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6};

struct BoxDraws {
    size_t count = 0;
    GLuint indirect = 0;
};

BoxDraws cpuDraws(const DecalVisibility& vis) {
    return {vis.visible.size(), 0};
}

// The camera of a frame relative to its eye, and what culling needs of it.
struct FrameCamera {
    glm::dmat4 view; // camera-relative world -> view
    glm::dmat4 viewProj;
    CullView cull;
};

FrameCamera frameCamera(const HostFrame& f) {
    FrameCamera c;
    c.view = f.view * glm::translate(glm::dmat4(1.0), f.eye);
    c.viewProj = f.projection * c.view;
    c.cull.viewProj = c.viewProj;
    c.cull.eye = f.eye;
    c.cull.reversedZ = f.depth.encoding == DepthEncoding::Window ? f.depth.reversedZ : false;
    c.cull.clipMinusOne = f.depth.clip == ClipDepth::MinusOneToOne;
    if (f.depth.encoding == DepthEncoding::LinearView) { // which way the projection runs decides
        const glm::dmat4 inv = glm::inverse(f.projection);
        const glm::dvec4 a = inv * glm::dvec4(0.0, 0.0, 0.25, 1.0), b = inv * glm::dvec4(0.0, 0.0, 0.5, 1.0);
        c.cull.reversedZ = b.z / b.w > a.z / a.w;
    }
    // The near plane's corners in view space (view space is the camera-relative world, rotated).
    const glm::dmat4 invProj = glm::inverse(f.projection);
    const double nearZ = c.cull.reversedZ ? 1.0 : (c.cull.clipMinusOne ? -1.0 : 0.0);
    for (int i = 0; i < 4; ++i) {
        const glm::dvec4 p = invProj * glm::dvec4((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, nearZ, 1.0);
        c.cull.nearRadius = std::max(c.cull.nearRadius, glm::length(glm::dvec3(p) / p.w));
    }
    return c;
}

} // namespace

struct DecalProjector::Impl {
    ProjectorSettings settings;
    ContextLimits limits; // bindForward's checks
    DecalBatch batch;
    DecalTextureArray textures;
    std::map<uint32_t, GlProgram> programs;
    std::vector<glm::dmat4> transforms;
    std::vector<uint8_t> ids;

    ProjectorBuffers buffers;
    GlVertexArray boxVao; // no attributes; the cube's indices (kCubeIndices)
    GlBuffer cubeIndices;
    GlFramebuffer fbo;
    GlTexture zeroIds;     // bound as s_ids when the frame has no ID texture
    GlSampler nearest;     // for the host's textures, whatever their own filters (an integer texture
                           // with a mipmap filter is incomplete and reads 0)
    NormalCopy normalCopy; // the host's normals as they were before the draw
    DecalBuffers dbuffer;
    ForwardBins forward;
    GpuCulling culling;
    DepthPyramid pyramid;
    ComputeResolve resolve;
    SurfaceProbe surfaceProbe;
    bool computeOnAuto = false; // DeferredResolve::Auto resolves in compute: not a software rasteriser
    int boxesSinceLeftOut = 0;  // draws Auto drew as boxes since a binning left decals out
    int drawsWithoutCopy = 0;   // draws and bins in a row that took no copy of the host's normals
    int drawsSinceProbe = 15;   // draws since occlusion culling last ran (the first draw tries it)
    size_t gpuCullingFrom = 0;  // settings.gpuCullingFrom, or its default for this context
    size_t gpuCullingInViewFrom = std::numeric_limits<size_t>::max(); // or its setting
    bool culledOnGpu = false; // the latest draw or bin culled on the GPU
    size_t cpuInView = 0;     // decals in view at the latest culling on the CPU
    GpuTimers timers;
    StageTimers stages; // with settings.stageTimers
    uint64_t draws = 0;

    Result<GLuint> program(uint32_t bits) {
        auto it = programs.find(bits);
        if (it != programs.end()) return it->second.get();
        Result<GlProgram> p = buildProgram(
            shaderLibrary(kProjectorShaders),
            {{GL_VERTEX_SHADER, "decal.vert"}, {GL_FRAGMENT_SHADER, "decal.frag"}}, variantDefines(bits));
        if (!p) return fail("projector: " + p.error());
        const GLuint name = p->get();
        programs.emplace(bits, std::move(p.value()));
        return name;
    }

    uint32_t variantBits(const HostFrame& f, const ProjectorDraw& o, uint32_t flags) const {
        uint32_t bits = conventionBits(f);
        const bool normals = f.normals.texture != 0;
        if (f.objectIdTexture != 0 && o.idClipping) bits |= kVariantIds;
        if (!o.angleReject) bits |= kVariantNoAngle;
        if ((flags & kDecalWrap) && normals) bits |= kVariantWrap;
        if (o.coverageTexture != 0) return bits | kVariantCoverage;
        if (o.path == ProjectorPath::DBuffer) bits |= kVariantDBuffer;
        if ((flags & kDecalNormalMap) && normals) {
            bits |= kVariantNormalMap;
            if (settings.normalFrame == DecalNormalFrame::DepthDerivatives) bits |= kVariantDepthFrame;
        }
        if (flags & (kDecalFadeLinear | kDecalFadeSmooth)) bits |= kVariantFade;
        return bits;
    }

    // Sends changed decal records and the visible list culled on the CPU; returns the bytes sent.
    size_t uploadDecals(const DecalVisibility& vis, size_t& uploads) {
        return buffers.uploadRecords(batch, uploads, culling.groupBounds()) +
               buffers.uploadVisible(vis.visible);
    }

    // Takes the copy of the host's normals that the decals read (NormalCopy.hpp); returns the draws
    // made.
    size_t copyNormals(const HostFrame& f, const DecalVisibility& vis, const BoxDraws& boxes,
                       NormalCopyMode mode, bool depthTest) {
        normalCopy.allocate(f.normals.texture);
        drawsWithoutCopy = -1; // endPass counts this draw
        if (mode == NormalCopyMode::Viewport) {
            normalCopy.copyViewport(f);
            return 0;
        }
        if (mode == NormalCopyMode::Rects) {
            normalCopy.copyRects(f, vis);
            return 0;
        }
        const GLuint fb = fbo.get();
        glNamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0, normalCopy.texture(), 0);
        glNamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT1, 0, 0);
        glNamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT2, 0, 0);
        glNamedFramebufferDrawBuffer(fb, GL_COLOR_ATTACHMENT0);
        glDisablei(GL_BLEND, 0);
        glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        return drawBoxes(f, boxes, normalCopy.program(), depthTest);
    }

    // Binds the projector's framebuffer with the host's depth attached where the depth test can use
    // it; returns whether it is.
    bool attachDepth(const HostFrame& f) {
        const GLuint fb = fbo.get();
        const bool depthTest =
            f.depth.encoding == DepthEncoding::Window && formatFacts(textureFormat(f.depth.texture)).depth;
        glNamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, depthTest ? f.depth.texture : 0, 0);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fb);
        return depthTest;
    }

    // Attaches the colour targets of the draw (the host's, or the decal buffers) and sets the blend
    // state of each; `writesNormals`: the host's normal texture is one of them.
    void bindTargets(const HostFrame& f, const ProjectorDraw& o, bool writesNormals) {
        if (fillsDBuffer(o))
            dbuffer.attach(fbo.get());
        else
            bindHostTargets(f, o, writesNormals);
    }

    void bindHostTargets(const HostFrame& f, const ProjectorDraw& o, bool writesNormals) {
        const GLuint fb = fbo.get();
        const bool coverage = o.coverageTexture != 0;
        const GLuint normals = writesNormals ? f.normals.texture : 0;
        const GLuint roughness = coverage || roughnessInAlpha(f, o) ? 0 : f.roughness.texture;
        glNamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0, coverage ? o.coverageTexture : f.albedoTexture,
                                  0);
        glNamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT1, normals, 0);
        glNamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT2, roughness, 0);
        const GLenum drawBuffers[3] = {GL_COLOR_ATTACHMENT0, GLenum(normals ? GL_COLOR_ATTACHMENT1 : GL_NONE),
                                       GLenum(roughness ? GL_COLOR_ATTACHMENT2 : GL_NONE)};
        glNamedFramebufferDrawBuffers(fb, 3, drawBuffers);
        for (GLuint i = 0; i < GLuint(GlStateGuard::kDrawBuffers); ++i) {
            glBlendEquationi(i, GL_FUNC_ADD);
            glBlendFunci(i, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
            if (coverage)
                glDisablei(GL_BLEND, i);
            else
                glEnablei(GL_BLEND, i);
        }
        if (coverage) {
            glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        } else {
            glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE); // albedo; the host's alpha stays
            const GLboolean third =
                f.normals.encoding == NormalEncoding::OctahedralWorld ? GL_FALSE : GL_TRUE;
            glColorMaski(1, GL_TRUE, GL_TRUE, third, GL_FALSE);
            const int c = f.roughness.channel;
            glColorMaski(2, c == 0, c == 1, c == 2, GL_FALSE);
        }
    }

    // The host's textures, the decal textures and buffers; normals from the host's texture (until a
    // copy replaces them on unit 1).
    void bindInputs(const HostFrame& f) {
        glBindTextureUnit(0, f.depth.texture);
        glBindTextureUnit(1, f.normals.texture);
        glBindTextureUnit(2, f.objectIdTexture != 0 ? f.objectIdTexture : zeroIds.get());
        glBindTextureUnit(3, textures.albedoTexture());
        glBindTextureUnit(4, textures.normalTexture());
        for (GLuint unit = 0; unit < 3; ++unit)
            glBindSampler(unit, nearest.get());
        glBindSampler(3, 0);
        glBindSampler(4, 0);
        buffers.bind();
    }

    // Roughness in an alpha channel: the decals again, into that texture alone, with dual-source
    // blending (a = roughness * w + a * (1 - w), w the decal's alpha), the other channels kept.
    void bindRoughnessTarget(const HostFrame& f) {
        const GLuint fb = fbo.get();
        glNamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0, f.roughness.texture, 0);
        glNamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT1, 0, 0);
        glNamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT2, 0, 0);
        glNamedFramebufferDrawBuffer(fb, GL_COLOR_ATTACHMENT0);
        glEnablei(GL_BLEND, 0);
        glBlendEquationi(0, GL_FUNC_ADD);
        glBlendFuncSeparatei(0, GL_ZERO, GL_ONE, GL_ONE, GL_ONE_MINUS_SRC1_ALPHA);
        glColorMaski(0, GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
    }

    // Whether this frame's visible list is built on the GPU: from gpuCullingFrom decals on (from the
    // first such frame on the CPU copy of the records is let go), and below that while many are in
    // view (gpuCullingInViewFrom, by the latest count of either culling; back below half of it).
    bool cullsOnGpu() {
        bool onGpu = batch.size() > 0 && (batch.size() >= gpuCullingFrom || !batch.mirrored());
        if (onGpu) batch.setMirrorLimit(gpuCullingFrom);
        if (!onGpu && batch.size() > 0) {
            const size_t inView =
                culledOnGpu ? size_t(culling.visibleCount(false)) + culling.occludedCount() : cpuInView;
            onGpu = culledOnGpu ? inView * 2 >= gpuCullingInViewFrom : inView >= gpuCullingInViewFrom;
        }
        culledOnGpu = onGpu;
        return onGpu;
    }

    DecalVisibility cullOnCpu(const CullView& cull) {
        DecalVisibility vis = batch.cull(transforms, cull);
        cpuInView = vis.visible.size();
        buffers.orderLeftBehind();
        batch.takeOrderChanges();
        return vis;
    }

    // The counts of a draw or bin known before the GPU runs.
    ProjectorStats cpuStats(const DecalVisibility& vis, bool onGpu) const {
        ProjectorStats stats;
        stats.decals = batch.size();
        stats.invalid = onGpu ? batch.invalidCount() : vis.invalid;
        stats.hostDrawn = vis.hostDrawn;
        stats.culled = vis.culled;
        stats.drawn = vis.visible.size();
        stats.inside = vis.inside;
        stats.gpuCulled = onGpu;
        stats.skipped = onGpu ? stats.invalid == stats.decals : stats.drawn == 0;
        return stats;
    }

    // Whether this draw tests the boxes against a depth pyramid (occlusionCulling): while the latest
    // culling the GPU has finished hid at least 256 boxes and one in 20 of those in the frustum (the
    // pyramid costs about what 500 small boxes cost), and otherwise once every 16 draws and on the
    // first draw after setDecals, to notice when it would.
    bool occlusionPays() {
        if (!settings.occlusionCulling) return false;
        const size_t hidden = culling.occludedCount(), inFrustum = hidden + buffers.visibleCount();
        if ((hidden >= 256 && hidden * 20 >= inFrustum) || ++drawsSinceProbe >= 16) {
            drawsSinceProbe = 0;
            return true;
        }
        return false;
    }

    // Builds the visible list on the GPU and sets the counts of `stats` from it (this run's when
    // `wait`, else the latest the GPU has finished); returns the indirect draw. With a host frame
    // (draw()) the boxes hidden behind its depth are culled too where that pays. Needs
    // culling.prepare() and, with a host frame, pyramid.prepare().
    BoxDraws cullOnGpu(const CullView& cull, const HostFrame* host, bool wait, ProjectorStats& stats) {
        const Occlusion occlusion =
            host && occlusionPays() ? pyramid.build(*host, nearest.get()) : Occlusion{};
        buffers.bind();
        culling.run({batch.size(), cull.reversedZ, cull.clipMinusOne, !batch.typesPlain()}, occlusion,
                    buffers.visible(), buffers.visibleCapacity());
        buffers.bind(); // the visible list may have grown
        takeGpuCounts(wait, stats);
        return {0, culling.draws()};
    }

    // The counts of the GPU culling (visibleCount) in `stats`.
    void takeGpuCounts(bool wait, ProjectorStats& stats) {
        stats.drawn = culling.visibleCount(wait);
        stats.invalid = culling.invalidCount();
        stats.hostDrawn = culling.hostDrawnCount();
        stats.groupsTested = culling.testedGroupCount();
        const size_t counted = stats.invalid + stats.hostDrawn + stats.drawn;
        stats.culled =
            batch.size() > counted ? batch.size() - counted : 0; // counts of an earlier draw may exceed
        buffers.setVisibleCount(stats.drawn);
    }

    // Bins the visible decals into the screen tiles of `frame` (ForwardBins): those the GPU culls, or
    // `vis` culled on the CPU. Adds the bytes sent and the calls made to `stats`. Needs
    // forward.prepare() and, on the GPU, culling.prepare(). Returns whether the tiles' runs are short
    // (ForwardBins::shortRuns; only those of a GPU binning, whose runs are sized by the fullest tile).
    // `shownOnly`: the GPU bins each decal by the part of its box that can show (ForwardBins::binCulled).
    bool binVisible(const ForwardFrame& frame, const FrameCamera& camera, bool onGpu,
                    const DecalVisibility& vis, ProjectorStats& stats, bool shownOnly) {
        ForwardGridGpu head{};
        head.info.y = settings.normalFrame == DecalNormalFrame::DepthDerivatives ? 1 : 0;
        head.params.x = settings.fadeStart;
        if (onGpu) {
            stats.bytesUploaded +=
                buffers.uploadRecords(batch, stats.instanceUploads, culling.groupBounds()) +
                buffers.uploadDrawOrder(batch, culling);
            cullOnGpu(camera.cull, nullptr, false, stats); // waitForTimers: read after the pass
            // Before the GPU has given any count, the binning waits for this one's here (once: the
            // first binning's buffers are sized by it, not guessed), as waitForTimers does.
            if (!culling.hasCounted() || (settings.waitForTimers && stats.drawn == 0))
                takeGpuCounts(true, stats);
            markStage(PassStage::Culled);
            // Room for twice the decals in the frustum of the latest count the GPU has given (the
            // binning tests no occlusion, which a draw of boxes in between may have): a sudden jump
            // past it leaves decals out for a frame.
            const size_t inFrustum = stats.drawn + culling.occludedCount();
            const size_t capacity = std::min(batch.size(), std::max<size_t>(4096, 2 * inFrustum));
            const uint32_t run = tileRun();
            stats.bytesUploaded +=
                forward.binCulled(frame, settings.forwardTileSize, head, culling.draws(), capacity, run,
                                  uint32_t(settings.forwardTileCapacity), shownOnly);
            markStage(PassStage::Binned);
            stats.drawCalls += 5;
            return ForwardBins::shortRuns(run);
        }
        stats.bytesUploaded += uploadDecals(vis, stats.instanceUploads);
        markStage(PassStage::Culled);
        buffers.bind();
        stats.bytesUploaded += forward.bin(frame, vis, settings.forwardTileSize, head);
        markStage(PassStage::Binned);
        stats.drawCalls += stats.skipped ? 0 : 4;
        return false;
    }

    // The length of the screen tiles' runs when the GPU culls: twice the most decals of one tile in the
    // latest binning the GPU has finished (16 before it has said), a power of two from 16, at most
    // forwardTileCapacity. A tile with more, up to forwardTileCapacity, gets a run over every decal
    // binned (exact, slower for that tile), and the next binning's runs are long enough. The runs take
    // 4 bytes a tile each: 8.4 MB at 1080p with 16-pixel tiles and 256, 0.5 MB with 16.
    uint32_t tileRun() {
        const uint64_t fullest = forward.fullestTile(false).value_or(16);
        return uint32_t(
            std::clamp<uint64_t>(nextPowerOfTwo(2 * fullest), 16, uint64_t(settings.forwardTileCapacity)));
    }

    // The decals in view when the GPU culls, as DeferredResolve::Auto weighs them: the GPU's latest
    // count; before its first, the CPU's where it culled before, and at least kComputeResolveFrom. A
    // world culled on the GPU from its first draw holds gpuCullingFrom decals or more, where the
    // compute resolve is the likelier choice and costs a few hundredths of a millisecond more where it
    // is not; the boxes would make the copy of the normals, which a later compute resolve leaves
    // unused.
    size_t gpuInView() {
        const size_t counted = culling.visibleCount(false);
        if (culling.hasCounted()) return counted;
        return std::max(cpuInView, ProjectorSettings::kComputeResolveFrom);
    }

    // The visible list (culled on the GPU, or `vis`), the normal copy the decals read when they write
    // normals, then the boxes, and the roughness pass.
    void drawDecals(const HostFrame& f, const ProjectorDraw& o, const FrameCamera& camera, bool onGpu,
                    const DecalVisibility& vis, const Passes& passes, ProjectorStats& stats) {
        stats.bytesUploaded = buffers.uploadRecords(batch, stats.instanceUploads, culling.groupBounds());
        BoxDraws boxes = cpuDraws(vis);
        if (onGpu) {
            stats.bytesUploaded += buffers.uploadDrawOrder(batch, culling);
            boxes = cullOnGpu(camera.cull, &f, false, stats); // waitForTimers: read after the pass
            culling.readBack(); // before the boxes, so that its mark waits on the culling alone
        } else {
            stats.bytesUploaded += buffers.uploadVisible(vis.visible);
        }
        markStage(PassStage::Culled);
        const bool inPlace = !(vis.flags & kDecalWrap) && passes.roughness == 0;
        const NormalCopyMode copy = !passes.writesNormals ? NormalCopyMode::None
                                    : onGpu               ? normalCopyMode(culling.visibleCount(false))
                                                          : normalCopyMode(vis, f.width, f.height, inPlace);
        stats.normalCopy = normalCopyName(copy);
        const bool depthTest = attachDepth(f);
        bindInputs(f);
        // The boxes read the host's depth while it is attached for their depth test (and, in place,
        // the normals they write): a feedback loop, in which the host's last writes to them show only
        // after a texture barrier (without one, llvmpipe's boxes read depth that craters had just
        // written as it stood before, or not, by the timing of its flushes).
        if (depthTest || copy == NormalCopyMode::InPlace) glTextureBarrier();
        if (copy != NormalCopyMode::None && copy != NormalCopyMode::InPlace) {
            stats.drawCalls += copyNormals(f, vis, boxes, copy, depthTest);
            glBindTextureUnit(1, normalCopy.texture());
        }
        bindTargets(f, o, passes.writesNormals);
        stats.drawCalls += drawBoxes(f, boxes, passes.main, depthTest);
        if (passes.roughness != 0) {
            bindRoughnessTarget(f);
            stats.drawCalls += drawBoxes(f, boxes, passes.roughness, depthTest);
        }
    }

    // The targets when draw() resolves `o` into `f` by ComputeResolve rather than by boxes, with
    // `inView` decals in view (culled on the GPU: the latest count it has given); nothing for boxes.
    // Auto draws boxes for 16 draws after a binning that left decals out of a tile past
    // forwardTileCapacity, then tries the tiles again. Decals left out for want of room in the buffers
    // (a sudden jump in the decals in view) change nothing: the next binning has room for the count.
    std::optional<ComputeResolve::Targets> computeTargets(const HostFrame& f, const ProjectorDraw& o,
                                                          size_t inView) {
        const DeferredResolve mode = settings.deferredResolve;
        if (mode == DeferredResolve::Boxes) return std::nullopt;
        if (mode == DeferredResolve::Auto) {
            if (!computeOnAuto || inView < ProjectorSettings::kComputeResolveFrom) return std::nullopt;
            if (forward.tileOverflowed(false) && boxesSinceLeftOut < 16) {
                ++boxesSinceLeftOut;
                return std::nullopt;
            }
            boxesSinceLeftOut = 0;
        }
        return ComputeResolve::targets(f, o, dbuffer);
    }

    // The G-buffer blend or DBuffer by one compute pass (ComputeResolve) over the visible decals binned into
    // the tiles of `f`, whose targets are `targets`, with the variant `bits`' conventions and features.
    Result<ProjectorStats> resolveInCompute(const HostFrame& f, const ComputeResolve::Targets& targets,
                                            const FrameCamera& camera, bool onGpu, const DecalVisibility& vis,
                                            uint32_t bits, ProjectorStats stats) {
        if (Status s = forward.prepare(); !s) return fail(s.error());
        if (onGpu)
            if (Status s = culling.prepare(); !s) return fail(s.error());
        constexpr uint32_t kResolveBits =
            kVariantIds | kVariantNormalMap | kVariantDBuffer | kVariantClipMinusOne | kVariantStandardZ |
            kVariantNormalWorldSigned | kVariantNormalWorldUnorm | kVariantNormalViewUnorm;
        const std::vector<std::string> defines = variantDefines(bits & kResolveBits);
        stats.variant = join(defines) + (defines.empty() ? "" : " ") + "COMPUTE";
        GlStateGuard guard(settings.restoreGlState);
        beginPass(f, camera);
        const bool shortRuns = binVisible(forwardFrame(f), camera, onGpu, vis, stats, true);
        bindInputs(f);
        forward.bind(ForwardBindings{});
        // Runs sized for a fullest tile of a few decals: most pixels of a tile lie in none of them.
        std::vector<std::string> resolveDefines = defines;
        if (shortRuns) resolveDefines.push_back("SPARSE_TILES");
        const Status resolved = resolve.run(f, targets, resolveDefines);
        ++stats.drawCalls;
        endPass(onGpu, stats);
        if (!resolved) return fail(resolved.error());
        return stats;
    }

    // The start of a draw's or a bin's GPU work: its timer, and the frame's block and objects sent.
    void beginPass(const HostFrame& f, const FrameCamera& camera) {
        if (settings.passTimer) {
            timers.beginFrame(draws);
            timers.begin(GpuPass::Decals);
        }
        if (settings.stageTimers) stages.beginFrame(draws);
        buffers.uploadFrame(f, camera.view, camera.viewProj, settings.fadeStart, transforms, ids, batch);
    }

    // Marks the end of a stage of the pass (ProjectorSettings::stageTimers).
    void markStage(PassStage stage) {
        if (settings.stageTimers) stages.mark(stage);
    }

    // The end of it: the GPU time (and, with waitForTimers, this draw's counts when `gpuCounts`: it
    // culled on the GPU) in `stats`.
    void endPass(bool gpuCounts, ProjectorStats& stats) {
        markStage(PassStage::Drawn);
        culling.readBack(); // the counts the next draws size and choose by
        forward.readBack();
        if (settings.passTimer) timers.end();
        if (settings.stageTimers) stats.stages = stages.endFrame(settings.waitForTimers);
        // This draw's counts once the pass is queued: waiting between the culling and the boxes would
        // leave the GPU idle inside the pass.
        if (gpuCounts && settings.waitForTimers) takeGpuCounts(true, stats);
        stats.tilesLeftOut = forward.leftOut(settings.waitForTimers);
        const GpuPassTimes times =
            settings.passTimer ? timers.endFrame(settings.waitForTimers) : GpuPassTimes{};
        stats.gpuMs = times.decalsMs;
        stats.gpuFrame = times.frame;
        ++draws;
        constexpr int kIdle = ProjectorMemory::kNormalCopyIdleDraws;
        if (drawsWithoutCopy < kIdle && ++drawsWithoutCopy == kIdle) normalCopy.release();
    }

    // The pass itself: one instanced draw of the boxes (BoxDraws). Returns the draws made.
    size_t drawBoxes(const HostFrame& f, const BoxDraws& boxes, GLuint prog, bool depthTest) {
        GlStateGuard::neutralise();
        glViewport(f.x, f.y, f.width, f.height);
        glClipControl(GL_LOWER_LEFT,
                      f.depth.clip == ClipDepth::ZeroToOne ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_STENCIL_TEST);
        glDepthMask(GL_FALSE);
        glFrontFace(GL_CCW);
        glEnable(GL_FRAMEBUFFER_SRGB);
        glEnable(GL_CULL_FACE);
        glCullFace(GL_FRONT);
        // Far faces not in front of the scene (where the whole box is in front of it, no surface lies
        // inside), clamped rather than clipped at the far plane.
        if (depthTest) {
            glEnable(GL_DEPTH_TEST);
            glDepthFunc(f.depth.reversedZ ? GL_LEQUAL : GL_GEQUAL);
        } else {
            glDisable(GL_DEPTH_TEST);
        }
        glEnable(GL_DEPTH_CLAMP);
        glUseProgram(prog);
        glBindVertexArray(boxVao.get());
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, boxes.indirect);
        if (boxes.indirect)
            glDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_SHORT, nullptr);
        else
            glDrawElementsInstanced(GL_TRIANGLES, 36, GL_UNSIGNED_SHORT, nullptr, GLsizei(boxes.count));
        return 1;
    }
};

DecalProjector::DecalProjector(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
DecalProjector::DecalProjector(DecalProjector&&) noexcept = default;
DecalProjector& DecalProjector::operator=(DecalProjector&&) noexcept = default;
DecalProjector::~DecalProjector() = default;

Result<DecalProjector> DecalProjector::create(const ProjectorSettings& settings) {
    if (Status s = validateSettings(settings); !s) return fail(s.error());
    const ContextLimits limits = contextLimits();
    if (Status s = checkStorageBindings(limits); !s) return fail(s.error());
    GlStateGuard guard(settings.restoreGlState);
    auto impl = std::make_unique<Impl>();
    impl->settings = settings;
    impl->limits = limits;
    impl->computeOnAuto = !softwareRasteriser();
    impl->gpuCullingFrom =
        settings.gpuCullingFrom.value_or(softwareRasteriser() ? ProjectorSettings::kGpuCullingFromSoftware
                                                              : ProjectorSettings::kGpuCullingFrom);
    impl->gpuCullingInViewFrom = settings.gpuCullingInViewFrom.value_or(
        softwareRasteriser() ? std::numeric_limits<size_t>::max() : ProjectorSettings::kGpuCullingInViewFrom);
    if (Status s = impl->textures.create(settings.decalTextureSize); !s)
        return fail("projector: " + s.error());
    impl->batch.configure(settings.wrapMaxAngleDeg, impl->textures.cutouts());
    impl->buffers.create();
    impl->boxVao = createVertexArray();
    impl->cubeIndices = createBuffer();
    glNamedBufferStorage(impl->cubeIndices.get(), sizeof kCubeIndices, kCubeIndices, 0);
    glVertexArrayElementBuffer(impl->boxVao.get(), impl->cubeIndices.get());
    impl->fbo = createFramebuffer();
    impl->nearest = createSampler();
    glSamplerParameteri(impl->nearest.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(impl->nearest.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(impl->nearest.get(), GL_TEXTURE_COMPARE_MODE, GL_NONE);
    impl->zeroIds = createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(impl->zeroIds.get(), 1, GL_R8UI, 1, 1);
    const uint8_t zero = 0;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(impl->zeroIds.get(), 0, 0, 0, 1, 1, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &zero);
    if (settings.passTimer) impl->timers.create();
    if (settings.stageTimers) impl->stages.create();
    return DecalProjector(std::move(impl));
}

void DecalProjector::setDecalTypes(const std::vector<DecalType>& types) {
    impl_->batch.setTypes(types);
    impl_->buffers.typesChanged();
}

void DecalProjector::setDecals(const std::vector<Decal>& decals) {
    impl_->batch.setDecals(decals);
    impl_->drawsSinceProbe = 15; // a new set of decals: the next draw tries occlusion culling
}

void DecalProjector::updateDecals(const std::vector<Decal>& decals, const DecalChanges& changes) {
    impl_->batch.applyChanges(decals, changes);
}

void DecalProjector::setHostDrawn(std::vector<uint8_t> types, std::vector<uint8_t> objects) {
    impl_->batch.setHostDrawn(std::move(types), std::move(objects));
    impl_->buffers.typesChanged();
}

Status DecalProjector::setObjects(const std::vector<glm::dmat4>& transforms,
                                  const std::vector<uint8_t>& ids) {
    if (transforms.size() != ids.size())
        return fail("projector: " + std::to_string(transforms.size()) + " transforms but " +
                    std::to_string(ids.size()) + " object IDs");
    if (transforms.size() > kMaxProjectorObjects)
        return fail("projector: " + std::to_string(transforms.size()) + " objects (" +
                    std::to_string(kMaxProjectorObjects) + " at most)");
    for (size_t i = 0; i < transforms.size(); ++i)
        if (const std::string p = transformProblem(transforms[i]); !p.empty())
            return fail("projector: object " + std::to_string(i) + ": " + p);
    impl_->transforms = transforms;
    impl_->ids = ids;
    impl_->batch.setObjectCount(transforms.size());
    return {};
}

Result<int> DecalProjector::addDecalTexture(const Image& albedo, const Image& normalMap) {
    GlStateGuard guard(impl_->settings.restoreGlState);
    Result<int> layer = impl_->textures.add(albedo, normalMap);
    if (layer) {
        impl_->batch.configure(impl_->settings.wrapMaxAngleDeg, impl_->textures.cutouts());
        impl_->buffers.typesChanged();
    }
    return layer;
}

Result<int> DecalProjector::addDecalTextureFile(const std::string& albedoPath,
                                                const std::string& normalMapPath) {
    Result<Image> albedo = loadImage(albedoPath);
    if (!albedo) return fail(albedo.error());
    Image normal;
    if (!normalMapPath.empty()) {
        Result<Image> n = loadImage(normalMapPath);
        if (!n) return fail(n.error());
        normal = std::move(n.value());
    }
    return addDecalTexture(albedo.value(), normal);
}

int DecalProjector::decalTextureLayers() const {
    return impl_->textures.layers();
}

std::vector<glm::vec4> DecalProjector::decalTextureCutouts() const {
    return impl_->textures.cutouts();
}

std::string DecalProjector::frameProblem(const HostFrame& frame, const ProjectorDraw& options) const {
    return hostFrameProblem(frame, options);
}

Result<ProjectorStats> DecalProjector::bin(const ForwardFrame& frame) {
    Impl& m = *impl_;
    if (const std::string p = forwardFrameProblem(frame); !p.empty()) return fail("projector: " + p);
    const HostFrame host = cameraFrame(frame);
    const FrameCamera camera = frameCamera(host);
    const bool onGpu = m.cullsOnGpu();
    DecalVisibility vis;
    if (!onGpu) {
        CullView cull = camera.cull;
        cull.rects = true;
        vis = m.cullOnCpu(cull);
    }
    if (Status s = m.forward.prepare(); !s) return fail(s.error());
    if (onGpu)
        if (Status s = m.culling.prepare(); !s) return fail(s.error());
    ProjectorStats stats = m.cpuStats(vis, onGpu);
    stats.variant = "FORWARD";

    GlStateGuard guard(m.settings.restoreGlState);
    m.beginPass(host, camera);
    m.binVisible(frame, camera, onGpu, vis, stats, false);
    m.endPass(onGpu, stats);
    return stats;
}

Status DecalProjector::bindForward(const ForwardBindings& bindings) const {
    const Impl& m = *impl_;
    if (const std::string p = forwardBindingsProblem(bindings, m.limits); !p.empty())
        return fail("projector: " + p);
    m.forward.bind(bindings);
    glBindTextureUnit(bindings.albedoUnit, m.textures.albedoTexture());
    glBindTextureUnit(bindings.normalUnit, m.textures.normalTexture());
    glBindSampler(bindings.albedoUnit, 0);
    glBindSampler(bindings.normalUnit, 0);
    return {};
}

Result<ProjectorStats> DecalProjector::draw(const HostFrame& frame, const ProjectorDraw& options) {
    Impl& m = *impl_;
    if (const std::string p = hostFrameProblem(frame, options); !p.empty()) return fail("projector: " + p);
    const FrameCamera camera = frameCamera(frame);
    const bool onGpu = m.cullsOnGpu();
    DecalVisibility vis;
    if (onGpu) {
        vis.flags = m.batch.flagsUnion();
    } else {
        CullView cull = camera.cull;
        // The screen rectangles: for the normal copy, and for the tiles of the DBuffer's compute resolve.
        cull.rects = (blendsIntoHost(options) && frame.normals.texture != 0) || fillsDBuffer(options);
        vis = m.cullOnCpu(cull);
    }
    ProjectorStats stats = m.cpuStats(vis, onGpu);
    // The decal buffers are cleared, even when nothing is drawn.
    if (fillsDBuffer(options)) m.dbuffer.prepare(frame.depth.texture, m.settings.restoreGlState);
    if (stats.skipped) return stats;
    const uint32_t bits = m.variantBits(frame, options, vis.flags);
    const size_t inView = onGpu ? m.gpuInView() : vis.visible.size();
    if (const std::optional<ComputeResolve::Targets> targets = m.computeTargets(frame, options, inView)) {
        if (fillsDBuffer(options)) m.dbuffer.markWritten();
        return m.resolveInCompute(frame, *targets, camera, onGpu, vis, bits, stats);
    }
    Passes passes;
    Result<GLuint> program = m.program(bits);
    if (!program) return fail(program.error());
    passes.main = program.value();
    stats.variant = join(variantDefines(bits));
    if (roughnessInAlpha(frame, options) && (vis.flags & kDecalRoughness)) {
        Result<GLuint> p =
            m.program((bits & ~(kVariantNormalMap | kVariantDepthFrame)) | kVariantRoughnessAlpha);
        if (!p) return fail(p.error());
        passes.roughness = p.value();
    }
    // Decals that blend normal maps into the host's normals read a copy of them (or read them in place
    // where no pixel reads another's); others read the host's texture, which the draw then does not
    // write.
    passes.writesNormals = blendsIntoHost(options) && (bits & kVariantNormalMap);
    if (passes.writesNormals)
        if (Status s = m.normalCopy.prepare(); !s) return fail(s.error());
    if (onGpu)
        if (Status s = m.culling.prepare(); !s) return fail(s.error());
    if (onGpu && m.settings.occlusionCulling)
        if (Status s = m.pyramid.prepare(frame); !s) return fail(s.error());

    GlStateGuard guard(m.settings.restoreGlState);
    m.beginPass(frame, camera);
    m.drawDecals(frame, options, camera, onGpu, vis, passes, stats);
    m.endPass(onGpu, stats);
    return stats;
}

Result<uint64_t> DecalProjector::findSurface(const HostFrame& frame, const std::vector<SurfaceLine>& lines) {
    Impl& m = *impl_;
    HostFrame read = frame; // what the search reads: the DBuffer path's checks leave albedo out
    read.albedoTexture = 0;
    read.roughness = {};
    if (const std::string p = hostFrameProblem(read, ProjectorDraw{ProjectorPath::DBuffer}); !p.empty())
        return fail("projector: " + p);
    GlStateGuard guard(m.settings.restoreGlState);
    return m.surfaceProbe.find(read, lines, m.nearest.get());
}

std::optional<std::vector<SurfacePoint>> DecalProjector::surfaceFound(uint64_t request, bool wait) {
    return impl_->surfaceProbe.take(request, wait);
}

ProjectorResources DecalProjector::resources() const {
    const Impl& m = *impl_;
    ProjectorResources r;
    r.albedoLayers = m.textures.albedoTexture();
    r.normalLayers = m.textures.normalTexture();
    r.decals = m.buffers.records().bodies();
    r.decalBounds = m.buffers.records().bounds();
    r.types = m.buffers.types();
    r.visible = m.buffers.visibleBuffer();
    r.objects = m.buffers.objects();
    r.visibleCount = m.buffers.visibleCount();
    r.dbufferAlbedo = m.dbuffer.albedo();
    r.dbufferNormal = m.dbuffer.normal();
    r.dbufferMaterial = m.dbuffer.material();
    r.forwardDecals = m.forward.decals();
    r.forwardTiles = m.forward.tiles();
    r.forwardItems = m.forward.items();
    return r;
}

Result<std::string> DecalProjector::hostShader(const std::string& name) {
    if (name != "dbuffer.glsl" && name != "forward.glsl")
        return fail("projector: no host shader '" + name + "' (dbuffer.glsl, forward.glsl)");
    return includeText(shaderLibrary(kProjectorShaders), name);
}

ProjectorMemory DecalProjector::memory() const {
    const Impl& m = *impl_;
    ProjectorMemory r;
    r.cpuBytes = m.batch.cpuBytes() + m.culling.cpuBytes();
    r.gpuScreenBytes = m.forward.gpuBytes() + m.pyramid.gpuBytes() + m.normalCopy.gpuBytes();
    r.gpuBufferBytes = m.buffers.gpuBytes() + m.culling.gpuBytes() + r.gpuScreenBytes;
    return r;
}

const ProjectorSettings& DecalProjector::settings() const {
    return impl_->settings;
}

} // namespace spatter
