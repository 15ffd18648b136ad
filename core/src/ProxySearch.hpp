#pragma once
// Internal to core: the search for the coarsest certified proxy (docs/PROXIES.md, "The search"). A
// backend's target error is bisected, each run judged by sampled distances and the candidates judged
// within certified; buildProxy (ProxyBuilder.cpp) prepares the search's inputs and takes its result.

#include "spatter/core/HausdorffBound.hpp"
#include "spatter/core/Mesh.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/SampleMemory.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <future>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace spatter::detail {

// The settings of every certificate of a build at `tolerance` (absolute): its margin, `marginFraction`
// of the tolerance (of a thousandth of `diagonal` for a tolerance of 0), shrinking near the tolerance,
// on `threads` threads (ProxySettings::threads).
HausdorffSettings certifyingSettings(double tolerance, double diagonal, float marginFraction,
                                     unsigned threads);

// A run of the search made a proxy: its mesh, how it was made, and its certificate once made.
struct Candidate {
    Mesh mesh; // welded: positions and indices (finishProxy makes the kept one a proxy)
    ProxyBackend backend = ProxyBackend::None;
    bool budgetLimited = false; // the budget, not the tolerance, stopped simplification
    double target = 0.0;        // the backend's tolerance for this run (absolute)
    // meshoptimizer from the render mesh or a pre-simplified copy: the error it reports for the result
    // (absolute); its collapses run in order of error, so a target between this and `target` gives the
    // same mesh from that input. Otherwise (OpenMesh, or a run from an earlier run): `target`.
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

// Certifies a candidate against the render mesh (HausdorffBound.hpp): both directions at once
// (boundBothWays: with a finite `settings.tolerance`, the first distance above it either way stops
// both).
Status certify(Candidate& c, const HausdorffSurface& render, const HausdorffSettings& settings,
               const ProgressCallback& progress);

// Progress of the whole search as one fraction: run k of an expected number, each run split into
// simplification and certification; never going back, below 1 until the end.
class SearchProgress {
public:
    explicit SearchProgress(const ProgressCallback& progress) : progress_(progress) {}
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
    double expected_ = 5.0; // runs the progress is scaled to (a typical search)
    double run_ = 0.0;
    double reported_ = 0.0;
};

struct SearchOutcome {
    std::optional<Candidate> best; // the coarsest certified candidate, or the finest one if none was
    bool removedNothing = false;   // the finest run kept every triangle and none coarser was certified
    uint32_t runs = 0;
};

// The render mesh prepared for the certifier (its hierarchy and closest-point structure) on a thread
// of its own, while the mesh is welded and first simplified; the first judgement waits for it. With
// one thread (ProxySettings::threads), or when a thread cannot be started, on this thread when needed.
class PendingSurface {
public:
    PendingSurface(const Mesh& render, unsigned threads)
        : future_(
              std::async(threads == 1 ? std::launch::deferred : std::launch::async | std::launch::deferred,
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
                                      bool lockBorder);

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
    SampleMemory& judged; // what the runs' judgements measured on their triangles toward the render mesh
};

// The coarsest certified proxy one backend gives (see "The search" in docs/PROXIES.md). The
// backend's target error is bisected, each run judged by a sampled lower bound of its distance, until
// the coarsest target judged within is known within kSearchPrecision or maxRuns runs are spent; the
// candidates judged within are then certified from the coarsest down, and the first certified is the
// proxy. When none is, the search goes on below them with every run certified.
Result<SearchOutcome> searchBackend(const SearchContext& k, uint32_t maxRuns);

} // namespace spatter::detail
