#include "PosedCollisionMesh.hpp"

#include <cmath>

namespace spatter {

Result<std::optional<PosedCollisionMesh>> posedCollisionMesh(const Scene& scene, size_t object,
                                                             const Mesh& collision) {
    const SceneObject& so = scene.objects[object];
    if (so.skin == -1 && so.morphTargets.empty()) return std::optional<PosedCollisionMesh>();
    PosedCollisionMesh out;
    out.rest = collision.positions;
    if (so.skin != -1) out.jointCount = scene.animation.skins[size_t(so.skin)].joints.size();
    if (&collision == &so.mesh) {
        out.deformation = deformationOf(so);
    } else {
        Result<VertexDeformation> moved = transferDeformation(so.mesh, deformationOf(so), collision);
        if (!moved) return fail(moved.error());
        out.deformation = std::move(moved).value();
    }
    return std::optional<PosedCollisionMesh>(std::move(out));
}

Result<std::vector<glm::vec3>> poseCollisionMesh(const PosedCollisionMesh& mesh, const glm::dmat4& transform,
                                                 const std::vector<glm::dmat4>& joints,
                                                 const std::vector<double>& morphWeights) {
    if (const std::string problem = poseProblem(mesh.deformation, mesh.jointCount, joints, morphWeights);
        !problem.empty())
        return fail(problem);
    const std::vector<glm::dvec3> posed =
        posePositions(mesh.rest, mesh.deformation, joints, morphWeights, glm::inverse(transform));
    std::vector<glm::vec3> out(posed.size());
    for (size_t v = 0; v < posed.size(); ++v) {
        out[v] = glm::vec3(posed[v]);
        if (!std::isfinite(out[v].x) || !std::isfinite(out[v].y) || !std::isfinite(out[v].z))
            return fail("the pose puts vertex " + std::to_string(v) +
                        " of the collision mesh at a position "
                        "that is not finite");
    }
    return out;
}

} // namespace spatter
