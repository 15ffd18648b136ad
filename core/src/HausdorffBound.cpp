#include "spatter/core/HausdorffBound.hpp"

#include "HausdorffSurfaceImpl.hpp"
#include "PieceOverlay.hpp"
#include "SurfaceGeometry.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace spatter {

namespace {

// A node of at most this many triangles is bounded over its triangles' corners (the convex hull of
// its surface) instead of its box corners.
constexpr uint32_t kHullTriangles = 16;
// Triangle centroids of A measured before the walk: the starting lower bound of every subtree.
constexpr size_t kStartSamples = 1024, kStartChunk = 64;
// Subtrees handed out to the threads: a fixed number, whatever the thread count, since each subtree's
// walk raises its own acceptance level, so that the bound depends on how the hierarchy is cut (16 a
// thread for the most threads, kMaxThreads; on two, as fast as 64 over 96 proxy builds).
constexpr size_t kSubtrees = 256;
// Subtrees walked first, per thread: those with the farthest starting samples (walkAll).
constexpr size_t kFarthestFirstPerWorker = 2;
// How far outside an edge of B the overlay bound clips a part, relative to the largest coordinates of
// both meshes: above the rounding of the parts' corners, so that neighbouring parts overlap (and a
// proxy corner lying on an edge, as one of the render mesh's vertices does, belongs to both sides).
constexpr double kOverlayEps = 1e-12;
// The overlay's cost model: it pays where it likely costs less than cutting, counting four steps per
// triangle of B under a piece and four steps as one exact distance query (it visits about one triangle
// per triangle under the piece; counting one to four steps per triangle gave the same build times on
// the shared meshes and the gallery).
constexpr double kStepsPerTriangle = 4.0, kStepsPerQuery = 4.0;
// B's mean triangle area, as a fraction of the acceptance level squared, below which no piece is
// laid over B: pieces are then bounded by Lipschitz long before they cover enough of B's triangles
// for the overlay to pay, and B's edges need not be linked at all.
constexpr double kOverlayArea = 0.05;

using Impl = HausdorffSurface::Impl;
using Node = detail::HausdorffNode;

// Which of a surface's triangles (hierarchy order) the other surface shares corner for corner, and
// which of its nodes hold only such triangles: every distance from them to the other surface is 0.
// Empty where none was looked for.
struct Shared {
    std::vector<uint8_t> triangles, nodes;
    bool triangle(uint32_t t) const { return !triangles.empty() && triangles[t] != 0; }
    bool node(uint32_t n) const { return !nodes.empty() && nodes[n] != 0; }
};

void markNodes(const Impl& s, Shared& shared) {
    shared.nodes.assign(s.nodes.size(), 0);
    for (size_t i = s.nodes.size(); i-- > 0;) { // children come after their parent
        const Node& n = s.nodes[i];
        uint8_t all = 1;
        if (n.child != 0) {
            all = shared.nodes[n.child] & shared.nodes[n.child + 1];
        } else {
            for (uint32_t t = n.first; t < n.first + n.count; ++t)
                all &= shared.triangles[t];
        }
        shared.nodes[i] = all;
    }
}

// The triangles a and b share, for each of them: the smaller surface's looked up in the larger's table;
// none where the larger has too many more triangles (detail::looksForShared).
std::pair<Shared, Shared> sharedTriangles(const Impl& a, const Impl& b) {
    const bool aLarger = a.triangles.size() >= b.triangles.size();
    const Impl& large = aLarger ? a : b;
    const Impl& small = aLarger ? b : a;
    if (!detail::looksForShared(large.triangles.size(), small.triangles.size())) return {};
    Shared sa, sb;
    sa.triangles.assign(a.triangles.size(), 0);
    sb.triangles.assign(b.triangles.size(), 0);
    std::vector<uint8_t>& onLarge = (aLarger ? sa : sb).triangles;
    std::vector<uint8_t>& onSmall = (aLarger ? sb : sa).triangles;
    for (size_t i = 0; i < small.triangles.size(); ++i) {
        const std::array<uint32_t, 3>& t = small.triangles[i];
        large.corners().forEachSame(large.positions, large.triangles,
                                    {small.positions[t[0]], small.positions[t[1]], small.positions[t[2]]},
                                    [&](uint32_t j) {
                                        onLarge[j] = 1;
                                        onSmall[i] = 1;
                                    });
    }
    markNodes(a, sa);
    markNodes(b, sb);
    return {std::move(sa), std::move(sb)};
}

struct Measured {
    double distance = 0.0;
    uint32_t triangle = 0; // mesh triangle of the target holding the closest point
};

// Distances at A's vertices, measured at most once per bound: a claim flag, then the value.
class VertexCache {
public:
    explicit VertexCache(size_t n) : state_(n), value_(n) {}
    // `queries` counts the vertex once, for the thread that stores it (two threads may measure it at
    // once), so that the count does not depend on timing.
    template <class Measure> Measured get(uint32_t v, Measure&& measure, size_t& queries) {
        if (state_[v].load(std::memory_order_acquire) == 2) return value_[v];
        const Measured m = measure();
        uint8_t expected = 0;
        if (state_[v].compare_exchange_strong(expected, 1, std::memory_order_relaxed)) {
            value_[v] = m;
            state_[v].store(2, std::memory_order_release);
            ++queries;
        }
        return m;
    }

private:
    std::vector<std::atomic<uint8_t>> state_; // 0 unmeasured, 1 being stored, 2 ready
    std::vector<Measured> value_;
};

// A triangle piece of A: corners, their distances to B and the triangles of B closest to them.
struct Piece {
    glm::dvec3 p[3];
    Measured m[3];
};

// Bounds one subtree of A's hierarchy against B (see the top of HausdorffBound.hpp).
class Walker {
public:
    Walker(const Impl& a, const Impl& b, const Shared& shared, const HausdorffSettings& s, VertexCache& cache,
           std::atomic<bool>& exceeded, double lowerStart)
        : lower(lowerStart), a_(a), b_(b), shared_(shared), s_(s), cache_(cache), exceeded_(exceeded),
          // Bounds at most this are at most the tolerance once the rounding allowance is added.
          accept_(std::isfinite(s.tolerance)
                      ? std::max(0.0, (s.tolerance - detail::kRoundingAllowance * a.scale) /
                                          (1.0 + detail::kRoundingAllowance))
                      : 0.0),
          overlayEps_(kOverlayEps * (a.scale + b.scale)) {}

    // Measures the point p of A (raises the lower bound); its distance.
    double sample(const glm::dvec3& p) {
        ++queries;
        const double d = measure(p).distance;
        see(d, p);
        return d;
    }

    void walk(uint32_t root) {
        std::vector<uint32_t> stack{root};
        while (!stack.empty() && !exceeded_.load(std::memory_order_relaxed)) {
            const uint32_t i = stack.back();
            stack.pop_back();
            if (shared_.node(i)) continue; // on B: every distance 0
            const Node& n = a_.nodes[i];
            const double bound = nodeBound(n);
            if (bound <= level()) {
                accept(bound);
            } else if (n.child != 0) {
                stack.push_back(n.child + 1);
                stack.push_back(n.child);
            } else {
                for (uint32_t t = n.first; t < n.first + n.count; ++t)
                    if (!shared_.triangle(t)) triangle(a_.triangles[t]);
            }
        }
    }

    double lower;                  // the acceptance's: the known lower bound and every distance measured
    double measured = 0.0;         // the largest distance this walker measured
    glm::dvec3 farthestPoint{0.0}; // where it was measured
    double upper = 0.0;
    size_t queries = 0;

private:
    // The acceptance level: the margin above the lower bound, shrunk near the tolerance
    // (HausdorffSettings::roomShare), or the tolerance when that is higher.
    double level() const {
        double margin = s_.margin;
        const double room = s_.tolerance - lower;
        if (s_.roomShare > 0.0 && std::isfinite(s_.tolerance) && room >= s_.minRoom * s_.tolerance)
            margin = std::min(margin, s_.roomShare * room);
        return std::max(lower + margin, accept_);
    }
    void accept(double bound) { upper = std::max(upper, bound); }

    void see(double distance, const glm::dvec3& p) {
        lower = std::max(lower, distance);
        if (distance > measured) {
            measured = distance;
            farthestPoint = p;
        }
        if (distance > s_.tolerance) exceeded_.store(true, std::memory_order_relaxed);
    }

    Measured measure(const glm::dvec3& p) const {
        const std::optional<ClosestPoint> c = b_.query.closest(p);
        return c ? Measured{c->distance, c->triangle} : Measured{std::numeric_limits<double>::infinity(), 0};
    }

    Measured atVertex(uint32_t v) {
        const Measured m = cache_.get(
            v, [&] { return measure(a_.positions[v]); }, queries);
        see(m.distance, a_.positions[v]);
        return m;
    }

    double toTriangle(const glm::dvec3& p, uint32_t t) const {
        return glm::length(p -
                           detail::closestOnTriangle(p, b_.corner(t, 0), b_.corner(t, 1), b_.corner(t, 2)));
    }

    double nodeBound(const Node& n) {
        const uint32_t v = a_.triangles[n.first][0];
        const Measured m = atVertex(v);
        const glm::dvec3 p = a_.positions[v];
        double farthest = 0.0;
        for (int k = 0; k < 8; ++k) {
            const glm::dvec3 c(k & 1 ? n.hi.x : n.lo.x, k & 2 ? n.hi.y : n.lo.y, k & 4 ? n.hi.z : n.lo.z);
            farthest = std::max(farthest, glm::length(c - p));
        }
        const double lipschitz = m.distance + farthest;
        if (lipschitz <= level()) return lipschitz;
        double convex = 0.0;
        if (n.count <= kHullTriangles) {
            for (uint32_t t = n.first; t < n.first + n.count && convex < lipschitz; ++t)
                for (uint32_t c : a_.triangles[t])
                    convex = std::max(convex, toTriangle(a_.positions[c], m.triangle));
        } else {
            for (int k = 0; k < 8 && convex < lipschitz; ++k) {
                const glm::dvec3 c(k & 1 ? n.hi.x : n.lo.x, k & 2 ? n.hi.y : n.lo.y, k & 4 ? n.hi.z : n.lo.z);
                convex = std::max(convex, toTriangle(c, m.triangle));
            }
        }
        return std::min(lipschitz, convex);
    }

    // Convexity against the triangles of B closest to q's corners: min over them of the largest
    // distance from a corner of q to it (the corner's own distance to its closest triangle is known).
    // Stops at `cap`.
    double convexBound(const Piece& q, double cap) const {
        double best = cap;
        for (int j = 0; j < 3; ++j) {
            const uint32_t t = q.m[j].triangle;
            if ((j > 0 && t == q.m[0].triangle) || (j > 1 && t == q.m[1].triangle)) continue;
            double convex = q.m[j].distance;
            for (int i = 0; i < 3 && convex < best; ++i)
                if (i != j) convex = std::max(convex, toTriangle(q.p[i], t));
            best = std::min(best, convex);
        }
        return best;
    }

    // Convexity against two triangles of B that share an edge, each over its side of the piece: the
    // plane through the edge between them (along the mean of their normals) cuts the piece into two
    // convex parts, and on each d_B is at most the distance to that side's triangle, whose largest
    // value is at the part's corners. A piece lying across the edge, where no single triangle covers
    // it, is then bounded without being cut. Infinity when the triangles share no edge.
    double pairBound(const Piece& q, uint32_t ta, uint32_t tb, double cap) const {
        glm::dvec3 a[3], b[3], shared[2];
        int common = 0, aOnly = -1;
        for (int k = 0; k < 3; ++k) {
            a[k] = b_.corner(ta, k);
            b[k] = b_.corner(tb, k);
        }
        for (int k = 0; k < 3; ++k) {
            const bool inB = a[k] == b[0] || a[k] == b[1] || a[k] == b[2];
            if (inB && common < 2)
                shared[common++] = a[k];
            else if (!inB)
                aOnly = k;
        }
        if (common != 2 || aOnly < 0) return std::numeric_limits<double>::infinity();
        glm::dvec3 na = glm::cross(a[1] - a[0], a[2] - a[0]), nb = glm::cross(b[1] - b[0], b[2] - b[0]);
        na /= glm::length(na);
        nb /= glm::length(nb);
        if (glm::dot(na, nb) < 0.0) nb = -nb;
        glm::dvec3 normal = glm::cross(shared[1] - shared[0], na + nb);
        if (glm::dot(normal, a[aOnly] - shared[0]) < 0.0) normal = -normal; // positive side: ta's
        double side[3];
        for (int k = 0; k < 3; ++k)
            side[k] = glm::dot(normal, q.p[k] - shared[0]);
        double bound = 0.0;
        auto take = [&](const glm::dvec3& p, uint32_t t) {
            bound = std::max(bound, toTriangle(p, t));
            return bound < cap;
        };
        for (int k = 0; k < 3; ++k) {
            const int k1 = (k + 1) % 3;
            if (side[k] >= 0.0 && !take(q.p[k], ta)) return cap;
            if (side[k] <= 0.0 && !take(q.p[k], tb)) return cap;
            if ((side[k] < 0.0) != (side[k1] < 0.0) && side[k] != 0.0 && side[k1] != 0.0) {
                const glm::dvec3 cut = q.p[k] + (q.p[k1] - q.p[k]) * (side[k] / (side[k] - side[k1]));
                if (!take(cut, ta) || !take(cut, tb)) return cap;
            }
        }
        return bound;
    }

    // Whether laying q over B (kStepsPerTriangle steps per triangle of B under it) likely costs less
    // than cutting it until Lipschitz bounds it (about (radius / room)^2 pieces, a query each).
    // `farthest`: the largest distance at q's corners; `radius`: q's enclosing radius.
    bool overlayPays(const Piece& q, double farthest, double radius) const {
        if (b_.triangleArea < kOverlayArea * level() * level()) return false;
        const double room = level() - farthest;
        const double area = 0.5 * glm::length(glm::cross(q.p[1] - q.p[0], q.p[2] - q.p[0]));
        const double steps = kStepsPerTriangle * area / std::max(b_.triangleArea, 1e-300) + 3.0;
        return !(room > 0.0) || kStepsPerQuery * (radius / room) * (radius / room) >= steps;
    }

    // The bound of a piece: Lipschitz from its corners; when that is above the level, convexity
    // against the corners' closest triangles of B one at a time, then two at a time across an edge
    // they share, then laid over B's triangles from the first corner's (PieceOverlay.hpp). The
    // smallest.
    double pieceBound(const Piece& q) const {
        const double farthest = std::max({q.m[0].distance, q.m[1].distance, q.m[2].distance});
        const double radius = detail::enclosingRadius(q.p[0], q.p[1], q.p[2]);
        const double lipschitz = farthest + radius;
        if (lipschitz <= level()) return lipschitz;
        double best = convexBound(q, lipschitz);
        for (int i = 0; i < 3 && best > level(); ++i)
            for (int j = i + 1; j < 3 && best > level(); ++j)
                if (q.m[i].triangle != q.m[j].triangle)
                    best = std::min(best, pairBound(q, q.m[i].triangle, q.m[j].triangle, best));
        // Capped just above the level: an overlay above it bounds nothing (the piece is cut), and
        // the overlay tries its next direction.
        if (best > level() && overlayPays(q, farthest, radius))
            best = detail::overlayBound(
                {q.p[0], q.p[1], q.p[2]}, {q.m[0].triangle, q.m[1].triangle, q.m[2].triangle},
                {b_.positions, b_.indices, b_.neighbours()}, overlayEps_,
                std::min(best, std::nextafter(level(), std::numeric_limits<double>::infinity())));
        return best;
    }

    void triangle(const std::array<uint32_t, 3>& t) {
        Piece first;
        for (int k = 0; k < 3; ++k) {
            first.p[k] = a_.positions[t[size_t(k)]];
            first.m[k] = atVertex(t[size_t(k)]);
        }
        std::vector<Piece>& stack = pieces_;
        stack.assign(1, first);
        while (!stack.empty() && !exceeded_.load(std::memory_order_relaxed)) {
            const Piece q = stack.back();
            stack.pop_back();
            const double bound = pieceBound(q);
            if (bound <= level()) {
                accept(bound);
                continue;
            }
            const int k = detail::longestEdge(q.p), k1 = (k + 1) % 3;
            const glm::dvec3 mid = 0.5 * (q.p[k] + q.p[k1]);
            const Measured m = measure(mid);
            ++queries;
            see(m.distance, mid);
            Piece x = q, y = q;
            x.p[k1] = mid;
            x.m[k1] = m;
            y.p[k] = mid;
            y.m[k] = m;
            stack.push_back(x);
            stack.push_back(y);
        }
    }

    const Impl& a_;
    const Impl& b_;
    const Shared& shared_;
    const HausdorffSettings& s_;
    VertexCache& cache_;
    std::atomic<bool>& exceeded_;
    double accept_;
    double overlayEps_;
    std::vector<Piece> pieces_;
};

// Subtrees of A's hierarchy for the threads: nodes split breadth first until there are enough.
std::vector<uint32_t> subtrees(const Impl& a, size_t wanted) {
    std::vector<uint32_t> out{0};
    for (bool split = true; split && out.size() < wanted;) {
        split = false;
        std::vector<uint32_t> next;
        for (uint32_t i : out) {
            if (a.nodes[i].child != 0) {
                next.push_back(a.nodes[i].child);
                next.push_back(a.nodes[i].child + 1);
                split = true;
            } else {
                next.push_back(i);
            }
        }
        out = std::move(next);
    }
    return out;
}

} // namespace

namespace {

Status checkSettings(const HausdorffSettings& s) {
    if (!(std::isfinite(s.margin) && s.margin > 0.0))
        return fail("Hausdorff bound: margin " + std::to_string(s.margin) + " is not finite and > 0");
    if (!(s.tolerance >= 0.0)) return fail("Hausdorff bound: tolerance is negative or NaN");
    if (!(s.roomShare >= 0.0 && s.roomShare < 1.0) || !(s.minRoom > 0.0 && s.minRoom <= 1.0))
        return fail("Hausdorff bound: roomShare must lie in [0, 1) and minRoom in (0, 1]");
    if (const std::string p = detail::threadsProblem(s.threads); !p.empty())
        return fail("Hausdorff bound: " + p);
    return {};
}

// One direction of the bound in steps, so that two directions can share one pool of threads and one
// early answer: the starting samples, the walks of the subtrees, the result.
class OneSided {
public:
    OneSided(const Impl& a, const Impl& b, const Shared& shared, const HausdorffSettings& s,
             std::atomic<bool>& exceeded)
        : a_(a), b_(b), shared_(shared), s_(s), exceeded_(exceeded), cache_(a.positions.size()) {}

    // The starting lower bound of every subtree: distances at the centroids of a fixed stride of A's
    // triangles (where a coarse proxy is farthest from the render mesh, so a "no" comes early).
    void sampleStart(unsigned workers) {
        starts_.reserve(workers);
        for (unsigned w = 0; w < workers; ++w)
            starts_.emplace_back(a_, b_, shared_, s_, cache_, exceeded_, std::max(0.0, s_.knownLower));
        const size_t stride = std::max<size_t>(1, (a_.triangles.size() + kStartSamples - 1) / kStartSamples);
        std::vector<double> sampled((a_.triangles.size() + stride - 1) / stride, 0.0);
        detail::parallelChunks(
            sampled.size(), kStartChunk, workers,
            [&](size_t begin, size_t end, unsigned w) {
                for (size_t i = begin; i < end && !exceeded_.load(std::memory_order_relaxed); ++i) {
                    if (shared_.triangle(uint32_t(i * stride))) continue; // at distance 0
                    const std::array<uint32_t, 3>& t = a_.triangles[i * stride];
                    sampled[i] = starts_[w].sample(
                        (a_.positions[t[0]] + a_.positions[t[1]] + a_.positions[t[2]]) / 3.0);
                }
            },
            [](double) { return true; }, &exceeded_);
        for (const Walker& w : starts_)
            walkLower_ = std::max(walkLower_, w.lower);
        roots_ = subtrees(a_, kSubtrees);
        parts_.assign(roots_.size(), {});
        // A subtree's farthest sampled centroid: its triangles' range holds samples i * stride.
        farthest_.assign(roots_.size(), 0.0);
        for (size_t r = 0; r < roots_.size(); ++r) {
            const Node& n = a_.nodes[roots_[r]];
            for (size_t i = (n.first + stride - 1) / stride; i * stride < size_t(n.first) + n.count; ++i)
                farthest_[r] = std::max(farthest_[r], sampled[i]);
        }
    }
    // The largest distance sampled in subtree i's triangles (0 where none was sampled).
    double farthestSampled(size_t i) const { return farthest_[i]; }
    double startLower() const { return walkLower_; }
    // Every subtree's walk starts from at least this distance (one known to be attained).
    void raiseWalkLower(double known) { walkLower_ = std::max(walkLower_, known); }
    size_t subtreeCount() const { return roots_.size(); }
    void walk(size_t i) {
        Walker w(a_, b_, shared_, s_, cache_, exceeded_, walkLower_);
        w.walk(roots_[i]);
        parts_[i] = {w.measured, w.upper, false, w.queries, w.farthestPoint};
    }
    HausdorffResult result() const {
        HausdorffResult out;
        auto take = [&out](double lower, const glm::dvec3& where) {
            if (lower > out.lower) out.lower = lower, out.farthest = where;
        };
        for (const Walker& w : starts_) {
            take(w.measured, w.farthestPoint);
            out.queries += w.queries;
        }
        for (const HausdorffResult& r : parts_) {
            take(r.lower, r.farthest);
            out.upper = std::max(out.upper, r.upper);
            out.queries += r.queries;
        }
        out.exceeded = exceeded_.load();
        if (out.exceeded) {
            out.upper = std::numeric_limits<double>::infinity();
            return out;
        }
        out.upper = std::max(out.upper, out.lower) * (1.0 + detail::kRoundingAllowance) +
                    detail::kRoundingAllowance * a_.scale;
        return out;
    }

private:
    const Impl& a_;
    const Impl& b_;
    const Shared& shared_;
    const HausdorffSettings& s_;
    std::atomic<bool>& exceeded_;
    VertexCache cache_;
    std::vector<Walker> starts_; // one per thread
    double walkLower_ = 0.0;
    std::vector<uint32_t> roots_;
    std::vector<double> farthest_; // farthestSampled
    std::vector<HausdorffResult> parts_;
};

// The farthest sample of the `count`-th farthest-sampled subtree of `order` (infinity for none).
double farthestCut(const std::vector<std::pair<OneSided*, size_t>>& order, size_t count) {
    if (count == 0) return std::numeric_limits<double>::infinity();
    std::vector<double> d;
    d.reserve(order.size());
    for (const auto& [job, i] : order)
        d.push_back(job->farthestSampled(i));
    std::nth_element(d.begin(), d.begin() + std::ptrdiff_t(count - 1), d.end(), std::greater<>());
    return d[count - 1];
}

// Walks the subtrees of the given directions on one pool of threads, taking them in turn.
bool walkAll(const std::vector<OneSided*>& jobs, unsigned workers, std::atomic<bool>& exceeded,
             const ProgressCallback& progress) {
    std::vector<std::pair<OneSided*, size_t>> order;
    for (size_t i = 0, more = 1; more; ++i) {
        more = 0;
        for (OneSided* j : jobs)
            if (i < j->subtreeCount()) {
                order.emplace_back(j, i);
                more = 1;
            }
    }
    // The few subtrees with the farthest samples first, the others in turn as before: where a
    // candidate lies beyond the tolerance, the walk that finds it, and with it the answer, comes
    // early. Each subtree is walked on its own, so the order changes no bound.
    const size_t first = std::min(order.size(), kFarthestFirstPerWorker * size_t(workers));
    const double cut = farthestCut(order, first);
    std::stable_partition(order.begin(), order.end(),
                          [cut](const auto& x) { return x.first->farthestSampled(x.second) >= cut; });
    auto report = [&](double f) { return !progress || progress(float(f), "measure"); };
    return detail::parallelChunks(
        order.size(), 1, workers,
        [&](size_t begin, size_t end, unsigned) {
            for (size_t i = begin; i < end; ++i)
                order[i].first->walk(order[i].second);
        },
        report, &exceeded);
}

} // namespace

Result<HausdorffResult> boundOneSided(const HausdorffSurface& from, const HausdorffSurface& to,
                                      const HausdorffSettings& s, const ProgressCallback& progress) {
    if (Status st = checkSettings(s); !st) return fail(st.error());
    const Impl& a = from.impl();
    const Impl& b = to.impl();
    if (a.triangles.empty()) return HausdorffResult{};
    if (b.triangles.empty()) return fail("the target mesh has no surface (no triangle of non-zero area)");
    const unsigned workers = detail::workersFor(s.threads);
    std::atomic<bool> exceeded{false};
    const Shared shared = sharedTriangles(a, b).first;
    OneSided job(a, b, shared, s, exceeded);
    job.sampleStart(workers);
    if (!walkAll({&job}, workers, exceeded, progress)) return fail("cancelled");
    if (!exceeded.load() && progress && !progress(1.0f, "measure")) return fail("cancelled");
    return job.result();
}

Result<HausdorffPair> boundBothWays(const HausdorffSurface& a, const HausdorffSurface& b,
                                    const HausdorffSettings& s, const ProgressCallback& progress) {
    if (Status st = checkSettings(s); !st) return fail(st.error());
    if ((a.surfaceTriangleCount() == 0) != (b.surfaceTriangleCount() == 0))
        return fail(std::string("mesh ") + (a.surfaceTriangleCount() == 0 ? "A" : "B") +
                    " has no surface (no triangle of non-zero area) but the other has one");
    if (a.surfaceTriangleCount() == 0) return HausdorffPair{};
    const unsigned workers = detail::workersFor(s.threads);
    std::atomic<bool> exceeded{false};
    const auto [sharedA, sharedB] = sharedTriangles(a.impl(), b.impl());
    OneSided ab(a.impl(), b.impl(), sharedA, s, exceeded), ba(b.impl(), a.impl(), sharedB, s, exceeded);
    ab.sampleStart(workers);
    ba.sampleStart(workers);
    const double known = std::max(ab.startLower(), ba.startLower());
    ab.raiseWalkLower(known);
    ba.raiseWalkLower(known);
    if (!walkAll({&ab, &ba}, workers, exceeded, progress)) return fail("cancelled");
    if (!exceeded.load() && progress && !progress(1.0f, "measure")) return fail("cancelled");
    return HausdorffPair{ab.result(), ba.result()};
}

Result<HausdorffResult> boundHausdorff(const HausdorffSurface& a, const HausdorffSurface& b,
                                       const HausdorffSettings& s, const ProgressCallback& progress) {
    if ((a.surfaceTriangleCount() == 0) != (b.surfaceTriangleCount() == 0))
        return fail(std::string("mesh ") + (a.surfaceTriangleCount() == 0 ? "A" : "B") +
                    " has no surface (no triangle of non-zero area) but the other has one");
    auto half = [&](float offset) -> ProgressCallback {
        if (!progress) return {};
        return [&progress, offset](float f, const char* stage) { return progress(offset + 0.5f * f, stage); };
    };
    Result<HausdorffResult> ab = boundOneSided(a, b, s, half(0.0f));
    if (!ab || ab->exceeded) return ab;
    HausdorffSettings back = s;
    back.knownLower = std::max(s.knownLower, ab->lower);
    Result<HausdorffResult> ba = boundOneSided(b, a, back, half(0.5f));
    if (!ba) return ba;
    HausdorffResult out = ba.value();
    if (ab->lower > out.lower) out.lower = ab->lower, out.farthest = ab->farthest;
    if (!out.exceeded) out.upper = std::max(out.upper, ab->upper);
    out.queries += ab->queries;
    return out;
}

} // namespace spatter
