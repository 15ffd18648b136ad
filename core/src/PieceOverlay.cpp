#include "PieceOverlay.hpp"

#include "SurfaceGeometry.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace spatter::detail {

namespace {

// Corners a part may have: three of the piece, and at most one more per cut it went through.
constexpr int kMaxCorners = 10;
// Parts bounded or passed on before overlayBound gives up (a piece over more triangles is cut by the
// caller first).
constexpr int kMaxSteps = 512;
// The cosine of the largest angle between the piece's normal and a triangle it is laid over: a
// triangle seen more edge-on, or from behind (a fold of the mesh under the piece), ends the overlay.
constexpr double kMinFacing = 0.1;

// A convex part of the piece and the triangle it is to be laid over.
struct Part {
    std::array<glm::dvec3, kMaxCorners> corner;
    int count = 0;
    uint32_t triangle = 0;

    bool add(const glm::dvec3& p) {
        if (count == kMaxCorners) return false;
        corner[size_t(count++)] = p;
        return true;
    }
};

// Cuts `part` by the plane dot(s, x - o) = -eps (s unit): `in` is the part where dot(s, x - o) >=
// -eps, `out` where it is <= -eps, each crossing point given to both. False when a part would have
// more than kMaxCorners corners.
bool cut(const Part& part, const glm::dvec3& s, const glm::dvec3& o, double eps, Part& in, Part& out) {
    double d[kMaxCorners];
    bool anyIn = false, anyOut = false;
    for (int i = 0; i < part.count; ++i) {
        d[i] = glm::dot(s, part.corner[size_t(i)] - o) + eps;
        anyIn = anyIn || d[i] > 0.0;
        anyOut = anyOut || d[i] < 0.0;
    }
    in.count = out.count = 0;
    if (!anyOut) {
        in = part;
        return true;
    }
    if (!anyIn) {
        out = part;
        return true;
    }
    bool ok = true;
    for (int i = 0; i < part.count; ++i) {
        const int j = (i + 1) % part.count;
        const glm::dvec3& a = part.corner[size_t(i)];
        if (d[i] >= 0.0) ok = in.add(a) && ok;
        if (d[i] <= 0.0) ok = out.add(a) && ok;
        if ((d[i] < 0.0 && d[j] > 0.0) || (d[i] > 0.0 && d[j] < 0.0)) {
            const glm::dvec3 x = a + (part.corner[size_t(j)] - a) * (d[i] / (d[i] - d[j]));
            ok = in.add(x) && out.add(x) && ok;
        }
    }
    return ok;
}

// The unit normal of t's side plane through its edge k (corner k to k + 1) and along `n`, pointing
// to t's third corner; nothing when t is seen edge-on along n.
bool sidePlane(const std::array<glm::dvec3, 3>& t, int k, const glm::dvec3& n, glm::dvec3& s) {
    const glm::dvec3 edge = t[(k + 1) % 3] - t[k], toThird = t[(k + 2) % 3] - t[k];
    s = glm::cross(edge, n);
    const double length = glm::length(s), inward = glm::dot(s, toThird);
    if (!(length > 0.0) || !(std::abs(inward) > 1e-9 * length * glm::length(toThird))) return false;
    s *= (inward > 0.0 ? 1.0 : -1.0) / length;
    return true;
}

// The corners of mesh triangle t.
std::array<glm::dvec3, 3> cornersOf(const OverlayMesh& mesh, uint32_t t) {
    const uint32_t* c = &mesh.indices[3 * size_t(t)];
    return {mesh.positions[c[0]], mesh.positions[c[1]], mesh.positions[c[2]]};
}

// Whether the triangle `t` faces along n, steeply enough for its part of a piece to be well defined.
bool facesAlong(const std::array<glm::dvec3, 3>& t, const glm::dvec3& n) {
    const glm::dvec3 facing = glm::cross(t[1] - t[0], t[2] - t[0]);
    return glm::dot(facing, n) > kMinFacing * glm::length(facing);
}

} // namespace

EdgeNeighbours edgeNeighbours(const std::vector<glm::dvec3>& positions, const std::vector<uint32_t>& indices,
                              const std::vector<uint32_t>& triangles) {
    // Each vertex's one index for its position (meshoptimizer's remap, as the proxy builder welds).
    std::vector<uint32_t> weld(positions.size());
    meshopt_generateVertexRemap(weld.data(), nullptr, positions.size(), positions.data(), positions.size(),
                                sizeof(glm::dvec3));
    std::vector<uint32_t> welded(indices.size() - indices.size() % 3); // each triangle's welded corners
    for (size_t i = 0; i < welded.size(); ++i)
        welded[i] = weld[indices[i]];
    auto corner = [&](uint32_t t, uint32_t k) { return welded[3 * size_t(t) + k % 3]; };
    // The listed triangles around each welded vertex.
    std::vector<uint32_t> first(positions.size() + 1, 0), ring(3 * triangles.size());
    for (uint32_t t : triangles)
        for (uint32_t k = 0; k < 3; ++k)
            ++first[corner(t, k) + 1];
    std::partial_sum(first.begin(), first.end(), first.begin());
    std::vector<uint32_t> fill(first.begin(), first.end() - 1);
    for (uint32_t t : triangles)
        for (uint32_t k = 0; k < 3; ++k)
            ring[fill[corner(t, k)]++] = t;
    // Across each edge, the one other triangle around both of its corners: vertex by vertex, the
    // edges that start there, matched among the triangles around it.
    EdgeNeighbours out;
    out.across.assign(indices.size() - indices.size() % 3, EdgeNeighbours::kNoTriangle);
    std::vector<std::array<uint32_t, 4>> around; // triangle, its welded corners
    for (uint32_t a = 0; a + 1 < uint32_t(first.size()); ++a) {
        around.clear();
        for (uint32_t i = first[a]; i < first[a + 1]; ++i)
            around.push_back({ring[i], corner(ring[i], 0), corner(ring[i], 1), corner(ring[i], 2)});
        for (const std::array<uint32_t, 4>& t : around)
            for (uint32_t k = 0; k < 3; ++k) {
                const uint32_t b = t[1 + (k + 1) % 3];
                if (t[1 + k] != a || b == a) continue;
                uint32_t found = EdgeNeighbours::kNoTriangle, others = 0;
                for (const std::array<uint32_t, 4>& u : around)
                    if (u[0] != t[0] && (u[1] == b || u[2] == b || u[3] == b)) found = u[0], ++others;
                if (others == 1) out.across[3 * size_t(t[0]) + k] = found;
            }
    }
    return out;
}

double overlayBound(const std::array<glm::dvec3, 3>& piece, const std::array<uint32_t, 3>& near,
                    const OverlayMesh& mesh, double eps, double cap) {
    glm::dvec3 n = glm::cross(piece[1] - piece[0], piece[2] - piece[0]);
    const double length = glm::length(n);
    if (!(length > 0.0)) return cap;
    n /= length;
    for (uint32_t t : near) // a piece whose corners lie over a fold of the mesh: no overlay
        if (size_t(t) >= mesh.neighbours.across.size() / 3 || !facesAlong(cornersOf(mesh, t), n)) return cap;
    const uint32_t start = near[0];
    thread_local std::vector<Part> waiting; // parts still to lay, each with its triangle
    waiting.assign(1, Part());
    waiting[0].corner[0] = piece[0];
    waiting[0].corner[1] = piece[1];
    waiting[0].corner[2] = piece[2];
    waiting[0].count = 3;
    waiting[0].triangle = start;
    double bound = 0.0;
    Part in, out;
    for (int steps = 0; !waiting.empty(); ++steps) {
        if (steps == kMaxSteps) return cap;
        Part remaining = waiting.back();
        waiting.pop_back();
        const uint32_t t = remaining.triangle;
        const std::array<glm::dvec3, 3> corners = cornersOf(mesh, t);
        if (!facesAlong(corners, n)) return cap;
        for (int k = 0; k < 3 && remaining.count >= 3; ++k) {
            glm::dvec3 s;
            if (!sidePlane(corners, k, n, s) || !cut(remaining, s, corners[k], eps, in, out)) return cap;
            if (out.count >= 3) {
                out.triangle = mesh.neighbours.across[3 * size_t(t) + size_t(k)];
                if (out.triangle == EdgeNeighbours::kNoTriangle) return cap;
                waiting.push_back(out);
            }
            remaining = in;
        }
        for (int i = 0; i < remaining.count && remaining.count >= 3; ++i) {
            const glm::dvec3& p = remaining.corner[size_t(i)];
            bound =
                std::max(bound, glm::length(p - closestOnTriangle(p, corners[0], corners[1], corners[2])));
            if (bound >= cap) return cap;
        }
    }
    return bound;
}

} // namespace spatter::detail
