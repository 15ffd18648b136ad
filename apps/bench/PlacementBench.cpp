#include "PlacementBench.hpp"

#include "BenchSupport.hpp"
#include "RawEmbree.hpp"

#include "spatter/core/GalleryScene.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <benchmark/benchmark.h>

#include <array>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace spatter::bench {

namespace {

const char* kPlacementCommand = "placement";

const char* kPlacementUsage =
    R"(usage: spatter-bench placement [MESH] [--backend meshopt|openmesh|auto|render] [--tolerance T%]
                               [--rays N] [--batches N] [--batch-size N] [--cone DEG] [--burst-cone DEG]
                               [--min-time S]
                               [--repetitions N] [--seed N] [--quick] [--json FILE]

What spawning costs over tracing the same ray with raw Embree, on the same collision proxy and the
same rays, measured in one run with Google Benchmark (repetitions randomly interleaved, medians):

  raw_single    rtcIntersect1 per ray on an Embree triangle scene of the proxy
  raw_packet    rtcIntersect16 on packets of 16 consecutive rays of the set
  world_single  CollisionWorld::intersect (validation, double-precision clipping and refinement,
                watertight user-geometry triangles, order-independent closest hit)
  world_batch   CollisionWorld::intersectBatch on batches of --batch-size rays
  spawn         DecalSystem::spawn (the above plus the decal: frame, size, limits, handle),
                the decals projected along the shot (the default)
  spawn_normal  the same with a type projected along the normal: what the shot's axis costs
                (shot_over_normal)
  spawn_batch   DecalSystem::spawnBatch on batches of --batch-size rays, one thread

Three ray sets: 'scattered' (rays from random points around the mesh to random surface points),
'shotgun' (--batches shots, each --batch-size rays from one origin in a --cone degree cone) and
'burst' (the same in a --burst-cone degree cone).
Targets: spawn within 1.25x of raw_single on scattered rays (spawn_over_raw); spawn_batch at least
1.3x faster per decal than spawn on shotgun batches (batch_speedup).

MESH       anything loadScene reads, or a file in the shared data (default: stanford-bunny.obj when
           the shared data is there, else builtin:gallery; with --quick, a coarse gallery)
--backend  proxy backend (default meshopt); 'render' traces the render mesh itself
--tolerance proxy tolerance, % of the bounding diagonal (default 0.5%)
--rays N   scattered rays (default 4096)        --batches N  shotgun shots (default 256)
--batch-size N  rays per batch (default 16)     --cone DEG   shotgun cone apex angle (default 10)
--burst-cone DEG  burst cone apex angle (default 3)
--min-time S    Google Benchmark's minimum time per repetition (default 0.3)
--repetitions N repetitions of each measurement (default 7)
--quick    small and short: for the smoke test (256 rays, 16 shots, 3 repetitions of 0.01 s)
--embree-config CONFIG  Embree device configuration for both sides, e.g. "isa=avx2" (default: Embree's)
--filter REGEX  run only the measurements whose "set/method" name matches (for profiling)
--json FILE     the numbers as JSON: raw_single_ns, spawn_ns, spawn_over_raw and shot_over_normal
                of the scattered rays; raw_packet_ns, spawn_batch_ns and batch_speedup of the
                shotgun shots; targets: {spawn_over_raw_met, batch_speedup_met} (null for a set left
                out); sets: every figure of every set of rays
)";

// Collects the per-iteration real time (ns) of every repetition, by benchmark name.
class Collector : public benchmark::BenchmarkReporter {
public:
    bool ReportContext(const Context&) override { return true; }
    void ReportRuns(const std::vector<Run>& runs) override {
        for (const Run& r : runs) {
            if (r.run_type != Run::RT_Iteration || r.error_occurred) continue;
            times[r.run_name.function_name].push_back(r.GetAdjustedCPUTime());
        }
    }
    std::map<std::string, std::vector<double>> times;
};

struct RaySet {
    std::string name;
    std::vector<Ray> rays;
    std::vector<std::vector<Ray>> batches; // consecutive slices of batch-size rays
};

std::vector<std::vector<Ray>> slices(const std::vector<Ray>& rays, size_t size) {
    std::vector<std::vector<Ray>> out;
    for (size_t i = 0; i < rays.size(); i += size)
        out.emplace_back(rays.begin() + std::ptrdiff_t(i),
                         rays.begin() + std::ptrdiff_t(std::min(rays.size(), i + size)));
    return out;
}

struct Method {
    const char* key;
    const char* label;
};
constexpr std::array<Method, 7> kMethods{{
    {"raw_single", "raw rtcIntersect1"},
    {"raw_packet", "raw rtcIntersect16"},
    {"world_single", "CollisionWorld::intersect"},
    {"world_batch", "CollisionWorld::intersectBatch"},
    {"spawn", "DecalSystem::spawn"},
    {"spawn_normal", "DecalSystem::spawn, along the normal"},
    {"spawn_batch", "DecalSystem::spawnBatch"},
}};

} // namespace

int runPlacementCommand(int argc, char** argv) {
    Result<Args> parsed = parseArgs(argc, argv,
                                    {"--backend", "--tolerance", "--rays", "--batches", "--batch-size",
                                     "--cone", "--burst-cone", "--min-time", "--repetitions", "--seed",
                                     "--filter", "--embree-config", "--json"},
                                    {"--quick", "--help", "-h"});
    if (!parsed) return usageError(kPlacementCommand, parsed.error());
    const Args& args = parsed.value();
    if (args.has("--help") || args.has("-h")) {
        std::cout << kPlacementUsage;
        return 0;
    }
    if (args.positional.size() > 1) return usageError(kPlacementCommand, "at most one MESH");
    if (args.has("--filter"))
        if (Status s = checkFilter(args.value("--filter"), "--filter"); !s)
            return usageError(kPlacementCommand, s.error());
    const bool quick = args.has("--quick");

    auto count = [&](const std::string& name, uint64_t fallback) -> Result<uint64_t> {
        return args.has(name) ? parseCount(args.value(name), name) : Result<uint64_t>(fallback);
    };
    Result<uint64_t> rayCount = count("--rays", quick ? 256 : 4096);
    Result<uint64_t> batchCount = count("--batches", quick ? 16 : 256);
    Result<uint64_t> batchSize = count("--batch-size", 16);
    Result<uint64_t> repetitions = count("--repetitions", quick ? 3 : 7);
    Result<uint64_t> seed = count("--seed", 1);
    Result<double> cone = parseNumber(args.value("--cone", "10"), "--cone");
    Result<double> burstCone = parseNumber(args.value("--burst-cone", "3"), "--burst-cone");
    Result<double> minTime = parseNumber(args.value("--min-time", quick ? "0.01" : "0.3"), "--min-time");
    std::string tolText = args.value("--tolerance", "0.5%");
    if (!tolText.empty() && tolText.back() == '%') tolText.pop_back();
    Result<double> tolerance = parseNumber(tolText, "--tolerance");
    for (const std::string& e :
         {rayCount.error(), batchCount.error(), batchSize.error(), repetitions.error(), seed.error(),
          cone.error(), burstCone.error(), minTime.error(), tolerance.error()})
        if (!e.empty()) return usageError(kPlacementCommand, e);
    if (rayCount.value() == 0 || batchCount.value() == 0 || batchSize.value() == 0 ||
        repetitions.value() == 0)
        return usageError(kPlacementCommand, "counts must be positive");
    if (!(cone.value() > 0.0 && cone.value() < 180.0) ||
        !(burstCone.value() > 0.0 && burstCone.value() < 180.0))
        return usageError(kPlacementCommand, "--cone and --burst-cone must be in (0, 180)");
    if (!(minTime.value() > 0.0)) return usageError(kPlacementCommand, "--min-time must be positive");
    if (!(tolerance.value() > 0.0 && tolerance.value() < 100.0))
        return usageError(kPlacementCommand, "--tolerance must be in (0, 100)%");
    const std::string backendName = args.value("--backend", "meshopt");
    std::optional<ProxyBackend> backend;
    if (backendName == "meshopt")
        backend = ProxyBackend::MeshOpt;
    else if (backendName == "openmesh")
        backend = ProxyBackend::OpenMesh;
    else if (backendName == "auto")
        backend = ProxyBackend::Auto;
    else if (backendName != "render")
        return usageError(kPlacementCommand, "--backend must be meshopt, openmesh, auto or render");

    // The mesh.
    InputMesh input;
    if (!args.positional.empty() || !quick) {
        std::string spec = args.positional.empty() ? std::string("stanford-bunny.obj") : args.positional[0];
        if (args.positional.empty() && resolveInput(spec).empty()) spec = "builtin:gallery";
        Result<InputMesh> loaded = loadInputMesh(spec, 0);
        if (!loaded) {
            std::cerr << "spatter-bench placement: " << loaded.error() << "\n";
            return 1;
        }
        input = std::move(loaded).value();
    } else {
        GallerySettings coarse;
        coarse.detail = 0;
        input.name = "gallery-detail0";
        input.source = "builtin:gallery (detail 0)";
        input.mesh = mergeReceivers(makeGalleryScene(coarse));
        input.diagonal = referencedDiagonal(input.mesh);
    }

    // The proxy both sides trace.
    Mesh proxyMesh = input.mesh;
    double errorBound = 0.0;
    if (backend) {
        ProxySettings ps;
        ps.backend = *backend;
        ps.tolerance = float(tolerance.value() / 100.0);
        Result<Proxy> proxy = buildProxy(input.mesh, ps);
        if (!proxy) {
            std::cerr << "spatter-bench placement: proxy of " << input.name << ": " << proxy.error() << "\n";
            return 1;
        }
        proxyMesh = proxy->mesh;
        errorBound = proxy->errorBound;
    }
    const Scene scene = singleObjectScene(proxyMesh, input.name);
    std::vector<std::shared_ptr<const Proxy>> noProxies;

    std::vector<RaySet> sets(3);
    sets[0].name = "scattered";
    sets[0].rays = scatteredRays(input.mesh, rayCount.value(), seed.value());
    sets[1].name = "shotgun";
    sets[1].rays =
        shotgunRays(input.mesh, batchCount.value(), batchSize.value(), cone.value(), seed.value() + 1);
    sets[2].name = "burst";
    sets[2].rays =
        shotgunRays(input.mesh, batchCount.value(), batchSize.value(), burstCone.value(), seed.value() + 2);
    for (RaySet& s : sets)
        s.batches = slices(s.rays, batchSize.value());

    DecalSettings ds;
    ds.seed = seed.value();
    ds.cellSize = float(input.diagonal / 40.0);
    DecalType type;
    type.name = "bench";
    type.size = glm::vec2(float(0.02 * input.diagonal));
    DecalType alongNormal = type;
    alongNormal.name = "bench-normal";
    alongNormal.projection = Projection::Normal;

    // One decal system per ray set and spawning method, so that neither sees the other's decals.
    struct Setup {
        std::optional<RawEmbree> raw;
        std::vector<DecalSystem> systems; // spawn, spawn_batch, statuses, spawn_normal
        uint16_t type = 0;
        uint16_t normalType = 0; // the same type projected along the normal
    };
    std::vector<Setup> setups(sets.size());
    for (size_t k = 0; k < sets.size(); ++k) {
        Result<RawEmbree> raw =
            RawEmbree::build(proxyMesh, RawGeometry::Triangles, args.value("--embree-config"));
        if (!raw) {
            std::cerr << "spatter-bench placement: " << raw.error() << "\n";
            return 1;
        }
        setups[k].raw.emplace(std::move(raw).value());
        setups[k].raw->prepare(sets[k].rays);
        for (int s = 0; s < 4; ++s) {
            WorldSettings ws;
            ws.deviceConfig = args.value("--embree-config");
            Result<CollisionWorld> world = CollisionWorld::build(scene, {}, ws);
            if (!world) {
                std::cerr << "spatter-bench placement: " << world.error() << "\n";
                return 1;
            }
            Result<DecalSystem> sys = DecalSystem::create(std::move(world).value(), ds);
            if (!sys) {
                std::cerr << "spatter-bench placement: " << sys.error() << "\n";
                return 1;
            }
            setups[k].type = sys->registerType(type).value();
            setups[k].normalType = sys->registerType(alongNormal).value();
            setups[k].systems.push_back(std::move(sys).value());
        }
    }

    // What the rays do (untimed): hits of each path, and the spawn statuses.
    Json setJson = Json::object();
    std::vector<std::array<size_t, kSpawnStatusCount>> statuses(sets.size());
    for (size_t k = 0; k < sets.size(); ++k) {
        Setup& su = setups[k];
        DecalSystem& sys = su.systems[2];
        std::array<size_t, kSpawnStatusCount>& st = statuses[k];
        st.fill(0);
        size_t worldHits = 0;
        for (const Ray& r : sets[k].rays) {
            worldHits += sys.world().intersect(r).has_value();
            st[size_t(sys.spawn(r, su.type).status)]++;
        }
        Json j;
        j["rays"] = sets[k].rays.size();
        j["raw_hits"] = su.raw->traceSingle();
        j["world_hits"] = worldHits;
        Json sj = Json::object();
        for (size_t s = 0; s < kSpawnStatusCount; ++s)
            if (st[s]) sj[toString(SpawnStatus(s))] = st[s];
        j["spawn_statuses"] = sj;
        setJson[sets[k].name] = j;
    }

    // The measurements.
    std::vector<std::string> gbArgs = {"spatter-bench", "--benchmark_min_time=" + fmt(minTime.value(), 6),
                                       "--benchmark_repetitions=" + std::to_string(repetitions.value()),
                                       "--benchmark_enable_random_interleaving=true"};
    if (args.has("--filter")) gbArgs.push_back("--benchmark_filter=" + args.value("--filter"));
    std::vector<char*> gbArgv;
    for (std::string& a : gbArgs)
        gbArgv.push_back(a.data());
    int gbArgc = int(gbArgv.size());
    benchmark::Initialize(&gbArgc, gbArgv.data());
    for (size_t k = 0; k < sets.size(); ++k) {
        RaySet& set = sets[k];
        Setup& su = setups[k];
        auto add = [&](const char* method, std::function<void()> body) {
            const std::string name = set.name + "/" + method;
            benchmark::RegisterBenchmark(name.c_str(), [body](benchmark::State& state) {
                for (auto _ : state)
                    body();
            })->Unit(benchmark::kNanosecond);
        };
        add("raw_single", [&] { benchmark::DoNotOptimize(su.raw->traceSingle()); });
        add("raw_packet", [&] { benchmark::DoNotOptimize(su.raw->tracePackets()); });
        add("world_single", [&] {
            const CollisionWorld& w = su.systems[0].world();
            for (const Ray& r : set.rays)
                benchmark::DoNotOptimize(w.intersect(r));
        });
        add("world_batch", [&] {
            const CollisionWorld& w = su.systems[0].world();
            for (const std::vector<Ray>& b : set.batches)
                benchmark::DoNotOptimize(w.intersectBatch(b));
        });
        add("spawn", [&] {
            for (const Ray& r : set.rays)
                benchmark::DoNotOptimize(su.systems[0].spawn(r, su.type));
        });
        add("spawn_normal", [&] {
            for (const Ray& r : set.rays)
                benchmark::DoNotOptimize(su.systems[3].spawn(r, su.normalType));
        });
        add("spawn_batch", [&] {
            std::vector<SpawnResult> results;
            for (const std::vector<Ray>& b : set.batches) {
                su.systems[1].spawnBatch(b, su.type, results);
                benchmark::DoNotOptimize(results.data());
            }
        });
    }
    std::printf("spatter-bench placement: %s, %zu proxy triangles (%s), %s\n", input.name.c_str(),
                proxyMesh.triangleCount(), backendName.c_str(), describe(machineInfo()).c_str());
    std::fflush(stdout);
    Collector collector;
    benchmark::RunSpecifiedBenchmarks(&collector);
    benchmark::ClearRegisteredBenchmarks();

    auto perRay = [&](size_t k, const char* method) {
        auto it = collector.times.find(sets[k].name + "/" + method);
        if (it == collector.times.end() || it->second.empty()) return std::nan("");
        return median(it->second) / double(sets[k].rays.size());
    };
    std::vector<std::vector<std::string>> table;
    for (size_t k = 0; k < sets.size(); ++k) {
        const double raw = perRay(k, "raw_single");
        Json& j = setJson[sets[k].name];
        for (const Method& m : kMethods) {
            const double ns = perRay(k, m.key);
            j[std::string(m.key) + "_ns"] = number(ns);
            if (std::isnan(ns)) continue; // left out by --filter
            table.push_back(
                {sets[k].name, m.label, fixed(ns, 1), std::isnan(raw) ? "-" : fixed(ns / raw, 2) + "x"});
        }
        j["spawn_over_raw"] = number(perRay(k, "spawn") / raw);
        j["batch_speedup"] = number(perRay(k, "spawn") / perRay(k, "spawn_batch"));
        j["shot_over_normal"] = number(perRay(k, "spawn") / perRay(k, "spawn_normal"));
    }
    const double spawnOverRaw = perRay(0, "spawn") / perRay(0, "raw_single");
    const double batchSpeedup = perRay(1, "spawn") / perRay(1, "spawn_batch");
    std::printf("\n");
    printTable({"rays", "method", "ns/ray", "vs raw single"}, table);
    // The summary lines of the sets measured (--filter may leave some out).
    const double burstSpawn = perRay(2, "spawn") / perRay(2, "spawn_batch");
    const double burstTrace = perRay(2, "world_single") / perRay(2, "world_batch");
    std::printf("\n");
    if (!std::isnan(spawnOverRaw))
        std::printf("spawn_over_raw (scattered) %.2fx, target <= 1.25x: %s\n", spawnOverRaw,
                    spawnOverRaw <= 1.25 ? "met" : "missed");
    if (!std::isnan(batchSpeedup))
        std::printf(
            "batch_speedup (shotgun, %u rays per shot in a %g degree cone) %.2fx, target >= 1.3x: %s\n",
            unsigned(batchSize.value()), cone.value(), batchSpeedup, batchSpeedup >= 1.3 ? "met" : "missed");
    const double shotOverNormal = perRay(0, "spawn") / perRay(0, "spawn_normal");
    if (!std::isnan(shotOverNormal))
        std::printf("shot_over_normal (scattered) %.3fx: spawn along the shot against along the normal\n",
                    shotOverNormal);
    if (!std::isnan(burstSpawn) || !std::isnan(burstTrace))
        std::printf(
            "burst: spawn_batch %.2fx and intersectBatch %.2fx as fast per ray as one by one (%g degree "
            "cone)\n",
            burstSpawn, burstTrace, burstCone.value());
    for (size_t k = 0; k < sets.size(); ++k) {
        std::printf("%s: %zu rays, spawn statuses:", sets[k].name.c_str(), sets[k].rays.size());
        for (size_t s = 0; s < kSpawnStatusCount; ++s)
            if (statuses[k][s]) std::printf(" %s %zu", toString(SpawnStatus(s)), statuses[k][s]);
        std::printf("\n");
    }

    if (args.has("--json")) {
        Json j;
        j["command"] = "placement";
        j["machine"] = toJson(machineInfo());
        j["mesh"] = input.name;
        j["render_triangles"] = input.mesh.triangleCount();
        j["backend"] = backendName;
        j["tolerance_rel"] = backend ? tolerance.value() / 100.0 : 0.0;
        j["proxy_triangles"] = proxyMesh.triangleCount();
        j["error_bound_rel"] = errorBound / input.diagonal;
        j["batch_size"] = batchSize.value();
        j["cone_deg"] = cone.value();
        j["burst_cone_deg"] = burstCone.value();
        j["repetitions"] = repetitions.value();
        j["min_time_s"] = minTime.value();
        j["embree_config"] = args.value("--embree-config");
        j["raw_single_ns"] = number(perRay(0, "raw_single"));
        j["raw_packet_ns"] = number(perRay(1, "raw_packet"));
        j["spawn_ns"] = number(perRay(0, "spawn"));
        j["spawn_batch_ns"] = number(perRay(1, "spawn_batch"));
        j["spawn_over_raw"] = number(spawnOverRaw);
        j["batch_speedup"] = number(batchSpeedup);
        j["shot_over_normal"] = number(shotOverNormal);
        j["targets"] = {
            {"spawn_over_raw_met", std::isnan(spawnOverRaw) ? Json() : Json(spawnOverRaw <= 1.25)},
            {"batch_speedup_met", std::isnan(batchSpeedup) ? Json() : Json(batchSpeedup >= 1.3)}};
        j["sets"] = setJson;
        if (Status s = writeJson(j, args.value("--json")); !s) {
            std::cerr << "spatter-bench placement: " << s.error() << "\n";
            return 1;
        }
    }
    return 0;
}

} // namespace spatter::bench
