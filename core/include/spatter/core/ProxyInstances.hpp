#pragma once
// ProxyInstances: the objects of a scene that get the same proxy. A level places one mesh many times
// (crates, pillars, moving targets, every instance of a glTF mesh or of EXT_mesh_gpu_instancing), and
// a proxy lives in its object's space: objects with the same render mesh and authored collider get the
// same proxy, whatever their transforms. Building it once for all of them costs one build where a
// build per object cost one per placement.

#include "spatter/core/Scene.hpp"

#include <cstddef>
#include <vector>

namespace spatter {

// For each object of `scene`, the first object whose proxy buildObjectProxy makes from the same input:
// both receive decals, neither is a dynamic object that deforms (its proxy holds over its own poses),
// and their render meshes and authored colliders hold the same positions and indices, bit for bit
// (what the proxy is built from; normals, UVs and submeshes do not change it). The object's own index
// where no object before it has the same input, and for an object that takes no decals or deforms.
// Build the proxies of the objects that are their own source and copy them to the others.
std::vector<size_t> proxySources(const Scene& scene);

} // namespace spatter
