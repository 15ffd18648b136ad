#include "GallerySim.hpp"

#include "spatter/core/DeformingProxy.hpp"
#include "spatter/core/ProxyInstances.hpp"
#include "spatter/core/SceneLoader.hpp"
#include "spatter/core/SkinnedDummy.hpp"
#include "spatter/core/Threads.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <mutex>
#include <thread>

namespace spatter::gallery {

using Clock = std::chrono::steady_clock;

static std::string defaultCacheDir() {
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/spatter";
    if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/spatter";
    return "";
}

// The gallery's decal types: bullet holes, paint in three colours, scorch marks.
static std::vector<std::pair<ShotKind, DecalType>> galleryTypes() {
    std::vector<std::pair<ShotKind, DecalType>> types;
    DecalType bullet;
    bullet.name = "bullet_hole";
    bullet.size = {0.15f, 0.15f};
    bullet.sizeJitter = 0.25f;
    bullet.maxAngleDeg = 85.0f;
    bullet.fadeOutTime = 1.5f;
    bullet.texture = int(DecalTexture::BulletHole);
    bullet.roughness = 0.9f;
    types.push_back({ShotKind::Bullet, bullet});

    // A bullet hole with real depth: a crater behind a stencil-cut hole in the surface.
    DecalType crater = bullet;
    crater.name = "bullet_crater";
    crater.size = {0.12f, 0.12f};
    crater.volumetric = true;
    types.push_back({ShotKind::Crater, crater});

    const glm::vec4 paints[] = {
        {0.95f, 0.2f, 0.15f, 1.0f}, {0.15f, 0.55f, 0.95f, 1.0f}, {0.95f, 0.8f, 0.1f, 1.0f}};
    const char* paintNames[] = {"paint_red", "paint_blue", "paint_yellow"};
    for (int i = 0; i < 3; ++i) {
        DecalType paint;
        paint.name = paintNames[i];
        paint.size = {0.8f, 0.8f};
        paint.sizeJitter = 0.3f;
        paint.maxAngleDeg = 88.0f;
        paint.fadeOutTime = 2.0f;
        paint.texture = int(DecalTexture::Paint);
        paint.tint = paints[i];
        paint.wrapAround = true;
        paint.roughness = 0.35f;
        types.push_back({ShotKind::Paint, paint});
    }

    DecalType scorch;
    scorch.name = "scorch";
    scorch.size = {0.6f, 0.6f};
    scorch.sizeJitter = 0.2f;
    scorch.maxAngleDeg = 85.0f;
    scorch.fadeOutTime = 2.0f;
    scorch.texture = int(DecalTexture::Scorch);
    scorch.normalMap = false;
    types.push_back({ShotKind::Scorch, scorch});
    return types;
}

bool isBanner(const SceneObject& object) {
    return object.name.rfind("banner_", 0) == 0;
}

Result<GallerySim> GallerySim::create(const GalleryOptions& options) {
    Result<Scene> scene = loadScene(options.scene);
    if (!scene) return fail(scene.error());
    GallerySim sim;
    sim.options_ = options;
    if (sim.options_.cacheDir.empty()) sim.options_.cacheDir = defaultCacheDir();
    sim.scene_ = std::make_unique<Scene>(std::move(scene).value());
    if (sim.scene_->source == "builtin:gallery") // in front of the arch, left of the way in
        addSkinnedDummy(*sim.scene_, glm::translate(glm::dmat4(1.0), glm::dvec3(-2.2, 0.0, 0.8)));
    for (const std::string& w : sim.scene_->warnings)
        std::fprintf(stderr, "spatter-gallery: warning: %s\n", w.c_str());
    if (!sim.scene_->animation.animations.empty()) {
        sim.evaluator_ = std::make_unique<SceneEvaluator>(*sim.scene_);
        for (uint32_t i = 0; i < sim.scene_->objects.size(); ++i)
            if (sim.scene_->objects[i].node >= 0) sim.animated_.push_back(i);
    }
    sim.rng_ = Rng(options.seed, 0x9a11e7);

    // Rails: every dynamic receiver slides along world X and turns about the vertical; the
    // gallery's banners wave in place instead (GalleryView).
    for (uint32_t i = 0; i < sim.scene_->objects.size(); ++i) {
        const SceneObject& o = sim.scene_->objects[i];
        if (!o.dynamic || !o.receivesDecals) continue;
        sim.moving_.push_back(i);
        if (isBanner(o) || (o.node >= 0 && sim.evaluator_)) continue;
        const Bounds b = o.mesh->bounds();
        Rail rail;
        rail.object = i;
        rail.base = o.transform;
        rail.amplitude = std::max(0.3, 1.6 * double(std::max(b.extent().x, b.extent().z)));
        rail.speed = 0.6 + 0.25 * double(sim.rails_.size() % 3);
        rail.phase = 2.1 * double(sim.rails_.size());
        rail.turn = 0.45;
        sim.rails_.push_back(rail);
    }
    if (Status s = sim.rebuildProxies(options.tolerancePercent); !s) return fail(s.error());
    return sim;
}

Status GallerySim::registerTypes() {
    types_.clear();
    for (auto& kindTypes : typeOf_)
        kindTypes.clear();
    for (const auto& [kind, type] : galleryTypes()) {
        Result<uint16_t> index = system_->registerType(type);
        if (!index) return fail(index.error());
        typeOf_[int(kind)].push_back(index.value());
        types_.push_back(type);
    }
    return {};
}

Status GallerySim::rebuildProxies(float tolerancePercent) {
    Result<ProxySet> set = buildProxies(tolerancePercent);
    if (!set) return fail(set.error());
    return useProxies(std::move(set).value());
}

namespace {

// The objects whose proxies are built, one for the objects that share a mesh (the targets, the
// banners), the longest builds first: a deforming object's, which measures the poses of its
// animations (in scene order the dummy's came last and took 0.42 s of a 0.8 s start while the other
// threads had nothing left), then the others by their triangles. The threads then finish together.
std::vector<size_t> buildOrder(const Scene& scene, const std::vector<size_t>& sources) {
    std::vector<size_t> order;
    for (size_t i = 0; i < scene.objects.size(); ++i)
        if (scene.objects[i].receivesDecals && sources[i] == i) order.push_back(i);
    auto cost = [&](size_t i) {
        const SceneObject& o = scene.objects[i];
        return std::make_pair(takesDeformingProxy(o), o.mesh->triangleCount());
    };
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return cost(a) > cost(b); });
    return order;
}

} // namespace

Result<ProxySet> GallerySim::buildProxies(float tolerancePercent, std::atomic<float>* progress) const {
    const Clock::time_point start = Clock::now();
    ProxySettings settings;
    settings.tolerance = tolerancePercent / 100.0f;
    settings.toleranceRelative = true;
    settings.cacheDirectory = options_.cacheDir;
    // The fast path, one object per thread: a cold start builds the whole gallery in seconds. Each
    // build takes its share of the cores rather than all of them (on two cores the gallery's 21
    // objects build in 0.86x of the time that way).
    settings.backend = ProxyBackend::MeshOpt;
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const unsigned builders = std::min(8u, cores);
    settings.threads = std::clamp(cores / builders, 1u, kMaxThreads); // above kMaxThreads a build refuses
    ProxySet set;
    set.tolerancePercent = tolerancePercent;
    set.proxies.resize(scene_->objects.size());
    std::vector<std::string> errors(scene_->objects.size());
    std::atomic<size_t> next{0}, done{0};
    std::mutex say;
    const std::vector<size_t> sources = proxySources(*scene_);
    const std::vector<size_t> order = buildOrder(*scene_, sources);
    size_t totalTriangles = 0;
    std::atomic<size_t> doneTriangles{0};
    for (size_t i : order)
        totalTriangles += scene_->objects[i].mesh->triangleCount();
    auto work = [&]() {
        for (size_t k = next++; k < order.size(); k = next++) {
            const size_t i = order[k];
            const SceneObject& o = scene_->objects[i];
            Result<Proxy> proxy = buildObjectProxy(*scene_, i, settings);
            const size_t finished = ++done;
            const size_t triangles = doneTriangles += o.mesh->triangleCount();
            const double fraction = double(triangles) / double(std::max<size_t>(totalTriangles, 1));
            if (progress) progress->store(float(fraction));
            if (proxy && !proxy->cached) { // a cold build: say how far it is
                const std::lock_guard<std::mutex> lock(say);
                std::fprintf(stderr, "spatter-gallery: proxies %3d%%: built %s (%zu of %zu, %.2f s)\n",
                             int(100.0 * fraction), o.name.c_str(), finished, order.size(), proxy->seconds);
            }
            if (proxy)
                set.proxies[i] = shareProxy(std::move(proxy).value());
            else
                errors[i] = "proxy of " + o.name + ": " + proxy.error();
        }
    };
    std::vector<std::thread> threads(builders - 1);
    for (std::thread& t : threads)
        t = std::thread(work);
    work();
    for (std::thread& t : threads)
        t.join();
    for (const std::string& e : errors)
        if (!e.empty()) return fail(e);
    for (size_t i = 0; i < scene_->objects.size(); ++i)
        if (sources[i] != i) set.proxies[i] = set.proxies[sources[i]];
    set.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return set;
}

Status GallerySim::useProxies(ProxySet set) {
    const Clock::time_point start = Clock::now();
    std::vector<Mesh> meshes(scene_->objects.size());
    for (size_t i = 0; i < set.proxies.size() && i < meshes.size(); ++i)
        if (set.proxies[i]) meshes[i] = set.proxies[i]->mesh;
    Result<CollisionWorld> world = CollisionWorld::build(*scene_, set.proxies);
    if (!world) return fail(world.error());
    for (const std::string& warning : world->warnings())
        std::fprintf(stderr, "spatter-gallery: warning: %s\n", warning.c_str());
    DecalSettings decalSettings;
    decalSettings.seed = options_.seed;
    decalSettings.cellSize = 0.5f;
    decalSettings.maxPerCell = 6;
    decalSettings.policy = LimitPolicy::FadeOldest;
    decalSettings.budget = 20000;
    decalSettings.maxPerObject = 400;
    Result<DecalSystem> system = DecalSystem::create(std::move(world).value(), decalSettings);
    if (!system) return fail(system.error());
    system_.emplace(std::move(system).value());
    ++systemNumber_;
    proxyMeshes_ = std::move(meshes);
    if (Status s = registerTypes(); !s) return s;
    for (const Rail& rail : rails_)
        system_->setTransform(rail.object, transform(rail.object));
    pose();
    counters_ = {};
    tolerancePercent_ = set.tolerancePercent;
    proxySeconds_ = set.seconds + std::chrono::duration<double>(Clock::now() - start).count();
    return {};
}

void GallerySim::pose() {
    if (!evaluator_) return;
    const double duration = scene_->animation.animations[0].duration;
    const double t = options_.startTime + time_;
    evaluator_->evaluate(0, duration > 0.0 ? t - duration * std::floor(t / duration) : 0.0);
    static const std::vector<glm::dmat4> noJoints;
    for (uint32_t object : animated_) {
        const SceneObject& o = scene_->objects[object];
        if (!o.dynamic || !o.receivesDecals) continue;
        if (o.deforms())
            system_->setPose(object, evaluator_->objectTransform(object),
                             o.skin >= 0 ? evaluator_->jointMatrices(size_t(o.skin)) : noJoints,
                             evaluator_->morphWeights(object));
        else
            system_->setTransform(object, evaluator_->objectTransform(object));
    }
}

glm::dmat4 GallerySim::transform(uint32_t object) const {
    if (evaluator_ && object < scene_->objects.size() && scene_->objects[object].node >= 0)
        return evaluator_->objectTransform(object);
    for (const Rail& rail : rails_) {
        if (rail.object != object) continue;
        const double slide = rail.amplitude * std::sin(rail.speed * time_ + rail.phase);
        const double turn = rail.turn * std::sin(0.7 * rail.speed * time_ + 1.3 * rail.phase);
        glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(slide, 0.0, 0.0)) * rail.base;
        const glm::dvec3 origin(m[3]);
        m[3] = glm::dvec4(0.0, 0.0, 0.0, 1.0);
        m = glm::rotate(glm::dmat4(1.0), turn, glm::dvec3(0.0, 1.0, 0.0)) * m;
        m[3] = glm::dvec4(origin, 1.0);
        return m;
    }
    return object < scene_->objects.size() ? scene_->objects[object].transform : glm::dmat4(1.0);
}

void GallerySim::advance(double dt) {
    time_ += dt;
    for (const Rail& rail : rails_)
        system_->setTransform(rail.object, transform(rail.object));
    pose();
    system_->update(dt);
}

GallerySim::Shot GallerySim::shoot(const Ray& ray, ShotKind kind) {
    const std::vector<uint16_t>& candidates = typeOf_[int(kind)];
    Shot shot{ray, candidates[rng_.below(uint32_t(candidates.size()))], {}};
    const Clock::time_point start = Clock::now();
    shot.result = system_->spawn(ray, shot.type);
    counters_.placementSeconds += std::chrono::duration<double>(Clock::now() - start).count();
    ++counters_.shots;
    countPlaced(shot.result);
    return shot;
}

void GallerySim::countPlaced(const SpawnResult& result) {
    if (!result.placed()) return;
    const Decal* decal = system_->get(result.handle);
    if (decal && scene_->objects[decal->object].dynamic) ++counters_.onMovingTargets;
    if (decal && system_->world().deforms(decal->object)) ++counters_.onSkinnedTargets;
}

SpawnResult GallerySim::spawnOnDrawnSurface(const Shot& shot, const glm::dvec3& point,
                                            const glm::dvec3& normal) {
    SpawnResult result = system_->spawnOnDrawnSurface(shot.ray, point, normal, shot.type);
    countPlaced(result);
    return result;
}

SpawnResult GallerySim::replaceOnDrawnSurface(const Shot& shot, const glm::dvec3& point,
                                              const glm::dvec3& normal) {
    SpawnResult result = system_->replaceOnDrawnSurface(shot.result.handle, shot.ray, point, normal);
    countPlaced(result);
    return result;
}

Status GallerySim::save(const std::string& path) const {
    return saveDecalsToFile(*system_, path);
}

Result<DrawnSurfaceLaying> GallerySim::layOnDrawnSurface(DecalHandle handle, const glm::dvec3& point,
                                                         const glm::dvec3& normal) {
    return system_->layOnDrawnSurface(handle, point, normal);
}

Result<DecalLoadReport> GallerySim::load(const std::string& path) {
    Result<DecalLoadReport> r = loadDecalsFromFile(*system_, path);
    if (r) {
        ++systemNumber_;
        time_ = system_->time();
        pose();
    }
    return r;
}

std::vector<uint8_t> GallerySim::objectIds() const {
    return system_->objectIds();
}

size_t GallerySim::proxyTriangles() const {
    return system_->world().triangleCount();
}

double GallerySim::errorBound() const {
    double h = 0.0;
    for (uint32_t i = 0; i < scene_->objects.size(); ++i)
        h = std::max(h, system_->world().worldErrorBound(i));
    return h;
}

void GallerySim::setPaintWrapAround(bool on) {
    for (uint16_t index : typeOf_[int(ShotKind::Paint)])
        types_[index].wrapAround = on;
}

} // namespace spatter::gallery
