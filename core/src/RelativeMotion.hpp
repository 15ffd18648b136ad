#pragma once
// Internal to core: how far two deforming meshes move against each other over an interval of an
// animation (PoseBound.cpp). Between two sampled poses every vertex is taken to move straight at
// even speed, so every point of a triangle does too, by the blend of its corners' displacements. A
// point x of the collision mesh and a point y of the render mesh then move against each other by at
// most the largest difference between the displacement of a corner of x's triangle and that of a
// corner of y's triangle. Where y is x's nearest point on the other surface (or x is y's), the two
// lie within the pose's bound of each other, and so do their triangles' bounding boxes; only such
// pairs count. A collision triangle larger than the render triangles is cut into pieces first (each
// piece's corners moving by the blend of the triangle's), so that a proxy triangle spanning a joint,
// whose corners move apart, is paired piece by piece with the render triangles near each piece.

#include "spatter/core/Mesh.hpp"

#include <glm/glm.hpp>

#include <array>
#include <vector>

namespace spatter::detail {

// The displacements measured at a pose: to the sample before it and to the one after it.
constexpr int kIntervals = 2;
using Motions = std::array<double, kIntervals>;

// A mesh at one pose and its vertices' displacements from there over the interval before the pose
// and the one after it (null where the pose has no such neighbour: no motion).
struct MovingMesh {
    const Mesh& topology; // indices; positions are not read
    const std::vector<glm::dvec3>& positions;
    std::array<const std::vector<glm::dvec3>*, kIntervals> displacements;
};

// For each interval, the largest |displacement(i) - displacement(k)| over corners i of a piece of a
// collision triangle and k of a render triangle whose bounding boxes lie within `reach` of each other
// at this pose (a superset of the pairs within `reach`, with room for the rounding of the float
// meshes `reach` was certified on), on `threads` threads (0: all cores). The pairs are found once for both
// intervals. 0 when either mesh has no triangle; infinity when a position, a displacement or `reach` is not
// finite.
Motions relativeMotion(const MovingMesh& render, const MovingMesh& collision, double reach, unsigned threads);

} // namespace spatter::detail
