#pragma once
// PosedCollisionMesh: what a skinned or morphed object's collision mesh needs to follow the pose that
// is drawn: its rest positions and the deformation of its vertices, its render mesh's own when the
// render mesh is the collision mesh, otherwise transferred from the render mesh (transferDeformation:
// each proxy vertex moves as the nearest point of the render surface does).

#include "spatter/core/Mesh.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/core/VertexDeformation.hpp"

#include <glm/glm.hpp>
#include <optional>
#include <vector>

namespace spatter {

struct PosedCollisionMesh {
    std::vector<glm::vec3> rest; // collision mesh positions, object space, rest pose
    VertexDeformation deformation;
    size_t jointCount = 0; // joints of the object's skin (0 when not skinned)
};

// The posing data of `scene.objects[object]` for its collision mesh `collision` (the render mesh
// itself, a proxy or a collider, in object space); nothing for an object that neither is skinned nor
// has morph targets. Fails when the deformation cannot be transferred (the message says why).
Result<std::optional<PosedCollisionMesh>> posedCollisionMesh(const Scene& scene, size_t object,
                                                             const Mesh& collision);

// The collision mesh's positions at a pose: object-to-world `transform`, joint matrices `joints`
// (bind space to world, one per joint of the skin) and `morphWeights` (one per morph target), in the
// object's space at that pose. Fails, naming the problem, on joints or weights that do not fit, or
// when a posed position is not finite in float.
Result<std::vector<glm::vec3>> poseCollisionMesh(const PosedCollisionMesh& mesh, const glm::dmat4& transform,
                                                 const std::vector<glm::dmat4>& joints,
                                                 const std::vector<double>& morphWeights);

} // namespace spatter
