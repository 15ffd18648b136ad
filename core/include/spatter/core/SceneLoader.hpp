#pragma once
// Loading scenes from files and from the builtin generators. Every loader validates what it
// returns: on any problem it returns an error naming the file and the problem, never a
// half-loaded scene, and never reads out of bounds.

#include "spatter/core/Scene.hpp"

#include <string>

namespace spatter {

// Loads by source: "builtin:gallery", or a file chosen by extension (.gltf, .glb, .obj, .ply,
// .off, .stl; case-insensitive).
Result<Scene> loadScene(const std::string& source);

// glTF 2.0 (.gltf with external or embedded buffers, or .glb) through tinygltf. The default scene's
// node hierarchy becomes objects, one per node with a mesh (its triangle primitives become
// submeshes). Node extras {"dynamic": true} and {"decals": false} set the flags. Nodes named
// UCX_* or *-col become the collider of the nearest ancestor that is an object and are not drawn.
// Animations, skins and morph targets fill Scene::animation and each object's node, skin, joint
// influences and morph targets (spatter/core/Animation.hpp); objects stay in their rest pose, and an object
// that an animation moves or deforms is dynamic without extras. Sparse accessors and accessors without a
// buffer view are read wherever accessors are. Extensions: KHR_mesh_quantization, KHR_draco_mesh_compression
// and EXT_meshopt_compression (decoded while loading), EXT_mesh_gpu_instancing (one object per instance,
// named "node#i", sharing the node's mesh and not animated), KHR_texture_transform (applied to the UVs),
// KHR_materials_unlit (Material::unlit). Images that cannot be decoded and that only an image extension uses
// (KHR_texture_basisu and the like, listed as used but not required) become a 1x1 white image, with
// a line in Scene::warnings. Any other required extension, an image extension too, is an error that
// names it.
Result<Scene> loadGltf(const std::string& path);

// OBJ, PLY, OFF or STL through OpenMesh, as one static object named after the file.
Result<Scene> loadMeshFile(const std::string& path);

// Writes the positions and triangles of `mesh` as OBJ (9 significant digits, so floats read back
// exactly), its normals too where it has one per position, after `comment` as a comment line where
// given (one line); the error names the file.
Status writeObj(const Mesh& mesh, const std::string& path, const std::string& comment = {});

} // namespace spatter
