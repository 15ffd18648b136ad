#pragma once
// High-detail versions of the benchmark meshes: Loop subdivision through OpenMesh.

#include "spatter/core/Mesh.hpp"
#include "spatter/core/Result.hpp"

#include <cstddef>

namespace spatter::bench {

// `steps` rounds of Loop subdivision (OpenMesh's LoopT; each multiplies the triangles by 4) of
// `mesh` welded by exact position. Faces OpenMesh refuses as non-manifold, and faces with a
// repeated vertex, are left out and counted in `dropped`. The result has area-weighted normals.
// Fails when no face can be added.
Result<Mesh> loopSubdivide(const Mesh& mesh, int steps, size_t& dropped);

} // namespace spatter::bench
