#include "spatter/core/ProxyBuilder.hpp"
#include "Pi.hpp"
#include "ProxySimplifiers.hpp"

#include "spatter/core/HausdorffBound.hpp"
#include "spatter/core/ProxyCache.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <future>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace spatter {

const char* proxyBackendName(ProxyBackend backend) {
    switch (backend) {
    case ProxyBackend::Auto:
        return "auto";
    case ProxyBackend::OpenMesh:
        return "openmesh";
    case ProxyBackend::MeshOpt:
        return "meshopt";
    case ProxyBackend::None:
        return "none";
    }
    return "unknown";
}

const char* proxySourceName(ProxySource source) {
    switch (source) {
    case ProxySource::Simplified:
        return "simplified";
    case ProxySource::OwnMesh:
        return "own-mesh";
    case ProxySource::AuthoredCollider:
        return "authored-collider";
    }
    return "unknown";
}

ProxyBackend resolveProxyBackend(ProxyBackend requested, size_t, double, double) {
    return requested == ProxyBackend::Auto ? ProxyBackend::MeshOpt : requested;
}

namespace {

// The search's first target error for each backend, as a fraction of the tolerance (indexed by
// ProxyBackend: OpenMesh, MeshOpt); tuned on the shared meshes, where the coarsest certified target
// lay between 0.2 and 1 times the tolerance.
constexpr double kStartFraction[3] = {0.0, 0.5, 0.4};
// The search stops once the coarsest certified target is known within this fraction; until it has
// both a certified and a failed run it steps by a factor in this range (see nextTarget).
constexpr double kSearchPrecision = 0.1;
constexpr double kSearchStep = 1.5, kSearchStepMax = 4.0;
// Triangles sampled (centroid and edge midpoints) to judge a run of the search: of the proxy, where a
// coarse triangle hides its largest distance inside, and of the render mesh. A run whose sampled
// distance is at most kLikelyFraction of the tolerance is taken as likely within and certified at the
// end; one between that and the tolerance is certified at once (the samples often miss the last few
// percent of the distance), unless a run certified within already sampled as far (the distance is then
// a feature the runs share, which that certificate saw).
constexpr size_t kSampledProxyTriangles = 8192, kSampledRenderTriangles = 1024;
constexpr double kLikelyFraction = 0.9;
// Where a certificate's measured distance comes within its margin of the tolerance, the margin
// shrinks to kRoomShare of the room left under it while that room is at least kMinRoom of the
// tolerance (HausdorffSettings::roomShare), so that such a candidate is decided in one walk.
constexpr double kRoomShare = 0.25, kMinRoom = 0.01;
// Where likely candidates failed their certificate, the search goes on between the coarsest certified
// one and them only when that one has more than this many times the triangles of the finest that
// failed (less is all further runs could gain).
constexpr double kRefineGain = 1.1;
// Pre-simplified inputs of the search (CoarseInput): a render mesh of more than `triangles` (welded) is
// simplified once at `fraction` of the tolerance, from the previous level's result where there is one,
// and the search's runs at or above that target start from the coarsest such result below them. Two
// passes keep fewer triangles than one at the same measured distance, and a run costs in proportion to
// its input (docs/PROXIES.md, "The search").
struct CoarseLevel {
    size_t triangles;
    double fraction;
};
constexpr CoarseLevel kCoarseLevels[] = {{100'000, 0.05}, {10'000, 0.2}};
// A proxy that misses the tolerance gets a sharp bound with this many times the certification margin:
// its h only sizes decal boxes, and a tighter one costs many more queries.
constexpr double kMissedMarginScale = 4.0;
// Runs the progress of a build is scaled to (a typical search).
constexpr double kExpectedRuns = 5.0;
// With a tolerance of 0 (possible for an authored collider) the sampling margin is taken relative to
// this fraction of the render mesh's diagonal instead.
constexpr double kZeroToleranceScale = 0.001;

using Clock = std::chrono::steady_clock;

Status checkMesh(const Mesh& mesh, const char* what) {
    const size_t n = mesh.positions.size();
    const std::string prefix = std::string(what) + ": ";
    if (mesh.indices.size() % 3 != 0)
        return fail(prefix + "index count " + std::to_string(mesh.indices.size()) +
                    " is not a multiple of 3");
    if (n > size_t(UINT32_MAX)) return fail(prefix + "too many vertices (" + std::to_string(n) + ")");
    for (size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= n)
            return fail(prefix + "index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) +
                        ", past the vertex count " + std::to_string(n));
    for (size_t i = 0; i < n; ++i) {
        const glm::vec3& p = mesh.positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return fail(prefix + "position " + std::to_string(i) + " is not finite (NaN or Inf)");
    }
    return {};
}

Status checkSettings(const ProxySettings& s) {
    if (!std::isfinite(s.tolerance) || s.tolerance < 0.0f)
        return fail("proxy settings: tolerance " + std::to_string(s.tolerance) + " is not finite and >= 0");
    if (s.backend == ProxyBackend::None) return fail("proxy settings: backend 'none' cannot simplify");
    if (uint32_t(s.backend) > uint32_t(ProxyBackend::None)) return fail("proxy settings: unknown backend");
    if (!(s.featureAngleDegrees >= 0.0f && s.featureAngleDegrees <= 180.0f))
        return fail("proxy settings: feature angle " + std::to_string(s.featureAngleDegrees) +
                    " is not in [0, 180]");
    if (!(s.marginFraction > 0.0f && s.marginFraction < 1.0f))
        return fail("proxy settings: margin fraction " + std::to_string(s.marginFraction) +
                    " is not in (0, 1)");
    if (s.maxAttempts < 1) return fail("proxy settings: maxAttempts must be at least 1");
    return {};
}

bool isSurfaceTriangle(const std::vector<glm::vec3>& positions, uint32_t a, uint32_t b, uint32_t c) {
    if (a == b || b == c || c == a) return false;
    const glm::dvec3 pa(positions[a]);
    const glm::dvec3 n = glm::cross(glm::dvec3(positions[b]) - pa, glm::dvec3(positions[c]) - pa);
    return n.x != 0.0 || n.y != 0.0 || n.z != 0.0;
}

size_t surfaceTriangleCount(const Mesh& m) {
    size_t n = 0;
    for (size_t t = 0; t < m.triangleCount(); ++t)
        n += isSurfaceTriangle(m.positions, m.indices[3 * t], m.indices[3 * t + 1], m.indices[3 * t + 2]);
    return n;
}

double referencedDiagonal(const Mesh& m) {
    Bounds b;
    for (uint32_t i : m.indices)
        b.extend(m.positions[i]);
    return double(b.diagonal());
}

// Positions and indices only: vertices with bit-identical positions merged, triangles with a repeated
// index or zero area dropped, unreferenced vertices removed.
Mesh weldedSurface(const Mesh& in) {
    std::vector<glm::vec3> positions(in.positions.size());
    for (size_t i = 0; i < positions.size(); ++i)
        positions[i] = in.positions[i] + glm::vec3(0.0f); // -0 -> +0
    Mesh out;
    if (in.indices.empty() || positions.empty()) return out;
    std::vector<unsigned int> remap(positions.size());
    const size_t unique = meshopt_generateVertexRemap(remap.data(), in.indices.data(), in.indices.size(),
                                                      positions.data(), positions.size(), sizeof(glm::vec3));
    std::vector<glm::vec3> welded(unique);
    meshopt_remapVertexBuffer(welded.data(), positions.data(), positions.size(), sizeof(glm::vec3),
                              remap.data());
    std::vector<uint32_t> indices;
    indices.reserve(in.indices.size());
    for (size_t t = 0; t < in.triangleCount(); ++t) {
        const uint32_t a = remap[in.indices[3 * t]], b = remap[in.indices[3 * t + 1]],
                       c = remap[in.indices[3 * t + 2]];
        if (!isSurfaceTriangle(welded, a, b, c)) continue;
        indices.insert(indices.end(), {a, b, c});
    }
    // Compact: dropping triangles can leave vertices unreferenced.
    std::vector<uint32_t> slot(welded.size(), UINT32_MAX);
    for (uint32_t& i : indices) {
        if (slot[i] == UINT32_MAX) {
            slot[i] = uint32_t(out.positions.size());
            out.positions.push_back(welded[i]);
        }
        i = slot[i];
    }
    out.indices = std::move(indices);
    return out;
}

// Gives each vertex one copy per fan of triangles joined across edges whose dihedral angle is at most
// `angleDegrees`; edges used by other than two triangles separate fans too. Afterwards vertices along
// sharp edges are split, which keeps normals crisp there and makes meshoptimizer treat the edges as
// seams (collapsible only along themselves).
void splitCreases(Mesh& m, float angleDegrees) {
    const size_t corners = m.indices.size();
    const size_t triangles = m.triangleCount();
    std::vector<glm::dvec3> normal(triangles);
    for (size_t t = 0; t < triangles; ++t) {
        const glm::dvec3 a(m.positions[m.indices[3 * t]]);
        const glm::dvec3 n = glm::cross(glm::dvec3(m.positions[m.indices[3 * t + 1]]) - a,
                                        glm::dvec3(m.positions[m.indices[3 * t + 2]]) - a);
        const double len = glm::length(n);
        normal[t] = len > 0.0 ? n / len : glm::dvec3(0.0);
    }
    struct EdgeUse {
        uint64_t key;
        uint32_t corner; // the edge runs from indices[corner] to the next corner of its triangle
    };
    auto nextCorner = [](uint32_t c) { return c % 3 == 2 ? c - 2 : c + 1; };
    std::vector<EdgeUse> uses(corners);
    for (uint32_t c = 0; c < corners; ++c) {
        const uint32_t a = m.indices[c], b = m.indices[nextCorner(c)];
        uses[c] = {(uint64_t(std::min(a, b)) << 32) | std::max(a, b), c};
    }
    std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
        return x.key != y.key ? x.key < y.key : x.corner < y.corner;
    });
    std::vector<uint32_t> parent(corners);
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](uint32_t c) {
        while (parent[c] != c)
            c = parent[c] = parent[parent[c]];
        return c;
    };
    auto unite = [&](uint32_t x, uint32_t y) {
        x = find(x);
        y = find(y);
        if (x != y) parent[std::max(x, y)] = std::min(x, y);
    };
    // The corner of triangle t that holds vertex v.
    auto cornerOf = [&](uint32_t t, uint32_t v) {
        for (uint32_t k = 0; k < 3; ++k)
            if (m.indices[3 * t + k] == v) return 3 * t + k;
        return 3 * t;
    };
    const double cosLimit = std::cos(double(angleDegrees) * kPi / 180.0);
    for (size_t i = 0; i < uses.size();) {
        size_t j = i + 1;
        while (j < uses.size() && uses[j].key == uses[i].key)
            ++j;
        if (j - i == 2) {
            const uint32_t t1 = uses[i].corner / 3, t2 = uses[i + 1].corner / 3;
            if (glm::dot(normal[t1], normal[t2]) >= cosLimit) {
                const uint32_t a = uint32_t(uses[i].key >> 32), b = uint32_t(uses[i].key & 0xffffffffu);
                unite(cornerOf(t1, a), cornerOf(t2, a));
                unite(cornerOf(t1, b), cornerOf(t2, b));
            }
        }
        i = j;
    }
    std::vector<uint32_t> vertexOfRoot(corners, UINT32_MAX);
    std::vector<bool> used(m.positions.size(), false);
    for (uint32_t c = 0; c < corners; ++c) {
        const uint32_t root = find(c);
        if (vertexOfRoot[root] == UINT32_MAX) {
            const uint32_t v = m.indices[c];
            if (!used[v]) {
                used[v] = true;
                vertexOfRoot[root] = v;
            } else {
                vertexOfRoot[root] = uint32_t(m.positions.size());
                m.positions.push_back(m.positions[v]);
            }
        }
        m.indices[c] = vertexOfRoot[root];
    }
}

// The mesh a backend returned, made into a proxy: welded, degenerate triangles dropped, creases split
// (so that normals stay crisp along sharp edges), normals computed.
Mesh finishProxy(const Mesh& simplified, const ProxySettings& s) {
    Mesh out = weldedSurface(simplified);
    splitCreases(out, s.featureAngleDegrees);
    computeNormals(out);
    return out;
}

struct Candidate {
    Mesh mesh;
    ProxyBackend backend = ProxyBackend::None;
    bool budgetLimited = false; // the budget, not the tolerance, stopped simplification
    double target = 0.0;        // the backend's tolerance for this run (absolute)
    // meshoptimizer: the error it reports for the result (absolute); its collapses run in order of
    // error, so a target between this and `target` gives the same mesh. For OpenMesh: `target`.
    double resultError = 0.0;
    // The mesh prepared for the certifier, made once for the judgement and the certificate.
    std::shared_ptr<const HausdorffSurface> surface;
    HausdorffResult proxyToRender, renderToProxy;
    bool certified = false; // the two results above are the certificate's
    double sampled = 0.0;   // the largest distance its sampled judgement measured (Judge::Sampled)
    double bound() const { return std::max(proxyToRender.upper, renderToProxy.upper); }
    double lower() const { return std::max(proxyToRender.lower, renderToProxy.lower); }
    bool within(double tolerance) const {
        return proxyToRender.within(tolerance) && renderToProxy.within(tolerance);
    }
};

// One simplification run with the chosen backend, made to respect the budget: a run stopped by the
// tolerance above the budget is redone without the tolerance, and as a last resort with the sloppy
// simplifier.
Result<Candidate> simplifyOnce(ProxyBackend backend, const Mesh& welded, const Mesh& meshoptInput,
                               double tolerance, const ProxySettings& s, const ProgressCallback& progress,
                               std::vector<std::string>& notes) {
    const uint32_t budget = s.maxTriangles;
    Candidate c;
    c.backend = backend;
    c.target = tolerance;
    c.resultError = tolerance;
    auto run = [&](double tol) -> Result<Mesh> {
        if (progress && !progress(0.0f, "simplify")) return fail("cancelled");
        if (backend == ProxyBackend::MeshOpt)
            return detail::simplifyMeshopt(meshoptInput, tol, budget, s.keepBoundaries, c.resultError);
        size_t detached = 0;
        Result<Mesh> m = detail::simplifyOpenMesh(welded, tol, budget, s, progress, detached);
        const std::string note = "openmesh: " + std::to_string(detached) +
                                 " non-manifold faces were added on their own vertex copies";
        if (m && detached > 0 && std::find(notes.begin(), notes.end(), note) == notes.end())
            notes.push_back(note);
        return m;
    };
    Result<Mesh> m = run(tolerance);
    if (!m) return fail(m.error());
    c.mesh = finishProxy(m.value(), s);
    if (budget > 0 && c.mesh.triangleCount() > budget) {
        c.budgetLimited = true;
        m = run(std::numeric_limits<double>::infinity());
        if (!m) return fail(m.error());
        c.mesh = finishProxy(m.value(), s);
    }
    if (budget > 0 && c.mesh.triangleCount() > budget) {
        notes.push_back(std::string(proxyBackendName(backend)) + " stopped at " +
                        std::to_string(c.mesh.triangleCount()) + " triangles, above the budget of " +
                        std::to_string(budget) + ": sloppy simplification used");
        c.mesh = finishProxy(detail::simplifySloppy(welded, budget), s);
    }
    if (budget > 0 && c.mesh.triangleCount() > budget)
        return fail("no proxy within the budget of " + std::to_string(budget) + " triangles could be made (" +
                    std::to_string(c.mesh.triangleCount()) + " left)");
    if (progress && !progress(1.0f, "simplify")) return fail("cancelled");
    return c;
}

// The candidate's mesh prepared for the certifier (once).
Status prepare(Candidate& c) {
    if (c.surface) return {};
    Result<HausdorffSurface> proxy = HausdorffSurface::create(c.mesh);
    if (!proxy) return fail("proxy: " + proxy.error());
    c.surface = std::make_shared<const HausdorffSurface>(std::move(proxy).value());
    return {};
}

// The error of a direction of the certificate, named.
std::string directionError(const std::string& error, const char* which) {
    return error == "cancelled" ? error : std::string(which) + ": " + error;
}

// Certifies a candidate against the render mesh (HausdorffBound.hpp): both directions at once
// (boundBothWays: with a finite `settings.tolerance`, the first distance above it either way stops
// both).
Status certify(Candidate& c, const HausdorffSurface& render, const HausdorffSettings& settings,
               const ProgressCallback& progress) {
    if (c.mesh.indices.empty()) { // simplified away entirely: never within a tolerance
        c.proxyToRender.exceeded = c.renderToProxy.exceeded = true;
        c.proxyToRender.upper = c.renderToProxy.upper = std::numeric_limits<double>::infinity();
        c.certified = true;
        return {};
    }
    if (Status st = prepare(c); !st) return st;
    const HausdorffSurface& proxy = *c.surface;
    Result<HausdorffPair> both = boundBothWays(render, proxy, settings, progress);
    if (!both) return fail(directionError(both.error(), "certificate"));
    c.renderToProxy = both->ab;
    c.proxyToRender = both->ba;
    c.certified = true;
    return {};
}

// Progress of the whole search as one fraction: run k of an expected number, each run split into
// simplification and certification; never going back, below 1 until the end.
class SearchProgress {
public:
    SearchProgress(const ProgressCallback& progress, double expectedRuns)
        : progress_(progress), expected_(expectedRuns) {}
    void nextRun() { ++run_; }
    ProgressCallback stage(double offset, double share) {
        return [this, offset, share](float f, const char* stage) {
            const double runs = std::max(expected_, run_ + 1.0);
            reported_ = std::max(reported_, std::min(0.99, (run_ + offset + share * double(f)) / runs));
            return !progress_ || progress_(float(reported_), stage);
        };
    }

private:
    const ProgressCallback& progress_;
    double expected_;
    double run_ = 0.0;
    double reported_ = 0.0;
};

struct SearchOutcome {
    std::optional<Candidate> best; // the coarsest certified candidate, or the finest one if none was
    bool removedNothing = false;   // the finest run kept every triangle and none coarser was certified
    uint32_t runs = 0;
};

// How a run of the search is judged: by a sampled lower bound of its distance (a quick "likely
// within", certified afterwards) or by the certificate itself.
enum class Judge { Sampled, Certified };

// A run of the search: simplified at `target`, judged, and whether it is within the tolerance.
struct Judged {
    Candidate candidate;
    double measured = 0.0; // the largest distance measured
    bool within = false;
    bool removedNothing = false;
    bool repeated = false; // the triangles of the coarsest run judged within: not judged again
};

// The quick judgement of a run: the larger of two sampled lower bounds, proxy to render first (where
// a coarse triangle hides its largest distance inside), each stopping above the tolerance.
Status judgeQuickly(Candidate& c, const HausdorffSurface& render, double tolerance, double& measured,
                    const ProgressCallback& progress) {
    measured = std::numeric_limits<double>::infinity();
    if (c.mesh.indices.empty()) return {};
    if (Status st = prepare(c); !st) return st;
    Result<double> p2r = sampledLowerBound(*c.surface, render, kSampledProxyTriangles, tolerance, progress);
    if (!p2r) return fail(p2r.error());
    measured = p2r.value();
    if (measured > tolerance) return {};
    Result<double> r2p = sampledLowerBound(render, *c.surface, kSampledRenderTriangles, tolerance, progress);
    if (!r2p) return fail(r2p.error());
    measured = std::max(measured, r2p.value());
    return {};
}

// The next target of the search. While no run failed: up from the last target by the room that run
// left (tolerance / its largest measured distance, within [kSearchStep, kSearchStepMax]); while none
// was within: down by kSearchStep. Either step is doubled for every earlier step the same way (a
// distance that hardly follows the target, as where one collapse decides, is then bracketed in a few
// runs). Then the geometric middle of the bracket [lo, hi]. A failed run's measured distance is not
// used: it stops at the first distance above the tolerance, which depends on timing.
// `runs`: the runs of this bisection so far.
double nextTarget(double lo, double hi, double withinMeasuredOverTolerance, uint32_t runs) {
    const double streak = std::ldexp(1.0, int(std::min(runs, 8u)) - 1);
    if (!std::isfinite(hi))
        return lo * streak *
               std::clamp(1.0 / std::max(withinMeasuredOverTolerance, 1e-9), kSearchStep, kSearchStepMax);
    if (lo <= 0.0) return hi / (streak * kSearchStep);
    return std::sqrt(lo * hi);
}

// The state of the search: the largest target judged within (lo), the smallest judged not (hi).
struct Bracket {
    double lo = 0.0, hi = std::numeric_limits<double>::infinity();
    bool closed() const { return lo > 0.0 && hi <= (1.0 + kSearchPrecision) * lo; }
};

// The render mesh prepared for the certifier (its hierarchy and closest-point structure) on a thread
// of its own, while the mesh is welded and first simplified; the first judgement waits for it.
class PendingSurface {
public:
    explicit PendingSurface(const Mesh& render)
        // (Built on this thread when a thread cannot be started.)
        : future_(std::async(std::launch::async | std::launch::deferred,
                             [&render] { return HausdorffSurface::create(render); })) {}
    // The surface, once ready; fails like HausdorffSurface::create.
    Result<const HausdorffSurface*> get() {
        if (!result_) result_.emplace(future_.get());
        if (!*result_) return fail("render mesh: " + result_->error());
        return &result_->value();
    }

private:
    std::future<Result<HausdorffSurface>> future_;
    std::optional<Result<HausdorffSurface>> result_;
};

// The render mesh simplified once at a fraction of the tolerance (kCoarseLevels).
struct CoarseInput {
    double target = 0.0; // absolute
    Mesh mesh;
};

// The levels of kCoarseLevels that a mesh of `weldedTriangles` gets, by ascending target, each simplified
// from the one before it (the first from `input`).
std::vector<CoarseInput> coarseInputs(const Mesh& input, size_t weldedTriangles, double tolerance,
                                      bool lockBorder) {
    std::vector<CoarseInput> out;
    for (const CoarseLevel& level : kCoarseLevels) {
        if (weldedTriangles <= level.triangles) continue;
        double ignored = 0.0;
        const double target = level.fraction * tolerance;
        Mesh mesh =
            detail::simplifyMeshopt(out.empty() ? input : out.back().mesh, target, 0, lockBorder, ignored);
        out.push_back({target, std::move(mesh)});
    }
    return out;
}

// Everything a search run needs besides its target.
struct SearchContext {
    ProxyBackend backend;
    const Mesh& welded;
    const Mesh& meshoptInput;
    // Pre-simplified inputs by ascending target (kCoarseLevels): a run starts from the last one whose
    // target is at most its own, or from meshoptInput.
    const std::vector<CoarseInput>& coarse;
    double tolerance;
    size_t surfaceTriangles;
    bool withinBudget;
    PendingSurface& render;
    const HausdorffSettings& certifying;
    const ProxySettings& settings;
    SearchProgress& progress;
    std::vector<std::string>& notes;
};

// The largest sampled distance of the runs in `accepted` certified within (-1 when none is).
double certifiedSampled(const std::vector<Candidate>& accepted, double tolerance) {
    double largest = -1.0;
    for (const Candidate& c : accepted)
        if (c.certified && c.within(tolerance)) largest = std::max(largest, c.sampled);
    return largest;
}

// `accepted`: the runs judged within so far, the coarsest last. A coarser target that keeps as many
// triangles as that one gains nothing over it (mostly it is the same proxy: meshoptimizer's collapses
// run in order of error) and is not judged.
Result<Judged> runAndJudge(const SearchContext& k, double target, Judge judge,
                           const std::vector<Candidate>& accepted) {
    const Mesh* input = &k.meshoptInput;
    for (const CoarseInput& level : k.coarse)
        if (target >= level.target) input = &level.mesh;
    Result<Candidate> c =
        simplifyOnce(k.backend, k.welded, *input, target, k.settings, k.progress.stage(0.0, 0.2), k.notes);
    if (!c) return fail(c.error());
    Judged j;
    j.candidate = std::move(c).value();
    if (k.withinBudget && j.candidate.mesh.triangleCount() >= k.surfaceTriangles) { // as good as the render
        j.removedNothing = j.within = true;
        return j;
    }
    if (!accepted.empty() && j.candidate.mesh.triangleCount() == accepted.back().mesh.triangleCount()) {
        j.repeated = true;
        return j;
    }
    Result<const HausdorffSurface*> render = k.render.get();
    if (!render) return fail(render.error());
    if (judge == Judge::Sampled) {
        if (Status st = judgeQuickly(j.candidate, *render.value(), k.tolerance, j.measured,
                                     k.progress.stage(0.2, 0.8));
            !st)
            return fail(st.error());
        j.within = j.measured <= k.tolerance;
        j.candidate.sampled = j.measured;
        if (!j.within || j.measured <= kLikelyFraction * k.tolerance ||
            j.measured <= certifiedSampled(accepted, k.tolerance))
            return j;
    }
    if (Status st = certify(j.candidate, *render.value(), k.certifying, k.progress.stage(0.2, 0.8)); !st)
        return fail(st.error());
    j.measured = j.candidate.lower();
    j.within = j.candidate.within(k.tolerance);
    return j;
}

// Bisects the target from `target` within `bracket` until it closes or the runs are spent. Candidates
// judged within go to `accepted` (coarser ones later); the finest judged not within to `finest`.
Status bisect(const SearchContext& k, Judge judge, double target, Bracket& bracket, uint32_t maxRuns,
              SearchOutcome& out, std::vector<Candidate>& accepted, std::optional<Candidate>& finest) {
    for (uint32_t runs = 1; out.runs < maxRuns && !bracket.closed(); ++runs) {
        Result<Judged> j = runAndJudge(k, target, judge, accepted);
        if (!j) return fail(j.error());
        ++out.runs;
        k.progress.nextRun();
        Candidate& c = j->candidate;
        const bool budgetLimited = c.budgetLimited;
        if (j->repeated) return {}; // converged: a coarser target gives the same proxy
        if (j->removedNothing) {
            out.removedNothing = accepted.empty();
            bracket.lo = target;
        } else if (j->within) {
            bracket.lo = target;
            out.removedNothing = false;
            accepted.push_back(std::move(c));
        } else {
            bracket.hi = std::min(bracket.hi, std::max(c.resultError, bracket.lo));
            if (!finest || c.target < finest->target) finest = std::move(c);
        }
        if (budgetLimited) return {}; // the budget decides the proxy, not the target
        target = nextTarget(bracket.lo, bracket.hi, j->measured / k.tolerance, runs);
    }
    return {};
}

// The coarsest certified proxy one backend gives (see "The search" in docs/PROXIES.md). The
// backend's target error is bisected, each run judged by a sampled lower bound of its distance, until
// the coarsest target judged within is known within kSearchPrecision or maxRuns runs are spent; the
// candidates judged within are then certified from the coarsest down, and the first certified is the
// proxy. When none is, the search goes on below them with every run certified.
Result<SearchOutcome> searchBackend(const SearchContext& k, uint32_t maxRuns) {
    SearchOutcome out;
    std::vector<Candidate> likely;
    std::optional<Candidate> finest; // the finest run not within, for when none is
    Bracket bracket;
    if (Status st = bisect(k, Judge::Sampled, k.tolerance * kStartFraction[uint32_t(k.backend)], bracket,
                           maxRuns, out, likely, finest);
        !st)
        return fail(st.error());
    if (out.removedNothing) return out;
    const uint32_t moreRuns = std::max(2u, maxRuns / 2);
    double failedAbove = std::numeric_limits<double>::infinity(); // finest likely run that failed
    size_t failedTriangles = 0;                                   // and its triangles
    for (; !likely.empty(); likely.pop_back()) {
        Candidate& c = likely.back();
        if (!c.certified)
            if (Status st = certify(c, *k.render.get().value(), k.certifying, k.progress.stage(0.2, 0.8));
                !st)
                return fail(st.error());
        if (c.within(k.tolerance)) {
            out.best = std::move(c);
            break;
        }
        failedAbove = c.resultError;
        failedTriangles = c.mesh.triangleCount();
        if (!finest || c.target < finest->target) finest = std::move(c);
    }
    std::vector<Candidate> certified;
    Bracket rest; // where the search goes on with every run certified
    if (out.best) {
        // Between it and the finest likely run that failed, where that one is enough coarser.
        rest.lo = out.best->target;
        const bool worth = double(out.best->mesh.triangleCount()) > kRefineGain * double(failedTriangles);
        rest.hi = worth ? std::max(failedAbove, rest.lo) : rest.lo;
        certified.push_back(std::move(*out.best));
    } else if (finest) {
        rest.hi = finest->target; // below every run
    }
    if (std::isfinite(rest.hi) && !rest.closed()) {
        const double target = rest.lo > 0.0 ? std::sqrt(rest.lo * rest.hi) : rest.hi / kSearchStep;
        if (Status st =
                bisect(k, Judge::Certified, target, rest, out.runs + moreRuns, out, certified, finest);
            !st)
            return fail(st.error());
    }
    if (!certified.empty()) {
        out.best = std::move(
            *std::min_element(certified.begin(), certified.end(), [](const Candidate& x, const Candidate& y) {
                return x.mesh.triangleCount() < y.mesh.triangleCount();
            }));
        return out;
    }
    if (out.removedNothing || !finest) return out;
    // Nothing certified: the finest candidate, with its sharp bound.
    HausdorffSettings sharp = k.certifying;
    sharp.tolerance = std::numeric_limits<double>::infinity();
    sharp.margin *= kMissedMarginScale;
    if (Status st = certify(*finest, *k.render.get().value(), sharp, k.progress.stage(0.2, 0.8)); !st)
        return fail(st.error());
    k.notes.push_back(std::string(proxyBackendName(k.backend)) + ": no candidate in " +
                      std::to_string(out.runs) + " runs was certified within the tolerance");
    out.best = std::move(finest);
    return out;
}

// The render mesh's own positions, indices and normals.
Mesh ownMesh(const Mesh& m) {
    Mesh out;
    out.positions = m.positions;
    out.indices = m.indices;
    out.normals = m.normals;
    repairNormals(out);
    return out;
}

void finishResult(Proxy& p, const Clock::time_point& start) {
    p.proxyTriangles = p.mesh.triangleCount();
    p.seconds = std::chrono::duration<double>(Clock::now() - start).count();
}

// Cache lookup: the proxy on a hit; nothing on a miss (a corrupt entry adds a note).
std::optional<Proxy> lookUp(const ProxySettings& s, uint64_t key, const ProgressCallback& progress,
                            std::vector<std::string>& notes) {
    if (s.cacheDirectory.empty()) return std::nullopt;
    Result<Proxy> hit = loadCachedProxy(s.cacheDirectory, key);
    if (hit) {
        if (progress) progress(1.0f, "cache");
        return std::move(hit).value();
    }
    if (hit.error().rfind("no cache entry", 0) != 0) notes.push_back(hit.error() + "; rebuilt");
    return std::nullopt;
}

void store(const ProxySettings& s, uint64_t key, Proxy& p) {
    if (s.cacheDirectory.empty()) return;
    if (Status st = storeCachedProxy(s.cacheDirectory, key, p); !st) p.notes.push_back(st.error());
}

// The report fields of a certified candidate.
void takeBound(Proxy& p, const Candidate& c, double tolerance) {
    p.errorBound = c.bound();
    p.proxyToRenderMax = c.proxyToRender.lower;
    p.renderToProxyMax = c.renderToProxy.lower;
    p.samplingMargin = p.errorBound - c.lower();
    p.samples = c.proxyToRender.queries + c.renderToProxy.queries;
    p.toleranceMet = c.within(tolerance);
}

} // namespace

Result<Proxy> buildProxy(const Mesh& render, const ProxySettings& s, const Mesh* authoredCollider,
                         const ProgressCallback& progress) {
    const Clock::time_point start = Clock::now();
    if (Status st = checkSettings(s); !st) return fail(st.error());
    if (Status st = checkMesh(render, "render mesh"); !st) return fail(st.error());
    if (authoredCollider)
        if (Status st = checkMesh(*authoredCollider, "authored collider"); !st) return fail(st.error());

    const double diagonal = referencedDiagonal(render);
    const double tolerance = s.toleranceRelative ? double(s.tolerance) * diagonal : double(s.tolerance);
    const size_t inputTriangles = render.triangleCount();
    const size_t surfaceTriangles = surfaceTriangleCount(render);
    HausdorffSettings certifying;
    certifying.margin =
        double(s.marginFraction) * (tolerance > 0.0 ? tolerance : kZeroToleranceScale * diagonal);
    certifying.tolerance = tolerance;
    certifying.roomShare = kRoomShare;
    certifying.minRoom = kMinRoom;

    Proxy proxy;
    proxy.tolerance = tolerance;
    proxy.inputTriangles = inputTriangles;

    if (authoredCollider) {
        const uint64_t key = proxyCacheKey(render, s, authoredCollider);
        if (std::optional<Proxy> hit = lookUp(s, key, progress, proxy.notes)) {
            hit->notes = std::move(proxy.notes);
            finishResult(*hit, start);
            return std::move(*hit);
        }
        proxy.mesh = ownMesh(*authoredCollider);
        proxy.source = ProxySource::AuthoredCollider;
        proxy.backend = ProxyBackend::None;
        Result<HausdorffSurface> renderSurface = HausdorffSurface::create(render);
        if (!renderSurface) return fail("render mesh: " + renderSurface.error());
        if ((renderSurface->surfaceTriangleCount() == 0) != (surfaceTriangleCount(proxy.mesh) == 0))
            return fail("authored collider: exactly one of the collider and the render mesh has a surface");
        Candidate c;
        c.mesh = proxy.mesh;
        HausdorffSettings sharp = certifying;
        sharp.tolerance = std::numeric_limits<double>::infinity();
        auto measure = [&](float f, const char* stage) { return !progress || progress(f, stage); };
        if (Status st = certify(c, renderSurface.value(), sharp, measure); !st)
            return fail(st.error() == "cancelled" ? st.error() : "authored collider: " + st.error());
        takeBound(proxy, c, tolerance);
        proxy.drawnNormals =
            DrawnNormals::build(render, renderSurface->query(), proxy.mesh, proxy.errorBound);
        finishResult(proxy, start);
        store(s, key, proxy);
        return proxy;
    }

    const bool withinBudget = s.maxTriangles == 0 || inputTriangles <= s.maxTriangles;
    if (surfaceTriangles == 0 ||
        (withinBudget && (inputTriangles < s.smallMeshTriangles || tolerance == 0.0))) {
        if (surfaceTriangles == 0)
            proxy.notes.push_back("the render mesh has no surface: the proxy is empty");
        else
            proxy.mesh = ownMesh(render);
        proxy.source = ProxySource::OwnMesh;
        finishResult(proxy, start);
        return proxy;
    }

    const uint64_t key = proxyCacheKey(render, s, nullptr);
    if (std::optional<Proxy> hit = lookUp(s, key, progress, proxy.notes)) {
        hit->notes = std::move(proxy.notes);
        finishResult(*hit, start);
        return std::move(*hit);
    }

    const ProxyBackend backend = resolveProxyBackend(s.backend, inputTriangles, tolerance, diagonal);
    PendingSurface renderSurface(render);
    const Mesh welded = weldedSurface(render);
    SearchProgress searchProgress(progress, kExpectedRuns);
    Mesh meshoptInput;
    if (backend == ProxyBackend::MeshOpt) {
        meshoptInput = welded;
        if (s.keepSharpFeatures) splitCreases(meshoptInput, s.featureAngleDegrees);
    }
    // The certificate still measures every candidate against the render mesh.
    const std::vector<CoarseInput> coarse =
        backend == ProxyBackend::MeshOpt && s.maxTriangles == 0
            ? coarseInputs(meshoptInput, welded.triangleCount(), tolerance, s.keepBoundaries)
            : std::vector<CoarseInput>();
    const SearchContext context{backend,          welded,       meshoptInput,  coarse,     tolerance,
                                surfaceTriangles, withinBudget, renderSurface, certifying, s,
                                searchProgress,   proxy.notes};
    Result<SearchOutcome> outcome = searchBackend(context, s.maxAttempts);
    if (!outcome) return fail(outcome.error());
    proxy.attempts = outcome->runs;
    if (!outcome->best) {
        proxy.notes.push_back("the render mesh is its own proxy");
        proxy.mesh = ownMesh(render);
        proxy.source = ProxySource::OwnMesh;
    } else {
        Candidate& best = outcome->best.value();
        proxy.mesh = std::move(best.mesh);
        proxy.source = ProxySource::Simplified;
        proxy.backend = best.backend;
        takeBound(proxy, best, tolerance);
        Result<const HausdorffSurface*> drawn = renderSurface.get(); // ready: the search certified `best`
        if (!drawn) return fail(drawn.error());
        proxy.drawnNormals =
            DrawnNormals::build(render, drawn.value()->query(), proxy.mesh, proxy.errorBound);
        if (!proxy.toleranceMet)
            proxy.notes.push_back(
                std::string("h = ") + std::to_string(proxy.errorBound) + " is above the tolerance " +
                std::to_string(tolerance) +
                (best.budgetLimited ? " (the triangle budget stopped simplification)" : ""));
    }
    if (progress && !progress(1.0f, "measure")) return fail("cancelled");
    finishResult(proxy, start);
    store(s, key, proxy);
    return proxy;
}

} // namespace spatter
