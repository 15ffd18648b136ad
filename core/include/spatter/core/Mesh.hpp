#pragma once
// Mesh: an indexed triangle mesh in its object's space, as drawn (the render mesh) or as used for
// collision (a proxy).

#include "spatter/core/Bounds.hpp"
#include "spatter/core/Result.hpp"

#include <cstdint>
#include <vector>

namespace spatter {

// A range of `indices` drawn with one material.
struct Submesh {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int material = -1; // index into Scene::materials, -1 for the default material
};

struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;  // unit length, one per position
    std::vector<glm::vec2> uvs;      // empty, or one per position
    std::vector<glm::vec4> tangents; // empty, or one per position (xyz unit, w = handedness +-1)
    std::vector<uint32_t> indices;   // three per triangle
    std::vector<Submesh> submeshes;  // empty means one range over all indices with material -1

    size_t vertexCount() const { return positions.size(); }
    size_t triangleCount() const { return indices.size() / 3; }
    Bounds bounds() const; // bounds of the referenced and unreferenced positions alike
};

// Checks that the mesh can be used safely: index count a multiple of 3, at most 2^32 vertices, every
// index below the vertex count, every position finite, one finite normal per position (computeNormals
// makes them), UVs and tangents empty or one per position, submeshes whole triangle ranges inside
// `indices`. The error names the first problem found.
Status validateMesh(const Mesh& mesh);

// Replaces `mesh.normals` with area-weighted vertex normals. Vertices touched only by zero-area
// triangles, and unreferenced vertices, get +Z so that every normal is unit length and finite.
void computeNormals(Mesh& mesh);

// Replaces non-finite or zero normals with the area-weighted normal of their triangles (or +Z) and
// normalises the rest. Returns the number of normals that had to be replaced.
size_t repairNormals(Mesh& mesh);

// Fills `mesh.tangents` from UVs (per-triangle UV derivatives, Gram-Schmidt against the normal).
// Without UVs, or where UVs are degenerate, a tangent perpendicular to the normal is chosen.
void computeTangents(Mesh& mesh);

} // namespace spatter
