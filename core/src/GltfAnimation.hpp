#pragma once
// The glTF loader's animation part: joint influences and morph targets of meshes, and the nodes,
// skins and animations of a scene. Internal to spatter::core (called from GltfLoader.cpp).

#include "spatter/core/Scene.hpp"

#include <tiny_gltf.h>

namespace spatter::gltf {

// The deforming data of one glTF mesh, gathered primitive by primitive like its render mesh.
struct MeshDeformation {
    SkinWeights skinWeights;               // influences 0 when no primitive has JOINTS_0
    std::vector<MorphTarget> morphTargets; // empty when the primitives have no targets
};

// Appends the joint influences (JOINTS_n / WEIGHTS_n, weights normalised) and morph target deltas of
// `prim`, whose `vertexCount` vertices were just appended to the render mesh of `vertexBase`
// vertices before. Attributes a primitive lacks are zero. The error names the accessor and the problem.
Status appendDeformation(const tinygltf::Model& model, const tinygltf::Primitive& prim, size_t vertexBase,
                         size_t vertexCount, MeshDeformation& out);

// The local transform of `node` in `out`: its matrix (hasMatrix), or its translation, rotation
// (normalised) and scale. The error says which property has the wrong number of components, or that
// the rotation is zero.
Status readTrs(const tinygltf::Node& node, SceneNode& out);

// Pads every array of `out` to `vertexCount` vertices once the whole mesh was read.
void finishDeformation(size_t vertexCount, MeshDeformation& out);

// Fills `scene.animation` (nodes, skins, animations) when the file has animations, skins or morph
// targets, binds every object to its node, skin and its mesh's deformation (`deformations`, one per
// glTF mesh), and makes every object that an animation moves or deforms dynamic. Objects carry the
// glTF index of their node in `node` on entry, or -1 for an object that stays as loaded (an instance
// of EXT_mesh_gpu_instancing). Without animation data every object's node becomes -1. The error names the
// glTF part and the problem, or the limit on the deforming data of a scene.
Status addAnimation(const tinygltf::Model& model, const std::vector<MeshDeformation>& deformations,
                    Scene& scene);

} // namespace spatter::gltf
