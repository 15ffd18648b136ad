#pragma once
// Reference geometry for the mesh-distance and proxy tests: a closed sphere of known shape, the
// gallery's meshes by name, and point-to-surface distances found by brute force with a method
// independent of the library's closest-point code (ClosestPointQuery), to check it and the proxy
// error bounds against.

#include "spatter/core/Mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

namespace spatter::test {

// The render mesh of builtin:gallery's object `name` (GalleryScene.hpp); null when there is none.
std::shared_ptr<const Mesh> galleryMesh(const std::string& name);

// A closed sphere of latitude/longitude quads split into triangles, poles on the z axis, with
// normals; `bump` displaces the radius by bump * sin(8 theta) * sin(8 phi) (0: a plain sphere).
Mesh latLongSphere(float radius, uint32_t stacks, uint32_t slices, float bump = 0.0f);

// The axis-aligned box [-h, h]^3: 8 vertices, 12 triangles facing out, with normals.
Mesh box(float h);

// `m` with every triangle on vertices of its own (a seam along every edge, as a mesh split by UVs).
Mesh unshared(const Mesh& m);

// `m` with `count` more copies of its first vertex (every attribute) that no triangle uses: the same
// surface, not the same mesh bit for bit, so that code sharing work between copies of a mesh treats
// it as a mesh of its own.
Mesh withUnusedVertices(Mesh m, size_t count);

// Distance from `p` to the segment [a, b] (a point where a == b).
double segmentDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b);

// Distance from `p` to the triangle (a, b, c), by projection onto its plane and, outside the
// triangle, the nearest edge; a zero-area triangle counts as its edges.
double triangleDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

// Distance from `p` to the nearest triangle of `m`, over every triangle; infinity for no triangles.
double bruteMeshDistance(const glm::dvec3& p, const Mesh& m);

// The corners of the triangles of `m` with non-zero area (the drawn surface), then `count` seeded
// area-weighted random points on them.
std::vector<glm::dvec3> surfacePoints(const Mesh& m, size_t count, uint64_t seed);

// Lower estimate of the one-sided distance from `from` to `to`: the largest exact distance, through
// the library's ClosestPointQuery (checked against brute force in MeshDistanceTest), at
// surfacePoints(from, count, seed). A failure to query fails the calling test and gives 0.
double denseOneSided(const Mesh& from, const Mesh& to, size_t count, uint64_t seed);

} // namespace spatter::test
