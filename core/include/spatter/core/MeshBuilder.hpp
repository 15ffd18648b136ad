#pragma once
// MeshBuilder: procedural primitives (boxes, spheres, surfaces of revolution, grids) and the
// operations that combine them (displacement along normals, appending with a transform). Used by
// builtin:gallery and by tests that need meshes with known geometry.
//
// Unless a function says otherwise, a builder returns a mesh with
// - normals from computeNormals (unit length, one per position),
// - UVs in object-space metres (1 unit = 1 texture tile), so textures tile at world scale,
// - tangents from computeTangents,
// - triangles wound counter-clockwise seen from outside (their cross products point outward),
// - no submeshes (one range with the default material).
// Closed builders share vertices along every edge and seam, so every edge of the result is used by
// exactly two triangles, once in each direction. Bad arguments (non-finite, non-positive sizes)
// give an empty mesh; counts are clamped to the documented ranges. Nothing here throws.

#include "spatter/core/Mesh.hpp"

#include <array>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

namespace spatter {

// The unit cube [-0.5, 0.5]^3: exactly 8 vertices and 12 triangles, closed. Vertex i lies at
// ((i & 1) ? 0.5 : -0.5, (i & 2) ? 0.5 : -0.5, (i & 4) ? 0.5 : -0.5) with normal
// normalize(position) (the corner diagonal); uv = (x + 0.5, y + 0.5); tangents from computeTangents.
// Triangles, as vertex triples: -X {0,4,6} {0,6,2}, +X {1,3,7} {1,7,5}, -Y {0,1,5} {0,5,4},
// +Y {2,6,7} {2,7,3}, -Z {0,2,3} {0,3,1}, +Z {4,5,7} {4,7,6}.
Mesh makeUnitCube();

// An axis-aligned box centred on the origin spanning [-halfExtents, halfExtents], with flat faces,
// each cut into n x n squares (n = subdivisions clamped to [1, 256]); closed, 6n^2 + 2 vertices,
// 12n^2 triangles. UVs are box-projected (see makeBeveledBox). Returns an empty mesh when a half
// extent is not finite and positive.
Mesh makeBox(glm::vec3 halfExtents, int subdivisions);

struct BoxSettings {
    glm::vec3 halfExtents{0.5f}; // the box spans [-halfExtents, halfExtents]
    float bevel = 0.0f;          // radius of the rounded edges and corners, clamped to [0, 0.45 * min extent]
    int bevelSteps = 2;          // lattice rows each face gives a rounded edge, clamped to [1, 16]:
                                 // a quarter circle has 2 * bevelSteps segments
    float maxEdge = 1.0f;        // longest lattice step on the flat parts (clamped to >= 1e-3)
    // Extra lattice coordinates per axis (object space, x, y, z). Values inside the flat part
    // (closer to the centre than halfExtents - bevel) become lattice lines, so relief applied with
    // displace() can have sharp features exactly there; others are ignored.
    std::array<std::vector<float>, 3> breaks;
};

// A box with rounded edges and corners, built on a lattice: per axis the samples of makeSamples
// over the flat part plus bevelSteps rows per side that map onto quarter circles of radius `bevel`.
// Flat faces stay exactly on the planes +-halfExtents, so the bounds equal the box. Closed.
// UVs are box-projected: a vertex whose normal is mostly along X gets (z, y), along Y (x, z),
// along Z (x, y) (ties pick the earlier axis), so each face tiles in metres. Returns an empty mesh
// when a half extent is not finite and positive.
Mesh makeBeveledBox(const BoxSettings& settings);

// Sorted coordinates from lo to hi, both included: lo, every value of `breaks` strictly between
// lo and hi, hi, and then every gap wider than maxStep cut into equal steps (at most 65536 per gap),
// so no gap is wider than maxStep. A break closer than 1e-4 to lo, hi or an earlier kept break is
// dropped. Returns {lo} when hi <= lo, {lo, hi} when hi - lo < 1e-4, and an empty vector when lo or
// hi is not finite.
std::vector<float> makeSamples(float lo, float hi, float maxStep, const std::vector<float>& breaks = {});

// A grid on the plane y = 0 with vertex (i, j) at (xs[i], 0, zs[j]) (index i + j * xs.size()),
// facing +Y; open (its border edges are used once). UVs are (x, z). `xs` and `zs` must be strictly
// increasing with at least two values each; otherwise the result is empty.
Mesh makeGrid(const std::vector<float>& xs, const std::vector<float>& zs);

// Surface of revolution about the +Y axis. profile[i] = (radius, y), running from the bottom of
// the axis around the outside of the solid to the top (with that direction triangles face
// outward). An end point with radius 0 becomes one pole vertex (closing that end); any other point
// becomes a ring of `segments` vertices (clamped to [3, 4096]), vertex k at angle
// t = 2 pi k / segments lying at (r sin t, y, r cos t). Both ends at radius 0 give a closed mesh.
// UVs: u = rMax * t (metres round the widest ring), v = arc length along the profile; the column of
// triangles from vertex segments-1 back to vertex 0 is the UV seam, where u runs back to 0 (vertices
// stay shared to keep the mesh closed). Returns an empty mesh for fewer than two
// points, a non-finite value, or a radius <= 0 at an interior point or < 0 at an end.
Mesh makeLathe(const std::vector<glm::vec2>& profile, int segments);

// UV sphere centred on the origin (a makeLathe of a half circle from (0, -radius) to (0, radius)):
// closed, 2 + (rings - 1) * segments vertices, 2 * segments * (rings - 1) triangles, rings clamped
// to [2, 4096] and segments to [3, 4096]. Ring i (1..rings-1) lies at polar angle pi * i / rings
// from the bottom pole. Every position lies at distance `radius` from the origin (to float
// rounding), and its normal is exactly normalize(position), not computeNormals. Returns an empty
// mesh when radius is not finite and positive.
Mesh makeSphere(float radius, int rings, int segments);

// Closed cylinder about +Y from y = 0 to y = height (a makeLathe with both caps fanned to a centre
// vertex). bevel > 0 rounds the two rim edges with quarter circles of that radius (4 segments),
// clamped to 0.45 * min(radius, height / 2); bevel = 0 leaves sharp rims whose shared vertices get
// averaged normals. Returns an empty mesh when radius or height is not finite and positive.
Mesh makeCylinder(float radius, float height, int segments, float bevel = 0.0f);

// Moves every vertex along its normal by height(position, normal) (a non-finite height counts as
// 0), then recomputes normals and tangents from the displaced geometry. UVs and indices are kept,
// so a closed mesh stays closed. Does nothing when the mesh has no normals for its positions.
void displace(Mesh& mesh,
              const std::function<float(const glm::vec3& position, const glm::vec3& normal)>& height);

// Appends `src` transformed by `xf` to `dst`: positions by xf, normals by its inverse transpose and
// tangents by its linear part (both renormalised; tangent w flips when xf mirrors), UVs copied,
// indices offset by dst's old vertex count (copied as they are otherwise: validateMesh reports
// any that src had out of range). When xf mirrors (negative determinant) the triangles'
// winding is reversed so that they keep facing outward. Submeshes: when either mesh has any, the
// result lists dst's (or one default-material range over dst's old indices) followed by src's (or
// one default range over the appended indices). An attribute (normals, uvs, tangents) is kept only
// when both meshes have it, except that an empty dst takes src's attributes.
void appendMesh(Mesh& dst, const Mesh& src, const glm::mat4& xf);

} // namespace spatter
