#pragma once
// Internal to core: the geometry shared by the closest-point queries (MeshDistance.cpp) and the
// Hausdorff certifier (HausdorffBound.cpp): mesh checks, the drawn surface of a mesh, the exact
// point-triangle distance, the enclosing radius of a triangle, and a small parallel loop.

#include "spatter/core/Mesh.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Threads.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

namespace spatter::detail {

// Relative allowance added to every bound for the rounding of double arithmetic (points and
// point-triangle distances are computed in double from float vertex positions).
constexpr double kRoundingAllowance = 1e-9;

inline Status checkTriangles(const Mesh& mesh) {
    const size_t n = mesh.positions.size();
    if (mesh.indices.size() % 3 != 0)
        return fail("index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
    for (size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= n)
            return fail("index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) +
                        ", past the vertex count " + std::to_string(n));
    for (size_t i = 0; i < n; ++i) {
        const glm::vec3& p = mesh.positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return fail("position " + std::to_string(i) + " is not finite (NaN or Inf)");
    }
    return {};
}

// The corner k at which the longest edge of the triangle `p` starts (it runs from k to k + 1): the
// edge a subdivision halves.
inline int longestEdge(const glm::dvec3 p[3]) {
    int k = 0;
    double longest = -1.0;
    for (int e = 0; e < 3; ++e) {
        const glm::dvec3 d = p[(e + 1) % 3] - p[e];
        if (glm::dot(d, d) > longest) longest = glm::dot(d, d), k = e;
    }
    return k;
}

inline glm::dvec3 corner(const Mesh& mesh, size_t triangle, int k) {
    return glm::dvec3(mesh.positions[mesh.indices[3 * triangle + size_t(k)]]);
}

// Whether the triangle (a, b, c) of `positions` is part of the drawn surface: three distinct indices
// and a non-zero cross product.
inline bool isSurfaceTriangle(const std::vector<glm::vec3>& positions, uint32_t a, uint32_t b, uint32_t c) {
    if (a == b || b == c || c == a) return false;
    const glm::dvec3 pa(positions[a]);
    const glm::dvec3 n = glm::cross(glm::dvec3(positions[b]) - pa, glm::dvec3(positions[c]) - pa);
    return n.x != 0.0 || n.y != 0.0 || n.z != 0.0;
}

// The triangles of the drawn surface (isSurfaceTriangle).
inline std::vector<uint32_t> surfaceTriangles(const Mesh& mesh) {
    std::vector<uint32_t> out;
    out.reserve(mesh.triangleCount());
    for (size_t t = 0; t < mesh.triangleCount(); ++t)
        if (isSurfaceTriangle(mesh.positions, mesh.indices[3 * t], mesh.indices[3 * t + 1],
                              mesh.indices[3 * t + 2]))
            out.push_back(uint32_t(t));
    return out;
}

// Closest point to `p` on the triangle (a, b, c) (Ericson, Real-Time Collision Detection, 5.1.5).
// The triangle has non-zero area.
inline glm::dvec3 closestOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                    const glm::dvec3& c) {
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return a;
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + ab * (d1 / (d1 - d3));
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + ac * (d2 / (d2 - d6));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const double denom = 1.0 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

// Radius of the smallest circle enclosing the triangle: the circumradius when no angle is obtuse,
// half the longest edge otherwise. Every point of the triangle lies within it of a corner.
inline double enclosingRadius(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const double ab2 = glm::dot(b - a, b - a), bc2 = glm::dot(c - b, c - b), ca2 = glm::dot(a - c, a - c);
    const double longest2 = std::max({ab2, bc2, ca2});
    const double halfLongest = 0.5 * std::sqrt(longest2);
    if (longest2 >= ab2 + bc2 + ca2 - longest2) return halfLongest;
    const double twiceArea = glm::length(glm::cross(b - a, c - a));
    const double circumradius = std::sqrt(ab2 * bc2 * ca2) / (2.0 * twiceArea);
    return std::isfinite(circumradius) ? std::max(circumradius, halfLongest) : halfLongest;
}

// Runs body(begin, end, worker) over [0, count) in chunks on up to `workers` threads. The calling
// thread takes part (as worker 0) and reports done/count between its chunks; when report returns
// false the remaining chunks are skipped and false is returned. `stop` set by a body skips the
// remaining chunks too (the call then returns true).
template <class Body, class Report>
bool parallelChunks(size_t count, size_t chunk, unsigned workers, Body&& body, Report&& report,
                    const std::atomic<bool>* stop = nullptr) {
    const size_t chunks = (count + chunk - 1) / chunk;
    std::atomic<size_t> next{0}, done{0};
    std::atomic<bool> cancelled{false};
    auto stopped = [&] {
        return cancelled.load(std::memory_order_relaxed) || (stop && stop->load(std::memory_order_relaxed));
    };
    auto run = [&](unsigned worker) {
        while (!stopped()) {
            const size_t c = next.fetch_add(1);
            if (c >= chunks) break;
            const size_t begin = c * chunk, end = std::min(count, begin + chunk);
            body(begin, end, worker);
            done.fetch_add(end - begin);
            if (worker == 0 && !report(double(done.load()) / double(std::max<size_t>(count, 1))))
                cancelled = true;
        }
    };
    std::vector<std::thread> threads;
    for (unsigned w = 1; w < workers && w < chunks; ++w)
        threads.emplace_back(run, w);
    run(0);
    for (std::thread& t : threads)
        t.join();
    return !cancelled.load();
}

inline unsigned workerCount() {
    const unsigned hw = std::thread::hardware_concurrency();
    return std::clamp(hw, 1u, kMaxThreads);
}

// What is wrong with `threads` as a thread count of the core's settings (0 to kMaxThreads); "" when
// nothing is.
inline std::string threadsProblem(unsigned threads) {
    if (threads <= kMaxThreads) return {};
    return "threads " + std::to_string(threads) + " is above " + std::to_string(kMaxThreads);
}

// The threads a step asked for `threads` uses: the hardware's for 0, else at most kMaxThreads.
inline unsigned workersFor(unsigned threads) {
    return threads > 0 ? std::min(threads, kMaxThreads) : workerCount();
}

} // namespace spatter::detail
