#pragma once
// Points of a skinned model's render surface as the skinned benchmarks follow them: a point as a
// triangle and barycentric coordinates (posed with the mesh), and the joint an engine would attach a
// decal at a point to.

#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/placement/CollisionWorld.hpp"

#include <glm/glm.hpp>
#include <vector>

namespace spatter::bench {

// The three vertex indices of a's triangle.
const uint32_t* cornersOf(const Mesh& mesh, const SurfaceAnchor& a);

// The point of `a` on the mesh with positions `p`.
glm::dvec3 pointOf(const Mesh& mesh, const std::vector<glm::dvec3>& p, const SurfaceAnchor& a);

// The nearest point of the render surface to `centre`, as triangle and barycentric coordinates
// (`query` built over `mesh`, whose positions are `p`).
SurfaceAnchor nearestPoint(const ClosestPointQuery& query, const Mesh& mesh, const std::vector<glm::dvec3>& p,
                           const glm::dvec3& centre);

// The joint of largest weight at the render vertex nearest to `centre` (ties: the first listed).
uint16_t carryingJoint(const SkinWeights& skin, const std::vector<glm::dvec3>& p, const glm::dvec3& centre);

} // namespace spatter::bench
