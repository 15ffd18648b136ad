#pragma once
// Internal to core: a bound of the Hausdorff certifier (HausdorffBound.cpp) that covers a planar
// piece lying over many triangles of the other mesh at once.
//
// For a triangle t, d_t (the distance to t) is convex, so on any convex region its largest value is
// taken at a corner of the region; and d_B <= d_t for every triangle t of B. So any convex parts
// that together cover a piece P, each paired with one triangle of B, bound sup over P of d_B by the
// largest d_t over the parts' corners. overlayBound lays P over B along a direction d: the part of P
// over triangle t is P clipped by t's three side planes (each through an edge of t and along d, and
// moved eps outside the edge, so that neighbouring parts overlap by more than the rounding of their
// corners). It visits B's triangles breadth first from those closest to P's corners, going on across
// an edge of t wherever t's part reaches that edge and P reaches past its line; each triangle is
// visited once, so the work is about one visit per triangle under P. The parts cover P: seen along
// d, a point of P outside them would be separated from them by an edge that the walk reached with P
// reaching past it, and the triangle across lies on the far side of that edge (around a vertex, the
// triangles of its fan follow one another around it). That needs P not to be seen edge-on along d,
// every visited triangle to face along d and each next one to lie on the far side of the edge it was
// reached across (not folded back over the one before, which a mesh wound inconsistently would not
// show by its facing); where that fails, where the walk would run past a border of B, or past a
// budget of visits, there is no bound (the caller's cap) and the caller cuts P instead. A point of P
// past an edge's line by at most eps, where the walk does not go on, lies within eps / |n . d| <= 10
// eps of a part (n: P's normal), so its distance is at most that much more, which the certifier's
// rounding allowance covers. A triangle lying wholly over P (each corner inside P's side planes along
// d by more than 2 eps) needs no clipping: its part is t itself moved along d onto P's plane, the walk
// goes on across each of its edges (P reaches past each by more than eps), and neighbouring parts of
// that kind meet without a gap, since the corners they share are moved by the same arithmetic; a
// moved corner's distance to t is at most how far it moved, so where that is at most the bound so far
// it is not measured.
//
// d is P's normal where the triangles closest to P's corners face along it (each side plane then
// crosses P at right angles). Beside a crease of B a corner may find the far face closest, and a
// piece over a thin sheet the sheet's far side: then d is halfway between P's normal and the mean of
// those triangles' normals (the parts over the faces like P's are tilted the least), and where that
// bounds nothing under the cap, the mean itself.

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace spatter::detail {

// The triangle across each edge of each triangle of a mesh: across[3 t + k] is the triangle sharing
// the edge from corner k to corner k + 1 of triangle t (corners matched by position), kNoTriangle
// at a border, at an edge of more than two triangles and for triangles not in `triangles`.
struct EdgeNeighbours {
    static constexpr uint32_t kNoTriangle = ~0u;
    std::vector<uint32_t> across;
};

// `triangles`: the mesh triangles to link (the others have no neighbours and are no one's).
EdgeNeighbours edgeNeighbours(const std::vector<glm::dvec3>& positions, const std::vector<uint32_t>& indices,
                              const std::vector<uint32_t>& triangles);

// A mesh as overlayBound reads it.
struct OverlayMesh {
    const std::vector<glm::dvec3>& positions;
    const std::vector<uint32_t>& indices;
    const EdgeNeighbours& neighbours;
};

// An upper bound of sup over the triangle `piece` of the distance to `mesh`, laid over it (see the
// top of this file); `cap` when there is none or it is at least `cap`. `eps`: how far outside an edge
// a part is clipped (absolute, >= 0). `near`: the mesh triangles closest to the piece's corners; the
// overlay starts from them, and gives up at once where no direction has them all facing along it.
// A direction whose bound is not under `cap` gives way to the next.
double overlayBound(const std::array<glm::dvec3, 3>& piece, const std::array<uint32_t, 3>& near,
                    const OverlayMesh& mesh, double eps, double cap);

} // namespace spatter::detail
