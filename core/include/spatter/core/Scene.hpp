#pragma once
// Scene: the objects a game draws and shoots at. Each object has a render mesh in its own space, a
// double-precision object-to-world transform, a material, and the flags that decide how decals
// treat it.

#include "spatter/core/Animation.hpp"
#include "spatter/core/Bounds.hpp"
#include "spatter/core/Image.hpp"
#include "spatter/core/Mesh.hpp"

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace spatter {

struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};
    int baseColorTexture = -1; // index into Scene::images, -1 for none
    int normalTexture = -1;    // index into Scene::images, -1 for none
    float normalScale = 1.0f;
    float roughness = 1.0f;
    float metallic = 0.0f;
    // KHR_materials_unlit: the material's colour is meant to be shown as it is, without lighting.
    // Loaded and kept here; spatter's renderer lights it like any other material.
    bool unlit = false;
    // A glTF material's KHR_texture_transform is not kept here: the loader applies it to the UVs of
    // the primitives that use the material.
};

struct SceneObject {
    std::string name;
    // Render mesh, object space; never null (validateScene). Objects placed with the same mesh share
    // one (every node of a glTF mesh used more than once, every instance of EXT_mesh_gpu_instancing, a
    // level's copies of a prop), so that a scene keeps each mesh once however often it is placed.
    std::shared_ptr<const Mesh> mesh;
    glm::dmat4 transform{1.0};    // object to world
    bool dynamic = false;         // moves at run time: placed as an Embree instance, gets an object ID
    bool receivesDecals = true;   // false: not in the collision world, never decaled
    std::optional<Mesh> collider; // authored collision proxy (UCX_ / -col), object space

    // Animation (spatter/core/Animation.hpp); `mesh` and `transform` are the rest pose.
    int node = -1;                         // index into Scene::animation.nodes; -1 when not animated
    int skin = -1;                         // index into Scene::animation.skins; -1: not skinned
    SkinWeights skinWeights;               // joint influences of `mesh`'s vertices when skinned
    std::vector<MorphTarget> morphTargets; // of `mesh`; the weights are its node's

    // Skinned or morphed: its surface changes shape with the pose.
    bool deforms() const { return skin >= 0 || !morphTargets.empty(); }
    // Gives this object a copy of its mesh of its own and returns it to be changed; the objects that
    // shared the mesh keep it as it was.
    Mesh& editMesh();
};

// `mesh` held for sharing between objects.
std::shared_ptr<const Mesh> shareMesh(Mesh mesh);

// An object of `mesh` placed by `transform`, static or dynamic, receiving decals.
SceneObject makeSceneObject(std::string name, Mesh mesh, const glm::dmat4& transform = glm::dmat4(1.0),
                            bool dynamic = false);
// The same with a mesh shared with other objects.
SceneObject makeSceneObject(std::string name, std::shared_ptr<const Mesh> mesh,
                            const glm::dmat4& transform = glm::dmat4(1.0), bool dynamic = false);

struct Scene {
    std::string source; // path or builtin name it was made from
    std::vector<SceneObject> objects;
    std::vector<Material> materials;
    std::vector<Image> images;
    SceneAnimation animation; // node hierarchy, skins and animations; empty when nothing animates
    // What the loader substituted or left out and the scene still works without, one line each
    // (an image it cannot decode that only an extension uses, a texture transform it could not follow).
    std::vector<std::string> warnings;
    // The glTF extensions the file uses and those it requires, as it lists them (empty for other formats).
    std::vector<std::string> extensionsUsed, extensionsRequired;

    size_t triangleCount() const; // render triangles of all objects
    // Render meshes the scene keeps: the objects placed with one mesh share it (counted once).
    size_t meshCount() const;
    size_t dynamicObjectCount() const;
    DBounds worldBounds() const; // bounds of every render mesh, transformed to world space
    // Adds `offset` to every object's translation (used to test precision far from the origin).
    void translate(const glm::dvec3& offset);
};

// Empty when `transform` can place an object: every entry finite and the bottom row (0, 0, 0, 1);
// otherwise "transform is not finite" or "transform is not affine". A singular transform is allowed
// (glTF hides nodes with a scale of 0): it draws nothing, and the collision world leaves out of its
// trace every transform that single precision cannot use (spatter/placement/TraceTransform.hpp).
std::string transformProblem(const glm::dmat4& transform);

// Checks every mesh (validateMesh), every transform (transformProblem), every material's texture
// indices, the animation data (validateAnimation) and each object's skin, joint influences and morph
// targets against it. The error names the object, material or animation part.
Status validateScene(const Scene& scene);

} // namespace spatter
