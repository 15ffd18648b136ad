#include "SkinnedBench.hpp"

#include "BenchSupport.hpp"
#include "CoverageProbe.hpp"
#include "ImageDrift.hpp"
#include "SkinPoints.hpp"
#include "SkinnedModels.hpp"

#include "spatter/core/DeformingProxy.hpp"
#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/placement/CollisionWorld.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/render/Camera.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace spatter::bench {

namespace {

const char* kSkinnedCommand = "skinned";
const std::vector<std::string> kModels = {kSkinnedArmSpec, kSkinnedDummySpec, "gltf/CesiumMan/CesiumMan.glb",
                                          "gltf/RiggedSimple/RiggedSimple.glb"};

constexpr double kPoseTargetMs = 0.2;
constexpr double kSpawnTargetRatio = 2.0;
constexpr double kDriftTarget = 0.02;     // of the decal's size
constexpr double kSpawnPhase = 0.3;       // the pose of the spawn rows, a fraction of the cycle
constexpr float kProxyTolerance = 0.005f; // relative to the render mesh's diagonal

const char* kSkinnedUsage =
    R"(usage: spatter-bench skinned [--model SPEC] [--frames N] [--repeat R] [--samples S] [--no-render]
                             [--quick] [--json FILE]

Decals on skinned objects, in one run, for builtin:skinned-arm (50 rings of 50 vertices: 5,000
triangles), the gallery's dummy (addSkinnedDummy), CesiumMan and RiggedSimple (the shared data).
Times are thread CPU time on one core (every Embree device made with threads=1, so that its refits
run on the timed thread), the median of R runs. Each model's skinned object is posed by its
animation 0, looped over its duration.

Pose update: CollisionWorld::setPose per call (skinning the collision mesh in double, then the
Embree refit), cycling through N poses of the cycle (the poses are evaluated beforehand), with
  render mesh       the render mesh as the collision mesh
  deforming proxy   buildDeformingProxy at 0.5% of the diagonal (its deformation transferred from
                    the render mesh)
  Target: at most 0.2 ms a call for a collision mesh of 5,000 triangles.

Spawn: DecalSystem::spawn per call on the skinned object posed at 30% of its cycle (render mesh as
collision mesh; each hit also anchored to the render surface) against spawn on the same posed mesh
built as a static object, the same rays (scattered around the posed mesh, 90% aimed at its surface),
each run into a fresh system with room for every decal, skinned and static runs in turns; and the
same through proxies: the skinned object through its 0.5% deforming proxy (each hit then also found
on the render mesh and the decal placed there), the static twin through a 0.5% proxy of its own.
Target: skinned at most 2x static.

Drift: decals (5% of the diagonal) shot at several times of the cycle, then the object posed at N
frames of the whole cycle. For each decal and frame, the distance along the surface (in the plane of
the render triangle under it) between the decal's centre and the render-surface point it was placed
on (the nearest render point to its centre at its spawn time, posed with the render mesh), as a
fraction of the decal's size; median and max over decals and frames (whole max: the full distance,
off the surface included):
  skin anchors, render mesh       DecalSystem::setPose moves the decals; render mesh as collision
  skin anchors, deforming proxy   the same over the 0.5% deforming proxy
  nearest joint                   a decal attached as engines attach them: its spawn-time centre
                                  carried by the joint of largest weight at the nearest render
                                  vertex, centre_t = J_t * inverse(J_t0) * centre_t0
  Target: within 2% of the decal's size.

Pose bounds: the deforming proxy's bound over S sampled poses of each animation (PoseBound: bound,
the largest sampled bound, the allowance for the surfaces' relative motion between samples), against
the proxy simplified at rest, absolute and as a fraction of the render mesh's diagonal ('rest,
sampled': where the deforming proxy certifies below the rest proxy's sampled distances, the rest
proxy is only sampled, and its figures are distances measured, a lower bound).

Accuracy: at 0, 25, 50 and 75% of the cycle, 200 shots from a camera framing the posed model (its
bounding sphere fills the height of a 45-degree view), each aimed at an area-weighted random point of
the posed render surface, placed afresh in two systems posed there (DecalSystem::setPose): through
the 0.5% deforming proxy and on the render mesh. Both sets of decals (5% of the diagonal, no random
rotation) are drawn by the renderer posed there (Renderer::setPose) in its coverage view at 640x480;
the IoU of the two masks, and the minimum over models and times. Needs an OpenGL context (headless
EGL); without one the rows are not measured. Target: IoU at least 0.97 at every time.

Drift in the image: 8 decals shot from a camera framing the model at 30% of its cycle, each drawn
alone at 16 poses of the cycle at 960x720, with a centre marker for texture (an opaque disc a fifth
of the decal's width across); the drawn centre is the centroid of the pixels the marker changes,
against the render-surface point the decal was placed on, posed and projected, as a fraction of the
decal's size in pixels there (frames where the point is seen more than 60 degrees off or the marker
shows less than 85% of a flat disc's pixels, hidden in part, are left out; "at spawn": what the
measure reads at the spawn pose itself; decals whose marker does not show whole then are not
followed), for
  skin anchors, projected   DecalSystem::setPose moves the decal, the decal pass projects it
  texture-space splat       splatted in the spawn pose into the object's 1024^2 decal texture
                            (DecalMode::TextureSpace; only on UV layouts without overlaps), with
                            the splat pass's GPU time per decal
  nearest joint             the spawn-time box carried by the nearest joint, as above
Needs an OpenGL context. Target: within 2% of the decal's size.

--model SPEC one model instead of the four (builtin:skinned-arm, "gallery dummy" or a skinned
             glTF file, of the shared data or not)
--frames N   poses of the cycle (default 60)      --repeat R  runs per timed row (default 7)
--samples S  poses a proxy bound is certified at (default 128)
--no-render  no OpenGL context: accuracy not measured
--quick      6 frames, 3 runs, 8 samples, fewer calls and shots (50 a time for accuracy; 2 decals at
             3 poses at 480x360 in the image; smoke test)
--json FILE  "targets" and arrays of rows: "models": model, render_triangles, joints, duration_s,
             decal_size, proxy_seconds; "pose_update": model, collision, triangles, ms_per_call,
             within_target; "spawn": model, rays, placed_skinned, placed_static, skinned_ns, static_ns,
             ratio, within_target, proxy_skinned_ns, proxy_static_ns, proxy_ratio,
             proxy_within_target; "drift": model, method, decals, samples, median, max, whole_max,
             within_target (fractions of the decal's size); "pose_bounds": model, proxy, triangles,
             bound, sampled_max, motion, poses, bound_fraction; "accuracy": model, phase, time_s, rays,
             placed_render, placed_proxy, covered_pixels, iou, within_target (null: not measured);
             "accuracy_min_iou", "coverage" ("measured" or why not), "gl_renderer";
             "image_drift": model, method, unavailable, decals, samples, at_spawn_max, median, max,
             within_target, splat_ms
)";

struct Sizes {
    size_t runs = 7;
    size_t frames = 60;        // poses of the cycle
    size_t poseCalls = 1000;   // setPose calls a run
    size_t spawnRays = 2000;   // spawns a run
    size_t spawnTimes = 8;     // when the drift's decals are shot
    size_t raysPerTime = 48;   // shots each time
    int samples = 128;         // poses of a proxy bound
    size_t accuracyRays = 200; // shots each time of the accuracy rows
    size_t imageDecals = 8;    // decals followed in the image
    size_t imageFrames = 16;   // poses of the cycle they are drawn at
    int imageWidth = 960, imageHeight = 720;
};

Sizes quickSizes() {
    Sizes s;
    s.runs = 3;
    s.frames = 6;
    s.poseCalls = 30;
    s.spawnRays = 200;
    s.spawnTimes = 2;
    s.raysPerTime = 12;
    s.samples = 8;
    s.accuracyRays = 50;
    s.imageDecals = 2;
    s.imageFrames = 3;
    s.imageWidth = 480;
    s.imageHeight = 360;
    return s;
}

// ---- Pose update -----------------------------------------------------------------------------

struct PoseRow {
    std::string model, collision;
    size_t triangles = 0;
    double seconds = 0.0; // per setPose call
};

// Median over the runs of the thread CPU time per setPose call, cycling through `poses`.
Result<double> poseSeconds(CollisionWorld& world, uint32_t object, const std::vector<ModelPose>& poses,
                           const Sizes& sizes) {
    std::vector<double> times;
    for (size_t r = 0; r < sizes.runs; ++r) {
        const double t0 = threadCpuNow();
        for (size_t i = 0; i < sizes.poseCalls; ++i) {
            const ModelPose& p = poses[i % poses.size()];
            if (Result<TransformUpdate> u = world.setPose(object, p.transform, p.joints, p.weights); !u)
                return fail(u.error());
        }
        times.push_back((threadCpuNow() - t0) / double(sizes.poseCalls));
    }
    return median(times);
}

Result<PoseRow> measurePose(const SkinnedModel& m, const std::optional<Proxy>& proxy, const Sizes& sizes) {
    SceneEvaluator evaluator(m.scene);
    std::vector<ModelPose> poses;
    for (size_t f = 0; f < sizes.frames; ++f)
        poses.push_back(modelPoseAt(m, evaluator, cycleTime(m, double(f) / double(sizes.frames))));
    Result<CollisionWorld> world = skinnedWorld(m, proxy);
    if (!world) return fail(m.name + ": " + world.error());
    Result<double> seconds = poseSeconds(world.value(), m.object, poses, sizes);
    if (!seconds) return fail(m.name + ": " + seconds.error());
    return PoseRow{m.name, proxy ? "deforming proxy 0.5%" : "render mesh", world->object(m.object)->triangles,
                   seconds.value()};
}

// ---- Spawn cost ------------------------------------------------------------------------------

struct SpawnTiming {
    double seconds = 0.0; // per spawn
    size_t placed = 0;    // in one run
};

using SystemMaker = std::function<Result<DecalSystem>()>;

// The thread CPU time per spawn of `rays` into a fresh system from `make`, so that every run places
// into the same empty system; `placed`: the decals it placed.
Result<double> spawnRunSeconds(const SystemMaker& make, const std::vector<Ray>& rays, size_t& placed) {
    Result<DecalSystem> system = make();
    if (!system) return fail(system.error());
    const double t0 = threadCpuNow();
    for (const Ray& ray : rays)
        system->spawn(ray, 0);
    const double seconds = (threadCpuNow() - t0) / double(rays.size());
    placed = system->stats().placed;
    return seconds;
}

// The medians over `runs` runs of each of `first` and `second`, run in turns (first, second, first,
// ...), so that the machine's load, which drifts over a run of several seconds, weighs on both alike.
Result<std::pair<SpawnTiming, SpawnTiming>> spawnSecondsInTurns(const SystemMaker& first,
                                                                const SystemMaker& second,
                                                                const std::vector<Ray>& rays, size_t runs) {
    std::vector<double> times[2];
    SpawnTiming out[2];
    for (size_t r = 0; r < runs; ++r)
        for (int k = 0; k < 2; ++k) {
            Result<double> t = spawnRunSeconds(k == 0 ? first : second, rays, out[k].placed);
            if (!t) return fail(t.error());
            times[k].push_back(t.value());
        }
    for (int k = 0; k < 2; ++k)
        out[k].seconds = median(times[k]);
    return std::make_pair(out[0], out[1]);
}

struct SpawnRow {
    std::string model;
    size_t rays = 0;
    SpawnTiming skinned, statik;           // the render mesh as collision mesh
    SpawnTiming skinnedProxy, staticProxy; // through 0.5% proxies
    double ratio() const { return skinned.seconds / statik.seconds; }
    double proxyRatio() const { return skinnedProxy.seconds / staticProxy.seconds; }
};

// The spawns of `rays` on the skinned object posed at `pose` (through `proxy`, or with its render
// mesh as collision mesh) against the same on the static `twin` (through `twinProxy`, or its render
// mesh): the pair of timings of one column of the spawn table.
Result<std::pair<SpawnTiming, SpawnTiming>> spawnPair(const SkinnedModel& m,
                                                      const std::optional<Proxy>& proxy, const Scene& twin,
                                                      const std::optional<Proxy>& twinProxy,
                                                      const ModelPose& pose, const std::vector<Ray>& rays,
                                                      const Sizes& sizes) {
    const SystemMaker skinned = [&]() -> Result<DecalSystem> {
        Result<DecalSystem> s = holeSystem(skinnedWorld(m, proxy), m.decalSize, rays.size());
        if (!s) return s;
        if (Status p = poseSystem(s.value(), m, pose); !p) return fail(p.error());
        return s;
    };
    const std::vector<std::shared_ptr<const Proxy>> twinProxies = {twinProxy ? shareProxy(*twinProxy)
                                                                             : nullptr};
    const SystemMaker statik = [&] {
        return holeSystem(CollisionWorld::build(twin, twinProxies, oneThreadWorld()), m.decalSize,
                          rays.size());
    };
    Result<std::pair<SpawnTiming, SpawnTiming>> timings =
        spawnSecondsInTurns(skinned, statik, rays, sizes.runs);
    if (!timings) return fail(m.name + ": " + timings.error());
    return timings.value();
}

Result<SpawnRow> measureSpawn(const SkinnedModel& m, const Proxy& proxy, const Sizes& sizes) {
    SceneEvaluator evaluator(m.scene);
    const double t = cycleTime(m, kSpawnPhase);
    const ModelPose pose = modelPoseAt(m, evaluator, t);
    const Mesh posed = meshAt(m, worldPositionsAt(m, evaluator, t));
    const std::vector<Ray> rays = scatteredRays(posed, sizes.spawnRays, 7);
    Scene twin = singleObjectScene(posed, m.name + " posed, static");
    twin.materials = m.scene.materials; // the submeshes name them
    twin.images = m.scene.images;
    auto sameMesh = spawnPair(m, std::nullopt, twin, std::nullopt, pose, rays, sizes);
    if (!sameMesh) return fail(sameMesh.error());
    // Through proxies: the skinned object's deforming proxy against a proxy of the twin's own at the
    // same tolerance.
    ProxySettings settings;
    settings.tolerance = kProxyTolerance;
    settings.toleranceRelative = true;
    Result<Proxy> own = buildProxy(*twin.objects[0].mesh, settings);
    if (!own) return fail(m.name + ": " + own.error());
    auto proxies = spawnPair(m, proxy, twin, own.value(), pose, rays, sizes);
    if (!proxies) return fail(proxies.error());
    return SpawnRow{m.name, rays.size(), sameMesh->first, sameMesh->second, proxies->first, proxies->second};
}

// ---- Drift -----------------------------------------------------------------------------------

// The part of `centre`'s offset from anchor `a` that lies in the plane of a's triangle (the whole
// offset when the triangle has collapsed): how far a decal has slid along the surface.
double alongSurface(const Mesh& mesh, const std::vector<glm::dvec3>& p, const SurfaceAnchor& a,
                    const glm::dvec3& centre) {
    const uint32_t* c = cornersOf(mesh, a);
    const glm::dvec3 off = centre - pointOf(mesh, p, a);
    const glm::dvec3 n = glm::cross(p[c[1]] - p[c[0]], p[c[2]] - p[c[0]]);
    const double n2 = glm::dot(n, n);
    return n2 > 0.0 ? glm::length(off - n * (glm::dot(n, off) / n2)) : glm::length(off);
}

// A decal the library moves, and the render-surface point it was placed on.
struct Anchored {
    DecalHandle handle;
    SurfaceAnchor point;
};

// A decal attached to a joint: its spawn-time world centre taken into the joint's bind space.
struct JointAttached {
    SurfaceAnchor point;
    uint16_t joint = 0;
    glm::dvec3 bindCentre{0.0}; // inverse(J_t0) * centre_t0
};

// Fractions of the decal size, over decals and frames.
struct DriftSamples {
    std::string method;
    std::vector<double> along;
    double wholeMax = 0.0;
    size_t decals = 0;
};

// The world at one time of the cycle, as the drift rows read it.
struct Moment {
    ModelPose pose;
    std::vector<glm::dvec3> positions; // render vertices, world space
    Mesh mesh;                         // with them
};

Moment momentAt(const SkinnedModel& m, double t) {
    SceneEvaluator evaluator(m.scene);
    Moment at{modelPoseAt(m, evaluator, t), worldPositionsAt(m, evaluator, t), {}};
    at.mesh = meshAt(m, at.positions);
    return at;
}

class DriftRun {
public:
    DriftRun(const SkinnedModel& m, DecalSystem onRender, DecalSystem onProxy)
        : m_(m), systems_{std::move(onRender), std::move(onProxy)} {}

    // Poses both systems at `t` and shoots `rays` rays at the posed object into both.
    Status shoot(double t, size_t rays, uint64_t seed) {
        const Moment at = momentAt(m_, t);
        if (Status s = poseBoth(at.pose); !s) return s;
        Result<ClosestPointQuery> query = ClosestPointQuery::create(at.mesh);
        if (!query) return fail(query.error());
        for (const Ray& ray : scatteredRays(at.mesh, rays, seed))
            for (size_t s = 0; s < 2; ++s)
                if (std::optional<Anchored> a = place(systems_[s], ray, query.value(), at)) {
                    anchored_[s].push_back(*a);
                    if (s == 0) attachToJoint(*a, at);
                }
        return {};
    }

    // Poses both systems at `t` and adds every decal's drift there.
    Status measure(double t) {
        const Moment at = momentAt(m_, t);
        if (Status s = poseBoth(at.pose); !s) return s;
        for (size_t s = 0; s < 2; ++s)
            for (const Anchored& a : anchored_[s])
                add(samples_[s], at, a.point, systems_[s].worldBox(a.handle)->center);
        for (const JointAttached& j : joints_)
            add(samples_[2], at, j.point,
                glm::dvec3(at.pose.joints[j.joint] * glm::dvec4(j.bindCentre, 1.0)));
        return {};
    }

    std::vector<DriftSamples> samples() {
        const char* methods[3] = {"skin anchors, render mesh", "skin anchors, deforming proxy",
                                  "nearest joint"};
        const size_t decals[3] = {anchored_[0].size(), anchored_[1].size(), joints_.size()};
        for (size_t s = 0; s < 3; ++s) {
            samples_[s].method = methods[s];
            samples_[s].decals = decals[s];
        }
        return std::vector<DriftSamples>(samples_, samples_ + 3);
    }

private:
    Status poseBoth(const ModelPose& pose) {
        for (DecalSystem& system : systems_)
            if (Status s = poseSystem(system, m_, pose); !s) return s;
        return {};
    }

    std::optional<Anchored> place(DecalSystem& system, const Ray& ray, const ClosestPointQuery& query,
                                  const Moment& at) const {
        const SpawnResult r = system.spawn(ray, 0);
        if (!r.placed() || system.get(r.handle)->object != m_.object) return std::nullopt;
        const glm::dvec3 centre = system.worldBox(r.handle)->center;
        return Anchored{r.handle, nearestPoint(query, at.mesh, at.positions, centre)};
    }

    void attachToJoint(const Anchored& a, const Moment& at) {
        const glm::dvec3 centre = systems_[0].worldBox(a.handle)->center;
        const uint16_t joint = carryingJoint(m_.scene.objects[m_.object].skinWeights, at.positions, centre);
        const glm::dvec3 bind(glm::inverse(at.pose.joints[joint]) * glm::dvec4(centre, 1.0));
        joints_.push_back({a.point, joint, bind});
    }

    void add(DriftSamples& to, const Moment& at, const SurfaceAnchor& point, const glm::dvec3& centre) const {
        to.along.push_back(alongSurface(at.mesh, at.positions, point, centre) / m_.decalSize);
        to.wholeMax =
            std::max(to.wholeMax, glm::length(centre - pointOf(at.mesh, at.positions, point)) / m_.decalSize);
    }

    const SkinnedModel& m_;
    DecalSystem systems_[2]; // render mesh, deforming proxy
    std::vector<Anchored> anchored_[2];
    std::vector<JointAttached> joints_; // the render-mesh system's decals, attached to joints
    DriftSamples samples_[3];
};

Result<std::vector<DriftSamples>> measureDrift(const SkinnedModel& m, const Proxy& proxy,
                                               const Sizes& sizes) {
    const size_t room = sizes.spawnTimes * sizes.raysPerTime;
    Result<DecalSystem> onRender = holeSystem(skinnedWorld(m, std::nullopt), m.decalSize, room);
    Result<DecalSystem> onProxy = holeSystem(skinnedWorld(m, proxy), m.decalSize, room);
    if (!onRender || !onProxy) return fail(m.name + ": " + (onRender ? onProxy.error() : onRender.error()));
    DriftRun run(m, std::move(onRender).value(), std::move(onProxy).value());
    // Spawn times fall between the frames, so that no frame is a decal's own spawn pose.
    for (size_t k = 0; k < sizes.spawnTimes; ++k)
        if (Status s = run.shoot(cycleTime(m, (double(k) + 0.5) / double(sizes.spawnTimes)),
                                 sizes.raysPerTime, 100 + k);
            !s)
            return fail(s.error());
    for (size_t f = 0; f < sizes.frames; ++f)
        if (Status s = run.measure(cycleTime(m, double(f) / double(sizes.frames))); !s)
            return fail(s.error());
    return run.samples();
}

// ---- Accuracy --------------------------------------------------------------------------------

constexpr double kAccuracyPhases[] = {0.0, 0.25, 0.5, 0.75}; // of the cycle
constexpr double kIouTarget = 0.97;
constexpr int kCoverageWidth = 640, kCoverageHeight = 480;

struct AccuracyRow {
    double phase = 0.0;
    size_t rays = 0, placedRender = 0, placedProxy = 0;
    size_t covered = 0;        // pixels the render mesh's decals cover
    double iou = std::nan(""); // NaN: not measured
};

// A camera looking at the centre of the posed mesh from where its bounding sphere just fills the
// height of the view: the whole model in view.
Camera framing(const Mesh& posed) {
    constexpr double kFovYDeg = 45.0;
    const Bounds b = posed.bounds();
    const double diagonal = double(b.diagonal());
    Camera c;
    c.target = glm::dvec3(b.center());
    c.eye = c.target +
            glm::normalize(glm::dvec3(0.6, 0.45, 1.0)) * (0.5 * diagonal / std::sin(kFovYDeg * kPi / 360.0));
    c.fovYDeg = kFovYDeg;
    c.nearPlane = 1e-3 * diagonal;
    return c;
}

// Shots from the eye at `count` area-weighted random points of the posed surface: where the point is
// hidden the shot lands on what hides it, as a player's would.
std::vector<Ray> cameraShots(const Mesh& posed, const Camera& camera, size_t count, uint64_t seed) {
    const SurfaceSampler surface(posed);
    std::vector<Ray> shots;
    Rng rng(seed);
    for (size_t i = 0; i < count && !surface.empty(); ++i) {
        const float u = rng.uniform(), v = rng.uniform(), w = rng.uniform();
        Ray r;
        r.origin = camera.eye;
        r.direction = surface.sample(u, v, w) - camera.eye;
        shots.push_back(r);
    }
    return shots;
}

struct Coverage {
    std::vector<uint8_t> mask;
    size_t placed = 0;
};

// The decals `shots` place on the model posed at `pose` through `proxy` (none: the render mesh),
// drawn by `probe`, whose scene stands in the same pose.
Result<Coverage> shotCoverage(const SkinnedModel& m, const std::optional<Proxy>& proxy, const ModelPose& pose,
                              const std::vector<Ray>& shots, CoverageProbe& probe, const Camera& camera) {
    Result<DecalSystem> system = coverageSystem(skinnedWorld(m, proxy), probe.type(), m.diagonal, 1);
    if (!system) return fail(system.error());
    if (Status s = poseSystem(system.value(), m, pose); !s) return fail(s.error());
    for (const Ray& ray : shots)
        system->spawn(ray, 0);
    if (Status s = probe.renderer().setObjectIds(system->objectIds()); !s) return fail(s.error());
    Result<std::vector<uint8_t>> mask = probe.mask(camera, system->decals());
    if (!mask) return fail(mask.error());
    return Coverage{std::move(mask).value(), size_t(system->stats().placed)};
}

// The same shots at `phase` of the cycle through the proxy and on the render mesh, both drawn with
// the scene posed there.
Result<AccuracyRow> measureAccuracyAt(const SkinnedModel& m, const Proxy& proxy, CoverageProbe& probe,
                                      double phase, size_t rays) {
    SceneEvaluator evaluator(m.scene);
    const double t = cycleTime(m, phase);
    const Mesh posed = meshAt(m, worldPositionsAt(m, evaluator, t));
    const ModelPose pose =
        modelPoseAt(m, evaluator, t); // leaves the evaluator at t, as the renderer takes it
    if (Status s = probe.renderer().setPose(evaluator); !s) return fail(m.name + ": " + s.error());
    const Camera camera = framing(posed);
    const std::vector<Ray> shots = cameraShots(posed, camera, rays, 300 + uint64_t(phase * 100.0));
    Result<Coverage> onRender = shotCoverage(m, std::nullopt, pose, shots, probe, camera);
    if (!onRender) return fail(m.name + ": " + onRender.error());
    Result<Coverage> onProxy = shotCoverage(m, proxy, pose, shots, probe, camera);
    if (!onProxy) return fail(m.name + ": " + onProxy.error());
    const std::vector<uint8_t>& reference = onRender->mask;
    return AccuracyRow{phase,
                       shots.size(),
                       onRender->placed,
                       onProxy->placed,
                       size_t(std::count(reference.begin(), reference.end(), uint8_t(1))),
                       iou(reference, onProxy->mask)};
}

// What the accuracy rows are drawn with: the OpenGL renderer, or why there is none.
struct CoverageContext {
    std::string glRenderer;
    std::string unavailable; // empty: a context is sought for each model
};

// Every phase's row, drawn in a context of the model's own; rows not measured without one (the first
// failure to make one, or --no-render, is kept in `gl` and no later model tries).
Result<std::vector<AccuracyRow>> measureAccuracy(const SkinnedModel& m, const Proxy& proxy,
                                                 const Sizes& sizes, CoverageContext& gl) {
    std::optional<CoverageProbe> probe;
    if (gl.unavailable.empty()) {
        Result<CoverageProbe> p =
            CoverageProbe::create(m.scene, kCoverageWidth, kCoverageHeight, coverageType(m.decalSize));
        if (p) {
            probe.emplace(std::move(p).value());
            gl.glRenderer = probe->glRenderer();
        } else {
            gl.unavailable = p.error();
        }
    }
    std::vector<AccuracyRow> rows;
    for (double phase : kAccuracyPhases) {
        AccuracyRow row{phase, sizes.accuracyRays};
        if (probe) {
            Result<AccuracyRow> r = measureAccuracyAt(m, proxy, *probe, phase, sizes.accuracyRays);
            if (!r) return fail(r.error());
            row = r.value();
        }
        rows.push_back(row);
    }
    return rows;
}

// ---- Drift in the image ------------------------------------------------------------------------

// Decals shot from a camera framing the model at the spawn phase, followed over the cycle in the image
// (ImageDrift.hpp); no rows without an OpenGL context.
Result<std::vector<ImageDriftRow>> measureImageDriftOf(const SkinnedModel& m, const Sizes& sizes,
                                                       const CoverageContext& gl) {
    if (!gl.unavailable.empty()) return std::vector<ImageDriftRow>();
    SceneEvaluator evaluator(m.scene);
    ImageDriftInput in;
    in.scene = &m.scene;
    in.object = m.object;
    in.spawnTime = cycleTime(m, kSpawnPhase);
    for (size_t f = 0; f < sizes.imageFrames; ++f)
        in.frameTimes.push_back(cycleTime(m, double(f) / double(sizes.imageFrames)));
    in.decalSize = m.decalSize;
    const Mesh posed = meshAt(m, worldPositionsAt(m, evaluator, in.spawnTime));
    in.camera = framing(posed);
    in.width = sizes.imageWidth;
    in.height = sizes.imageHeight;
    in.shots = cameraShots(posed, in.camera, 16 * sizes.imageDecals, 900);
    in.decals = sizes.imageDecals;
    Result<std::vector<ImageDriftRow>> rows = measureImageDrift(in);
    if (!rows) return fail(m.name + ": " + rows.error());
    return rows;
}

// ---- Output ----------------------------------------------------------------------------------

std::string verdict(bool met) {
    return met ? "yes" : "no";
}

// Three significant digits: the skin anchors' drift is a rounding error, millionths of a size.
std::string percent(double fraction) {
    return fmt(100.0 * fraction, 3) + "%";
}

struct ModelReport {
    const SkinnedModel* model = nullptr;
    DeformingProxy proxy;
    double proxySeconds = 0.0; // wall time of buildDeformingProxy
    std::vector<PoseRow> pose;
    SpawnRow spawn;
    std::vector<DriftSamples> drift;
    std::vector<AccuracyRow> accuracy;
    std::vector<ImageDriftRow> imageDrift;
};

Json modelJson(const ModelReport& r) {
    const SceneObject& o = r.model->scene.objects[r.model->object];
    Json j;
    j["model"] = r.model->name;
    j["render_triangles"] = o.mesh->triangleCount();
    j["joints"] = r.model->scene.animation.skins[size_t(o.skin)].joints.size();
    j["duration_s"] = number(r.model->duration);
    j["decal_size"] = number(r.model->decalSize);
    j["proxy_seconds"] = number(r.proxySeconds);
    return j;
}

Json poseSection(const std::vector<ModelReport>& reports) {
    Json rows = Json::array();
    std::vector<std::vector<std::string>> table;
    for (const ModelReport& r : reports)
        for (const PoseRow& p : r.pose) {
            const bool met = p.seconds * 1e3 <= kPoseTargetMs;
            table.push_back(
                {p.model, p.collision, std::to_string(p.triangles), fixed(p.seconds * 1e3, 4), verdict(met)});
            rows.push_back({{"model", p.model},
                            {"collision", p.collision},
                            {"triangles", p.triangles},
                            {"ms_per_call", number(p.seconds * 1e3)},
                            {"within_target", met}});
        }
    std::printf("pose update: CollisionWorld::setPose per call\n");
    printTable({"model", "collision", "triangles", "ms per call", "within 0.2 ms"}, table);
    return rows;
}

Json spawnSection(const std::vector<ModelReport>& reports) {
    Json rows = Json::array();
    std::vector<std::vector<std::string>> table;
    for (const ModelReport& r : reports) {
        const SpawnRow& s = r.spawn;
        const bool met = s.ratio() <= kSpawnTargetRatio;
        const bool proxyMet = s.proxyRatio() <= kSpawnTargetRatio;
        table.push_back({s.model, std::to_string(s.rays), std::to_string(s.skinned.placed),
                         fixed(s.skinned.seconds * 1e9, 0), fixed(s.statik.seconds * 1e9, 0),
                         fixed(s.ratio(), 2), verdict(met), fixed(s.skinnedProxy.seconds * 1e9, 0),
                         fixed(s.staticProxy.seconds * 1e9, 0), fixed(s.proxyRatio(), 2), verdict(proxyMet)});
        rows.push_back({{"model", s.model},
                        {"rays", s.rays},
                        {"placed_skinned", s.skinned.placed},
                        {"placed_static", s.statik.placed},
                        {"skinned_ns", number(s.skinned.seconds * 1e9)},
                        {"static_ns", number(s.statik.seconds * 1e9)},
                        {"ratio", number(s.ratio())},
                        {"within_target", met},
                        {"proxy_skinned_ns", number(s.skinnedProxy.seconds * 1e9)},
                        {"proxy_static_ns", number(s.staticProxy.seconds * 1e9)},
                        {"proxy_ratio", number(s.proxyRatio())},
                        {"proxy_within_target", proxyMet}});
    }
    std::printf(
        "\nspawn: on the posed skinned object against the same posed mesh built static, with the render "
        "mesh as collision mesh and through 0.5%% proxies\n");
    printTable({"model", "rays", "placed", "skinned ns", "static ns", "ratio", "within 2x",
                "proxy: skinned ns", "static ns", "ratio", "within 2x"},
               table);
    return rows;
}

Json driftSection(const std::vector<ModelReport>& reports) {
    Json rows = Json::array();
    std::vector<std::vector<std::string>> table;
    for (const ModelReport& r : reports)
        for (const DriftSamples& d : r.drift) {
            const bool measured = !d.along.empty(); // no decal followed: nothing to judge
            const double med = median(d.along), max = percentile(d.along, 1.0);
            const Json met = measured ? Json(max <= kDriftTarget) : Json();
            table.push_back({r.model->name, d.method, std::to_string(d.decals),
                             std::to_string(d.along.size()), measured ? percent(med) : "-",
                             measured ? percent(max) : "-", measured ? percent(d.wholeMax) : "-",
                             measured ? verdict(met.get<bool>()) : "-"});
            rows.push_back({{"model", r.model->name},
                            {"method", d.method},
                            {"decals", d.decals},
                            {"samples", d.along.size()},
                            {"median", measured ? number(med) : Json()},
                            {"max", measured ? number(max) : Json()},
                            {"whole_max", measured ? number(d.wholeMax) : Json()},
                            {"within_target", met}});
        }
    std::printf("\ndrift along the surface from the point placed on, of the decal's size\n");
    printTable({"model", "method", "decals", "samples", "median", "max", "whole max", "max within 2%"},
               table);
    return rows;
}

Json imageDriftSection(const std::vector<ModelReport>& reports, const CoverageContext& gl) {
    Json rows = Json::array();
    std::vector<std::vector<std::string>> table;
    for (const ModelReport& r : reports)
        for (const ImageDriftRow& d : r.imageDrift) {
            const bool measured = d.unavailable.empty() && !d.drift.empty();
            const double med = median(d.drift), max = percentile(d.drift, 1.0);
            const Json met = measured ? Json(max <= kDriftTarget) : Json();
            table.push_back({r.model->name, d.method, std::to_string(d.decals),
                             std::to_string(d.drift.size()), measured ? percent(d.atSpawnMax) : "-",
                             measured ? percent(med) : "-", measured ? percent(max) : "-",
                             measured ? verdict(met.get<bool>()) : "-",
                             std::isnan(d.splatMs) ? "-" : fixed(d.splatMs, 3)});
            rows.push_back({{"model", r.model->name},
                            {"method", d.method},
                            {"unavailable", d.unavailable.empty() ? Json() : Json(d.unavailable)},
                            {"decals", d.decals},
                            {"samples", d.drift.size()},
                            {"at_spawn_max", measured ? number(d.atSpawnMax) : Json()},
                            {"median", measured ? number(med) : Json()},
                            {"max", measured ? number(max) : Json()},
                            {"within_target", met},
                            {"splat_ms", number(d.splatMs)}});
            if (!d.unavailable.empty())
                std::printf("%s, %s: not measured: %s\n", r.model->name.c_str(), d.method.c_str(),
                            d.unavailable.c_str());
        }
    std::printf("\ndrift in the image: the drawn centre (a centre marker's pixels) from the projected point "
                "placed on, of the decal's size in pixels\n");
    if (!gl.unavailable.empty()) {
        std::printf("not measured: %s\n", gl.unavailable.c_str());
        return rows;
    }
    printTable(
        {"model", "method", "decals", "samples", "at spawn", "median", "max", "max within 2%", "splat ms"},
        table);
    return rows;
}

// The smallest IoU measured; NaN when none was.
double minimumIou(const std::vector<ModelReport>& reports) {
    double least = std::nan("");
    for (const ModelReport& r : reports)
        for (const AccuracyRow& a : r.accuracy)
            if (!std::isnan(a.iou) && !(a.iou >= least)) least = a.iou;
    return least;
}

Json accuracySection(const std::vector<ModelReport>& reports, const CoverageContext& gl) {
    Json rows = Json::array();
    std::vector<std::vector<std::string>> table;
    for (const ModelReport& r : reports)
        for (const AccuracyRow& a : r.accuracy) {
            const bool measured = !std::isnan(a.iou);
            const Json met = measured ? Json(a.iou >= kIouTarget) : Json();
            table.push_back({r.model->name, percent(a.phase), fixed(cycleTime(*r.model, a.phase), 3),
                             std::to_string(a.rays), measured ? std::to_string(a.placedRender) : "-",
                             measured ? std::to_string(a.placedProxy) : "-",
                             measured ? std::to_string(a.covered) : "-", measured ? fixed(a.iou, 4) : "-",
                             measured ? verdict(met.get<bool>()) : "-"});
            rows.push_back({{"model", r.model->name},
                            {"phase", a.phase},
                            {"time_s", number(cycleTime(*r.model, a.phase))},
                            {"rays", a.rays},
                            {"placed_render", measured ? Json(a.placedRender) : Json()},
                            {"placed_proxy", measured ? Json(a.placedProxy) : Json()},
                            {"covered_pixels", measured ? Json(a.covered) : Json()},
                            {"iou", number(a.iou)},
                            {"within_target", met}});
        }
    std::printf("\naccuracy: coverage IoU of the shots through the 0.5%% deforming proxy against the render "
                "mesh, posed\n");
    printTable({"model", "of cycle", "time s", "rays", "placed render", "placed proxy", "covered px", "IoU",
                "at least 0.97"},
               table);
    const double least = minimumIou(reports);
    if (std::isnan(least))
        std::printf("coverage IoU not measured: %s\n", gl.unavailable.c_str());
    else
        std::printf("minimum IoU %s: target at least 0.97 %s\n", fixed(least, 4).c_str(),
                    least >= kIouTarget ? "met" : "missed");
    return rows;
}

// `triangles` null: not known (the rest proxy when the posed one was kept).
Json boundRow(const ModelReport& r, const char* proxy, const PoseBound& b, const Json& triangles) {
    const double diagonal = referencedDiagonal(*r.model->scene.objects[r.model->object].mesh);
    return {{"model", r.model->name},
            {"proxy", proxy},
            {"triangles", triangles},
            {"bound", number(b.bound)},
            {"sampled_max", number(b.sampledMax)},
            {"motion", number(b.motion)},
            {"poses", b.poses},
            {"bound_fraction", number(b.bound / diagonal)}};
}

Json boundSection(const std::vector<ModelReport>& reports) {
    Json rows = Json::array();
    for (const ModelReport& r : reports) {
        const DeformingProxy& p = r.proxy;
        const Json kept = p.proxy.mesh.triangleCount();
        rows.push_back(boundRow(r, "deforming", p.poses, kept));
        rows.push_back(boundRow(r, p.restCertified ? "rest" : "rest, sampled", p.restPoses,
                                p.simplifiedPosed ? Json() : kept));
    }
    std::vector<std::vector<std::string>> table;
    for (const Json& row : rows)
        table.push_back({row["model"].get<std::string>(), row["proxy"].get<std::string>(),
                         row["triangles"].is_null() ? "-" : std::to_string(row["triangles"].get<size_t>()),
                         fmt(row["bound"].get<double>(), 4), fmt(row["sampled_max"].get<double>(), 4),
                         fmt(row["motion"].get<double>(), 4), percent(row["bound_fraction"].get<double>())});
    std::printf("\npose bounds over the sampled poses, object units (triangles -: not kept)\n");
    printTable({"model", "proxy", "triangles", "bound", "sampled max", "motion", "of diagonal"}, table);
    return rows;
}

// ---- The command -----------------------------------------------------------------------------

Result<ModelReport> measureModel(const SkinnedModel& m, const Sizes& sizes, CoverageContext& gl) {
    ModelReport r;
    r.model = &m;
    ProxySettings settings;
    settings.tolerance = kProxyTolerance;
    settings.toleranceRelative = true;
    const double t0 = now();
    Result<DeformingProxy> proxy = buildDeformingProxy(m.scene, m.object, settings, sizes.samples);
    if (!proxy) return fail(m.name + ": " + proxy.error());
    r.proxySeconds = now() - t0;
    r.proxy = std::move(proxy).value();
    for (const std::optional<Proxy>& collision :
         {std::optional<Proxy>(), std::optional<Proxy>(r.proxy.proxy)}) {
        Result<PoseRow> row = measurePose(m, collision, sizes);
        if (!row) return fail(row.error());
        r.pose.push_back(row.value());
    }
    Result<SpawnRow> spawn = measureSpawn(m, r.proxy.proxy, sizes);
    if (!spawn) return fail(spawn.error());
    r.spawn = spawn.value();
    Result<std::vector<DriftSamples>> drift = measureDrift(m, r.proxy.proxy, sizes);
    if (!drift) return fail(drift.error());
    r.drift = std::move(drift).value();
    Result<std::vector<AccuracyRow>> accuracy = measureAccuracy(m, r.proxy.proxy, sizes, gl);
    if (!accuracy) return fail(accuracy.error());
    r.accuracy = std::move(accuracy).value();
    Result<std::vector<ImageDriftRow>> image = measureImageDriftOf(m, sizes, gl);
    if (!image) return fail(image.error());
    r.imageDrift = std::move(image).value();
    return r;
}

Result<Sizes> parseSizes(const Args& args) {
    const bool quick = args.has("--quick");
    Sizes s = quick ? quickSizes() : Sizes{};
    Result<uint64_t> frames = parseCount(args.value("--frames", std::to_string(s.frames)), "--frames");
    if (!frames) return fail(frames.error());
    Result<uint64_t> runs = parseCount(args.value("--repeat", std::to_string(s.runs)), "--repeat");
    if (!runs) return fail(runs.error());
    Result<uint64_t> samples = parseCount(args.value("--samples", std::to_string(s.samples)), "--samples");
    if (!samples) return fail(samples.error());
    if (frames.value() == 0 || runs.value() == 0 || samples.value() == 0 || samples.value() > 100000)
        return fail("--frames and --repeat must be positive, --samples in [1, 100000]");
    s.frames = frames.value();
    s.runs = runs.value();
    s.samples = int(samples.value());
    return s;
}

Json report(const std::vector<ModelReport>& reports, const Sizes& sizes, const MachineInfo& machine,
            const CoverageContext& gl) {
    Json j;
    j["command"] = kSkinnedCommand;
    j["machine"] = toJson(machine);
    j["clock"] = "thread CPU time";
    j["embree_threads"] = 1;
    j["runs"] = sizes.runs;
    j["frames"] = sizes.frames;
    j["pose_calls"] = sizes.poseCalls;
    j["spawn_rays"] = sizes.spawnRays;
    j["spawn_phase"] = kSpawnPhase;
    j["spawn_times"] = sizes.spawnTimes;
    j["rays_per_time"] = sizes.raysPerTime;
    j["pose_samples"] = sizes.samples;
    j["decal_size_fraction"] = kSkinnedDecalSizeFraction;
    j["proxy_tolerance"] = kProxyTolerance;
    j["accuracy_rays"] = sizes.accuracyRays;
    j["coverage_size"] = {kCoverageWidth, kCoverageHeight};
    j["coverage"] = gl.unavailable.empty() ? "measured" : gl.unavailable;
    j["gl_renderer"] = gl.glRenderer;
    j["targets"] = {{"pose_update_ms", kPoseTargetMs},
                    {"spawn_ratio", kSpawnTargetRatio},
                    {"drift_fraction", kDriftTarget},
                    {"coverage_iou", kIouTarget}};
    Json models = Json::array();
    for (const ModelReport& r : reports)
        models.push_back(modelJson(r));
    j["models"] = models;
    j["pose_update"] = poseSection(reports);
    j["spawn"] = spawnSection(reports);
    j["drift"] = driftSection(reports);
    j["pose_bounds"] = boundSection(reports);
    j["accuracy"] = accuracySection(reports, gl);
    j["accuracy_min_iou"] = number(minimumIou(reports));
    j["image_drift_size"] = {sizes.imageWidth, sizes.imageHeight};
    j["image_drift"] = imageDriftSection(reports, gl);
    return j;
}

} // namespace

int runSkinnedCommand(int argc, char** argv) {
    int exitCode = 0;
    const std::optional<Args> parsed = commandArgs(argc, argv, kSkinnedCommand, kSkinnedUsage,
                                                   {"--model", "--frames", "--repeat", "--samples", "--json"},
                                                   {"--quick", "--no-render"}, exitCode);
    if (!parsed) return exitCode;
    const Args& args = *parsed;
    if (!args.positional.empty()) return usageError(kSkinnedCommand, "no positional arguments");
    const Result<Sizes> sizes = parseSizes(args);
    if (!sizes) return usageError(kSkinnedCommand, sizes.error());
    const MachineInfo machine = machineInfo();
    std::printf("spatter-bench skinned: %zu frames, %zu runs a row, %d poses a bound\nmachine: %s\n\n",
                sizes->frames, sizes->runs, sizes->samples, describe(machine).c_str());
    std::vector<SkinnedModel> models;
    const std::vector<std::string> specs = args.has("--model") ? std::vector{args.value("--model")} : kModels;
    for (const std::string& spec : specs) {
        Result<SkinnedModel> m = loadSkinnedModel(spec);
        if (!m) {
            std::fprintf(stderr, "spatter-bench skinned: %s\n", m.error().c_str());
            return 1;
        }
        models.push_back(std::move(m).value());
    }
    CoverageContext gl;
    if (args.has("--no-render")) gl.unavailable = "--no-render";
    std::vector<ModelReport> reports;
    for (const SkinnedModel& m : models) {
        Result<ModelReport> r = measureModel(m, sizes.value(), gl);
        if (!r) {
            std::fprintf(stderr, "spatter-bench skinned: %s\n", r.error().c_str());
            return 1;
        }
        reports.push_back(std::move(r).value());
    }
    const Json j = report(reports, sizes.value(), machine, gl);
    if (args.has("--json"))
        if (Status s = writeJson(j, args.value("--json")); !s) {
            std::fprintf(stderr, "spatter-bench skinned: %s\n", s.error().c_str());
            return 1;
        }
    return 0;
}

} // namespace spatter::bench
