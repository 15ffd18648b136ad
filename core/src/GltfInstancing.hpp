#pragma once
// EXT_mesh_gpu_instancing: a node that draws its mesh once per instance, each placed by a
// translation, rotation and scale in the node's space. Internal to spatter::core.

#include "spatter/core/Result.hpp"

#include <tiny_gltf.h>

#include <glm/glm.hpp>

#include <optional>
#include <vector>

namespace spatter::gltf {

// Upper bound on the instances of one node: each becomes an object with a copy of the mesh.
constexpr size_t kMaxInstances = size_t(1) << 16;

// The transform of every instance of `node` in the node's space (translation * rotation * scale, in
// double), or no value when the node has no EXT_mesh_gpu_instancing. TRANSLATION and SCALE are VEC3,
// ROTATION a VEC4 quaternion (float, or normalized integers under KHR_mesh_quantization); attributes
// whose names start with "_" belong to the application and are ignored. The error names the accessor
// and the problem: a wrong type, unequal counts, a rotation that is zero or not finite, or more
// instances than kMaxInstances.
Result<std::optional<std::vector<glm::dmat4>>> instanceTransforms(const tinygltf::Model& model,
                                                                  const tinygltf::Node& node);

} // namespace spatter::gltf
