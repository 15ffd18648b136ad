#include "ProxyBench.hpp"

#include "BenchSupport.hpp"

#include "spatter/core/HausdorffBound.hpp"
#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/ProxyInstances.hpp"
#include "spatter/core/SceneLoader.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace spatter::bench {

namespace {

const char* kProxyCommand = "proxy";

const char* kProxyUsage =
    R"(usage: spatter-bench proxy [--meshes LIST] [--tolerances LIST] [--samples N] [--no-gallery]
                           [--quick] [--json FILE]

Certified proxies against plain meshoptimizer, in one run on one machine. For each mesh and
tolerance (% of the mesh's bounding diagonal):

  anchor    the fewest triangles meshopt_simplify (LockBorder, on the mesh welded by position)
            reaches with a two-sided Hausdorff distance within the tolerance, measured by dense
            sampling (every vertex and N area-weighted random points per direction) and, where
            that comes within 80% of the tolerance, by the certifier's search for a point farther
            than the tolerance (a distance attained, which the samples can miss inside a coarse
            triangle); its target error is found by bisection
  mo s      wall time of one meshopt_simplify run at the anchor's target error (median of 3)
  proxy     triangles of buildProxy (default settings, the tolerance asked), its certified h and
            the dense estimate of its distance (% of the tolerance), whether h met the tolerance,
            and its wall time (uncached; the median of 3 builds, as the meshopt run is timed; the
            first build's time, which also pays for the memory the process touches first, goes
            to the JSON)
  tris x    proxy triangles / anchor triangles (target: at most 1.3)
  time x    proxy seconds / meshopt seconds (target: at most 4)

Then two more targets: builtin:gallery built cold (every receiver's proxy at 0.5%, uncached, one
build for the objects that share a mesh, as the gallery builds them) within 1.5 s, and 0.1%
certified (toleranceMet) on every shared mesh.

--meshes LIST      comma-separated cases: shared files (stanford-bunny.obj, fandisk.obj,
                   rocker-arm.obj, gltf/DamagedHelmet/DamagedHelmet.glb, ...), 'gallery' (each
                   object of builtin:gallery on its own; 'gallery/NAME' for one) and 'bunny-loop2'
                   (the bunny after two steps of Loop subdivision, 1.1 million triangles). Default:
                   all of those
--tolerances LIST  % of the diagonal (default 0.2,0.5,1,2)
--samples N        random dense samples per direction (default 100000)
--no-gallery       skip the cold build of builtin:gallery
--quick            fandisk and the gallery's first four objects at 0.5 and 2, 20000 samples
--json FILE        {"machine", "rows": [{"mesh", "tolerance_pct", "input_triangles",
                   "anchor_triangles", "anchor_target", "anchor_dense", "meshopt_s",
                   "proxy_triangles", "proxy_h", "proxy_dense", "proxy_met", "proxy_s",
                   "proxy_first_s", "triangles_ratio", "time_ratio"}], "gallery_cold": {...},
                   "tenth_percent": [...]}
)";

constexpr double kTrianglesTarget = 1.3;
// Builds of each case's proxy, timed as the meshopt run at the anchor is: the median of this many.
constexpr int kProxyBuilds = 3;
constexpr double kTimeTarget = 4.0;
constexpr double kGalleryTolerance = 0.005;
constexpr double kGalleryTargetSeconds = 1.5;
// The anchor's bisection stops when its bracket of target errors is this narrow (ratio).
constexpr double kAnchorPrecision = 1.02;
constexpr int kAnchorMaxRuns = 24;
// An anchor candidate whose dense estimate lies above this fraction of the tolerance is also searched
// by the certifier (DenseMeasure::searched); farther below, the samples are taken as they are.
constexpr double kAnchorSearchAbove = 0.8;

struct Case {
    std::string name;
    Mesh mesh;
};

// Largest of f(i) over [0, count) on all hardware threads; stops early (returning a value above
// `stopAbove`) as soon as one is above it.
template <class F> double parallelMax(size_t count, double stopAbove, F&& f) {
    const unsigned workers = std::max(1u, std::thread::hardware_concurrency());
    std::atomic<size_t> next{0};
    std::atomic<bool> stop{false};
    std::vector<double> worst(workers, 0.0);
    auto run = [&](unsigned w) {
        for (size_t begin; !stop.load() && (begin = next.fetch_add(4096)) < count;)
            for (size_t i = begin; i < std::min(count, begin + 4096); ++i) {
                worst[w] = std::max(worst[w], f(i));
                if (worst[w] > stopAbove) stop = true;
            }
    };
    std::vector<std::thread> threads;
    for (unsigned w = 1; w < workers; ++w)
        threads.emplace_back(run, w);
    run(0);
    for (std::thread& t : threads)
        t.join();
    return *std::max_element(worst.begin(), worst.end());
}

// Every corner of a triangle of non-zero area, and `count` area-weighted random points.
std::vector<glm::dvec3> densePoints(const Mesh& m, size_t count, uint64_t seed) {
    std::vector<glm::dvec3> out;
    for (size_t t = 0; t < m.triangleCount(); ++t) {
        const glm::dvec3 a(m.positions[m.indices[3 * t]]), b(m.positions[m.indices[3 * t + 1]]),
            c(m.positions[m.indices[3 * t + 2]]);
        if (glm::length(glm::cross(b - a, c - a)) > 0.0) out.insert(out.end(), {a, b, c});
    }
    SurfaceSampler sampler(m);
    Rng rng(seed);
    for (size_t i = 0; i < count && !sampler.empty(); ++i)
        out.push_back(sampler.sample(rng.uniform(), rng.uniform(), rng.uniform()));
    return out;
}

// Dense two-sided distance estimates between one render mesh and any number of proxies.
class DenseMeasure {
public:
    DenseMeasure(const Mesh& render, size_t samples)
        : samples_(samples), renderPoints_(densePoints(render, samples, 11)),
          renderQuery_(ClosestPointQuery::create(render)), renderSurface_(HausdorffSurface::create(render)) {}

    bool ok() const { return bool(renderQuery_) && bool(renderSurface_); }

    // The largest distance found both ways by the certifier's search with a sharp margin, stopping at
    // the first one above `tolerance`: a distance attained, like the dense samples, but found where a
    // coarse triangle hides it from them (0 when the candidate cannot be measured).
    double searched(const Mesh& proxy, double tolerance) const {
        Result<HausdorffSurface> surface = HausdorffSurface::create(proxy);
        if (!surface) return 0.0;
        HausdorffSettings s;
        s.margin = kSearchMargin * tolerance;
        s.tolerance = tolerance;
        Result<HausdorffPair> h = boundBothWays(surface.value(), renderSurface_.value(), s);
        return h ? std::max(h->ab.lower, h->ba.lower) : 0.0;
    }

    // The largest distance found both ways; above `stopAbove` as soon as one is (then not the largest).
    double twoSided(const Mesh& proxy, double stopAbove = std::numeric_limits<double>::infinity()) const {
        Result<ClosestPointQuery> proxyQuery = ClosestPointQuery::create(proxy);
        if (!proxyQuery || proxyQuery->surfaceTriangleCount() == 0)
            return std::numeric_limits<double>::infinity();
        const std::vector<glm::dvec3> proxyPoints = densePoints(proxy, samples_, 12);
        const double toRender = parallelMax(proxyPoints.size(), stopAbove, [&](size_t i) {
            return renderQuery_->closest(proxyPoints[i])->distance;
        });
        if (toRender > stopAbove) return toRender;
        return std::max(toRender, parallelMax(renderPoints_.size(), stopAbove, [&](size_t i) {
                            return proxyQuery->closest(renderPoints_[i])->distance;
                        }));
    }

private:
    static constexpr double kSearchMargin = 0.005;
    size_t samples_;
    std::vector<glm::dvec3> renderPoints_;
    Result<ClosestPointQuery> renderQuery_;
    Result<HausdorffSurface> renderSurface_;
};

// The mesh welded by position: what a caller hands meshopt_simplify for a collision mesh.
Mesh weldedByPosition(const Mesh& in) {
    std::vector<unsigned int> remap(in.positions.size());
    const size_t unique =
        meshopt_generateVertexRemap(remap.data(), in.indices.data(), in.indices.size(), in.positions.data(),
                                    in.positions.size(), sizeof(glm::vec3));
    Mesh out;
    out.positions.resize(unique);
    meshopt_remapVertexBuffer(out.positions.data(), in.positions.data(), in.positions.size(),
                              sizeof(glm::vec3), remap.data());
    out.indices.resize(in.indices.size());
    meshopt_remapIndexBuffer(out.indices.data(), in.indices.data(), in.indices.size(), remap.data());
    return out;
}

struct MeshoptRun {
    Mesh mesh;
    double resultError = 0.0; // relative, as meshoptimizer reports it
};

MeshoptRun plainMeshopt(const Mesh& welded, double relativeTarget) {
    std::vector<unsigned int> out(welded.indices.size());
    float error = 0.0f;
    const size_t count = meshopt_simplify(out.data(), welded.indices.data(), welded.indices.size(),
                                          &welded.positions[0].x, welded.positions.size(), sizeof(glm::vec3),
                                          0, float(relativeTarget), meshopt_SimplifyLockBorder, &error);
    MeshoptRun r;
    r.mesh.positions = welded.positions;
    r.mesh.indices.assign(out.begin(), out.begin() + ptrdiff_t(count));
    r.resultError = double(error);
    return r;
}

struct Anchor {
    size_t triangles = 0;
    double target = 0.0; // relative target error of the run that gave it
    double dense =
        0.0; // its largest distance measured: dense samples, and the certifier's search near the tolerance
    double seconds = 0.0;
};

// Bisection over meshoptimizer's target error for the fewest triangles within `tolerance` by the
// distances measured (the distance is not monotone in the target, so every run is a candidate).
Anchor findAnchor(const Mesh& welded, const DenseMeasure& dense, double tolerance) {
    const double scale =
        double(meshopt_simplifyScale(&welded.positions[0].x, welded.positions.size(), sizeof(glm::vec3)));
    Anchor best;
    best.triangles = welded.triangleCount();
    double lo = 0.0, hi = std::numeric_limits<double>::infinity(), target = tolerance / scale;
    for (int run = 0; run < kAnchorMaxRuns && !(lo > 0.0 && hi <= kAnchorPrecision * lo); ++run) {
        const MeshoptRun r = plainMeshopt(welded, target);
        double d = dense.twoSided(r.mesh, tolerance);
        if (d <= tolerance && d > kAnchorSearchAbove * tolerance)
            d = std::max(d, dense.searched(r.mesh, tolerance));
        if (d <= tolerance) {
            if (r.mesh.triangleCount() < best.triangles) best = {r.mesh.triangleCount(), target, d, 0.0};
            lo = target;
        } else {
            hi = std::max(std::min(hi, r.resultError), lo);
        }
        target = !std::isfinite(hi) ? 2.0 * target : lo <= 0.0 ? 0.5 * hi : std::sqrt(lo * hi);
    }
    std::vector<double> times;
    for (int i = 0; i < 3; ++i) {
        const double start = now();
        const MeshoptRun r = plainMeshopt(welded, best.target);
        times.push_back(now() - start);
    }
    best.seconds = median(times);
    return best;
}

struct ProxyRow {
    std::string mesh;
    double tolerancePct = 0.0;
    size_t input = 0;
    Anchor anchor;
    size_t proxyTriangles = 0;
    double h = 0.0, proxyDense = 0.0, tolerance = 0.0;
    double proxySeconds = 0.0, proxyFirstSeconds = 0.0; // the median of kProxyBuilds builds; the first
    bool met = false;
    std::string error;
    double trianglesRatio() const {
        return double(proxyTriangles) / double(std::max<size_t>(anchor.triangles, 1));
    }
    double timeRatio() const { return proxySeconds / std::max(anchor.seconds, 1e-9); }
};

Result<Proxy> buildAt(const Mesh& mesh, double fraction) {
    ProxySettings s;
    s.tolerance = float(fraction);
    return buildProxy(mesh, s);
}

ProxyRow measureCase(const Case& c, double tolerancePct, const DenseMeasure& dense, const Mesh& welded) {
    ProxyRow row;
    row.mesh = c.name;
    row.tolerancePct = tolerancePct;
    row.input = c.mesh.triangleCount();
    row.tolerance = tolerancePct / 100.0 * referencedDiagonal(c.mesh);
    Result<Proxy> p = buildAt(c.mesh, tolerancePct / 100.0);
    if (!p) {
        row.error = p.error();
        return row;
    }
    std::vector<double> times{p->seconds};
    for (int i = 1; i < kProxyBuilds; ++i) {
        Result<Proxy> again = buildAt(c.mesh, tolerancePct / 100.0);
        if (!again || again->proxyTriangles != p->proxyTriangles || again->errorBound != p->errorBound) {
            row.error = "a later build gave another proxy: the builder depended on timing";
            return row;
        }
        times.push_back(again->seconds);
    }
    row.proxyTriangles = p->proxyTriangles;
    row.h = p->errorBound;
    row.met = p->toleranceMet;
    row.proxySeconds = median(times);
    row.proxyFirstSeconds = times.front();
    row.proxyDense = p->mesh.triangleCount() > 0 ? dense.twoSided(p->mesh) : 0.0;
    row.anchor = findAnchor(welded, dense, row.tolerance);
    return row;
}

Result<std::vector<Case>> loadCases(const std::vector<std::string>& specs, bool quick) {
    std::vector<Case> cases;
    for (const std::string& spec : specs) {
        if (spec == "gallery" || spec.rfind("gallery/", 0) == 0) {
            Result<Scene> scene = loadScene("builtin:gallery");
            if (!scene) return fail(scene.error());
            size_t taken = 0;
            const std::string only = spec.size() > 8 ? spec.substr(8) : "";
            for (const SceneObject& o : scene->objects)
                if (o.receivesDecals && (only.empty() || o.name == only) && (!quick || taken++ < 4))
                    cases.push_back({"gallery/" + o.name, *o.mesh});
            if (cases.empty()) return fail("builtin:gallery has no receiver '" + only + "'");
            continue;
        }
        const bool loop = spec == "bunny-loop2";
        Result<InputMesh> in = loadInputMesh(loop ? "stanford-bunny.obj" : spec, loop ? 2 : 0);
        if (!in) return fail(in.error());
        cases.push_back({in->name, std::move(in->mesh)});
    }
    return cases;
}

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> out;
    std::string list = text + ",";
    for (size_t a = 0, b; (b = list.find(',', a)) != std::string::npos; a = b + 1)
        if (b > a) out.push_back(list.substr(a, b - a));
    return out;
}

std::string yesNo(bool met) {
    return met ? "met" : "MISSED";
}

Json proxyRowJson(const ProxyRow& r) {
    return {{"mesh", r.mesh},
            {"tolerance_pct", r.tolerancePct},
            {"tolerance", number(r.tolerance)},
            {"input_triangles", r.input},
            {"anchor_triangles", r.anchor.triangles},
            {"anchor_target", number(r.anchor.target)},
            {"anchor_dense", number(r.anchor.dense)},
            {"meshopt_s", number(r.anchor.seconds)},
            {"proxy_triangles", r.proxyTriangles},
            {"proxy_h", number(r.h)},
            {"proxy_dense", number(r.proxyDense)},
            {"proxy_met", r.met},
            {"proxy_s", number(r.proxySeconds)},
            {"proxy_first_s", number(r.proxyFirstSeconds)},
            {"triangles_ratio", number(r.trianglesRatio())},
            {"time_ratio", number(r.timeRatio())},
            {"error", r.error}};
}

// Every receiver of builtin:gallery at 0.5%, uncached, one after the other, one build for the objects
// that share a mesh (proxySources): the demo's cold start, on one thread.
Json galleryCold(bool& met) {
    Result<Scene> scene = loadScene("builtin:gallery");
    if (!scene) return {{"error", scene.error()}};
    const double start = now();
    const std::vector<size_t> sources = proxySources(scene.value());
    std::vector<std::shared_ptr<const Proxy>> proxies(scene->objects.size());
    size_t input = 0, output = 0, certified = 0, objects = 0, built = 0;
    for (size_t i = 0; i < scene->objects.size(); ++i) {
        const SceneObject& o = scene->objects[i];
        if (!o.receivesDecals) continue;
        if (sources[i] == i) {
            Result<Proxy> p = buildAt(*o.mesh, kGalleryTolerance);
            if (!p) return {{"error", o.name + ": " + p.error()}};
            proxies[i] = shareProxy(std::move(p).value());
            ++built;
        }
        const Proxy& p = *proxies[sources[i]];
        input += p.inputTriangles;
        output += p.proxyTriangles;
        certified += p.toleranceMet ? 1 : 0;
        ++objects;
    }
    const double seconds = now() - start;
    met = seconds <= kGalleryTargetSeconds;
    std::printf("\nbuiltin:gallery cold at 0.5%%: %zu objects (%zu proxies built), %zu -> %zu triangles, %zu "
                "certified, %.3f s (target %.1f s: %s)\n",
                objects, built, input, output, certified, seconds, kGalleryTargetSeconds, yesNo(met).c_str());
    return {{"tolerance_pct", 100.0 * kGalleryTolerance},
            {"objects", objects},
            {"built", built},
            {"input_triangles", input},
            {"proxy_triangles", output},
            {"certified", certified},
            {"seconds", seconds},
            {"target_seconds", kGalleryTargetSeconds},
            {"met", met}};
}

// 0.1% on the shared meshes: certified or not (`met` stays empty without a shared mesh among `cases`).
Json tenthPercent(const std::vector<Case>& cases, std::optional<bool>& met) {
    Json out = Json::array();
    std::printf("\n0.1%% of the diagonal:\n");
    for (const Case& c : cases) {
        if (c.name.rfind("gallery/", 0) == 0) continue;
        Result<Proxy> p = buildAt(c.mesh, 0.001);
        const bool ok = p && p->toleranceMet;
        met = met.value_or(true) && ok;
        if (p)
            std::printf("  %-16s %8zu -> %8zu triangles, h/tol %.4f, %.3f s: %s\n", c.name.c_str(),
                        p->inputTriangles, p->proxyTriangles, p->errorBound / p->tolerance, p->seconds,
                        ok ? "certified" : "NOT certified");
        else
            std::printf("  %-16s error: %s\n", c.name.c_str(), p.error().c_str());
        out.push_back({{"mesh", c.name},
                       {"proxy_triangles", p ? p->proxyTriangles : 0},
                       {"h_over_tolerance", p ? number(p->errorBound / p->tolerance) : Json()},
                       {"seconds", p ? number(p->seconds) : Json()},
                       {"certified", ok}});
    }
    return out;
}

} // namespace

int runProxyCommand(int argc, char** argv) {
    int exitCode = 0;
    const std::optional<Args> parsed = commandArgs(argc, argv, kProxyCommand, kProxyUsage,
                                                   {"--meshes", "--tolerances", "--samples", "--json"},
                                                   {"--no-gallery", "--quick"}, exitCode);
    if (!parsed) return exitCode;
    const Args& args = *parsed;
    if (!args.positional.empty()) return usageError(kProxyCommand, "no positional arguments");
    const bool quick = args.has("--quick");
    Result<uint64_t> samples = parseCount(args.value("--samples", quick ? "20000" : "100000"), "--samples");
    if (!samples) return usageError(kProxyCommand, samples.error());
    Result<std::vector<double>> tolerances =
        parseNumberList(args.value("--tolerances", quick ? "0.5,2" : "0.2,0.5,1,2"), "--tolerances");
    if (!tolerances) return usageError(kProxyCommand, tolerances.error());
    for (double t : tolerances.value())
        if (!(t > 0.0 && t < 100.0)) return usageError(kProxyCommand, "--tolerances: each in (0, 100)");
    const std::string defaultMeshes = quick ? "fandisk.obj,gallery"
                                            : "stanford-bunny.obj,fandisk.obj,rocker-arm.obj,"
                                              "gltf/DamagedHelmet/DamagedHelmet.glb,gallery,bunny-loop2";
    Result<std::vector<Case>> cases = loadCases(splitList(args.value("--meshes", defaultMeshes)), quick);
    if (!cases) return usageError(kProxyCommand, cases.error());

    const MachineInfo machine = machineInfo();
    std::printf("spatter-bench proxy\nmachine: %s\n", describe(machine).c_str());
    std::vector<ProxyRow> rows;
    std::vector<std::vector<std::string>> table;
    bool trianglesMet = true, timeMet = true, denseMet = true;
    for (const Case& c : cases.value()) {
        const DenseMeasure dense(c.mesh, samples.value());
        if (!dense.ok()) return usageError(kProxyCommand, c.name + ": the mesh cannot be measured");
        const Mesh welded = weldedByPosition(c.mesh);
        for (double t : tolerances.value()) {
            const ProxyRow r = measureCase(c, t, dense, welded);
            rows.push_back(r);
            if (!r.error.empty()) {
                table.push_back({r.mesh, fmt(t, 2), std::to_string(r.input), "error: " + r.error});
                trianglesMet = timeMet = false;
                continue;
            }
            trianglesMet = trianglesMet && r.trianglesRatio() <= kTrianglesTarget;
            timeMet = timeMet && r.timeRatio() <= kTimeTarget;
            denseMet = denseMet && r.h >= r.proxyDense;
            table.push_back({r.mesh, fmt(t, 2), std::to_string(r.input), std::to_string(r.anchor.triangles),
                             fixed(100.0 * r.anchor.dense / r.tolerance, 1), fixed(r.anchor.seconds, 4),
                             std::to_string(r.proxyTriangles), fixed(100.0 * r.h / r.tolerance, 1),
                             fixed(100.0 * r.proxyDense / r.tolerance, 1), r.met ? "yes" : "NO",
                             fixed(r.proxySeconds, 3), fixed(r.trianglesRatio(), 2),
                             fixed(r.timeRatio(), 1)});
            std::printf("  %s at %g%%: anchor %zu, proxy %zu triangles, %.3f s\n", r.mesh.c_str(), t,
                        r.anchor.triangles, r.proxyTriangles, r.proxySeconds);
            std::fflush(stdout);
        }
    }
    std::printf("\n");
    printTable({"mesh", "tol %", "input", "anchor", "dense %tol", "mo s", "proxy", "h %tol", "dense %tol",
                "met", "proxy s", "tris x", "time x"},
               table);
    const bool galleryRun = !args.has("--no-gallery");
    bool galleryMet = false;
    std::optional<bool> tenthMet;
    const Json gallery = galleryRun ? galleryCold(galleryMet) : Json();
    Json tenth = tenthPercent(cases.value(), tenthMet);
    std::printf(
        "\ntargets: triangles <= %.1fx anchor: %s; time <= %.0fx meshopt: %s; h >= dense estimate: %s; "
        "gallery cold <= %.1f s: %s; 0.1%% certified: %s\n",
        kTrianglesTarget, yesNo(trianglesMet).c_str(), kTimeTarget, yesNo(timeMet).c_str(),
        yesNo(denseMet).c_str(), kGalleryTargetSeconds, galleryRun ? yesNo(galleryMet).c_str() : "not run",
        tenthMet ? yesNo(*tenthMet).c_str() : "not run");

    if (args.has("--json")) {
        Json j;
        j["command"] = kProxyCommand;
        j["machine"] = toJson(machine);
        j["samples"] = samples.value();
        j["rows"] = Json::array();
        for (const ProxyRow& r : rows)
            j["rows"].push_back(proxyRowJson(r));
        j["gallery_cold"] = gallery;
        j["tenth_percent"] = tenth;
        j["targets"] = {{"triangles_ratio_max", kTrianglesTarget},
                        {"triangles_met", trianglesMet},
                        {"time_ratio_max", kTimeTarget},
                        {"time_met", timeMet},
                        {"h_at_least_dense", denseMet},
                        {"gallery_cold_met", galleryRun ? Json(galleryMet) : Json()},
                        {"tenth_percent_certified", tenthMet ? Json(*tenthMet) : Json()}};
        if (Status st = writeJson(j, args.value("--json")); !st) {
            std::fprintf(stderr, "spatter-bench proxy: %s\n", st.error().c_str());
            return 1;
        }
    }
    return 0;
}

} // namespace spatter::bench
