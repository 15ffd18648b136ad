#pragma once
// Renderer: the deferred renderer and its decal projector (Krassnigg, "A Deferred Decal Rendering
// Technique", Game Engine Gems 2). A frame is
//   0. splats     only when decals have arrived for texture-space objects (DecalMode.hpp): each is
//                 rendered once into its object's decal texture through the UVs, then the texture's
//                 UV islands are dilated by a texel;
//   1. geometry   the render meshes of every decal receiver, morphed and skinned by the pose
//                 (setPose) on the GPU, moved by their Deformation and with their texture-space
//                 decal layer, fill the G-buffer (albedo, octahedral normal, roughness/metallic,
//                 reversed-Z float depth, and object decal IDs when the scene has dynamic objects);
//   1b. volumetric only with decals of a volumetric type (DecalType::volumetric): each crater's
//                 footprint marks the stencil where the surface is visible (and the ID matches),
//                 then the crater mesh, behind the surface, replaces it there in the G-buffer with the
//                 surface's material continued into the hole (docs/RENDERING.md, "Volumetric decals");
//   2. decals     the decal projector (DecalProjector.hpp): one instanced draw of a unit cube per
//                 visible decal, its far faces (front faces culled, depth clamped, depth test
//                 GL_LEQUAL: the far face not in front of the scene under reversed-Z), or, on a GPU
//                 with many decals in view, one compute pass over screen tiles doing the same per
//                 pixel. Each fragment rebuilds the scene position from depth, keeps it when it is inside
//                 the box, has the decal's object ID, and has a normal within the type's angle of
//                 the decal axis, and writes albedo, normal (Whiteout) and roughness into the
//                 G-buffer, so that decals are lit like everything else;
//   3. late       objects that receive no decals, drawn over the decals;
//   4. lighting   one directional light, ambient, GGX specular, tone mapping, sRGB output
//                 (or one of the debug views);
//   5. overlays   only when RenderOptions asks for them: the collision proxies' wireframes and the
//                 decal boxes as lines over the output image, depth-tested against the scene.
// Positions reach the GPU relative to the eye: object transforms stay double on the CPU and have
// the eye subtracted before they become float.
//
//   Result<GlContext> gl = GlContext::createHeadless();
//   Result<Renderer> r = Renderer::create(*gl, {640, 360});
//   r->setScene(scene);
//   r->setDecalTypes(types);             // appearance, indexed by Decal::type
//   r->setObjectIds(ids);                // the decal system's 8-bit object IDs
//   r->setDecals(decalSystem.decals());  // once; then every frame only what changed:
//   r->updateDecals(decalSystem.decals(), decalSystem.changesSince(version)); version = ...version
//
// Texture-space decals (DecalMode.hpp) and vertex animation (Deformation.hpp), per object:
//   r->setObjectDecalMode(target, DecalMode::TextureSpace, 512); // fails on overlapping UVs
//   r->setObjectDeformation(target, {0.08f, 2.0f, 0.0f, 3.0f});  // amplitude, frequency, phase, speed
//   r->setTime(seconds);                                          // every frame
//   r->setDecals(decalSystem.decals()); // decals on `target` are splatted once, when first seen
//   Result<FrameStats> stats = r->render(camera, View::Final);
//   Result<Image> image = r->readback();
//
// Animation (skins, morph targets and animated nodes; spatter/core/SceneEvaluator.hpp), every frame:
//   evaluator.evaluate(0, std::fmod(seconds, scene.animation.animations[0].duration));
//   r->setPose(evaluator);               // or a ScenePose from the host's own animation system
//
// Debugging aids (RenderOptions.hpp):
//   r->setOverlayMeshes(proxyMeshes);    // after setScene: one object-space mesh per object
//   RenderOptions o;
//   o.view = View::Ids;
//   o.overlays.proxyWireframe = o.overlays.decalBoxes = true;
//   o.decals.idClipping = false;         // decals on targets also show on the wall behind
//   r->render(camera, o);
//
// Every call needs the context current on the calling thread; the context must outlive the
// renderer. Invalid input (a decal naming a missing object or type, NaN in a transform, a size
// out of range) never crashes: calls that can fail return a Status, and unusable decals are skipped
// and counted in FrameStats::decalsInvalid.

#include "spatter/core/CraterClip.hpp"
#include "spatter/core/Decal.hpp"
#include "spatter/core/DecalType.hpp"
#include "spatter/core/Image.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/DecalMode.hpp"
#include "spatter/render/DecalProjector.hpp"
#include "spatter/render/Deformation.hpp"
#include "spatter/render/FrameStats.hpp"
#include "spatter/render/GlContext.hpp"
#include "spatter/render/RenderOptions.hpp"
#include "spatter/render/View.hpp"

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace spatter {

struct LightSettings {
    glm::vec3 direction{-0.35f, 0.8f, 0.5f}; // towards the light, world space (normalised on use)
    glm::vec3 color{1.0f, 0.96f, 0.9f};
    float intensity = 3.2f;
    glm::vec3 skyAmbient{0.32f, 0.38f, 0.48f};
    glm::vec3 groundAmbient{0.14f, 0.12f, 0.1f};
    float exposure = 0.75f;
};

struct RendererSettings {
    int width = 1280;
    int height = 720;
    DecalNormalFrame normalFrame = DecalNormalFrame::DecalAxes;
    // Largest angle between a pixel's normal and the decal axis that a wrap-around type accepts:
    // a type's maxAngleDeg (at most 90, a placement limit) would cut the decal at every corner it
    // is meant to wrap around. Flat types use their own maxAngleDeg.
    float wrapMaxAngleDeg = 120.0f;
    // Depth fading starts at this fraction of the half-depth (|z| / halfDepth) and reaches zero at
    // the box face; DecalType::depthFade picks the curve (None, Linear, Smooth). In [0, 1).
    float fadeStart = 0.5f;
    int decalTextureSize = 256;           // size of the decal texture layers: a power of two in [16, 2048]
    bool waitForTimers = false;           // render() waits for this frame's GPU times (tools, benchmarks)
    std::optional<size_t> gpuCullingFrom; // decals from which the projector culls on the GPU
                                          // (ProjectorSettings::gpuCullingFrom)
    std::optional<size_t> gpuCullingInViewFrom;              // decals in view from which it does below that
                                                             // (ProjectorSettings::gpuCullingInViewFrom)
    bool occlusionCulling = true;                            // ProjectorSettings::occlusionCulling
    bool decalStageTimers = false;                           // ProjectorSettings::stageTimers
    DeferredResolve deferredResolve = DeferredResolve::Auto; // ProjectorSettings::deferredResolve
    // A G-buffer target of each pixel's triangle face normal (4 bytes a pixel, written by the geometry
    // passes), from which findSurface takes the normals of what it finds (HostFrame::faceNormalTexture):
    // the normal placement takes on a render mesh, where the depth around a point gives its pixels'.
    // A crater's inner wall keeps the face normal of the surface it is cut into.
    bool faceNormals = false;
    LightSettings light;
};

// A pose of the scene last given to Renderer::setScene, in plain values: what a host with its own
// animation system passes (spatter's SceneEvaluator fills one through Renderer::setPose).
struct ScenePose {
    std::vector<glm::dmat4> objectTransforms; // one per object, as setObjectTransform takes them
    // One list per skin of Scene::animation.skins, one matrix per joint: the joint's world transform
    // times its inverse bind matrix (bind space to world), finite and affine.
    std::vector<std::vector<glm::dmat4>> jointMatrices;
    // One list per object: one finite weight per morph target of the object (empty for none).
    std::vector<std::vector<double>> morphWeights;
};

class Renderer {
public:
    // Compiles the shaders, creates the G-buffer at settings.width x settings.height and the decal
    // texture array with the built-in layers. Fails on settings out of range or a shader that
    // does not build (the message carries the driver's log).
    static Result<Renderer> create(const GlContext& context, const RendererSettings& settings = {});

    // Movable, not copyable. A moved-from Renderer holds nothing: assign to it or destroy it, and call
    // nothing else on it.
    Renderer(Renderer&&) noexcept;
    Renderer& operator=(Renderer&&) noexcept;
    ~Renderer();

    // Uploads the scene's meshes, materials and textures and copies its transforms (validated with
    // validateScene; on failure the previous scene stays). Clears decals, object IDs and overlay
    // meshes. The ID target exists exactly when the scene has dynamic objects.
    Status setScene(const Scene& scene);
    // Moves an object (double precision, like SceneObject::transform). Fails for an index out of
    // range or a transform that is not finite and affine (a singular one is taken: the object is
    // drawn flattened).
    Status setObjectTransform(uint32_t object, const glm::dmat4& transform);
    // Poses the scene: every object moves to its transform, skinned objects (SceneObject::skin) are
    // skinned on the GPU by their joint matrices (their own transform then only places their decals,
    // as glTF ignores a skinned mesh's node transform), and morph targets are added with the weights.
    // Joint influences and morph deltas went to the GPU with setScene; a pose sends only the matrices
    // (camera-relative, every frame) and the weights. Until the first pose, skinned and morphed
    // objects are drawn in their rest pose as static meshes. Decals on skinned or morphed objects
    // follow the object's transform only. Fails, changing nothing, when a count does not match the
    // scene (the error names the list, object or skin), a transform or joint matrix is not finite and
    // affine, or a weight is not finite.
    Status setPose(const ScenePose& pose);
    // The same at `evaluator`'s current pose. Precondition: the evaluator was made for the scene last
    // given to setScene (one whose node count differs is refused).
    Status setPose(const SceneEvaluator& evaluator);
    // The 8-bit object decal ID of every object (0 for static geometry), as the decal system
    // assigns them; one entry per scene object. Without dynamic objects there is no ID target and
    // IDs are not compared. Before this call every object has ID 0.
    Status setObjectIds(const std::vector<uint8_t>& ids);

    // How the decals of `object` are drawn (DecalMode.hpp). TextureSpace creates the object's decal
    // textures at textureSize x textureSize (a power of two in [16, 4096]), cleared, and renders its
    // UV mask; it fails, changing nothing, when the object's render mesh has no UVs or its UV layout
    // is not usable (findUvOverlaps: overlapping triangles or UVs outside [0, 1]; the error names the
    // object and the first overlapping pair). Projected frees them. Decals already given are routed
    // anew by the next setDecals or updateDecals call (on a texture-space object: splatted).
    Status setObjectDecalMode(uint32_t object, DecalMode mode, int textureSize = 512);
    DecalMode objectDecalMode(uint32_t object) const; // Projected for an index out of range
    // Erases the texture-space decals splatted on `object` so far (decals still given to setDecals
    // are not splatted again). Fails for an index out of range or an object not in TextureSpace mode.
    Status clearObjectDecals(uint32_t object);
    // The object's vertex animation (Deformation.hpp); amplitude 0 switches it off. Fails, changing
    // nothing, for an index out of range, a non-finite value or a zero direction.
    Status setObjectDeformation(uint32_t object, const Deformation& deformation);
    // The time, in seconds, at which deformations are evaluated. Fails on a non-finite value.
    Status setTime(double seconds);

    // Decal appearance, indexed by Decal::type. Layers (DecalType::texture) refer to the decal
    // texture array: 0..3 are the built-in DecalTexture values.
    void setDecalTypes(const std::vector<DecalType>& types);
    // The decals to draw (object space, as DecalSystem::decals() gives them). Decals whose type,
    // as last given to setDecalTypes, is volumetric are drawn as holes, not by the decal pass, cut by
    // the clip planes `clips` gives for their index (DecalSystem::craterClips; none when empty).
    // Every decal is taken whole (updateDecals takes only what changed). Decals on texture-space
    // objects are not drawn by the decal pass: each is splatted into its object's decal texture by the next
    // render call after it first appears (recognised by its ID, object, type, frame and size; on a
    // skinned or morphed object, whose decals the decal system moves with the pose, by its ID, object,
    // type, size and spawn time), in the pose of that frame, and stays there.
    void setDecals(const std::vector<Decal>& decals, const CraterClipsOf& clips = {});
    // The decals after `changes` (DecalSystem::changesSince): only the decals the changes name are
    // built and uploaded (DecalProjector::updateDecals), new decals on texture-space objects splatted.
    // While some type is volumetric or some object texture-space the renderer keeps a byte per decal
    // (its kind), and a change to a volumetric decal takes the volumetric decals afresh (a scan of
    // `decals`). Takes the decals whole, as setDecals, when the changes are not complete or do not
    // fit, and after setDecalTypes or setObjectDecalMode.
    void updateDecals(const std::vector<Decal>& decals, const DecalChanges& changes,
                      const CraterClipsOf& clips = {});
    // Adds a decal texture layer (resized to the layer size); `normalMap` may be empty for a flat
    // one. Returns its layer index.
    Result<int> addDecalTexture(const Image& albedo, const Image& normalMap = {});
    // The same from image files (PNG, JPEG, ...); `normalMapPath` may be empty.
    Result<int> addDecalTextureFile(const std::string& albedoPath, const std::string& normalMapPath = "");
    int decalTextureLayers() const;
    // What the decal projector holds for the decals (DecalProjector::memory).
    ProjectorMemory decalMemory() const;

    // Wireframes for RenderOverlays::proxyWireframe, typically the collision proxies (Proxy::mesh):
    // one mesh per scene object, in that object's space (an empty mesh draws nothing for its
    // object), or an empty vector to remove them all. Each is welded by position and reduced to its
    // unique edges here, once; a frame then draws every wireframe in one draw, each with its
    // object's current transform (setObjectTransform). Fails, keeping the previous meshes, when the
    // count is not the scene's object count or a mesh fails validateMesh (the error names the
    // object).
    Status setOverlayMeshes(const std::vector<Mesh>& meshes);

    // Resizes the G-buffer and the output.
    Status resize(int width, int height);
    // Fails, changing nothing, on a non-finite value or a zero direction.
    Status setLight(const LightSettings& light);
    const RendererSettings& settings() const;

    // Renders one frame of `view` from `camera` into the output image.
    Result<FrameStats> render(const Camera& camera, View view = View::Final);
    // The same with overlays and decal-pass debug switches. Fails on an invalid camera or a depth
    // bias outside [0, 0.5], drawing nothing, and on a shader that does not build (the G-buffer may
    // then be written; the output image is not).
    Result<FrameStats> render(const Camera& camera, const RenderOptions& options);
    // The output image of the last render, RGBA8, row 0 at the top.
    Result<Image> readback() const;
    // The view depth of every pixel of the last render (distance from the eye along the view
    // direction, world units; 0 for the background), row 0 at the top, width * height values.
    Result<std::vector<float>> readbackDepth() const;
    // Looks for the drawn surface along `lines` in the last render's depth, from its camera
    // (DecalProjector::findSurface: object IDs checked where the scene has dynamic objects); the points
    // come from surfaceFound. Fails before the first render and on a line that is not finite.
    Result<uint64_t> findSurface(const std::vector<SurfaceLine>& lines);
    std::optional<std::vector<SurfacePoint>> surfaceFound(uint64_t request, bool wait = false);
    // Copies the output image into the current default framebuffer (a window) of the given size.
    void present(int framebufferWidth, int framebufferHeight) const;

private:
    struct Impl;
    explicit Renderer(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

} // namespace spatter
