#include "Headless.hpp"

#include "DecalMarker.hpp"
#include "GallerySim.hpp"
#include "GalleryView.hpp"
#include "SkinTracking.hpp"
#include "SurfaceLaying.hpp"
#include "Tracking.hpp"

#include "spatter/render/GlContext.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace spatter::gallery {

namespace {

constexpr double kShotInterval = 1.0 / 20.0; // seconds of motion between two shots

// The scripted shooter: single shots over the gallery and at the targets, and every 40 shots a
// burst of automatic fire (volumetric bullet holes) at one spot, which fills its area cell so the
// oldest decals give way.
class Script {
public:
    explicit Script(Rng& rng) : rng_(rng) {}

    std::pair<Ray, ShotKind> next(const GallerySim& sim, const Camera& camera, double aspect) {
        ++count_;
        if (count_ % 40 == 20) {
            burst_ = 14;
            burstAim_ = glm::dvec2(rng_.uniform(-0.6f, 0.6f), rng_.uniform(-0.5f, 0.3f));
        }
        if (burst_ > 0) {
            --burst_;
            const glm::dvec2 spread(rng_.uniform(-0.01f, 0.01f), rng_.uniform(-0.01f, 0.01f));
            const glm::dvec2 aim = burstAim_ + spread;
            return {rayThrough(camera, aspect, aim.x, aim.y), ShotKind::Crater};
        }
        Ray ray;
        const std::vector<uint32_t>& moving = sim.movingObjects();
        if (!moving.empty() && rng_.uniform() < 0.45f) {
            // At a target: its current bounds, jittered inside them.
            const uint32_t object = moving[rng_.below(uint32_t(moving.size()))];
            const DBounds b = sim.decals().world().worldBounds(object);
            const glm::dvec3 jitter(rng_.uniform(-0.3f, 0.3f), rng_.uniform(-0.3f, 0.3f), 0.0);
            ray.origin = camera.eye;
            ray.direction = b.center() + jitter * b.extent() - camera.eye;
        } else {
            ray = rayThrough(camera, aspect, rng_.uniform(-0.95f, 0.95f), rng_.uniform(-0.95f, 0.95f));
        }
        const float pick = rng_.uniform();
        const ShotKind kind = pick < 0.65f  ? ShotKind::Bullet
                              : pick < 0.9f ? ShotKind::Paint
                                            : ShotKind::Scorch;
        return {ray, kind};
    }

private:
    Rng& rng_;
    int count_ = 0;
    int burst_ = 0;
    glm::dvec2 burstAim_{0.0};
};

// Follows a decal on a target riding its rail (the smallest fully visible one, which its target does
// not clip, so that the centre of its pixels moves like its centre; the newest among equals) across
// frames of motion, in the world and in the rendered coverage image, and checks it still lies on its
// target's collision surface.
Result<nlohmann::ordered_json> trackTargetDecal(GallerySim& sim, Renderer& renderer, const Camera& camera) {
    const Decal* followed = nullptr;
    for (const Decal& d : sim.decals().decals()) {
        const bool onRail = std::any_of(sim.rails().begin(), sim.rails().end(),
                                        [&](const Rail& rail) { return rail.object == d.object; });
        if (!onRail || d.opacity < 1.0f) continue;
        if (!followed || d.size.x < followed->size.x ||
            (d.size.x == followed->size.x && d.spawnTime > followed->spawnTime))
            followed = &d;
    }
    if (!followed) return fail("no decal landed on a moving target to follow");
    const uint32_t id = followed->id;
    const int w = renderer.settings().width, h = renderer.settings().height;

    struct Sample {
        glm::dvec3 world;
        glm::dvec2 projected;
        std::optional<glm::dvec2> imaged;
    };
    auto sample = [&](const Decal& decal) -> Result<Sample> {
        for (const Rail& rail : sim.rails())
            renderer.setObjectTransform(rail.object, sim.transform(rail.object));
        Result<std::optional<glm::dvec2>> imaged = decalCentroid(renderer, camera, decal);
        if (!imaged) return fail(imaged.error());
        const glm::dvec3 world = sim.decals().worldBox(decal).center;
        return Sample{world, tracking::pixelOf(camera, w, h, world), imaged.value()};
    };
    Result<Sample> a = sample(*followed);
    if (!a) return fail(a.error());
    for (int i = 0; i < 15; ++i)
        sim.advance(1.0 / 30.0);
    const Decal* later = findDecal(sim.decals(), id);
    if (!later) return fail("the followed decal disappeared while its target moved");
    Result<Sample> b = sample(*later);
    if (!b) return fail(b.error());

    // Is the decal still on its target? Cast at its centre along its axis.
    const WorldDecal box = sim.decals().worldBox(*later);
    const glm::dvec3 axis(box.frame.normal);
    Ray probe;
    probe.origin = box.center + axis * double(box.halfDepth + 0.5);
    probe.direction = -axis;
    const std::optional<Hit> hit = sim.decals().world().intersect(probe);

    nlohmann::ordered_json out;
    out["object"] = sim.scene().objects[later->object].name;
    out["decal_id"] = id;
    out["world_moved_m"] = glm::length(b->world - a->world);
    out["on_target_after_move"] = hit && hit->object == later->object &&
                                  glm::length(hit->position - box.center) <= double(box.halfDepth);
    if (a->imaged && b->imaged) {
        out["image_moved_px"] = glm::length(*b->imaged - *a->imaged);
        // The decal may be clipped to its target, so compare motions rather than positions.
        out["image_motion_error_px"] = glm::length((*b->imaged - *a->imaged) - (b->projected - a->projected));
    } else {
        out["image_moved_px"] = nullptr;
        out["image_motion_error_px"] = nullptr;
    }
    return out;
}

// Loads options.loadPath into the sim when given, and says what came back.
Result<nlohmann::ordered_json> loadSaved(GallerySim& sim, const GalleryOptions& options) {
    if (options.loadPath.empty()) return nlohmann::ordered_json();
    Result<DecalLoadReport> r = sim.load(options.loadPath);
    if (!r) return fail(r.error());
    for (const std::string& line : r->droppedObjects)
        std::cout << "spatter-gallery: " << options.loadPath << ": " << line << "\n";
    return nlohmann::ordered_json{
        {"file", options.loadPath}, {"decals", r->decals}, {"dropped", r->droppedDecals}};
}

} // namespace

int runHeadless(const GalleryOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    Result<GallerySim> sim = GallerySim::create(options);
    if (!sim) {
        std::cerr << "spatter-gallery: " << sim.error() << "\n";
        return 1;
    }
    Result<nlohmann::ordered_json> loaded = loadSaved(sim.value(), options);
    if (!loaded) {
        std::cerr << "spatter-gallery: " << loaded.error() << "\n";
        return 1;
    }
    Result<GlContext> gl = GlContext::createHeadless();
    if (!gl) {
        std::cerr << "spatter-gallery: no OpenGL 4.5 context: " << gl.error() << "\n";
        return 1;
    }
    RendererSettings settings;
    settings.width = options.width ? options.width : 960;
    settings.height = options.height ? options.height : 540;
    settings.waitForTimers = true;
    settings.faceNormals = true; // the normals of the surface the shots' decals are laid on
    Result<Renderer> renderer = Renderer::create(gl.value(), settings);
    if (!renderer) {
        std::cerr << "spatter-gallery: " << renderer.error() << "\n";
        return 1;
    }
    if (Status s = prepareRenderer(renderer.value(), sim.value()); !s) {
        std::cerr << "spatter-gallery: " << s.error() << "\n";
        return 1;
    }

    const Camera camera = startCamera(sim->scene());
    const double aspect = double(settings.width) / settings.height;
    Rng rng(options.seed, 0x5ca1ab1e);
    const int frameEvery = std::max(1, options.shots / 24);
    int frames = 0;
    double gpuMs = 0.0;
    std::string glRenderer;
    SurfaceLaying laying; // the shots' decals laid on the drawn surface a frame after they land
    auto renderFrame = [&]() -> Status {
        syncRenderer(renderer.value(), sim.value());
        Result<FrameStats> stats = renderer->render(camera, View::Final);
        if (!stats) return fail(stats.error());
        ++frames;
        gpuMs += stats->gpu.totalMs();
        glRenderer = stats->glRenderer;
        laying.lay(renderer.value(), sim.value(), false);
        return laying.search(renderer.value(), sim.value());
    };

    Script script(rng);
    for (int shot = 0; shot < options.shots; ++shot) {
        sim->advance(kShotInterval);
        const auto [ray, kind] = script.next(sim.value(), camera, aspect);
        laying.shot(sim->shoot(ray, kind), sim.value());
        if ((shot + 1) % frameEvery == 0)
            if (Status s = renderFrame(); !s) {
                std::cerr << "spatter-gallery: " << s.error() << "\n";
                return 1;
            }
    }

    Result<nlohmann::ordered_json> tracked = trackTargetDecal(sim.value(), renderer.value(), camera);
    Result<nlohmann::ordered_json> skinned = trackSkinnedDecal(sim.value(), renderer.value(), camera);
    laying.lay(renderer.value(), sim.value(), true);
    if (Status s = renderFrame(); !s) {
        std::cerr << "spatter-gallery: " << s.error() << "\n";
        return 1;
    }
    Result<Image> image = renderer->readback();
    if (!image) {
        std::cerr << "spatter-gallery: " << image.error() << "\n";
        return 1;
    }

    if (!options.savePath.empty())
        if (Status s = sim->save(options.savePath); !s) {
            std::cerr << "spatter-gallery: " << s.error() << "\n";
            return 1;
        }
    std::error_code ec;
    std::filesystem::create_directories(options.outDir, ec);
    const std::string png = options.outDir + "/gallery.png", json = options.outDir + "/gallery.json";
    if (Status s = writePng(png, image.value()); !s) {
        std::cerr << "spatter-gallery: " << s.error() << "\n";
        return 1;
    }

    const DecalStats& st = sim->decals().stats();
    nlohmann::ordered_json out;
    out["shots"] = sim->counters().shots;
    out["placed"] = st.placed;
    out["rejected"] = st.rejectedTotal();
    out["evicted"] = st.evicted;
    out["on_moving_targets"] = sim->counters().onMovingTargets;
    out["on_skinned_targets"] = sim->counters().onSkinnedTargets;
    out["laid_on_drawn_surface"] = laying.laid();
    out["removed_on_drawn_surface"] = laying.removed();
    out["refused_placed_on_drawn_surface"] = laying.spawned();
    out["replaced_on_drawn_surface"] = laying.replaced();
    out["alive"] = st.alive;
    out["frames"] = frames;
    out["placement_us_per_shot"] =
        sim->counters().shots ? 1e6 * sim->counters().placementSeconds / double(sim->counters().shots) : 0.0;
    out["gpu_ms_per_frame"] = frames ? gpuMs / frames : 0.0;
    out["render_triangles"] = sim->renderTriangles();
    out["proxy_triangles"] = sim->proxyTriangles();
    out["error_bound"] = sim->errorBound();
    nlohmann::ordered_json reasons;
    for (size_t i = 1; i < kSpawnStatusCount; ++i)
        if (st.rejected[i]) reasons[toString(SpawnStatus(i))] = st.rejected[i];
    out["rejected_by_reason"] = reasons.is_null() ? nlohmann::ordered_json::object() : reasons;
    out["expired"] = st.expired;
    out["tolerance_percent"] = sim->tolerancePercent();
    out["proxy_build_s"] = sim->proxySeconds();
    out["tracked_decal"] = tracked ? tracked.value() : nlohmann::ordered_json{{"error", tracked.error()}};
    out["skinned_decal"] = skinned ? skinned.value() : nlohmann::ordered_json{{"error", skinned.error()}};
    out["size"] = {settings.width, settings.height};
    out["seed"] = options.seed;
    if (!loaded->is_null()) out["loaded"] = loaded.value();
    if (!options.savePath.empty()) out["saved"] = options.savePath;
    out["gl_renderer"] = glRenderer;
    out["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::ofstream file(json);
    file << out.dump(2) << "\n";
    if (!file) {
        std::cerr << "spatter-gallery: cannot write " << json << "\n";
        return 1;
    }
    std::cout << "spatter-gallery: " << st.placed << " of " << sim->counters().shots << " shots placed ("
              << sim->counters().onMovingTargets << " on moving targets), " << st.alive << " alive, "
              << st.evicted << " evicted; wrote " << png << " and " << json << "\n";
    return 0;
}

} // namespace spatter::gallery
