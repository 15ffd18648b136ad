#include "PieceOverlay.hpp"

#include "SurfaceGeometry.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace spatter::detail {

namespace {

// Corners a part may have: a triangle cut by three planes has at most six.
constexpr int kMaxCorners = 6;
// Triangles an overlay may visit before it gives up (the caller then cuts the piece).
constexpr size_t kMaxVisits = 1 << 14;
// The cosine of the largest angle between the direction a piece is laid along and the normal of a
// triangle it is laid over: a triangle seen more edge-on, or from behind (a fold of the mesh under
// the piece), ends the overlay. Also the least |cosine| between that direction and the piece's normal.
constexpr double kMinFacing = 0.1;
// Directions an overlay tries (overlayDirections).
constexpr int kDirections = 2;

// A convex part of the piece: its corners in order around it.
struct Part {
    std::array<glm::dvec3, kMaxCorners> corner;
    int count = 0;
};

// Clips `part` to the side dot(s, x - o) >= -eps of a plane (s unit). False when the result would
// have more than kMaxCorners corners.
bool clip(Part& part, const glm::dvec3& s, const glm::dvec3& o, double eps) {
    double d[kMaxCorners];
    bool anyOut = false;
    for (int i = 0; i < part.count; ++i) {
        d[i] = glm::dot(s, part.corner[size_t(i)] - o) + eps;
        anyOut = anyOut || d[i] < 0.0;
    }
    if (!anyOut) return true;
    Part in;
    for (int i = 0; i < part.count; ++i) {
        const int j = (i + 1) % part.count;
        const glm::dvec3& a = part.corner[size_t(i)];
        const bool crosses = (d[i] < 0.0 && d[j] > 0.0) || (d[i] > 0.0 && d[j] < 0.0);
        if (in.count + (d[i] >= 0.0) + crosses > kMaxCorners) return false;
        if (d[i] >= 0.0) in.corner[size_t(in.count++)] = a;
        if (crosses)
            in.corner[size_t(in.count++)] = a + (part.corner[size_t(j)] - a) * (d[i] / (d[i] - d[j]));
    }
    part = in;
    return true;
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

// The side planes of t through its three edges along n (sidePlane); false where t is seen edge-on.
bool sidePlanes(const std::array<glm::dvec3, 3>& t, const glm::dvec3& n, glm::dvec3 (&s)[3]) {
    for (int k = 0; k < 3; ++k)
        if (!sidePlane(t, k, n, s[k])) return false;
    return true;
}

// The corners of mesh triangle t.
std::array<glm::dvec3, 3> cornersOf(const OverlayMesh& mesh, uint32_t t) {
    const uint32_t* c = &mesh.indices[3 * size_t(t)];
    return {mesh.positions[c[0]], mesh.positions[c[1]], mesh.positions[c[2]]};
}

// The corner of mesh triangle u that is neither a nor b (u shares the edge ab).
glm::dvec3 apex(const OverlayMesh& mesh, uint32_t u, const glm::dvec3& a, const glm::dvec3& b) {
    const std::array<glm::dvec3, 3> c = cornersOf(mesh, u);
    for (const glm::dvec3& p : c)
        if (p != a && p != b) return p;
    return c[0];
}

// Whether the triangle `t` faces along n, steeply enough for its part of a piece to be well defined.
bool facesAlong(const std::array<glm::dvec3, 3>& t, const glm::dvec3& n) {
    const glm::dvec3 facing = glm::cross(t[1] - t[0], t[2] - t[0]);
    return glm::dot(facing, n) > kMinFacing * glm::length(facing);
}

// The triangles one overlay visits, breadth first, each queued once, at most kMaxVisits. Which were
// queued is kept in a table stamped by the overlay that wrote each slot, so that neither the size of
// the mesh nor switching between meshes costs anything; it starts small and doubles as an overlay
// fills it (most overlays visit a few triangles, and each thread of a certificate makes its own).
class Visits {
public:
    void start() {
        if (++call_ == 0) { // the stamps wrapped around: none may pass for this overlay's
            std::fill(slots_.begin(), slots_.end(), Slot());
            call_ = 1;
        }
        queue_.clear();
    }
    // Queues t unless it was queued; false when that would pass kMaxVisits.
    bool push(uint32_t t) {
        if (queue_.size() < kMaxVisits && 2 * (queue_.size() + 1) > slots_.size()) grow();
        const size_t i = slotOf(t);
        if (slots_[i].call == call_) return true;
        if (queue_.size() == kMaxVisits) return false;
        slots_[i] = {t, call_};
        queue_.push_back(t);
        return true;
    }
    size_t size() const { return queue_.size(); }
    uint32_t operator[](size_t i) const { return queue_[i]; }

private:
    static constexpr size_t kFirstSlots = 64, kMaxSlots = 2 * kMaxVisits; // powers of two, at most half full
    struct Slot {
        uint32_t triangle = 0, call = 0;
    };
    // The slot holding t for this overlay, or the free slot where it would go.
    size_t slotOf(uint32_t t) const {
        size_t i = (t * 2654435761u) & (slots_.size() - 1);
        while (slots_[i].call == call_ && slots_[i].triangle != t)
            i = (i + 1) & (slots_.size() - 1);
        return i;
    }
    // Twice the slots, this overlay's triangles stamped again.
    void grow() {
        slots_.assign(std::min(2 * slots_.size(), kMaxSlots), Slot());
        for (uint32_t t : queue_)
            slots_[slotOf(t)] = {t, call_};
    }
    std::vector<Slot> slots_ = std::vector<Slot>(kFirstSlots);
    std::vector<uint32_t> queue_;
    uint32_t call_ = 0;
};

// The part of the piece over triangle t: the piece clipped by t's side planes (each eps outside its
// edge), and those planes. False where t is seen edge-on.
bool partOver(const Part& piece, const std::array<glm::dvec3, 3>& t, const glm::dvec3& n, double eps,
              Part& part, glm::dvec3 (&side)[3]) {
    part = piece;
    for (int k = 0; k < 3 && part.count >= 3; ++k)
        if (!sidePlane(t, k, n, side[k]) || !clip(part, side[k], t[k], eps)) return false;
    return true;
}

// Whether the overlay goes on across edge k of t (side plane s through t[k]): where the part over t
// reaches the edge and the piece reaches past it by more than eps (a piece with an edge along it,
// as on a crease of the mesh, does not).
bool goesOn(const Part& part, const Part& piece, const glm::dvec3& s, const glm::dvec3& o, double eps) {
    bool reaches = false, past = false;
    for (int c = 0; c < part.count && !reaches; ++c)
        reaches = glm::dot(s, part.corner[size_t(c)] - o) <= eps;
    for (int c = 0; c < piece.count && !past; ++c)
        past = glm::dot(s, piece.corner[size_t(c)] - o) < -eps;
    return reaches && past;
}

// The largest distance to triangle t over `part`'s corners where it is above `bound`, else at most
// `bound`. The distance to t grows by at most the length moved, so a corner nearer to the last corner
// measured than `bound` less that corner's distance is not measured (most parts lie much nearer t than
// the piece's farthest point); nor is a corner whose distance is known to be at most `bound`
// (`atMost`, where given: one per corner).
double partBound(const Part& part, const std::array<glm::dvec3, 3>& t, double bound,
                 const double* atMost = nullptr) {
    constexpr double kRounding = 1.0 + 1e-12; // on the sum, so that a skipped corner cannot round past
    double largest = 0.0, known = 0.0;
    glm::dvec3 at(0.0);
    bool measured = false;
    for (int c = 0; c < part.count; ++c) {
        const glm::dvec3& p = part.corner[size_t(c)];
        if (atMost && atMost[c] * kRounding <= bound) continue;
        if (measured && (known + glm::length(p - at)) * kRounding <= bound) continue;
        known = glm::length(p - closestOnTriangle(p, t[0], t[1], t[2]));
        at = p;
        measured = true;
        largest = std::max(largest, known);
    }
    return largest;
}

// The side planes of a piece along a direction, for the part over a triangle lying wholly over the
// piece: there the part is the triangle itself moved along the direction onto the piece's plane, and
// the overlay goes on across each of its edges, without clipping.
class PieceSides {
public:
    // `margin`: how far inside every side a triangle's corners must lie (> 0).
    PieceSides(const Part& piece, const glm::dvec3& along, double margin) : along_(along), margin_(margin) {
        normal_ = glm::cross(piece.corner[1] - piece.corner[0], piece.corner[2] - piece.corner[0]);
        corner_ = {piece.corner[0], piece.corner[1], piece.corner[2]};
        valid_ = glm::dot(normal_, along) != 0.0 && sidePlanes(corner_, along, side_);
    }
    // Whether triangle t lies over the piece, each corner more than the margin inside every side.
    bool holds(const std::array<glm::dvec3, 3>& t) const {
        if (!valid_) return false;
        for (const glm::dvec3& p : t)
            for (int k = 0; k < 3; ++k)
                if (!(glm::dot(side_[k], p - corner_[k]) > margin_)) return false;
        return true;
    }
    // t's corners moved along the direction onto the piece's plane, and how far each moved.
    Part projected(const std::array<glm::dvec3, 3>& t, double (&moved)[3]) const {
        Part part;
        part.count = 3;
        const double across = glm::dot(normal_, along_);
        for (int k = 0; k < 3; ++k) {
            const double step = glm::dot(normal_, corner_[0] - t[k]) / across;
            part.corner[size_t(k)] = t[k] + along_ * step;
            moved[k] = std::abs(step);
        }
        return part;
    }

private:
    glm::dvec3 along_, normal_;
    double margin_;
    std::array<glm::dvec3, 3> corner_;
    glm::dvec3 side_[3];
    bool valid_ = false;
};

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

namespace {

// The overlay along the unit direction `along` (see the top of PieceOverlay.hpp).
double overlayAlong(const Part& whole, const std::array<uint32_t, 3>& near, const OverlayMesh& mesh,
                    const glm::dvec3& along, double eps, double cap) {
    thread_local Visits visits;
    visits.start();
    for (uint32_t t : near)
        visits.push(t);
    const PieceSides sides(whole, along, 2.0 * eps);
    double bound = 0.0;
    bool laid = false;
    for (size_t i = 0; i < visits.size(); ++i) {
        const uint32_t t = visits[i];
        const std::array<glm::dvec3, 3> corners = cornersOf(mesh, t);
        if (!facesAlong(corners, along)) return cap;
        Part part;
        glm::dvec3 side[3];
        double moved[3];
        const bool over = sides.holds(corners); // the part is t moved onto the piece
        if (over) {
            if (!sidePlanes(corners, along, side)) return cap;
            part = sides.projected(corners, moved);
        } else if (!partOver(whole, corners, along, eps, part, side)) {
            return cap;
        }
        if (part.count < 3) continue;
        bound = std::max(bound, partBound(part, corners, bound, over ? moved : nullptr));
        laid = true;
        if (bound >= cap) return cap;
        for (int k = 0; k < 3; ++k) {
            if (!over && !goesOn(part, whole, side[k], corners[k], eps)) continue;
            const uint32_t u = mesh.neighbours.across[3 * size_t(t) + size_t(k)];
            // Past a border, or onto a triangle on t's side of the edge (folded over it): the parts
            // would not cover the piece.
            if (u == EdgeNeighbours::kNoTriangle ||
                !(glm::dot(side[k], apex(mesh, u, corners[k], corners[(k + 1) % 3]) - corners[k]) < 0.0))
                return cap;
            if (!visits.push(u)) return cap;
        }
    }
    return laid ? bound : cap;
}

// Whether the triangles `near` all face along d and a piece of unit normal n is not seen edge-on
// along it.
bool fitsDirection(const glm::dvec3& d, const glm::dvec3& n, const std::array<uint32_t, 3>& near,
                   const OverlayMesh& mesh) {
    if (!(std::abs(glm::dot(d, n)) > kMinFacing)) return false;
    for (uint32_t t : near)
        if (!facesAlong(cornersOf(mesh, t), d)) return false;
    return true;
}

// The directions a piece of unit normal n is laid along, in the order tried (at most kDirections):
// n where the triangles closest to its corners all face along it. Otherwise (a piece by a crease,
// whose corner finds the far face closest, or over a sheet facing away from it) halfway between n
// and the mean of those triangles' unit normals, which tilts the parts over the faces like n's the
// least, then that mean; each where those triangles face along it.
int overlayDirections(const glm::dvec3& n, const std::array<uint32_t, 3>& near, const OverlayMesh& mesh,
                      glm::dvec3 (&out)[kDirections]) {
    if (fitsDirection(n, n, near, mesh)) {
        out[0] = n;
        return 1;
    }
    glm::dvec3 mean(0.0);
    for (uint32_t t : near) {
        const std::array<glm::dvec3, 3> c = cornersOf(mesh, t);
        const glm::dvec3 normal = glm::cross(c[1] - c[0], c[2] - c[0]);
        const double length = glm::length(normal);
        if (!(length > 0.0)) return 0;
        mean += normal / length;
    }
    int count = 0;
    for (const glm::dvec3& d : {n + mean / std::max(glm::length(mean), 1e-300), mean}) {
        const double length = glm::length(d);
        if (length > 1e-6 && fitsDirection(d / length, n, near, mesh)) out[count++] = d / length;
    }
    return count;
}

} // namespace

double overlayBound(const std::array<glm::dvec3, 3>& piece, const std::array<uint32_t, 3>& near,
                    const OverlayMesh& mesh, double eps, double cap) {
    glm::dvec3 n = glm::cross(piece[1] - piece[0], piece[2] - piece[0]);
    const double length = glm::length(n);
    if (!(length > 0.0)) return cap;
    n /= length;
    const size_t triangles = mesh.neighbours.across.size() / 3;
    for (uint32_t t : near)
        if (size_t(t) >= triangles) return cap;
    glm::dvec3 along[kDirections];
    const int directions = overlayDirections(n, near, mesh, along);
    double bound = cap;
    for (int i = 0; i < directions && !(bound < cap); ++i)
        bound = overlayAlong({{piece[0], piece[1], piece[2]}, 3}, near, mesh, along[i], eps, cap);
    return bound;
}

} // namespace spatter::detail
