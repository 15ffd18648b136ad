#pragma once
// Internal to core: a bound of the Hausdorff certifier (HausdorffBound.cpp) that covers a planar
// piece lying over many triangles of the other mesh at once.
//
// For a triangle t, d_t (the distance to t) is convex, so on any convex region its largest value is
// taken at a corner of the region; and d_B <= d_t for every triangle t of B. So any partition of a
// piece P into convex parts, each paired with one triangle of B, bounds sup over P of d_B by the
// largest d_t over the parts' corners. overlayBound makes such a partition by laying P over B along
// P's normal n: the part of P above triangle t is P cut by t's three side planes (each through an
// edge of t and along n, so that it crosses P's plane at right angles), and the part beyond an edge
// goes on to the triangle across that edge. Each cut computes its crossing points once and gives
// them to both sides, so the parts cover P exactly (up to the rounding of those points, which the
// certifier's rounding allowance covers); a cut is made eps outside the edge, so that a corner lying
// on an edge (a proxy's vertex is often one of the render mesh's) starts no sliver. Where the parts
// would run past a border of B, past a triangle seen edge-on along n, or past a budget of steps,
// there is no bound (the caller's cap) and the caller cuts P instead.

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

// An upper bound of sup over the triangle `piece` of the distance to `mesh`, laid over it from mesh
// triangle `start` (see the top of this file); `cap` when there is none or it is at least `cap`.
// `eps`: how far outside an edge its cut is made (absolute, >= 0). `near`: the mesh triangles
// closest to the piece's corners; the overlay starts from the first, and gives up at once where one
// of them does not face along the piece's normal (a fold of the mesh under the piece).
double overlayBound(const std::array<glm::dvec3, 3>& piece, const std::array<uint32_t, 3>& near,
                    const OverlayMesh& mesh, double eps, double cap);

} // namespace spatter::detail
