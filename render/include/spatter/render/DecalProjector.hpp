#pragma once
// DecalProjector: spatter's deferred decal projector (Krassnigg, "A Deferred Decal Rendering
// Technique", Game Engine Gems 2) as a component that any OpenGL 4.5 renderer hosts. It draws one
// box per visible decal over the host's frame: each pixel inside a box is rebuilt from the host's
// depth, kept when it lies inside the box, belongs to the decal's object (object IDs) and faces the
// decal within its type's angle, and gets the decal's albedo, normal and roughness blended into the
// host's G-buffer before the host's lighting runs (G-buffer blend), or into the projector's own decal
// buffers, which the host's material or lighting shader applies (DBuffer, as Unreal and Unity HDRP
// do: the host's G-buffer stays read-only). For forward renderers (as Godot 4 and Bevy do it) bin()
// sorts the visible decals into screen tiles on the GPU and the host's forward fragment shader
// applies those of its pixel (hostShader("forward.glsl")).
//
// It owns the decal records (44 bytes each, object space, on the GPU; uploaded when they change), the
// decal texture array
// (built-in layers and addDecalTexture*), the shader variants and the GPU timer of its pass. It knows
// nothing of scenes, meshes, materials or lighting: per frame the host hands it the decals (as
// DecalSystem::decals() gives them), the object transforms (double precision), the objects' 8-bit
// decal IDs and a HostFrame describing its textures, their conventions and the camera.
//
//   Result<DecalProjector> projector = DecalProjector::create();  // a GL 4.5 context is current
//   projector->setDecalTypes(types);                                 // appearance, by Decal::type
//   each frame, after the host's geometry pass and before its lighting:
//     projector->setObjects(transforms, ids);                        // one entry per object
//     const DecalChanges changes = decalSystem.changesSince(seen);   // what changed since last time
//     projector->updateDecals(decalSystem.decals(), changes);        // (setDecals: all of them)
//     seen = changes.version;
//     HostFrame f;                                                   // see HostFrame below
//     f.width = w; f.height = h; f.view = view; f.projection = proj; f.eye = eye;
//     f.depth = {depthTexture, DepthEncoding::Window, ClipDepth::ZeroToOne, /*reversedZ*/ true};
//     f.normals = {normalTexture, NormalEncoding::OctahedralWorld};
//     f.albedoTexture = albedo; f.roughness = {materialTexture, 0}; f.objectIdTexture = ids;
//     Result<ProjectorStats> stats = projector->draw(f);
//
// Which host input each feature needs (a feature whose input is not supplied is off, never an
// error at draw time):
//   depth (required)       the box test, distance fading
//   normals                wrap-around (WRAP types), the angle test by the drawn surface's normal,
//                          normal maps blended into the host's normals; without them the angle test
//                          uses the normal of the depth buffer (screen-space derivatives), decals
//                          do not wrap and their normal maps are not applied
//   albedoTexture          the decal's colour (required, except in coverage mode)
//   roughness              the type's roughness (DecalType::roughness >= 0)
//   objectIdTexture        clipping to the decal's object: without it a decal on a moving target
//                          also shows on whatever lies behind it inside its box
//
// GL state: every call that touches GL (create, setDecals, addDecalTexture*, draw, bin, findSurface) leaves
// the GL state exactly as it found it, as Dear ImGui's OpenGL 3 backend does: it saves and restores the bound
// draw and read framebuffers, viewport, program, vertex array, active texture unit and the 2D and 2D-array
// textures and samplers of units 0-7, the uniform buffer bindings 0-1 and shader storage bindings 0-10 (with
// their ranges), image units 0-2 and the generic uniform, shader storage, array, pixel unpack, draw indirect
// and dispatch indirect buffer bindings, blending (enable per draw buffer 0-3, equations, functions), colour
// masks of draw buffers 0-3, depth test, function and mask, stencil test, scissor test, face culling and cull
// mode, front face, clip control, GL_FRAMEBUFFER_SRGB, the unpack alignment, and polygon mode, rasterizer
// discard, colour logic op, depth clamp and clip distances 0-7 (which it sets for its draws, whatever the
// host left on: all off, except depth clamp on for the boxes). What it changes are the contents of the
// textures it writes (draw) and its own GL objects. bindForward alone changes bindings on purpose: those its
// ForwardBindings name, for the host's forward pass. With ProjectorSettings::restoreGlState off it saves and
// restores nothing, and the listed state is left as its passes set it (the host binds what its own passes
// use). It needs the host's context current on the calling thread, and that context must outlive the
// projector.
//
// Bad input changes nothing: a HostFrame with a missing required texture, an unsupported format,
// mismatched sizes, a viewport outside the textures, one texture in two roles (but roughness in the
// albedo's alpha) or a camera that cannot be inverted fails with an error naming the field, before
// any GL state changes (the checks only query the textures); decals naming a missing object or
// type, or with a degenerate or non-finite box, are skipped and counted (ProjectorStats::invalid).

#include "spatter/core/Decal.hpp"
#include "spatter/core/DecalChanges.hpp"
#include "spatter/core/DecalType.hpp"
#include "spatter/core/Image.hpp"
#include "spatter/core/Result.hpp"

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace spatter {

// What the host's depth texture holds.
enum class DepthEncoding {
    Window,     // window-space depth of `projection`, as a depth attachment holds it (any depth, float
                // or normalised colour format); ClipDepth and reversedZ say how it was produced
    LinearView, // the distance from the eye along the view direction, world units, > 0 on surfaces
                // (a float colour texture, R32F or R16F); 0 or less is the background
};

// The clip-space depth range the host's projection was used with (glClipControl).
enum class ClipDepth {
    ZeroToOne,     // GL_ZERO_TO_ONE: window depth = clip z / w
    MinusOneToOne, // GL's default, GL_NEGATIVE_ONE_TO_ONE: window depth = (clip z / w + 1) / 2
};

// How the host's normal texture encodes unit normals, and the formats each takes.
enum class NormalEncoding {
    OctahedralWorld, // RG in [-1, 1]: world-space normal, octahedral (Cigolle et al. 2014);
                     // a signed format of two or more channels (RG16F, RG16_SNORM, RG32F)
    WorldSigned,     // RGB in [-1, 1]: world-space normal; a signed format (RGBA16F, RGBA16_SNORM)
    WorldUnorm,      // RGB in [0, 1]: world-space normal as n * 0.5 + 0.5 (RGBA8, RGB10_A2, RGBA16F)
    ViewUnorm,       // RGB in [0, 1]: view-space normal as n * 0.5 + 0.5, the same formats
};

// The frame in which a decal's normal map is applied.
enum class DecalNormalFrame {
    DecalAxes,        // the decal's tangent, bitangent and axis (Krassnigg 20.7)
    DepthDerivatives, // per pixel: the drawn surface's normal from depth derivatives, with the
                      // decal's tangent projected into it (follows curvature and wrapped corners)
};

struct HostDepth {
    uint32_t texture = 0; // GL_TEXTURE_2D name; required
    DepthEncoding encoding = DepthEncoding::Window;
    ClipDepth clip = ClipDepth::ZeroToOne; // Window only
    bool reversedZ = false;                // Window only: near maps to 1 and far to 0 (cleared to 0); checked
                                           // against `projection`
};

struct HostNormals {
    uint32_t texture = 0; // GL_TEXTURE_2D name; 0: no normals (see the feature table above)
    NormalEncoding encoding = NormalEncoding::OctahedralWorld;
};

struct HostRoughness {    // G-buffer blend only
    uint32_t texture = 0; // GL_TEXTURE_2D colour texture; 0: roughness is not written. It may be the
                          // albedo texture when roughness lives in its alpha channel
    int channel = 0;      // 0 (R), 1 (G), 2 (B) or 3 (A): the channel roughness lives in; the others
                          // are kept. In A it takes a second draw of the boxes (dual-source blending)
};

// The host's frame, field by field. Every texture is a GL_TEXTURE_2D of the host's, read with
// texelFetch at level 0 through the projector's own nearest-filter sampler (the texture's filters do
// not matter: an integer texture left with a mipmap filter would otherwise read 0); the colour targets are
// attached to the projector's own framebuffer and written with blending (an sRGB albedo format is encoded and
// blended in linear space), or, by the compute resolve, bound to image units 0-2 and loaded and stored (an
// sRGB albedo through an RGBA8 view, encoded and decoded by the shader).
struct HostFrame {
    // The region of the host's textures this frame covers, in pixels from their lower left corner;
    // every texture must contain it.
    int x = 0, y = 0, width = 0, height = 0;
    // The camera in double precision: `view` maps world to view space (looking down -Z, as
    // glm::lookAt), `projection` view to clip space (any invertible OpenGL projection: perspective
    // or orthographic, finite or infinite far plane, standard or reversed Z), `eye` is the camera's
    // world position. Positions reach the GPU relative to `eye`, so a frame far from the world
    // origin keeps float precision.
    glm::dmat4 view{1.0};
    glm::dmat4 projection{1.0};
    glm::dvec3 eye{0.0};
    HostDepth depth;
    HostNormals normals;
    // RGBA colour texture, RGB = base colour (linear, or sRGB-encoded by an sRGB format); its alpha is
    // kept. Required for G-buffer blend, except in coverage mode; not read by the DBuffer path.
    uint32_t albedoTexture = 0;
    HostRoughness roughness;
    // Unsigned integer texture (R8UI, R16UI or R32UI) of the objects' 8-bit decal IDs, 0 for static
    // geometry; 0: no ID clipping.
    uint32_t objectIdTexture = 0;
    // Read by findSurface only: each pixel's triangle face normal (the geometric normal, neither
    // interpolated nor normal-mapped; either side), in the encoding and formats of `normals`; 0: the
    // normals findSurface gives come from the depth around each point.
    uint32_t faceNormalTexture = 0;
};

// How draw() blends the decals into the host's G-buffer.
enum class DeferredResolve {
    Auto,    // Compute on a GPU from kComputeResolveFrom decals in view (culled on the GPU: in an earlier
             // draw's view, and Compute before the GPU's first count), Boxes for fewer and on a
             // software rasteriser (llvmpipe): each where it costs less (the compute pass's binning is
             // a fixed cost that a few boxes undercut)
    Boxes,   // a box per visible decal, drawn over the G-buffer (the rasteriser hands each box its pixels)
    Compute, // one compute pass over the screen tiles of the forward path's binning: each pixel with
             // decals in its tile reads the host's targets once, applies its decals in drawing order
             // with the boxes' tests and blending and writes once (the DBuffer path: into the decal
             // buffers). It needs window depth, normals and, for the G-buffer blend, targets it can
             // load and store (albedo RGBA8 or SRGB8_ALPHA8 of immutable storage, normals RG16F,
             // RGBA16F, RGB10_A2 or RGBA8, roughness R8, RG8 or RGBA8 in R, G or B, or in the albedo's
             // alpha); other frames, coverage mode and angleReject off use boxes. Culled on the GPU,
             // the tiles are binned as bin()'s are
             // (forwardTileCapacity); decals left out are reported (ProjectorStats::tilesLeftOut), and
             // where a tile held more than forwardTileCapacity Auto then draws boxes for 16 draws
};

struct ProjectorSettings {
    // Largest angle between a pixel's normal and the decal axis that a wrap-around type accepts: a
    // type's maxAngleDeg (at most 90, a placement limit) would cut the decal at every corner it is
    // meant to wrap around. Flat types use their own maxAngleDeg. In [0, 180].
    float wrapMaxAngleDeg = 120.0f;
    // Depth fading starts at this fraction of the half-depth (|z| / halfDepth) and reaches zero at
    // the box face; DecalType::depthFade picks the curve. In [0, 1).
    float fadeStart = 0.5f;
    DecalNormalFrame normalFrame = DecalNormalFrame::DecalAxes;
    int decalTextureSize = 256; // size of the decal texture layers: a power of two in [16, 2048]
    int forwardTileSize = 16;   // side of the forward path's screen tiles, pixels: a power of two in [8, 64]
    // The longest run of decals a screen tile gets when the binning (bin(), the compute resolve) culls
    // on the GPU, in [16, 4096]. The count is not known on the CPU then: each tile gets a run of twice
    // the most decals of one tile in the latest binning the GPU has reported (16 before the first
    // report), a power of two from 16, at most this. A tile with more decals than its run holds, up to
    // this, gets a run over every decal in view instead (items 0, 1, 2, ... after the tiles' runs): the same
    // pixels, slower for that tile and that frame; decals past this in one tile are left out of it
    // (ProjectorStats::tilesLeftOut). The runs take 4 bytes a tile each: 8.4 MB at 1080p with 16-pixel
    // tiles and 256, 0.5 MB with 16.
    int forwardTileCapacity = 256;
    // draw() builds the visible list on the GPU from this many decals on (given to setDecals): the CPU
    // then does no per-decal work per frame, the pass is not skipped when nothing is in view, and the
    // counts in ProjectorStats are those of an earlier draw (of this one with waitForTimers). 0: always
    // on the GPU. Unset: kGpuCullingFrom on a GPU, kGpuCullingFromSoftware on a software rasteriser
    // (llvmpipe), where the compute passes cost more than the CPU's test of a few decals. The first
    // draw() or bin() that culls on the GPU lets the CPU copy of the decal records go (48 bytes per
    // decal). bin() culled on the GPU sizes its buffers by an earlier count (see bin()).
    std::optional<size_t> gpuCullingFrom;
    static constexpr size_t kGpuCullingFrom = 65536;
    static constexpr size_t kGpuCullingFromSoftware = 262144;
    // Below gpuCullingFrom, draw() and bin() also cull on the GPU while the latest count of decals in
    // view (in the frustum) is at least this many, and go back to the CPU once it falls below half of
    // it: the CPU's corner test of every decal in view costs about 0.3 microseconds each, the GPU's
    // passes tens of microseconds whatever their number, while few decals in view keep the CPU's
    // cheaper forms of the normal copy (ProjectorStats::normalCopy). The CPU copy of the records
    // stays. Unset: kGpuCullingInViewFrom on a GPU, never on a software rasteriser.
    std::optional<size_t> gpuCullingInViewFrom;
    static constexpr size_t kGpuCullingInViewFrom = 1024;
    static constexpr size_t kComputeResolveFrom = 256; // DeferredResolve::Auto
    // draw() culling on the GPU also culls the boxes hidden behind the host's depth where that pays: a
    // depth pyramid of the frame (a texel per 4 x 4 pixels at its finest level, farthest depth per
    // texel) is built, and a box whose
    // nearest point lies beyond every texel under its screen rectangle is not drawn (it could not
    // change a pixel). It runs while the GPU's latest counts show it hiding at least 256 boxes and one
    // in 20 of those in the frustum, and otherwise once every 16 draws and on the first draw after
    // setDecals. bin() has no depth to test.
    bool occlusionCulling = true;
    DeferredResolve deferredResolve = DeferredResolve::Auto;
    bool waitForTimers = false; // draw() waits for its GPU time (tools, benchmarks); otherwise the
                                // time reported is that of an earlier frame, read without stalling
    // The pass's GPU timer (ProjectorStats::gpuMs). Off, draw() makes no timer query and gpuMs stays 0
    // (gpuFrame -1): for a host that times its frame itself. On llvmpipe, where reading whether a
    // query has finished flushes the work queued, a pass of a few decals then costs 30 to 40% less.
    bool passTimer = true;
    // GPU timestamps between the pass's stages, for ProjectorStats::stages (profiling: each waits for
    // the GPU work queued before it, a few microseconds a mark on a GPU).
    bool stageTimers = false;
    // Every call saves and restores the GL state listed at the top of this file: about 150 queries, whose
    // save took 16 us a call on an H100's driver and 0.4 to 0.6 ms with its threaded optimisation
    // (__GL_THREADED_OPTIMIZATIONS), where a query waits for the driver's thread to catch up. Off,
    // a call queries and restores none of it: that state is left as the projector's last pass set it,
    // for a host that binds what each of its passes uses (or resets its state cache after the call).
    bool restoreGlState = true;
};

// Where a draw puts the decals (the forward path, DecalProjector::bin, draws nothing).
enum class ProjectorPath {
    GBufferBlend, // blended into the host's G-buffer (albedo, normals, roughness) before its lighting
    DBuffer,      // into the projector's own decal buffers (ProjectorResources::dbuffer*), which the
                  // host's material or lighting shader applies (hostShader("dbuffer.glsl")); the
                  // host's textures are only read: depth, normals and object IDs, never albedo or
                  // roughness
};

// The forward path's frame (DecalProjector::bin): the viewport and camera of the host's forward pass.
// No texture of the host's is read.
struct ForwardFrame {
    int x = 0, y = 0, width = 0, height = 0; // as HostFrame's; each side at most 16384
    glm::dmat4 view{1.0};                    // as HostFrame's
    glm::dmat4 projection{1.0};
    glm::dvec3 eye{0.0};
    ClipDepth clip = ClipDepth::ZeroToOne; // the clip depth range the projection is used with
    bool reversedZ = false;                // near maps to the larger depth; checked against `projection`
};

// Where bindForward binds the forward path's resources for the host's shader: the defaults of
// forward.glsl, moved there by defining SPATTER_FORWARD_DECALS_BINDING, SPATTER_FORWARD_TILES_BINDING,
// SPATTER_FORWARD_ITEMS_BINDING, SPATTER_DECAL_ALBEDO_UNIT and SPATTER_DECAL_NORMAL_UNIT.
struct ForwardBindings {
    uint32_t decals = 5, tiles = 6, items = 7; // shader storage binding points
    uint32_t albedoUnit = 14, normalUnit = 15; // texture units of the decal texture arrays
};

// Per-draw switches.
struct ProjectorDraw {
    ProjectorPath path = ProjectorPath::GBufferBlend;
    // Coverage mode: instead of blending the decals, write 1 into every channel of this colour
    // texture (R8 or any colour format) wherever a decal changes the pixel (inside its box, ID
    // matching, within its angle); other pixels are left as they are. 0: blend as usual.
    uint32_t coverageTexture = 0;
    bool idClipping = true;  // false: ignore object IDs even when the frame has them (debugging)
    bool angleReject = true; // false: no angle test (debugging)
};

// Where a pass's GPU time went (ProjectorSettings::stageTimers), in milliseconds, each stage from the
// end of the one before it: the frame's and decals' uploads and the culling (on the GPU, or the CPU's
// visible list sent), the binning into screen tiles (the compute resolve and bin(); 0 for boxes), the
// drawing (the normal copy and the boxes, or the compute resolve; 0 for bin()), and the copies of the
// counts the CPU reads back.
struct ProjectorStageTimes {
    double cullMs = 0.0, binMs = 0.0, drawMs = 0.0, readBackMs = 0.0;
    int64_t frame = -1; // the draw call count the times belong to (as ProjectorStats::gpuFrame); -1: none
};

// What one draw did.
struct ProjectorStats {
    size_t decals = 0;          // decals given to setDecals
    size_t invalid = 0;         // skipped: object or type out of range, degenerate or non-finite box
    size_t hostDrawn = 0;       // left to the host (setHostDrawn): kept, not drawn
    size_t culled = 0;          // outside the view frustum (test of the box corners) or occluded, or on
                                // an object whose transform is singular
    size_t drawn = 0;           // instances drawn
    size_t inside = 0;          // of those, boxes that may hold the eye or cross the near plane (a
                                // conservative test; 0 with GPU culling, which does not tell)
    size_t bytesUploaded = 0;   // instance and visibility data sent to the GPU by this draw
    size_t instanceUploads = 0; // runs of changed decals uploaded (each one write to the bounds, one to
                                // the bodies)
    size_t drawCalls = 0;
    bool skipped = true; // no visible decal: no normal copy, no draw
    // The copy of the host's normals that decals blending normal maps read (G-buffer blend): "" (none
    // taken: no such decal in view); "in-place" (none needed: a few boxes whose screen rectangles do
    // not overlap, none wrapping, each pixel read and written by one box at most); when the visible
    // boxes cover at most a quarter of the viewport, "rects" (each box's screen rectangle, for a few
    // boxes) or "boxes" (a draw of the boxes); otherwise "viewport". Culled on the GPU, where only an
    // earlier count of the decals in view is known: "boxes" while it is at most 1,024, else "viewport".
    std::string normalCopy;
    bool gpuCulled = false; // the visible list was built on the GPU (ProjectorSettings::gpuCullingFrom)
    // Culled on the GPU: the groups of 256 places of the draw order (spawn order within a priority)
    // whose decals were tested one by one; the others held no decal or lay out of view whole.
    size_t groupsTested = 0;
    // The latest binning culled on the GPU that the GPU has finished (this one's with waitForTimers), of
    // bin() or of the compute resolve, left decals out of screen tiles: a tile past forwardTileCapacity,
    // or more decals in view than twice an earlier count. DeferredResolve::Auto then draws boxes for a
    // while after the first; the next binning has room for the second.
    bool tilesLeftOut = false;
    std::string variant;        // shader features used, e.g. "IDS WRAP NORMAL_MAP FADE"
    double gpuMs = 0.0;         // GPU time of the pass, of frame `gpuFrame` (see waitForTimers, passTimer)
    int64_t gpuFrame = -1;      // the draw call count (0 for the first) the time belongs to; -1: none yet
    ProjectorStageTimes stages; // with ProjectorSettings::stageTimers (frame -1 without)
};

// A line along which DecalProjector::findSurface looks for the surface the host drew (world space),
// from `from` on: for a decal placed through a collision proxy, its axis line through its box
// (DecalSystem::axisLine), from the side its shot came from; for a shot that the collision surface
// refused (met none, or met it too steeply), the shot (DecalSystem::spawnOnDrawnSurface), with
// `anyObject`.
// The most lines one findSurface call takes: 64 a work group, and the 65,535 work groups every GL 4.5
// implementation dispatches at once.
constexpr size_t kMaxSurfaceLines = size_t(65535) * 64;

struct SurfaceLine {
    glm::dvec3 from{0.0}, to{0.0};
    uint8_t objectId = 0;   // with the frame's object ID texture: the surface must carry this decal ID
    bool anyObject = false; // the surface may carry any object ID (objectId is not checked)
};

// Where a SurfaceLine first meets the drawn surface (world space), as the host's depth gives it.
struct SurfacePoint {
    bool found = false;     // false: the camera does not see the line meet a surface (off screen,
                            // hidden, behind the camera, another object's ID, or no surface along it)
    glm::dvec3 point{0.0};  // on the line
    glm::dvec3 normal{0.0}; // unit, facing the camera: the face normal texture's triangle normal, or
                            // without one, from the depth of the pixels around the point
    uint8_t objectId = 0;   // the object decal ID of the surface there, where the frame has an ID
                            // texture (0 otherwise)
};

// GL objects of the projector that a host may read: the decal texture arrays, and the instance data
// for its own debug drawing (decal box outlines). Valid until the next setDecals, addDecalTexture* or
// draw. Layouts: glsl/decal_data.glsl (DecalBounds at binding 9, DecalBody at binding 3,
// DecalTypeRecord, the visible list, and decalData(), which unpacks a decal) and glsl/projector.glsl
// (ProjectorObject), installed beside this header.
struct ProjectorResources {
    uint32_t albedoLayers = 0; // GL_TEXTURE_2D_ARRAY, SRGB8_ALPHA8: decal albedo, straight alpha
    uint32_t normalLayers = 0; // GL_TEXTURE_2D_ARRAY, RGBA8: tangent-space normal maps
    uint32_t decals = 0;       // shader storage: DecalBody (28 bytes) per decal given to setDecals
    uint32_t decalBounds = 0;  // shader storage: DecalBounds (16 bytes) per decal (decal_data.glsl)
    uint32_t types = 0;        // shader storage: DecalTypeRecord per decal type
    uint32_t visible = 0;      // shader storage: uint decal indices of the last draw, visibleCount of them
    uint32_t objects = 0;      // shader storage: ProjectorObject per object (relative to the last eye)
    size_t visibleCount = 0;   // with culling on the GPU, the count of an earlier draw (unless
                               // waitForTimers): entries past this draw's list may name gone decals
    // The decal buffers of the last ProjectorPath::DBuffer draw (0 before the first): GL_TEXTURE_2D,
    // the size of the host's depth texture, cleared whole (RGB 0, A 1) before each such draw where an
    // earlier one wrote them. RGB
    // holds the decals premultiplied by their alpha, A the fraction of the surface that shows through.
    uint32_t dbufferAlbedo = 0;   // SRGB8_ALPHA8: linear albedo
    uint32_t dbufferNormal = 0;   // RGBA16F: world-space normal
    uint32_t dbufferMaterial = 0; // RGBA8: roughness in R
    // The forward path's buffers of the last bin() (0 before the first); layouts in forward_data.glsl.
    uint32_t forwardDecals = 0; // shader storage: SpatterForwardDecal per visible decal
    uint32_t forwardTiles = 0;  // shader storage: the tile grid and each tile's run of items
    uint32_t forwardItems = 0;  // shader storage: the tiles' decal indices, in drawing order
};

// What the projector holds for its decals (DecalProjector::memory), counted from its own
// allocations; the driver's own copies and bookkeeping are not in it.
struct ProjectorMemory {
    size_t cpuBytes = 0;       // each decal's place in the draw order, a validity bit per decal, the
                               // draw order's entries and the CPU copy of the records (until draw()
                               // culls on the GPU), records waiting for upload, and a bit per group
                               // of 256 places whose culling bounds changed
    size_t gpuBufferBytes = 0; // the decal records, types, objects, draw order, culling (with the
                               // groups' bounds) and forward buffers, the visible list (capacities,
                               // grown ahead of need), and the textures: the depth pyramid and the
                               // copy of the host's normals
    size_t gpuScreenBytes = 0; // the part of gpuBufferBytes sized by the viewport and the decals in
                               // view, not by the decals held: the depth pyramid, the screen tiles
                               // and the normal copy
    // The normal copy is held while draws read it: kNormalCopyIdleDraws draws and bins in a row with
    // decals in view that take none (no decal writing normals in view, normals blended in place, or the
    // compute resolve, which reads the targets before it writes them) free it, and the next draw that needs
    // it makes it again. Half a second at 60 frames a second, so that a view hovering between a draw that
    // copies and one that does not keeps the copy rather than making it anew every frame.
    static constexpr int kNormalCopyIdleDraws = 30;
};

class DecalProjector {
public:
    // Compiles nothing yet (variants are built on first use) and builds the decal texture array with
    // the built-in layers. Needs a current OpenGL 4.5 core context. Fails on settings out of range
    // (an enum naming none of its values included) and on a context with fewer than 11 shader storage
    // buffer bindings.
    static Result<DecalProjector> create(const ProjectorSettings& settings = {});

    // Movable, not copyable. A moved-from DecalProjector holds nothing: assign to it or destroy it, and call
    // nothing else on it.
    DecalProjector(DecalProjector&&) noexcept;
    DecalProjector& operator=(DecalProjector&&) noexcept;
    ~DecalProjector();

    // Decal appearance, indexed by Decal::type; DecalType::texture is a layer of the texture array
    // (0..3 are the built-in DecalTexture values). Volumetric types are drawn like flat ones here.
    void setDecalTypes(const std::vector<DecalType>& types);
    // The decals, in their objects' space (as DecalSystem::decals() gives them), taken whole: every
    // record is built and uploaded (at the next draw) and the draw order sorted afresh.
    void setDecals(const std::vector<Decal>& decals);
    // The decals after `changes` (DecalSystem::changesSince, DecalChanges.hpp): only the records the
    // changes name are built and uploaded, and the draw order is kept without sorting (a decal added
    // draws over the older ones of its priority). The decals are taken whole, as by setDecals, when
    // the changes are not complete or do not fit the decals held, and after setDecalTypes changed the
    // types' priorities. The projector keeps no copy of the decals: the changes and `decals` together
    // say what changed. Per decal it keeps 44 bytes on the GPU, and on the CPU about 4 bytes (its
    // place in the draw order, a validity bit) plus, for culling on the CPU, a 48-byte record and the
    // draw order's entries (5 bytes), which go once it holds ProjectorSettings::gpuCullingFrom decals
    // or more: the draw order's changes then go to the GPU as writes.
    void updateDecals(const std::vector<Decal>& decals, const DecalChanges& changes);
    // Object-to-world transforms (double) and 8-bit decal IDs, one entry per object that decals may
    // name (Decal::object); a decal clips to its object's decal ID (Decal::objectId is not read).
    // Fails, changing nothing, when the counts differ, there are more than 16,777,215 objects (a
    // decal's object index takes 24 bits on the GPU) or a transform is not finite and affine; a
    // singular transform is taken (its decals collapse and are not drawn).
    Status setObjects(const std::vector<glm::dmat4>& transforms, const std::vector<uint8_t>& ids);
    // Decals the host draws by other means, which the projector keeps but does not draw (counted in
    // ProjectorStats::hostDrawn): those of the types with a nonzero entry in `types` (indexed as
    // setDecalTypes' types) and those on the objects with a nonzero entry in `objects` (indexed as
    // setObjects' objects). Entries past the end are 0. spatter's renderer draws the decals of
    // volumetric types as craters and splats those on texture-space objects into their textures,
    // and gives the projector every decal with its change list all the same. Takes effect at the next
    // draw; the decals are kept as they are.
    void setHostDrawn(std::vector<uint8_t> types, std::vector<uint8_t> objects);

    // Adds a decal texture layer (resized to the layer size); `normalMap` may be empty for a flat
    // one. Returns its layer index.
    Result<int> addDecalTexture(const Image& albedo, const Image& normalMap = {});
    // The same from image files (PNG, JPEG, ...); `normalMapPath` may be empty.
    Result<int> addDecalTextureFile(const std::string& albedoPath, const std::string& normalMapPath = "");
    int decalTextureLayers() const;
    // Each layer's cutout: the rectangle in texture coordinates (min u, min v, max u, max v; v = 0 at
    // the image's bottom row) outside which the layer shows nothing. It is where the albedo's alpha
    // is not zero at full resolution, widened by a sixteenth of the layer's size; the shaders take
    // the alpha as zero outside it at every mip level, and boxes are drawn over it alone. Empty (min
    // above max) for a layer with no visible texel. Types carry it to the shaders in
    // DecalTypeRecord::info.w (decal_data.glsl).
    std::vector<glm::vec4> decalTextureCutouts() const;

    // Projects the decals into the host's frame (G-buffer blend: albedo, normals and roughness are
    // blended into the host's textures; DBuffer: into the projector's decal buffers), or writes their
    // coverage (ProjectorDraw). Fails, drawing
    // nothing and leaving the GL state as it was, on a HostFrame that does not fit (the error names
    // the field) or a shader that does not build.
    Result<ProjectorStats> draw(const HostFrame& frame, const ProjectorDraw& options = {});

    // Forward path: culls the decals against `frame` (on the CPU: see gpuCullingFrom) and sorts the visible
    // ones into screen tiles on the GPU (ProjectorSettings::forwardTileSize), for the host's forward shader,
    // which applies them per pixel (hostShader("forward.glsl")) after bindForward. Draws nothing and leaves
    // the GL state as it found it. Fails, changing nothing, on a frame that does not fit (the error names the
    // field).
    Result<ProjectorStats> bin(const ForwardFrame& frame);
    // Binds the buffers of the last bin() and the decal texture arrays for the host's forward pass.
    // It changes exactly the shader storage bindings and texture units `bindings` names (and binds
    // sampler 0 to those units), and the generic shader storage buffer binding: the one call that leaves GL
    // state changed, for the host's next draws. Fails, binding nothing, on a binding point or texture
    // unit past the context's limits, or two of them the same.
    Status bindForward(const ForwardBindings& bindings = {}) const;

    // Looks for the drawn surface along each line in the host's depth (on the GPU; the frame's depth,
    // camera, object ID and face normal textures are read, nothing is written): the first point from a
    // line's start where it passes from in front of the surface the depth holds to behind it (or, for a
    // line that starts behind it, from behind it to in front), seen by the camera, where the depth is
    // continuous across it (a jump of more than 8 pixels' size is the edge of something in front), and
    // the normal there. With a face normal texture that is the normal of
    // the triangle the line meets and the point lies on its plane (a meet within a pixel of an edge
    // takes the triangle beside the one the pixel shows where the line meets that one: of the planes the
    // 3 x 3 pixels around show, the later crossing across a convex edge for a line from in front, the
    // earlier across a concave one); without, the normal the pixels around the point give (the steps to
    // its neighbours in the quadrant whose pixels lie flattest on their plane, so that a crease or an
    // edge beside it stays out). Call it after the host's geometry pass,
    // as draw(). For decals placed through a collision proxy: the lines of the decals just spawned,
    // then DecalSystem::layOnDrawnSurface with each point found, which lays them on the drawn surface
    // rather than the proxy's (ACCURACY.md). A line whose ends lie past float's range from the camera
    // meets nothing. Returns the request's number for surfaceFound. Fails,
    // queuing nothing, on a frame that does not fit (the depth, object ID texture and camera checks of
    // draw()), a line that is not finite or more than kMaxSurfaceLines lines.
    Result<uint64_t> findSurface(const HostFrame& frame, const std::vector<SurfaceLine>& lines);
    // The points of a findSurface request, in its lines' order, once the GPU has finished it (waiting
    // for it with `wait`, which stalls); empty while it has not, and for a request taken already or
    // never made. The 16 newest requests wait to be taken; an older one is dropped.
    std::optional<std::vector<SurfacePoint>> surfaceFound(uint64_t request, bool wait = false);

    // The checks draw() makes on `frame` (and `options`), without drawing: empty when it fits.
    std::string frameProblem(const HostFrame& frame, const ProjectorDraw& options = {}) const;

    ProjectorResources resources() const;
    ProjectorMemory memory() const;

    // GLSL for a host's own shaders, to paste after its #version line: "dbuffer.glsl" (applying the
    // decal buffers of the DBuffer path) or "forward.glsl" (the forward path). Fails on another name.
    static Result<std::string> hostShader(const std::string& name);
    const ProjectorSettings& settings() const;

private:
    struct Impl;
    explicit DecalProjector(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

} // namespace spatter
