#include "SkipBench.hpp"

#include "BenchSupport.hpp"
#include "DecalField.hpp"

#include "spatter/core/GalleryScene.hpp"
#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/SceneLoader.hpp"
#include "spatter/placement/CollisionWorld.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/render/GlContext.hpp"

#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace spatter::bench {

namespace {

const char* kSkipCommand = "skip";

const char* kSkipUsage =
    R"(usage: spatter-bench skip [--decals N] [--frames N] [--no-gpu] [--quick] [--json FILE]

What each skip of the design saves, measured with the skip on and forced off in the same run:

  no-id-target        no object-ID target and no ID test when nothing is dynamic; forced off by one
                      dynamic cube in the scene (GPU ms of all passes, N decals in view, 1080p)
  shader-variants     the decal shader built for the features in use; forced off by one more visible
                      decal whose type uses wrap-around, a normal map and a fade (decal pass ms)
  decal-culling       boxes outside the view are not drawn (1,000,000 decals, N in view); forced off by
                      putting the others in view under the floor, with the occlusion test off, where
                      every one is drawn and hidden (decal pass ms; render() CPU ms beside it)
  empty-decal-pass    no normal copy and no decal pass when no decal is in view; forced off by one
                      decal of about one pixel in view (GPU ms of all passes)
  small-mesh-proxy    a mesh under 512 triangles is its own proxy; forced off by smallMeshTriangles 0
                      (buildProxy seconds; a box of 432 triangles, which simplifies to 12)
  proxy-cache         a proxy built before is loaded from the cache; forced off by no cache directory
                      (buildProxy seconds, meshoptimizer at 0.5%)
  static-no-instances static receivers share one Embree scene; forced off by marking every receiver of
                      builtin:gallery dynamic, one instance each (CollisionWorld::build seconds, and
                      spawn ns per ray)
  shared-instances    objects that place one mesh and collider many times take the first one's
                      measured collider bound and trace one Embree scene (the dynamic ones, and the
                      static ones placed four times or more); forced off by giving each copy's render
                      mesh unused vertices of its own (100 copies of the gallery's crate, half dynamic:
                      CollisionWorld::build seconds with a box collider each, intersect ns per ray
                      without colliders)

--decals N  decals in view in the GPU rows (default 10000)   --frames N  timed frames (default 7)
--no-gpu    skip the GPU rows                                --quick     smaller and shorter
--json FILE {"skips": [{"name", "metric", "on", "off", "saving", ...}], ...}
)";

struct Skip {
    std::string name;
    std::string metric;
    double on = std::nan(""), off = std::nan("");
    std::string note;
    std::string error;
};

Skip makeSkip(const char* name, const char* metric) {
    Skip s;
    s.name = name;
    s.metric = metric;
    return s;
}

DecalSettings unlimited(uint64_t seed) {
    DecalSettings s;
    s.seed = seed;
    s.maxPerCell = 1u << 30;
    s.maxPerObject = 1u << 30;
    s.budget = 1u << 30;
    return s;
}

// GPU rows: one renderer at 1080p on the decal field.
class GpuSkips {
public:
    static Result<GpuSkips> create(size_t frames) {
        Result<GlContext> gl = GlContext::createHeadless();
        if (!gl) return fail(gl.error());
        GpuSkips g;
        g.context_ = std::make_unique<GlContext>(std::move(gl).value());
        RendererSettings rs;
        rs.width = 1920;
        rs.height = 1080;
        rs.waitForTimers = true;
        for (bool occlusion : {true, false}) {
            rs.occlusionCulling = occlusion;
            Result<Renderer> r = Renderer::create(*g.context_, rs);
            if (!r) return fail(r.error());
            (occlusion ? g.renderer_ : g.unoccluded_).emplace(std::move(r).value());
        }
        g.view_ = decalFieldView(16.0 / 9.0);
        g.frames_ = frames;
        return g;
    }

    const std::string& glRenderer() const { return context_->info().renderer; }

    // GPU times of `decals` of `types` on the decal field (with a dynamic cube when `dynamicCube`),
    // with the occlusion test of the decal culling or without.
    Result<FrameTimes> frame(bool dynamicCube, const std::vector<DecalType>& types,
                             const std::vector<Decal>& decals, bool occlusion = true) {
        Renderer& r = occlusion ? *renderer_ : *unoccluded_;
        if (Status s = r.setScene(decalFieldScene(view_, dynamicCube)); !s) return fail(s.error());
        if (dynamicCube)
            if (Status s = r.setObjectIds({0, 1}); !s) return fail(s.error());
        r.setDecalTypes(types);
        r.setDecals(decals);
        return timeFrames(r, view_.camera, RenderOptions{}, 1, frames_, 30.0);
    }

    const DecalFieldView& view() const { return view_; }

private:
    GpuSkips() = default;
    std::unique_ptr<GlContext> context_;
    std::optional<Renderer> renderer_, unoccluded_; // with the occlusion test, without
    DecalFieldView view_;
    size_t frames_ = 7;
};

DecalType plainType(const char* name) {
    DecalType t;
    t.name = name;
    t.normalMap = false;
    t.depthFade = DepthFade::None;
    return t;
}

void gpuSkips(GpuSkips& g, size_t visible, bool quick, std::vector<Skip>& out) {
    const DecalFieldView& v = g.view();
    DecalType def;
    def.name = "default";
    const std::vector<Decal> field = decalField(v, visible, visible, 0.015, 0, 1);
    auto addGpu = [&](Skip s, const Result<FrameTimes>& on, const Result<FrameTimes>& off,
                      bool decalPassOnly) {
        if (!on || !off) {
            s.error = !on ? on.error() : off.error();
        } else {
            s.on = decalPassOnly ? on->decalsMs : on->totalMs;
            s.off = decalPassOnly ? off->decalsMs : off->totalMs;
            if (s.note.empty())
                s.note = "variants '" + on->last.decalVariant + "' / '" + off->last.decalVariant + "'";
        }
        out.push_back(s);
    };

    {
        Skip s = makeSkip("no-id-target", "GPU ms, all passes");
        const Result<FrameTimes> on = g.frame(false, {def}, field);
        const Result<FrameTimes> off = g.frame(true, {def}, field);
        addGpu(s, on, off, false);
    }
    {
        Skip s = makeSkip("shader-variants", "decal pass GPU ms");
        std::vector<Decal> more = field;
        std::vector<Decal> extra = decalField(v, 1, 1, 0.015, 1, 2);
        more.push_back(extra[0]);
        DecalType full;
        full.name = "full";
        full.wrapAround = true;
        const Result<FrameTimes> on = g.frame(false, {plainType("plain"), full}, field);
        const Result<FrameTimes> off = g.frame(false, {plainType("plain"), full}, more);
        addGpu(s, on, off, true);
    }
    {
        const size_t world = quick ? 100000 : 1000000;
        Skip s = makeSkip("decal-culling", "decal pass GPU ms");
        std::vector<Decal> culled = decalField(v, world, visible, 0.015, 0, 1);
        const Result<FrameTimes> on = g.frame(false, {def}, culled);
        // The same decals, those out of view moved into view under the floor, without the occlusion
        // test (which would cull them there): drawn, every pixel hidden.
        std::vector<Decal> hidden = culled;
        Rng rng(3);
        for (size_t i = visible; i < hidden.size(); ++i) {
            hidden[i].center.x = float(v.halfWidth * 0.9 * double(rng.uniform(-1.0f, 1.0f)));
            hidden[i].center.z = float(v.halfHeight * 0.9 * double(rng.uniform(-1.0f, 1.0f)));
            hidden[i].center.y = -1.0f;
        }
        const Result<FrameTimes> off = g.frame(false, {def}, hidden, false);
        if (on && off)
            s.note = std::to_string(world) + " decals, " + std::to_string(on->last.decalsDrawn) + " / " +
                     std::to_string(off->last.decalsDrawn) + " drawn; render() CPU ms " +
                     fixed(on->cpuMs, 1) + " / " + fixed(off->cpuMs, 1);
        addGpu(s, on, off, true);
    }
    {
        Skip s = makeSkip("empty-decal-pass", "GPU ms, all passes");
        std::vector<Decal> away = decalField(v, 1000, 0, 0.015, 0, 1);
        const Result<FrameTimes> on = g.frame(false, {def}, away);
        std::vector<Decal> one = away;
        std::vector<Decal> dot = decalField(v, 1, 1, 1.0 / 1080.0, 0, 4);
        one.push_back(dot[0]);
        const Result<FrameTimes> off = g.frame(false, {def}, one);
        if (on && off)
            s.note = "decal pass " + fixed(on->decalsMs, 3) + " / " + fixed(off->decalsMs, 3) + " ms (" +
                     (on->last.decalPassSkipped ? "skipped" : "ran") + " / " +
                     (off->last.decalPassSkipped ? "skipped" : "ran") + ")";
        addGpu(s, on, off, false);
    }
}

// Fastest of `repeats` runs of `f`, seconds.
template <class F> double fastest(size_t repeats, F&& f) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < repeats; ++i) {
        const double start = now();
        f();
        best = std::min(best, now() - start);
    }
    return best;
}

// `copies` placements of the gallery's crate, every second one dynamic, with `colliders` each with a
// box collider around it (as a level's props come with UCX_ boxes); with `distinct`, each copy's
// render mesh gets unused copies of a vertex of its own count, so that no two are the same input.
Scene crateCopies(size_t copies, bool distinct, bool colliders) {
    const Scene gallery = makeGalleryScene();
    SceneObject crate;
    for (const SceneObject& o : gallery.objects)
        if (o.name.rfind("crate", 0) == 0) crate = o;
    const Bounds b = crate.mesh->bounds();
    Mesh collider = makeBox(0.5f * (b.max - b.min), 1);
    for (glm::vec3& p : collider.positions)
        p += 0.5f * (b.max + b.min);
    Scene s;
    s.source = "gallery crate copies";
    s.materials = gallery.materials;
    for (size_t i = 0; i < copies; ++i) {
        SceneObject o = crate;
        o.name = "crate_copy_" + std::to_string(i);
        o.transform =
            glm::translate(glm::dmat4(1.0), glm::dvec3(3.0 * double(i % 10), 0.0, 3.0 * double(i / 10)));
        o.dynamic = i % 2 == 1;
        if (colliders) o.collider = collider;
        if (distinct) {
            Mesh& m = o.editMesh();
            for (size_t k = 0; k <= i; ++k) {
                m.positions.push_back(m.positions[0]);
                m.normals.push_back(m.normals[0]);
                if (!m.uvs.empty()) m.uvs.push_back(m.uvs[0]);
                if (!m.tangents.empty()) m.tangents.push_back(m.tangents[0]);
            }
        }
        s.objects.push_back(std::move(o));
    }
    return s;
}

// The thread CPU time of intersect per ray of `rays` in the world of `scene`, fastest of `repeats`.
double nsPerRay(const Scene& scene, const std::vector<Ray>& rays, size_t repeats) {
    const Result<CollisionWorld> world = CollisionWorld::build(scene);
    if (!world || rays.empty()) return std::nan("");
    double best = std::numeric_limits<double>::infinity();
    for (size_t p = 0; p < repeats; ++p) {
        const double start = threadCpuNow();
        for (const Ray& r : rays)
            world->intersect(r);
        best = std::min(best, threadCpuNow() - start);
    }
    return best * 1e9 / double(rays.size());
}

void sharedInstancesSkips(bool quick, std::vector<Skip>& out) {
    Skip build = makeSkip("shared-instances", "CollisionWorld::build s");
    Skip trace = makeSkip("shared-instances", "intersect ns per ray");
    const size_t copies = quick ? 20 : 100;
    const size_t repeats = quick ? 1 : 3;
    const std::string what = std::to_string(copies) + " copies of the gallery's crate, " +
                             std::to_string(copies / 2) + " dynamic, ";
    // With colliders, whose bounds are measured once: the build. The crates as their own collision
    // meshes: the trace.
    const auto buildSeconds = [repeats](const Scene& scene) {
        return fastest(repeats, [&] { CollisionWorld::build(scene); });
    };
    build.on = buildSeconds(crateCopies(copies, false, true));
    build.off = buildSeconds(crateCopies(copies, true, true));
    build.note = what + "each with a box collider";
    const Scene shared = crateCopies(copies, false, false), distinct = crateCopies(copies, true, false);
    const std::vector<Ray> rays = scatteredRays(mergeReceivers(shared), quick ? 2000 : 20000, 9);
    trace.on = nsPerRay(shared, rays, repeats);
    trace.off = nsPerRay(distinct, rays, repeats);
    trace.note = what + "their own collision meshes (" +
                 std::to_string(shared.objects[0].mesh->triangleCount()) + " triangles)";
    out.push_back(build);
    out.push_back(trace);
}

void cpuSkips(bool quick, std::vector<Skip>& out) {
    const size_t repeats = quick ? 1 : 3;
    {
        Skip s = makeSkip("small-mesh-proxy", "buildProxy s");
        const Mesh box = makeBox(glm::vec3(0.5f), 6); // 432 triangles on six flat faces
        ProxySettings own;
        ProxySettings forced;
        forced.smallMeshTriangles = 0;
        Result<Proxy> a = buildProxy(box, own), b = buildProxy(box, forced);
        s.on = fastest(repeats, [&] { buildProxy(box, own); });
        s.off = fastest(repeats, [&] { buildProxy(box, forced); });
        if (a && b)
            s.note = std::to_string(box.triangleCount()) + " triangles -> " +
                     std::to_string(a->proxyTriangles) + " (h 0) / " + std::to_string(b->proxyTriangles) +
                     " (h " + fmt(100.0 * b->errorBound / double(box.bounds().diagonal()), 2) +
                     "% of the diagonal)";
        out.push_back(s);
    }
    {
        Skip s = makeSkip("proxy-cache", "buildProxy s");
        std::string spec = quick ? "builtin:gallery" : "stanford-bunny.obj";
        if (resolveInput(spec).empty()) spec = "builtin:gallery";
        Result<InputMesh> in = loadInputMesh(spec, 0);
        if (!in) {
            s.error = in.error();
        } else {
            const ScratchDirectory cache("skip-cache");
            ProxySettings ps;
            ps.backend = ProxyBackend::MeshOpt;
            ps.cacheDirectory = cache.path();
            Result<Proxy> first = buildProxy(in->mesh, ps);
            Result<Proxy> again = buildProxy(in->mesh, ps);
            ProxySettings none = ps;
            none.cacheDirectory.clear();
            if (first && again && again->cached) {
                s.on = fastest(repeats, [&] { buildProxy(in->mesh, ps); });
                s.off = fastest(repeats, [&] { buildProxy(in->mesh, none); });
                s.note = in->name + ", " + std::to_string(in->mesh.triangleCount()) + " -> " +
                         std::to_string(first->proxyTriangles) + " triangles";
            } else {
                s.error = "the second build was not a cache hit";
            }
        }
        out.push_back(s);
    }
    {
        Skip build = makeSkip("static-no-instances", "CollisionWorld::build s");
        Skip spawn = makeSkip("static-no-instances", "spawn ns per ray");
        GallerySettings gs;
        gs.detail = quick ? 0 : 2;
        const Scene scene = makeGalleryScene(gs);
        Scene instanced = scene;
        size_t receivers = 0;
        for (SceneObject& o : instanced.objects) {
            receivers += o.receivesDecals ? 1 : 0;
            o.dynamic = true;
        }
        const std::vector<Ray> rays = scatteredRays(mergeReceivers(scene), quick ? 1000 : 8000, 5);
        double seconds[2] = {0, 0}, ns[2] = {0, 0};
        for (int k = 0; k < 2; ++k) {
            const Scene& sc = k == 0 ? scene : instanced;
            seconds[k] = fastest(repeats, [&] { CollisionWorld::build(sc); });
            Result<DecalSystem> sys = DecalSystem::create(sc, unlimited(1));
            if (!sys) {
                build.error = spawn.error = sys.error();
                break;
            }
            DecalType t;
            t.name = "skip";
            const uint16_t ti = sys->registerType(t).value();
            double best = std::numeric_limits<double>::infinity();
            for (size_t p = 0; p < repeats; ++p) {
                const double start = threadCpuNow();
                for (const Ray& r : rays)
                    sys->spawn(r, ti);
                best = std::min(best, threadCpuNow() - start);
            }
            ns[k] = best * 1e9 / double(rays.size());
        }
        build.on = seconds[0];
        build.off = seconds[1];
        spawn.on = ns[0];
        spawn.off = ns[1];
        build.note = spawn.note = "builtin:gallery (detail " + std::to_string(gs.detail) + "), " +
                                  std::to_string(receivers) + " receivers, " +
                                  std::to_string(scene.triangleCount()) + " triangles";
        out.push_back(build);
        out.push_back(spawn);
    }
    sharedInstancesSkips(quick, out);
}

} // namespace

int runSkipCommand(int argc, char** argv) {
    int exitCode = 0;
    const std::optional<Args> parsed =
        commandArgs(argc, argv, kSkipCommand, kSkipUsage, {"--decals", "--frames", "--json"},
                    {"--no-gpu", "--quick"}, exitCode);
    if (!parsed) return exitCode;
    const Args& args = *parsed;
    if (!args.positional.empty()) return usageError(kSkipCommand, "no positional arguments");
    const bool quick = args.has("--quick");
    Result<uint64_t> decals = parseCount(args.value("--decals", quick ? "1000" : "10000"), "--decals");
    Result<uint64_t> frames = parseCount(args.value("--frames", quick ? "2" : "7"), "--frames");
    if (!decals) return usageError(kSkipCommand, decals.error());
    if (!frames) return usageError(kSkipCommand, frames.error());
    if (decals.value() == 0 || frames.value() == 0)
        return usageError(kSkipCommand, "counts must be positive");

    const MachineInfo machine = machineInfo();
    std::printf("spatter-bench skip\nmachine: %s\n", describe(machine).c_str());
    std::fflush(stdout);
    std::vector<Skip> skips;
    std::string glRenderer;
    if (!args.has("--no-gpu")) {
        Result<GpuSkips> g = GpuSkips::create(frames.value());
        if (g) {
            glRenderer = g->glRenderer();
            std::printf("GL: %s\n", glRenderer.c_str());
            gpuSkips(g.value(), decals.value(), quick, skips);
        } else {
            std::printf("GPU rows skipped: no OpenGL context (%s)\n", g.error().c_str());
        }
    }
    cpuSkips(quick, skips);

    std::vector<std::vector<std::string>> table;
    for (const Skip& s : skips) {
        if (!s.error.empty()) {
            table.push_back({s.name, s.metric, "-", "-", "-", "error: " + s.error});
            continue;
        }
        table.push_back(
            {s.name, s.metric, fmt(s.on, 4), fmt(s.off, 4), fixed(s.off / s.on, 2) + "x", s.note});
    }
    std::printf("\n");
    printTable({"skip", "metric", "on", "forced off", "off/on", "note"}, table);

    if (args.has("--json")) {
        Json j;
        j["command"] = "skip";
        j["machine"] = toJson(machine);
        j["gl_renderer"] = glRenderer;
        j["decals_in_view"] = decals.value();
        j["skips"] = Json::array();
        for (const Skip& s : skips) {
            Json x;
            x["name"] = s.name;
            x["metric"] = s.metric;
            x["on"] = number(s.on);
            x["off"] = number(s.off);
            x["saving"] = number(s.off / s.on);
            x["note"] = s.note;
            if (!s.error.empty()) x["error"] = s.error;
            j["skips"].push_back(x);
        }
        if (Status s = writeJson(j, args.value("--json")); !s) {
            std::cerr << "spatter-bench skip: " << s.error() << "\n";
            return 1;
        }
    }
    return 0;
}

} // namespace spatter::bench
