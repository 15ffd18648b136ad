#include "ProxySearch.hpp"

#include "ProxyMeshes.hpp"
#include "ProxySimplifiers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace spatter::detail {

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
constexpr size_t kSampledProxyTriangles = 8192, kSampledRenderTriangles = 512;
constexpr double kLikelyFraction = 0.9;
// Points kept that showed earlier candidates beyond the tolerance (Witnesses).
constexpr size_t kMaxWitnesses = 16;
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
constexpr CoarseLevel kCoarseLevels[] = {{100'000, 0.05}, {5'000, 0.2}};
// A run above the coarsest run judged within starts from that run's mesh instead (creases split
// again) where that run measured at most kCascadeRoom of the tolerance: meshoptimizer then measures
// its error from that mesh, not from the render mesh, and often goes further at the same certified
// distance. The two distances add up, so a base with less room than this mostly fails, and a run
// from a base that fails is redone from the render mesh.
constexpr double kCascadeRoom = 0.65;
// A proxy that misses the tolerance gets a sharp bound with this many times the certification margin:
// its h only sizes decal boxes, and a tighter one costs many more queries.
constexpr double kMissedMarginScale = 4.0;
// With a tolerance of 0 (possible for an authored collider) the sampling margin is taken relative to
// this fraction of the render mesh's diagonal instead.
constexpr double kZeroToleranceScale = 0.001;

// One simplification run with the chosen backend, welded (weldedSurface; the proxy the search keeps is
// finished by the builder), made to respect the budget: a run stopped by the
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
    c.mesh = weldedSurface(m.value());
    if (budget > 0 && c.mesh.triangleCount() > budget) {
        c.budgetLimited = true;
        m = run(std::numeric_limits<double>::infinity());
        if (!m) return fail(m.error());
        c.mesh = weldedSurface(m.value());
    }
    if (budget > 0 && c.mesh.triangleCount() > budget) {
        notes.push_back(std::string(proxyBackendName(backend)) + " stopped at " +
                        std::to_string(c.mesh.triangleCount()) + " triangles, above the budget of " +
                        std::to_string(budget) + ": sloppy simplification used");
        c.mesh = weldedSurface(detail::simplifySloppy(welded, budget));
    }
    if (budget > 0 && (c.mesh.triangleCount() > budget || c.mesh.indices.empty()))
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

// Points that showed earlier candidates beyond the tolerance, against which later candidates are
// checked before they are certified: a certificate costs several runs, the check a query or two a
// point. A candidate that bridges a groove of the render mesh, which the samples miss, is often
// followed by others that bridge it too.
class Witnesses {
public:
    // Keeps where c's certificate measured a distance above `tolerance`, each way.
    void keep(const Candidate& c, double tolerance) {
        if (c.renderToProxy.lower > tolerance) add({c.renderToProxy.farthest, true});
        if (c.proxyToRender.lower > tolerance) add({c.proxyToRender.farthest, false});
    }
    // The largest distance the witnesses show on c (its surface prepared): a render point's
    // distance to c, and, for a point of an earlier proxy too far from the render mesh, the
    // distance to the render mesh of c's point closest to it. Each is a distance attained.
    double largest(const Candidate& c, const HausdorffSurface& render) const {
        double out = 0.0;
        for (const Point& w : points_) {
            const std::optional<ClosestPoint> onC = c.surface->query().closest(w.p);
            if (!onC) continue;
            if (w.onRender) {
                out = std::max(out, onC->distance);
            } else if (const std::optional<ClosestPoint> back = render.query().closest(onC->point)) {
                out = std::max(out, back->distance);
            }
        }
        return out;
    }

private:
    struct Point {
        glm::dvec3 p;
        bool onRender;
    };
    void add(const Point& w) {
        if (points_.size() < kMaxWitnesses) points_.push_back(w);
    }
    std::vector<Point> points_;
};

// Turns c down where a witness shows it beyond the tolerance: its certificate is then that
// distance, exceeded. Whether it did.
Result<bool> turnedDownByWitness(Candidate& c, const HausdorffSurface& render, double tolerance,
                                 const Witnesses& witnesses) {
    if (c.mesh.indices.empty()) return false;
    if (Status st = prepare(c); !st) return fail(st.error());
    const double shown = witnesses.largest(c, render);
    if (!(shown > tolerance)) return false;
    c.proxyToRender = c.renderToProxy = {shown, std::numeric_limits<double>::infinity(), true};
    c.certified = true;
    return true;
}

// Certifies c unless a witness shows it beyond the tolerance already; keeps the certificate's
// witnesses where it fails. Either way the answer is exact, so the witnesses change what a decision
// costs, never the decision (nor, since a certificate's witness depends on which thread found it,
// the proxy).
Status certifyUnlessWitnessed(Candidate& c, const HausdorffSurface& render, const SearchContext& k,
                              Witnesses& witnesses) {
    Result<bool> down = turnedDownByWitness(c, render, k.tolerance, witnesses);
    if (!down) return fail(down.error());
    if (down.value()) return {};
    if (Status st = certify(c, render, k.certifying, k.progress.stage(0.2, 0.8)); !st) return st;
    if (!c.within(k.tolerance)) witnesses.keep(c, k.tolerance);
    return {};
}

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
// a coarse triangle hides its largest distance inside; the triangles earlier runs kept are measured
// again only where they could raise it, `judged`), each stopping above the tolerance.
Status judgeQuickly(Candidate& c, const HausdorffSurface& render, double tolerance, unsigned threads,
                    SampleMemory& judged, double& measured, const ProgressCallback& progress) {
    measured = std::numeric_limits<double>::infinity();
    if (c.mesh.indices.empty()) return {};
    Result<double> p2r =
        sampledLowerBound(c.mesh, render, kSampledProxyTriangles, tolerance, progress, threads, &judged);
    if (!p2r) return fail(p2r.error());
    measured = p2r.value();
    if (measured > tolerance) return {};
    if (Status st = prepare(c); !st) return st;
    Result<double> r2p =
        sampledLowerBound(render, *c.surface, kSampledRenderTriangles, tolerance, progress, threads);
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

// The largest sampled distance of the runs in `accepted` certified within (-1 when none is).
double certifiedSampled(const std::vector<Candidate>& accepted, double tolerance) {
    double largest = -1.0;
    for (const Candidate& c : accepted)
        if (c.certified && c.within(tolerance)) largest = std::max(largest, c.sampled);
    return largest;
}

// A run from `input` at `target`, judged. `accepted`: the runs judged within so far, the coarsest
// last. A coarser target that keeps as many triangles as that one gains nothing over it (mostly it is
// the same proxy: meshoptimizer's collapses run in order of error) and is not judged.
Result<Judged> runAndJudgeFrom(const SearchContext& k, const Mesh& input, double target, Judge judge,
                               const std::vector<Candidate>& accepted, Witnesses& witnesses) {
    Result<Candidate> c =
        simplifyOnce(k.backend, k.welded, input, target, k.settings, k.progress.stage(0.0, 0.2), k.notes);
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
        if (Status st = judgeQuickly(j.candidate, *render.value(), k.tolerance, k.settings.threads, k.judged,
                                     j.measured, k.progress.stage(0.2, 0.8));
            !st)
            return fail(st.error());
        j.within = j.measured <= k.tolerance;
        j.candidate.sampled = j.measured;
        if (!j.within || j.measured <= kLikelyFraction * k.tolerance ||
            j.measured <= certifiedSampled(accepted, k.tolerance))
            return j;
    }
    if (Status st = certifyUnlessWitnessed(j.candidate, *render.value(), k, witnesses); !st)
        return fail(st.error());
    j.measured = j.candidate.lower();
    j.within = j.candidate.within(k.tolerance);
    return j;
}

// The run to start a run at `target` from (kCascadeRoom), or none.
const Candidate* cascadeBase(const SearchContext& k, double target, const std::vector<Candidate>& accepted) {
    if (k.backend != ProxyBackend::MeshOpt || accepted.empty()) return nullptr;
    const Candidate& base = accepted.back(); // judged within: never empty
    const double measured = base.certified ? base.lower() : base.sampled;
    return measured <= kCascadeRoom * k.tolerance && target > base.target ? &base : nullptr;
}

// A run of the search at `target`: from the cascade's base where there is one, and where that run is
// not within, from the render mesh (or the coarsest pre-simplified input at most `target`).
Result<Judged> runAndJudge(const SearchContext& k, double target, Judge judge,
                           const std::vector<Candidate>& accepted, Witnesses& witnesses) {
    if (const Candidate* base = cascadeBase(k, target, accepted)) {
        Result<Judged> j =
            runAndJudgeFrom(k, meshoptInputOf(base->mesh, k.settings), target, judge, accepted, witnesses);
        if (j) j->candidate.resultError = target; // meshoptimizer's error is from the base, not the render
        if (!j || j->within || j->repeated) return j;
    }
    const Mesh* input = &k.meshoptInput;
    for (const CoarseInput& level : k.coarse)
        if (target >= level.target) input = &level.mesh;
    return runAndJudgeFrom(k, *input, target, judge, accepted, witnesses);
}

// Bisects the target from `target` within `bracket` until it closes or the runs are spent. Candidates
// judged within go to `accepted` (coarser ones later); the finest judged not within to `finest`.
Status bisect(const SearchContext& k, Judge judge, double target, Bracket& bracket, uint32_t maxRuns,
              SearchOutcome& out, std::vector<Candidate>& accepted, std::optional<Candidate>& finest,
              Witnesses& witnesses) {
    for (uint32_t runs = 1; out.runs < maxRuns && !bracket.closed(); ++runs) {
        Result<Judged> j = runAndJudge(k, target, judge, accepted, witnesses);
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

} // namespace

HausdorffSettings certifyingSettings(double tolerance, double diagonal, float marginFraction,
                                     unsigned threads) {
    HausdorffSettings s;
    s.margin = double(marginFraction) * (tolerance > 0.0 ? tolerance : kZeroToleranceScale * diagonal);
    s.tolerance = tolerance;
    s.roomShare = kRoomShare;
    s.minRoom = kMinRoom;
    s.threads = threads;
    return s;
}

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

Result<SearchOutcome> searchBackend(const SearchContext& k, uint32_t maxRuns) {
    SearchOutcome out;
    std::vector<Candidate> likely;
    std::optional<Candidate> finest; // the finest run not within, for when none is
    Witnesses witnesses;
    Bracket bracket;
    if (Status st = bisect(k, Judge::Sampled, k.tolerance * kStartFraction[uint32_t(k.backend)], bracket,
                           maxRuns, out, likely, finest, witnesses);
        !st)
        return fail(st.error());
    if (out.removedNothing) return out;
    const uint32_t moreRuns = std::max(2u, maxRuns / 2);
    double failedAbove = std::numeric_limits<double>::infinity(); // finest likely run that failed
    size_t failedTriangles = 0;                                   // and its triangles
    for (; !likely.empty(); likely.pop_back()) {
        Candidate& c = likely.back();
        if (!c.certified)
            if (Status st = certifyUnlessWitnessed(c, *k.render.get().value(), k, witnesses); !st)
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
        if (Status st = bisect(k, Judge::Certified, target, rest, out.runs + moreRuns, out, certified, finest,
                               witnesses);
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

} // namespace spatter::detail
