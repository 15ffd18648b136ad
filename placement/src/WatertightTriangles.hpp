#pragma once
// Internal to placement: the collision triangles as Embree user geometry, intersected with the
// watertight test of Woop, Benthin and Wald 2013 ("Watertight Ray/Triangle Intersection", JCGT 2(1)).
// Embree 3's robust triangle test (Pluecker coordinates) is watertight along shared edges but not
// around shared vertices: when the ray starts far from a triangle compared with its size, rounding
// can reject the ray in every triangle around a vertex, and a ray aimed at the vertex passes through.
// Here every vertex is sheared into the ray's space in float, giving the same values in every
// triangle that shares it, and the signs of the edge functions are exact (in double, where products of
// floats are exact), so neighbouring triangles agree along every edge and around every vertex.
//
// The test runs on all lanes of a packet at once: the shear and float edge functions of every lane
// first (branch-free, so that the compiler vectorises them), which already rule out most lanes
// exactly, then the exact signs and the distance of the lanes left, one by one. A single ray is a
// packet of one lane; every lane computes the same operations in the same order, so a packet gives
// every ray bit for bit the hits it gets alone.

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace spatter {

constexpr unsigned kInvalidId = RTC_INVALID_GEOMETRY_ID;

// The triangles of one user geometry, as its geometry user pointer names them.
struct TracedTriangles {
    std::vector<uint32_t> indices;
    std::vector<glm::vec3> traced; // the vertices Embree sees: float frame (static) or object space
    double reach = 0.0;            // largest |ray origin| in the space of `traced` that the boxes allow
};

// Embree's intersect context extended with the distance of the best hit so far of every ray of the
// call (indexed by RTCRay::id), and the slack the tie-break leaves in tfar beyond it.
struct TraceContext {
    RTCIntersectContext embree; // first member: Embree hands this pointer back to intersectTriangle
    float* bestT;
    float slack; // 1e-6 of the world's extent: how far past a ray's best hit its tfar is kept
};

// Embree's bounds function for TracedTriangles: each triangle's box, grown so that no rounding of
// Embree's box tests culls a ray through a corner or along an edge.
void triangleBounds(const RTCBoundsFunctionArguments* args);

// Embree's intersect function for TracedTriangles, traced with a TraceContext: each ray keeps its
// closest hit, ties broken by (instance, geometry, primitive) whatever the order of traversal.
void intersectTriangle(const RTCIntersectFunctionNArguments* args);

} // namespace spatter
