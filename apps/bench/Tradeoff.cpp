#include "Tradeoff.hpp"

#include "BenchSupport.hpp"
#include "CoverageProbe.hpp"
#include "DrawnSurface.hpp"
#include "IouBreakdown.hpp"
#include "ThreejsPeer.hpp"

#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/core/SceneLoader.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/render/Camera.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace spatter::bench {

namespace {

const char* kTradeoffCommand = "tradeoff";

const char* kTradeoffUsage =
    R"(usage: spatter-bench tradeoff MESH|SCENE [--subdivide N] [--backends LIST] [--tolerances LIST]
                              [--rays N] [--batch-size N] [--passes N] [--cap-seconds S]
                              [--openmesh-max-triangles N] [--coverage-decals N] [--size WxH]
                              [--probe-size WxH] [--probe-normals face|depth] [--camera SPEC] [--no-render]
                              [--no-peer] [--peer-seconds S]
                              [--seed N] [--quick] [--json FILE]

Run time against error. The receivers of MESH|SCENE (anything loadScene reads, or a file in the
shared data, e.g. stanford-bunny.obj) are merged into one mesh in world space, optionally made
finer by N steps of Loop subdivision. Rows: the render mesh itself (backend 'render', error 0),
then one proxy per backend and tolerance. Columns:

  tris      proxy triangles             build s   proxy build (certified bound included), uncached
  reload s  the same build from the proxy cache     bvh s     CollisionWorld::build
  spawn ns  DecalSystem::spawn per ray   batch ns  spawnBatch per ray (batches of --batch-size)
            (thread CPU time, fastest of --passes passes over the rays, no limits reached)
  d50 d99 dmax  distance of the proxy hits to the render surface (% of the bounding diagonal)
  off99     |t_proxy - t_render| where both hit, p99 (% of the diagonal)
  n99       angle between the proxy and render hit normals, p99 (degrees)
  disagree  rays that hit one surface and miss the other (%)
  IoU       decal coverage (render view 'coverage') of decals placed through the proxy against
            decals placed on the render mesh, same rays from the camera (needs an OpenGL context),
            projected along the shot (the default)
  IoU-n     the same, both projected along the normal
  IoU-p     IoU along the shot with each proxy-placed decal laid again on the drawn surface where a
            frame from the camera finds its axis line meets it in the depth buffer
            (Renderer::findSurface, DecalSystem::layOnDrawnSurface; removed where its shot meets it
            too steeply for its type; replaced by the shot's decal where the shot, searched from
            its origin, meets the drawn surface before the box: DecalSystem::replaceOnDrawnSurface),
            and each shot that the proxy refused (met none, or met it too steeply) placed where the
            frame finds it meeting the drawn surface (DecalSystem::spawnOnDrawnSurface), at
            --probe-size
  (--iou-breakdown: IoU again with fields of each proxy-placed decal taken from the decal the same
  shot places on the render mesh: its centre, its frame, frame and slant, all three, all three and
  the half-depth; centre and half-depth alone (what a decal pass that found the drawn surface along
  the shot in the depth buffer could take); what is lost with all of them is the shots one surface
  places and the other not; all of them with no decal where the render mesh places none; and, taking
  nothing from it, each decal re-laid where the line along its axis meets the drawn surface, its
  frame built on the drawn normal as placement builds one, dropped where the line meets none; and
  the same only where the camera sees that meet, as a decal pass reading the depth buffer could,
  and with the normal that the depth buffer's pixels around the meet give; last, each decal's frame
  laid on the face normal of the render triangle nearest its centre, centre and depth kept)
  h         the proxy's certified error bound (% of the diagonal); '!' marks a missed tolerance

The three.js peer (bench/peers/threejs: three-mesh-bvh raycast and DecalGeometry, on the same mesh
and rays) is run when node and npm are available and reported beside the rows.

--subdivide N      Loop subdivision steps (OpenMesh) applied to the merged mesh (default 0)
--backends LIST    comma-separated: openmesh, meshopt (default both)
--tolerances LIST  % of the diagonal (default 0.05,0.1,0.5,1,2,5)
--rays N           scattered rays (default 20000)     --batch-size N  (default 64)
--passes N         timed passes over the rays (default 3)
--cap-seconds S    a proxy build running longer (wall time) is cancelled and its row marked capped;
                   for OpenMesh, whose time grows with the tolerance, the larger tolerances are then
                   skipped (default 120)
--openmesh-max-triangles N  skip OpenMesh above N render triangles (default: no limit)
--coverage-decals N decals shot from the camera for the IoU (default 300)
--size WxH         coverage image size (default 640x480)
--probe-size WxH   size of the frame whose depth IoU-p's decals are laid on (default 1440x1080: the
                   coverage camera at 1080 rows)
--probe-normals N  the normals of the surface IoU-p's search finds: face (the default: the frame's
                   face normal target, RendererSettings::faceNormals) or depth (from the depth of
                   the pixels around each point)
--camera SPEC      "eye=x,y,z;target=x,y,z[;up=..;fov=..]" (default: outside the bounds, looking in)
--no-render        no OpenGL context: IoU not measured
--iou-breakdown    where the IoU along the shot is lost (above; a table after the rows)
--no-peer          do not run the three.js peer     --peer-seconds S  its DecalGeometry time cap (default 30)
--quick            2000 rays, one pass, tolerances 0.5,2, 60 coverage decals, peer capped at 5 s
--json FILE        {"rows": [{"backend", "tolerance_rel", "proxy_triangles", "build_s", "placement_ns",
                   "batch_ns", "dist_p50_rel", "dist_p99_rel", "dist_max_rel", "normal_deg_p99",
                   "disagree_rate", "coverage_iou", "coverage_iou_normal", "coverage_iou_probed",
                   "iou_breakdown": {"centre",
                   "frame", "frame_slant", "centre_frame_slant", "all", "centre_depth",
                   "all_placed_by_both", "drawn_probe", "drawn_probe_seen",
                   "drawn_probe_depth_normal", "nearest_face_frame"}, ...}], "probe_size",
                   "probe_normals", "peers": [...], ...}
)";

constexpr double kRadToDeg = 57.295779513082320876;

struct TradeoffRow {
    std::string backend;
    double toleranceRel = 0.0;
    std::string status = "ok"; // ok, capped, skipped, failed: ...
    size_t proxyTriangles = 0;
    double buildS = std::nan(""), reloadS = std::nan(""), bvhS = std::nan("");
    double placementNs = std::nan(""), batchNs = std::nan("");
    double distP50 = std::nan(""), distP99 = std::nan(""), distMax = std::nan("");
    double offsetP99 = std::nan(""), normalP99 = std::nan(""), disagree = std::nan("");
    double iou = std::nan(""), iouNormal = std::nan(""), iouProbed = std::nan(""),
           errorBoundRel = std::nan("");
    std::optional<IouBreakdown> breakdown; // --iou-breakdown
    bool toleranceMet = true;
    uint32_t attempts = 0;
    size_t placed = 0;
};

// The coverage probe from one camera, with the shots whose decals it compares.
struct ShotCoverage {
    // Shots aimed at `decals` points of the render surface seen from `camera` (random pixels), each
    // from a random point 0.5 diagonals away within 60 degrees of the direction to the camera, whose
    // ray reaches the point on the render mesh: so the decals are in view, and a proxy's offset along
    // the ray shows on screen.
    static Result<ShotCoverage> create(const Scene& scene, const CollisionWorld& renderWorld, int width,
                                       int height, const Camera& camera, size_t decals, double diagonal,
                                       uint64_t seed, bool faceNormals) {
        Result<CoverageProbe> probe =
            CoverageProbe::create(scene, width, height, coverageType(0.04 * diagonal), faceNormals);
        if (!probe) return fail(probe.error());
        ShotCoverage c{std::move(probe).value(), camera, {}};
        Rng rng(seed);
        for (size_t attempt = 0; attempt < 50 * decals && c.shots.size() < decals; ++attempt) {
            Ray view;
            view.origin = camera.eye;
            view.direction = pixelDirection(camera, width, height, int(rng.below(uint32_t(width))),
                                            int(rng.below(uint32_t(height))));
            const std::optional<Hit> seen = renderWorld.intersect(view);
            if (!seen) continue;
            const glm::dvec3 toEye = glm::normalize(camera.eye - seen->position);
            Ray shot;
            shot.origin = seen->position + randomConeDirection(toEye, kPi / 3.0, rng) * (0.5 * diagonal);
            shot.direction = seen->position - shot.origin;
            const std::optional<Hit> lands = renderWorld.intersect(shot);
            if (lands && glm::length(lands->position - seen->position) <= 1e-6 * diagonal)
                c.shots.push_back(shot);
        }
        return c;
    }

    // The coverage mask of the decals the shots place through `proxies` (empty: the render mesh),
    // projected along `projection`; with `laid`, also the mask of the same decals laid again on the
    // drawn surface as the camera's depth at `probeSize` finds it (DrawnSurface.hpp).
    Result<std::vector<uint8_t>> mask(const Scene& scene,
                                      const std::vector<std::shared_ptr<const Proxy>>& proxies,
                                      double diagonal, uint64_t seed, Projection projection,
                                      glm::ivec2 probeSize = {}, std::vector<uint8_t>* laid = nullptr) {
        DecalType t = probe.type();
        t.projection = projection;
        Result<DecalSystem> sys = coverageSystem(CollisionWorld::build(scene, proxies), t, diagonal, seed);
        if (!sys) return fail(sys.error());
        std::vector<SpawnResult> results;
        sys->spawnBatch(shots, 0, results);
        Result<std::vector<uint8_t>> placed = probe.mask(camera, sys->decals());
        if (!placed || !laid) return placed;
        if (Result<DrawnSurfaceCounts> n =
                layOnDrawnSurface(sys.value(), shots, results, probe.renderer(), camera, probeSize, diagonal);
            !n)
            return fail(n.error());
        Result<std::vector<uint8_t>> after = probe.mask(camera, sys->decals());
        if (!after) return fail(after.error());
        *laid = std::move(after).value();
        return placed;
    }

    // Where the IoU along the shot is lost (IouBreakdown.hpp), against `reference`.
    Result<IouBreakdown> breakdown(const Scene& scene,
                                   const std::vector<std::shared_ptr<const Proxy>>& proxies, double diagonal,
                                   uint64_t seed, const std::vector<uint8_t>& reference) {
        DecalType t = probe.type();
        t.projection = Projection::Shot;
        return iouBreakdown(probe, camera, scene, proxies, shots, t, diagonal, seed, reference);
    }

    const std::string& glRenderer() const { return probe.glRenderer(); }

    CoverageProbe probe;
    Camera camera;
    std::vector<Ray> shots;
};

struct Timing {
    double singleNs = std::nan(""), batchNs = std::nan("");
    size_t placed = 0;
};

// Spawning every ray, one by one and in batches, on the collision world of `scene` with `proxies`:
// the fastest of `passes` passes, thread CPU time per ray.
Result<Timing> timePlacement(const Scene& scene, const std::vector<std::shared_ptr<const Proxy>>& proxies,
                             const std::vector<Ray>& rays, const DecalType& type, double diagonal,
                             size_t batchSize, size_t passes, uint64_t seed) {
    Timing t;
    std::vector<std::vector<Ray>> batches;
    for (size_t i = 0; i < rays.size(); i += batchSize)
        batches.emplace_back(rays.begin() + std::ptrdiff_t(i),
                             rays.begin() + std::ptrdiff_t(std::min(rays.size(), i + batchSize)));
    for (int method = 0; method < 2; ++method) {
        Result<CollisionWorld> world = CollisionWorld::build(scene, proxies);
        if (!world) return fail(world.error());
        Result<DecalSystem> sys = DecalSystem::create(std::move(world).value(), unlimited(diagonal, seed));
        if (!sys) return fail(sys.error());
        const uint16_t ti = sys->registerType(type).value();
        double best = std::numeric_limits<double>::infinity();
        std::vector<SpawnResult> results;
        for (size_t p = 0; p < passes; ++p) {
            const uint64_t placedBefore = sys->stats().placed;
            const double start = threadCpuNow();
            if (method == 0) {
                for (const Ray& r : rays)
                    sys->spawn(r, ti);
            } else {
                for (const std::vector<Ray>& b : batches)
                    sys->spawnBatch(b, ti, results);
            }
            best = std::min(best, threadCpuNow() - start);
            if (method == 0) t.placed = size_t(sys->stats().placed - placedBefore);
        }
        (method == 0 ? t.singleNs : t.batchNs) = best * 1e9 / double(std::max<size_t>(1, rays.size()));
    }
    return t;
}

// Hit agreement and distances of `proxyHits` against `renderHits` (same rays).
void measureErrors(const std::vector<std::optional<Hit>>& proxyHits,
                   const std::vector<std::optional<Hit>>& renderHits, const std::vector<Ray>& rays,
                   const ClosestPointQuery& render, double diagonal, TradeoffRow& row) {
    std::vector<double> dist, offset, angle;
    size_t disagree = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const std::optional<Hit>& p = proxyHits[i];
        const std::optional<Hit>& r = renderHits[i];
        if (p.has_value() != r.has_value()) ++disagree;
        if (p) {
            const std::optional<ClosestPoint> c = render.closest(p->localPosition);
            if (c) dist.push_back(c->distance / diagonal);
        }
        if (p && r) {
            offset.push_back(std::fabs(p->t - r->t) * glm::length(rays[i].direction) / diagonal);
            angle.push_back(std::acos(std::clamp(glm::dot(p->normal, r->normal), -1.0, 1.0)) * kRadToDeg);
        }
    }
    row.distP50 = percentile(dist, 0.5);
    row.distP99 = percentile(dist, 0.99);
    row.distMax = dist.empty() ? 0.0 : *std::max_element(dist.begin(), dist.end());
    row.offsetP99 = percentile(offset, 0.99);
    row.normalP99 = percentile(angle, 0.99);
    row.disagree = rays.empty() ? 0.0 : double(disagree) / double(rays.size());
}

// The --iou-breakdown table, when some row has one.
void printBreakdowns(const std::vector<TradeoffRow>& rows) {
    std::vector<std::string> header = {"backend", "tol%", "IoU"};
    std::vector<std::vector<std::string>> table;
    for (const TradeoffRow& r : rows) {
        if (!r.breakdown) continue;
        if (table.empty())
            for (const IouVariant& v : *r.breakdown)
                header.push_back(v.column);
        table.push_back({r.backend, fmt(100.0 * r.toleranceRel, 3), fixed(r.iou, 4)});
        for (const IouVariant& v : *r.breakdown)
            table.back().push_back(fixed(v.iou, 4));
    }
    if (table.empty()) return;
    std::printf("\nIoU along the shot with the render-placed decal's fields taken\n");
    printTable(header, table);
}

Json tradeoffRowJson(const TradeoffRow& r) {
    Json j;
    j["backend"] = r.backend;
    j["tolerance_rel"] = r.toleranceRel;
    j["proxy_triangles"] = r.proxyTriangles;
    j["build_s"] = number(r.buildS);
    j["placement_ns"] = number(r.placementNs);
    j["batch_ns"] = number(r.batchNs);
    j["dist_p50_rel"] = number(r.distP50);
    j["dist_p99_rel"] = number(r.distP99);
    j["dist_max_rel"] = number(r.distMax);
    j["normal_deg_p99"] = number(r.normalP99);
    j["disagree_rate"] = number(r.disagree);
    j["coverage_iou"] = number(r.iou);
    j["coverage_iou_normal"] = number(r.iouNormal);
    j["coverage_iou_probed"] = number(r.iouProbed);
    if (r.breakdown) {
        j["iou_breakdown"] = Json::object();
        for (const IouVariant& v : *r.breakdown)
            j["iou_breakdown"][v.key] = number(v.iou);
    }
    j["status"] = r.status;
    j["reload_s"] = number(r.reloadS);
    j["bvh_s"] = number(r.bvhS);
    j["offset_p99_rel"] = number(r.offsetP99);
    j["error_bound_rel"] = number(r.errorBoundRel);
    j["tolerance_met"] = r.toleranceMet;
    j["attempts"] = r.attempts;
    j["placed"] = r.placed;
    return j;
}

std::string pct(double rel, int digits = 3) {
    return std::isnan(rel) ? "-" : fmt(100.0 * rel, digits);
}

std::vector<std::string> tableRow(const TradeoffRow& r) {
    const bool done = r.status == "ok";
    std::string h = pct(r.errorBoundRel);
    if (!r.toleranceMet) h += "!";
    return {r.backend,
            r.backend == "render" ? "0" : fmt(100.0 * r.toleranceRel, 3),
            done ? std::to_string(r.proxyTriangles) : "-",
            fixed(r.buildS, 2),
            fmt(r.reloadS, 2),
            fixed(r.bvhS, 3),
            fixed(r.placementNs, 0),
            fixed(r.batchNs, 0),
            pct(r.distP50),
            pct(r.distP99),
            pct(r.distMax),
            pct(r.offsetP99),
            fmt(r.normalP99, 3),
            pct(r.disagree),
            std::isnan(r.iou) ? "-" : fixed(r.iou, 4),
            std::isnan(r.iouNormal) ? "-" : fixed(r.iouNormal, 4),
            std::isnan(r.iouProbed) ? "-" : fixed(r.iouProbed, 4),
            done ? h : r.status};
}

} // namespace

int runTradeoffCommand(int argc, char** argv) {
    int exitCode = 0;
    const std::optional<Args> parsed =
        commandArgs(argc, argv, kTradeoffCommand, kTradeoffUsage,
                    {"--subdivide", "--backends", "--tolerances", "--rays", "--batch-size", "--passes",
                     "--cap-seconds", "--openmesh-max-triangles", "--coverage-decals", "--size",
                     "--probe-size", "--probe-normals", "--camera", "--peer-seconds", "--seed", "--json"},
                    {"--no-render", "--no-peer", "--quick", "--iou-breakdown"}, exitCode);
    if (!parsed) return exitCode;
    const Args& args = *parsed;
    if (args.positional.size() != 1) return usageError(kTradeoffCommand, "one MESH|SCENE is needed");
    const bool quick = args.has("--quick");

    std::vector<std::string> errors;
    auto count = [&](const std::string& name, uint64_t fallback) -> uint64_t {
        if (!args.has(name)) return fallback;
        Result<uint64_t> v = parseCount(args.value(name), name);
        if (!v) errors.push_back(v.error());
        return v ? v.value() : fallback;
    };
    auto real = [&](const std::string& name, double fallback) -> double {
        if (!args.has(name)) return fallback;
        Result<double> v = parseNumber(args.value(name), name);
        if (!v) errors.push_back(v.error());
        return v ? v.value() : fallback;
    };
    const uint64_t subdivide = count("--subdivide", 0);
    const uint64_t rayCount = count("--rays", quick ? 2000 : 20000);
    const uint64_t batchSize = count("--batch-size", 64);
    const uint64_t passes = count("--passes", quick ? 1 : 3);
    const uint64_t omMax = count("--openmesh-max-triangles", 0);
    const uint64_t coverageDecals = count("--coverage-decals", quick ? 60 : 300);
    const uint64_t seed = count("--seed", 1);
    const double cap = real("--cap-seconds", 120.0);
    const double peerSeconds = real("--peer-seconds", quick ? 5.0 : 30.0);
    std::vector<double> tolerances =
        quick ? std::vector<double>{0.5, 2} : std::vector<double>{0.05, 0.1, 0.5, 1, 2, 5};
    if (args.has("--tolerances")) {
        Result<std::vector<double>> t = parseNumberList(args.value("--tolerances"), "--tolerances");
        if (!t)
            errors.push_back(t.error());
        else
            tolerances = t.value();
    }
    std::vector<ProxyBackend> backends = {ProxyBackend::OpenMesh, ProxyBackend::MeshOpt};
    if (args.has("--backends")) {
        backends.clear();
        std::string list = args.value("--backends") + ",";
        for (size_t a = 0, b; (b = list.find(',', a)) != std::string::npos; a = b + 1) {
            const std::string name = list.substr(a, b - a);
            if (name == "openmesh")
                backends.push_back(ProxyBackend::OpenMesh);
            else if (name == "meshopt")
                backends.push_back(ProxyBackend::MeshOpt);
            else
                errors.push_back("--backends: unknown backend '" + name + "' (openmesh, meshopt)");
        }
    }
    int width = 640, height = 480;
    if (args.has("--size") && std::sscanf(args.value("--size").c_str(), "%dx%d", &width, &height) != 2)
        errors.push_back("--size must be WxH");
    glm::ivec2 probeSize(1440, 1080);
    if (args.has("--probe-size") &&
        std::sscanf(args.value("--probe-size").c_str(), "%dx%d", &probeSize.x, &probeSize.y) != 2)
        errors.push_back("--probe-size must be WxH");
    const std::string probeNormals = args.has("--probe-normals") ? args.value("--probe-normals") : "face";
    if (probeNormals != "face" && probeNormals != "depth")
        errors.push_back("--probe-normals must be face or depth");
    const bool faceNormals = probeNormals == "face";
    if (!errors.empty()) return usageError(kTradeoffCommand, errors.front());
    if (subdivide > 4)
        return usageError(kTradeoffCommand, "--subdivide at most 4 (each step makes 4 times the triangles)");
    if (rayCount == 0 || batchSize == 0 || passes == 0)
        return usageError(kTradeoffCommand, "counts must be positive");
    if (width < 16 || height < 16 || width > 8192 || height > 8192)
        return usageError(kTradeoffCommand, "--size must be between 16x16 and 8192x8192");
    if (probeSize.x < 16 || probeSize.y < 16 || probeSize.x > 8192 || probeSize.y > 8192)
        return usageError(kTradeoffCommand, "--probe-size must be between 16x16 and 8192x8192");
    for (double t : tolerances)
        if (!(t > 0.0 && t < 100.0))
            return usageError(kTradeoffCommand, "--tolerances must lie in (0, 100)%");
    if (!(cap > 0.0) || !(peerSeconds > 0.0)) return usageError(kTradeoffCommand, "times must be positive");

    const MachineInfo machine = machineInfo();
    const double loadStart = now();
    Result<InputMesh> loaded = loadInputMesh(args.positional[0], int(subdivide));
    if (!loaded) {
        std::cerr << "spatter-bench tradeoff: " << loaded.error() << "\n";
        return 1;
    }
    const InputMesh& input = loaded.value();
    const double diagonal = input.diagonal;
    const Scene scene = singleObjectScene(input.mesh, input.name);
    std::printf("spatter-bench tradeoff: %s (%s), %zu triangles, diagonal %.6g, loaded in %.1f s%s\n",
                input.name.c_str(), input.source.c_str(), input.mesh.triangleCount(), diagonal,
                now() - loadStart,
                input.droppedFaces
                    ? (", " + std::to_string(input.droppedFaces) + " non-manifold faces left out").c_str()
                    : "");
    std::printf("machine: %s\n", describe(machine).c_str());
    std::fflush(stdout);

    const std::vector<Ray> rays = scatteredRays(input.mesh, rayCount, seed);
    DecalType type;
    type.name = "tradeoff";
    type.size = glm::vec2(float(0.02 * diagonal));
    const ScratchDirectory scratch("tradeoff");
    const std::string& work = scratch.path();

    // The render mesh: the reference of every error column.
    Result<ClosestPointQuery> renderQuery = ClosestPointQuery::create(input.mesh);
    if (!renderQuery) {
        std::cerr << "spatter-bench tradeoff: " << renderQuery.error() << "\n";
        return 1;
    }
    double start = now();
    Result<CollisionWorld> renderWorld = CollisionWorld::build(scene);
    if (!renderWorld) {
        std::cerr << "spatter-bench tradeoff: " << renderWorld.error() << "\n";
        return 1;
    }
    const double renderBvh = now() - start;
    const std::vector<std::optional<Hit>> renderHits = renderWorld->intersectBatch(rays);

    // Coverage, when an OpenGL context can be had.
    std::optional<ShotCoverage> probe;
    std::vector<uint8_t> referenceMask, referenceNormalMask; // render-placed, along the shot and the normal
    std::string glRenderer, noCoverage;
    if (!args.has("--no-render")) {
        Camera camera;
        const glm::dvec3 centre = glm::dvec3(input.mesh.bounds().center());
        camera.target = centre;
        camera.eye = centre + glm::normalize(glm::dvec3(0.6, 0.45, 1.0)) * (1.1 * diagonal);
        camera.fovYDeg = 45.0;
        camera.nearPlane = 1e-3 * diagonal;
        if (args.has("--camera")) {
            Result<Camera> c = parseCamera(args.value("--camera"));
            if (!c) return usageError(kTradeoffCommand, "--camera: " + c.error());
            camera = c.value();
        }
        Result<ShotCoverage> p = ShotCoverage::create(scene, renderWorld.value(), width, height, camera,
                                                      coverageDecals, diagonal, seed + 7, faceNormals);
        if (p) {
            probe.emplace(std::move(p).value());
            Result<std::vector<uint8_t>> m = probe->mask(scene, {}, diagonal, seed, Projection::Shot);
            Result<std::vector<uint8_t>> n = probe->mask(scene, {}, diagonal, seed, Projection::Normal);
            if (m && n) {
                referenceMask = std::move(m).value();
                referenceNormalMask = std::move(n).value();
                glRenderer = probe->glRenderer();
            } else {
                noCoverage = m ? n.error() : m.error();
                probe.reset();
            }
        } else {
            noCoverage = p.error();
        }
    } else {
        noCoverage = "--no-render";
    }
    if (!probe) std::printf("coverage IoU not measured: %s\n", noCoverage.c_str());
    std::fflush(stdout);

    std::vector<TradeoffRow> rows;
    auto progress = [](const TradeoffRow& r) {
        std::fprintf(stderr, "  %s %s%%: %s\n", r.backend.c_str(), fmt(100.0 * r.toleranceRel, 3).c_str(),
                     r.status == "ok" ? (std::to_string(r.proxyTriangles) + " triangles, built in " +
                                         fixed(r.buildS, 2) + " s, spawn " + fixed(r.placementNs, 0) + " ns")
                                            .c_str()
                                      : r.status.c_str());
    };
    {
        TradeoffRow r;
        r.backend = "render";
        r.proxyTriangles = input.mesh.triangleCount();
        r.buildS = 0.0;
        r.bvhS = renderBvh;
        Result<Timing> t = timePlacement(scene, {}, rays, type, diagonal, batchSize, passes, seed);
        if (t) {
            r.placementNs = t->singleNs;
            r.batchNs = t->batchNs;
            r.placed = t->placed;
        }
        measureErrors(renderHits, renderHits, rays, renderQuery.value(), diagonal, r);
        r.errorBoundRel = 0.0;
        if (probe) r.iou = r.iouNormal = r.iouProbed = 1.0;
        rows.push_back(r);
        progress(r);
    }

    for (ProxyBackend backend : backends) {
        bool skipRest = false;
        for (double tol : tolerances) {
            TradeoffRow r;
            r.backend = proxyBackendName(backend);
            r.toleranceRel = tol / 100.0;
            if (skipRest) {
                r.status = "skipped";
            } else if (backend == ProxyBackend::OpenMesh && omMax && input.mesh.triangleCount() > omMax) {
                r.status = "skipped";
            } else {
                ProxySettings ps;
                ps.backend = backend;
                ps.tolerance = float(tol / 100.0);
                ps.cacheDirectory = work + "/cache";
                const double buildStart = now();
                Result<Proxy> proxy = buildProxy(
                    input.mesh, ps, nullptr, [&](float, const char*) { return now() - buildStart < cap; });
                if (!proxy) {
                    // The builder reports a cancellation as "cancelled", with the stage it stopped in.
                    const std::string& e = proxy.error();
                    const bool cancelled = e.size() >= 9 && e.compare(e.size() - 9, 9, "cancelled") == 0;
                    r.status = cancelled ? "capped" : "failed: " + e;
                    // OpenMesh's time grows with the tolerance (PROXIES.md): the larger ones would be capped
                    // too.
                    skipRest = cancelled && backend == ProxyBackend::OpenMesh;
                } else {
                    r.buildS = proxy->seconds;
                    r.proxyTriangles = proxy->proxyTriangles;
                    r.errorBoundRel = proxy->errorBound / diagonal;
                    r.toleranceMet = proxy->toleranceMet;
                    r.attempts = proxy->attempts;
                    Result<Proxy> again = buildProxy(input.mesh, ps);
                    if (again && again->cached) r.reloadS = again->seconds;
                    const std::vector<std::shared_ptr<const Proxy>> proxies{shareProxy(proxy.value())};
                    start = now();
                    Result<CollisionWorld> world = CollisionWorld::build(scene, proxies);
                    r.bvhS = now() - start;
                    if (!world) {
                        r.status = "failed: " + world.error();
                    } else {
                        measureErrors(world->intersectBatch(rays), renderHits, rays, renderQuery.value(),
                                      diagonal, r);
                        Result<Timing> t =
                            timePlacement(scene, proxies, rays, type, diagonal, batchSize, passes, seed);
                        if (t) {
                            r.placementNs = t->singleNs;
                            r.batchNs = t->batchNs;
                            r.placed = t->placed;
                        }
                        if (probe) {
                            std::vector<uint8_t> laid;
                            Result<std::vector<uint8_t>> m = probe->mask(scene, proxies, diagonal, seed,
                                                                         Projection::Shot, probeSize, &laid);
                            Result<std::vector<uint8_t>> n =
                                probe->mask(scene, proxies, diagonal, seed, Projection::Normal);
                            if (m) r.iou = iou(referenceMask, m.value());
                            if (m) r.iouProbed = iou(referenceMask, laid);
                            if (n) r.iouNormal = iou(referenceNormalMask, n.value());
                            if (args.has("--iou-breakdown")) {
                                Result<IouBreakdown> b =
                                    probe->breakdown(scene, proxies, diagonal, seed, referenceMask);
                                if (b) r.breakdown = b.value();
                            }
                        }
                    }
                }
            }
            rows.push_back(r);
            progress(r);
        }
    }

    // The peer.
    Json peers = Json::array();
    if (!args.has("--no-peer")) {
        const std::string obj = work + "/mesh.obj", rayFile = work + "/rays.txt";
        PeerRun peer;
        if (Status s = writeObj(input.mesh, obj); !s)
            peer.skipped = s.error();
        else if (Status s2 = writeRays(rays, rayFile); !s2)
            peer.skipped = s2.error();
        else
            peer = runThreejsPeer(obj, rayFile, 0.02 * diagonal, peerSeconds, seed, work);
        if (peer.ran) {
            peers.push_back(peer.result);
            const Json& p = peer.result;
            auto get = [&](const char* key) {
                return p.contains(key) && p[key].is_number() ? p[key].get<double>() : std::nan("");
            };
            std::printf("three.js peer (three r%s, three-mesh-bvh): %s ns per decal (raycast %s ns per ray, "
                        "DecalGeometry %s ns), BVH %s s, %s of %s hits decaled%s\n",
                        p.value("three_version", "?").c_str(), fixed(get("per_decal_ns"), 0).c_str(),
                        fixed(get("raycast_ns"), 0).c_str(), fixed(get("decal_geometry_ns"), 0).c_str(),
                        fixed(get("bvh_build_s"), 3).c_str(), fixed(get("decals"), 0).c_str(),
                        fixed(get("hits"), 0).c_str(), p.value("capped", false) ? " (time cap reached)" : "");
        } else {
            std::printf("three.js peer skipped: %s\n", peer.skipped.c_str());
        }
    }

    std::vector<std::vector<std::string>> table;
    for (const TradeoffRow& r : rows)
        table.push_back(tableRow(r));
    for (const Json& p : peers) {
        auto get = [&](const char* key) {
            return p.contains(key) && p[key].is_number() ? p[key].get<double>() : std::nan("");
        };
        table.push_back({"three.js", "0", std::to_string(input.mesh.triangleCount()), "0", "-",
                         fixed(get("bvh_build_s"), 3), fixed(get("per_decal_ns"), 0), "-", "0", "0", "0", "0",
                         "0", "0", "-", "-", "-", "0"});
    }
    std::printf("\n");
    printTable({"backend", "tol%", "tris", "build s", "reload s", "bvh s", "spawn ns", "batch ns", "d50%",
                "d99%", "dmax%", "off99%", "n99 deg", "disagree%", "IoU", "IoU-n", "IoU-p", "h%"},
               table);
    printBreakdowns(rows);

    if (args.has("--json")) {
        Json j;
        j["command"] = "tradeoff";
        j["machine"] = toJson(machine);
        j["gl_renderer"] = glRenderer;
        j["coverage"] = probe ? Json("measured") : Json(noCoverage);
        j["mesh"] = input.name;
        j["source"] = input.source;
        j["subdivide"] = subdivide;
        j["render_triangles"] = input.mesh.triangleCount();
        j["diagonal"] = diagonal;
        j["rays"] = rays.size();
        j["batch_size"] = batchSize;
        j["passes"] = passes;
        j["cap_seconds"] = cap;
        j["decal_size_rel"] = 0.02;
        j["probe_size"] = {probeSize.x, probeSize.y};
        j["probe_normals"] = probeNormals;
        j["rows"] = Json::array();
        for (const TradeoffRow& r : rows)
            j["rows"].push_back(tradeoffRowJson(r));
        j["peers"] = peers;
        if (Status s = writeJson(j, args.value("--json")); !s) {
            std::cerr << "spatter-bench tradeoff: " << s.error() << "\n";
            return 1;
        }
    }
    return 0;
}

} // namespace spatter::bench
