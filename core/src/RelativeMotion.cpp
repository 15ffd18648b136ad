#include "RelativeMotion.hpp"

#include "SurfaceGeometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

namespace spatter::detail {

namespace {

// Cells per axis at most: keeps a cell key within 21 bits per axis.
constexpr double kMaxCells = 1 << 20;
// A cell is at least this share of the largest triangle's box, so that no box meets more than about
// 17^3 cells.
constexpr double kLargestShare = 1.0 / 16.0;

// A triangle, or a piece of one, at the pose.
struct Triangle {
    glm::dvec3 p[3];             // corners
    glm::dvec3 d[kIntervals][3]; // their displacements over each interval

    double longestEdge() const {
        return std::max({glm::length(p[1] - p[0]), glm::length(p[2] - p[1]), glm::length(p[0] - p[2])});
    }
};

Triangle triangleOf(const MovingMesh& mesh, size_t t) {
    Triangle tri;
    for (int k = 0; k < 3; ++k) {
        const uint32_t v = mesh.topology.indices[3 * t + size_t(k)];
        tri.p[k] = mesh.positions[v];
        for (int j = 0; j < kIntervals; ++j)
            tri.d[j][k] =
                mesh.displacements[size_t(j)] ? (*mesh.displacements[size_t(j)])[v] : glm::dvec3(0.0);
    }
    return tri;
}

// The four triangles of `t` cut at its edges' midpoints, each point moving by the blend of its
// corners' displacements.
std::array<Triangle, 4> quarters(const Triangle& t) {
    Triangle m;
    for (int k = 0; k < 3; ++k) {
        m.p[k] = 0.5 * (t.p[k] + t.p[(k + 1) % 3]);
        for (int j = 0; j < kIntervals; ++j)
            m.d[j][k] = 0.5 * (t.d[j][k] + t.d[j][(k + 1) % 3]);
    }
    std::array<Triangle, 4> q;
    for (int k = 0; k < 3; ++k) { // the corner k with the midpoints of its two edges
        const int corner[3] = {k, k, (k + 2) % 3};
        const Triangle* from[3] = {&t, &m, &m};
        for (int c = 0; c < 3; ++c) {
            q[size_t(k)].p[c] = from[c]->p[corner[c]];
            for (int j = 0; j < kIntervals; ++j)
                q[size_t(k)].d[j][c] = from[c]->d[j][corner[c]];
        }
    }
    q[3] = m;
    return q;
}

// An axis-aligned box.
struct Box {
    glm::dvec3 lo, hi;
};

Box boxOf(const Triangle& t, double grow = 0.0) {
    return {glm::min(t.p[0], glm::min(t.p[1], t.p[2])) - grow,
            glm::max(t.p[0], glm::max(t.p[1], t.p[2])) + grow};
}

bool overlap(const Box& a, const Box& b) {
    return glm::all(glm::lessThanEqual(a.lo, b.hi)) && glm::all(glm::lessThanEqual(b.lo, a.hi));
}

// The render mesh's triangles in a uniform grid of cubes, each in every cell its box meets, for the
// triangles whose boxes meet a given box.
class TriangleGrid {
public:
    explicit TriangleGrid(const std::vector<Triangle>& triangles) {
        boxes_.reserve(triangles.size());
        Box all = boxOf(triangles.front());
        double size = 0.0, largest = 0.0;
        for (const Triangle& t : triangles) {
            boxes_.push_back(boxOf(t));
            all = {glm::min(all.lo, boxes_.back().lo), glm::max(all.hi, boxes_.back().hi)};
            const glm::dvec3 e = boxes_.back().hi - boxes_.back().lo;
            size += std::max(e.x, std::max(e.y, e.z));
            largest = std::max(largest, std::max(e.x, std::max(e.y, e.z)));
        }
        lo_ = all.lo;
        const glm::dvec3 extent = all.hi - all.lo;
        cell_ = std::max({size / double(triangles.size()), kLargestShare * largest,
                          std::max(extent.x, std::max(extent.y, extent.z)) / kMaxCells,
                          std::numeric_limits<double>::min()});
        for (size_t t = 0; t < boxes_.size(); ++t)
            forEachCell(boxes_[t], [&](uint64_t key) { cells_[key].push_back(uint32_t(t)); });
    }

    // One caller's marks of the triangles already visited, so that several threads can search.
    struct Visits {
        std::vector<uint32_t> seen;
        uint32_t stamp = 0;
    };
    Visits visits() const { return {std::vector<uint32_t>(boxes_.size(), 0), 0}; }

    // Calls f(triangle) once for every triangle whose box meets `box`: through the cells it meets, or
    // over every triangle where it meets more cells than there are triangles.
    template <class F> void forEachMeeting(const Box& box, Visits& v, F&& f) const {
        const glm::dvec3 cells = glm::dvec3(cellOf(box.hi) - cellOf(box.lo)) + 1.0;
        if (cells.x * cells.y * cells.z > double(boxes_.size())) {
            for (size_t t = 0; t < boxes_.size(); ++t)
                if (overlap(box, boxes_[t])) f(uint32_t(t));
            return;
        }
        ++v.stamp;
        forEachCell(box, [&](uint64_t key) {
            const auto it = cells_.find(key);
            if (it == cells_.end()) return;
            for (uint32_t t : it->second)
                if (v.seen[t] != v.stamp && overlap(box, boxes_[t])) {
                    v.seen[t] = v.stamp;
                    f(t);
                }
        });
    }

private:
    template <class F> void forEachCell(const Box& box, F&& f) const {
        const glm::ivec3 a = cellOf(box.lo), b = cellOf(box.hi);
        for (int x = a.x; x <= b.x; ++x)
            for (int y = a.y; y <= b.y; ++y)
                for (int z = a.z; z <= b.z; ++z)
                    f(uint64_t(x) | (uint64_t(y) << 21) | (uint64_t(z) << 42));
    }
    glm::ivec3 cellOf(const glm::dvec3& p) const {
        const glm::dvec3 q = glm::clamp((p - lo_) / cell_, glm::dvec3(0.0), glm::dvec3(kMaxCells));
        return glm::ivec3(glm::floor(q));
    }

    std::vector<Box> boxes_;
    glm::dvec3 lo_{0.0};
    double cell_ = 1.0;
    std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
};

std::vector<Triangle> trianglesOf(const MovingMesh& mesh) {
    std::vector<Triangle> out(mesh.topology.indices.size() / 3);
    for (size_t t = 0; t < out.size(); ++t)
        out[t] = triangleOf(mesh, t);
    return out;
}

// Takes, for each interval, the largest |displacement of a corner of `a` - displacement of a corner
// of `b`|, squared, into `most`.
void takeCornerMotion2(const Triangle& a, const Triangle& b, Motions& most) {
    for (int j = 0; j < kIntervals; ++j)
        for (const glm::dvec3& i : a.d[j])
            for (const glm::dvec3& k : b.d[j]) {
                const glm::dvec3 d = i - k;
                most[size_t(j)] = std::max(most[size_t(j)], glm::dot(d, d));
            }
}

void takeMax(Motions& most, const Motions& m) {
    for (size_t j = 0; j < most.size(); ++j)
        most[j] = std::max(most[j], m[j]);
}

// The room for rounding added to the pairs' reach, as a share of the largest coordinate: the bound is
// certified on the meshes rounded to float (a relative 6e-8) and the pairs are picked in double.
constexpr double kRoundingShare = 1e-6;

// Halvings of a collision triangle's edges at most, to pieces about as large as the render triangles.
constexpr int kMaxDepth = 5;

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool finite(const MovingMesh& mesh) {
    for (uint32_t v : mesh.topology.indices) {
        if (!finite(mesh.positions[v])) return false;
        for (const std::vector<glm::dvec3>* d : mesh.displacements)
            if (d && !finite((*d)[v])) return false;
    }
    return true;
}

// The largest magnitude of a coordinate of the mesh's triangles.
double largestCoordinate(const std::vector<Triangle>& triangles) {
    double most = 0.0;
    for (const Triangle& t : triangles)
        for (const glm::dvec3& p : t.p)
            most = std::max({most, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    return most;
}

// The render triangles and what a search among them needs.
struct Drawn {
    const std::vector<Triangle>& triangles;
    const TriangleGrid& grid;
    double edge;  // the longest render edge
    double reach; // the pose's bound, with room for rounding
};

// The largest squared corner motion between the collision triangle `p` and the render triangles near
// it. A collision triangle is cut until its pieces are no longer than the render triangles: the
// corners of a large one, spanning a joint, move apart, while each piece moves nearly as the render
// triangles near it do.
Motions pieceMotion2(const Triangle& p, int depth, const Drawn& drawn, TriangleGrid::Visits& visits) {
    Motions most{};
    if (depth < kMaxDepth && p.longestEdge() > drawn.edge) {
        for (const Triangle& q : quarters(p))
            takeMax(most, pieceMotion2(q, depth + 1, drawn, visits));
        return most;
    }
    drawn.grid.forEachMeeting(boxOf(p, drawn.reach), visits,
                              [&](uint32_t t) { takeCornerMotion2(p, drawn.triangles[t], most); });
    return most;
}

} // namespace

Motions relativeMotion(const MovingMesh& render, const MovingMesh& collision, double reach,
                       unsigned threads) {
    if (render.topology.indices.size() < 3 || collision.topology.indices.size() < 3) return {};
    if (!finite(render) || !finite(collision) || !std::isfinite(reach)) {
        Motions infinite;
        infinite.fill(std::numeric_limits<double>::infinity());
        return infinite;
    }
    const std::vector<Triangle> triangles = trianglesOf(render);
    const std::vector<Triangle> pieces = trianglesOf(collision);
    double edge = 0.0;
    for (const Triangle& t : triangles)
        edge = std::max(edge, t.longestEdge());
    const TriangleGrid grid(triangles);
    const double rounding =
        kRoundingShare * std::max(largestCoordinate(triangles), largestCoordinate(pieces));
    const Drawn drawn{triangles, grid, edge, reach + rounding};
    const unsigned workers = std::max(1u, std::min(workersFor(threads), unsigned(pieces.size() / 64 + 1)));
    std::vector<TriangleGrid::Visits> visits(workers, grid.visits());
    std::vector<Motions> most(workers, Motions{});
    parallelChunks(
        pieces.size(), 16, workers,
        [&](size_t begin, size_t end, unsigned w) {
            for (size_t i = begin; i < end; ++i)
                takeMax(most[w], pieceMotion2(pieces[i], 0, drawn, visits[w]));
        },
        [](double) { return true; });
    Motions out{};
    for (const Motions& m : most)
        takeMax(out, m);
    for (double& m : out)
        m = std::sqrt(m);
    return out;
}

} // namespace spatter::detail
