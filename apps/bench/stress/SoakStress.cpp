// The persistent decal store under a long run: spawns far past the budget with removals, evictions,
// fades and a moving object, each frame's changes given to the renderer (Renderer::updateDecals).

#include "StressCase.hpp"
#include "StressSupport.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/render/Renderer.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdlib>
#include <deque>

namespace spatter::stress {

namespace {

constexpr double kHalf = 20.0; // the floor spans [-20, 20] in x and z

Scene soakScene() {
    Scene scene = planeScene(kHalf);
    scene.objects.push_back(makeSceneObject("cart", makeBox(glm::vec3(1.0f, 0.5f, 1.0f), 1),
                                            glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.5, 0.0)),
                                            true));
    return scene;
}

std::vector<DecalType> soakTypes() {
    std::vector<DecalType> types = {makeType("mark", 0.3f, 90.0f), makeType("fading", 0.4f, 90.0f),
                                    makeType("cart", 0.2f, 90.0f)};
    types[1].lifetime = 2.0f;
    types[1].fadeOutTime = 0.5f;
    types[1].priority = 1;
    types[2].onDynamic = true;
    types[2].fadeOutTime = 0.25f;
    return types;
}

glm::dmat4 cartAt(int frame) {
    const double a = 0.01 * double(frame);
    return glm::translate(glm::dmat4(1.0), glm::dvec3(8.0 * std::cos(a), 0.5, 8.0 * std::sin(a)));
}

// What a run measures.
struct Soak {
    size_t bufferAtSteadyState = 0, bufferLargest = 0;
    size_t countMismatches = 0, unbalanced = 0, frames = 0;
};

// One frame of play: spawns on the floor and the cart, removals of recent decals, the cart moving, time.
void play(DecalSystem& sys, Renderer& renderer, Rng& rng, std::deque<DecalHandle>& recent, int frame,
          int spawns) {
    for (int k = 0; k < spawns; ++k) {
        const bool onCart = k % 8 == 0;
        const SpawnResult s =
            onCart ? sys.spawnAttached(1, {rng.uniform(-1.0f, 1.0f), 0.5f, rng.uniform(-1.0f, 1.0f)},
                                       {0, 1, 0}, 2)
                   : sys.spawnAttached(0,
                                       {float(kHalf) * rng.uniform(-1.0f, 1.0f), 0.0f,
                                        float(kHalf) * rng.uniform(-1.0f, 1.0f)},
                                       {0, 1, 0}, uint16_t(k % 2));
        if (s.placed()) recent.push_back(s.handle);
        if (recent.size() > 4096) recent.pop_front();
    }
    for (int k = 0; k < spawns / 100 && !recent.empty(); ++k) { // some already evicted: a stale handle
        sys.remove(recent.front());
        recent.pop_front();
    }
    sys.setTransform(1, cartAt(frame));
    renderer.setObjectTransform(1, cartAt(frame));
    sys.update(1.0 / 60.0);
}

// The covered pixels of a coverage frame.
size_t coveredPixels(Renderer& renderer, const Camera& camera, std::string& error) {
    Result<FrameStats> frame = renderer.render(camera, View::Coverage);
    if (!frame) {
        error = frame.error();
        return SIZE_MAX;
    }
    Result<Image> image = renderer.readback();
    if (!image) {
        error = image.error();
        return SIZE_MAX;
    }
    size_t covered = 0;
    for (size_t i = 0; i < image->rgba.size(); i += 4)
        covered += image->rgba[i] > 127 ? 1 : 0;
    return covered;
}

} // namespace

StressResult runSoak(const StressConfig& cfg) {
    StressResult r;
    r.technique = "a persistent GPU store fed by the decal system's change list (DecalSystem::changesSince, "
                  "Renderer::updateDecals): only changed records built and uploaded, the draw order kept "
                  "without sorting, no CPU copy of the records once the GPU culls";
    const size_t spawns = cfg.full ? 10'000'000 : 200'000;
    const int perFrame = cfg.full ? 20'000 : 500;
    DecalSettings ds = unlimitedSettings(cfg.seed);
    ds.budget = cfg.full ? 200'000 : 4'000;
    ds.maxPerObject = ds.budget;
    ds.maxPerCell = 64;
    ds.policy = LimitPolicy::FadeOldest;
    Result<Renderer> renderer = caseRenderer(cfg, 128, 96, r, 0); // culled on the GPU
    if (!renderer) return r;
    const Scene scene = soakScene();
    Result<DecalSystem> sys = DecalSystem::create(scene, ds);
    if (!sys) {
        r.failure(sys.error());
        r.row("decal system", INFINITY, 0.0, 0);
        return r;
    }
    const std::vector<DecalType> types = soakTypes();
    for (const DecalType& t : types)
        sys->registerType(t);
    if (Status s = renderer->setScene(scene); !s) {
        r.failure(s.error());
        r.row("renderer scene", INFINITY, 0.0, 0);
        return r;
    }
    renderer->setDecalTypes(types);
    renderer->setObjectIds(sys->objectIds());
    Camera camera;
    camera.eye = {0.0, 30.0, 0.1};
    camera.target = {0.0, 0.0, 0.0};

    Rng rng(cfg.seed);
    std::deque<DecalHandle> recent;
    Soak soak;
    uint64_t version = 0;
    const int frames = int(spawns / size_t(perFrame));
    std::string error;
    for (int f = 0; f < frames; ++f) {
        play(sys.value(), renderer.value(), rng, recent, f, perFrame);
        const DecalChanges changes = sys->changesSince(version);
        version = changes.version;
        renderer->updateDecals(sys->decals(), changes);
        if (f % 25 != 24) continue;
        Result<FrameStats> frame = renderer->render(camera, View::Final);
        if (!frame) {
            r.failure(frame.error());
            break;
        }
        const DecalStats& s = sys->stats();
        soak.countMismatches += frame->decals != sys->decals().size() ? 1 : 0;
        soak.unbalanced += s.placed != s.alive - s.fading + s.evicted + s.expired + s.removed ? 1 : 0;
        const size_t bytes = renderer->decalMemory().gpuBufferBytes;
        if (f >= frames / 4 && soak.bufferAtSteadyState == 0) soak.bufferAtSteadyState = bytes;
        if (soak.bufferAtSteadyState != 0) soak.bufferLargest = std::max(soak.bufferLargest, bytes);
        ++soak.frames;
    }
    r.row("GPU buffer growth after a quarter of the run, the budget long full (bytes)",
          double(soak.bufferLargest) - double(soak.bufferAtSteadyState), 0.0, soak.frames,
          std::to_string(soak.bufferAtSteadyState) + " bytes for " + std::to_string(sys->decals().size()) +
              " decals at the end, " + std::to_string(sys->stats().placed) + " placed");
    r.row("frames whose renderer decal count differs from the decal system's", double(soak.countMismatches),
          0.0, soak.frames);
    r.row("frames whose decal stats do not balance", double(soak.unbalanced), 0.0, soak.frames);

    // Every decal removed: no pixel of any may be drawn.
    sys->removeObject(0);
    sys->removeObject(1);
    const DecalChanges last = sys->changesSince(version);
    renderer->updateDecals(sys->decals(), last);
    const size_t covered = coveredPixels(renderer.value(), camera, error);
    if (!error.empty()) r.failure(error);
    r.row("pixels covered after every decal is removed", double(covered), 0.0, 128 * 96,
          std::to_string(sys->decals().size()) + " decals left");
    return r;
}

} // namespace spatter::stress
