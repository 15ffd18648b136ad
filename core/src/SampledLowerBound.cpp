#include "HausdorffSurfaceImpl.hpp"

#include "spatter/core/SampleMemory.hpp"

#include "SurfaceGeometry.hpp"

#include <algorithm>
#include <atomic>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace spatter {

namespace {

using Impl = HausdorffSurface::Impl;

// The samples of triangle p (its centroid and edge midpoints), each raising `largest` where it lies
// farther: "is b within `largest` of it?" first, a search that stops at the first triangle answering
// yes, and the exact distance only where it is not. What they showed of the triangle.
SampleMemory::Known measureSamples(const Impl& b, const glm::dvec3 (&p)[3], double& largest) {
    double exact = -1.0, bound = 0.0;
    for (const glm::dvec3& q :
         {(p[0] + p[1] + p[2]) / 3.0, 0.5 * (p[0] + p[1]), 0.5 * (p[1] + p[2]), 0.5 * (p[2] + p[0])}) {
        if (b.query.within(q, largest)) {
            bound = std::max(bound, largest);
            continue;
        }
        const std::optional<ClosestPoint> c = b.query.closest(q);
        exact = std::max(exact, c ? c->distance : std::numeric_limits<double>::infinity());
        largest = std::max(largest, exact);
    }
    return {std::max(exact, bound), exact >= bound};
}

// sampledLowerBound over `count` triangles of `from`, whose corners corner(i, k) gives (k = 0, 1, 2),
// with `memory` (SampleMemory.hpp) where given: a triangle it knows is measured only where its samples
// could lie farther than the largest distance found so far, and what is measured is added to it.
template <class Corner>
Result<double> sampledFrom(size_t count, Corner&& corner, const Impl& b, size_t maxTriangles,
                           double stopAbove, const ProgressCallback& progress, unsigned threads,
                           SampleMemory* memory) {
    if (count == 0) return 0.0;
    if (b.triangles.empty()) return fail("the target mesh has no surface (no triangle of non-zero area)");
    const size_t stride = std::max<size_t>(1, count / std::max<size_t>(maxTriangles, 1));
    const size_t sampled = (count + stride - 1) / stride;
    const unsigned workers = detail::workersFor(threads);
    std::vector<double> worst(workers, 0.0);
    std::vector<std::vector<std::pair<SampleMemory::TriangleKey, SampleMemory::Known>>> learned(workers);
    std::atomic<bool> above{false};
    // Only a sample farther than the worker's largest so far changes the result.
    auto sample = [&](const glm::dvec3(&p)[3], unsigned w) {
        if (!memory) {
            measureSamples(b, p, worst[w]);
            return;
        }
        const SampleMemory::TriangleKey key = SampleMemory::keyOf(p[0], p[1], p[2]);
        const SampleMemory::Known* known = memory->find(key);
        if (known && known->attained)
            worst[w] = std::max(worst[w], known->farthest);
        else if (!known || known->farthest > worst[w])
            learned[w].emplace_back(key, measureSamples(b, p, worst[w]));
    };
    auto report = [&](double f) { return !progress || progress(float(f), "measure"); };
    const bool finished = detail::parallelChunks(
        sampled, 256, workers,
        [&](size_t begin, size_t end, unsigned w) {
            for (size_t i = begin; i < end && !above.load(std::memory_order_relaxed); ++i) {
                const glm::dvec3 p[3] = {corner(i * stride, 0), corner(i * stride, 1), corner(i * stride, 2)};
                sample(p, w);
                if (worst[w] > stopAbove) above.store(true, std::memory_order_relaxed);
            }
        },
        report, &above);
    if (memory) // read-only while the workers ran
        for (const auto& found : learned)
            for (const auto& [key, known] : found)
                memory->keep(key, known);
    if (!finished) return fail("cancelled");
    return *std::max_element(worst.begin(), worst.end());
}

} // namespace

Result<double> sampledLowerBound(const HausdorffSurface& from, const HausdorffSurface& to,
                                 size_t maxTriangles, double stopAbove, const ProgressCallback& progress,
                                 unsigned threads) {
    const Impl& a = from.impl();
    auto corner = [&a](size_t i, int k) { return a.positions[a.triangles[i][size_t(k)]]; };
    return sampledFrom(a.triangles.size(), corner, to.impl(), maxTriangles, stopAbove, progress, threads,
                       nullptr);
}

Result<double> sampledLowerBound(const Mesh& from, const HausdorffSurface& to, size_t maxTriangles,
                                 double stopAbove, const ProgressCallback& progress, unsigned threads,
                                 SampleMemory* memory) {
    if (Status st = detail::checkTriangles(from); !st) return fail(st.error());
    const std::vector<uint32_t> surface = detail::surfaceTriangles(from);
    auto corner = [&](size_t i, int k) { return detail::corner(from, surface[i], k); };
    return sampledFrom(surface.size(), corner, to.impl(), maxTriangles, stopAbove, progress, threads, memory);
}

} // namespace spatter
