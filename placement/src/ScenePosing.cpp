#include "spatter/placement/ScenePosing.hpp"

#include "spatter/core/SceneEvaluator.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace spatter {

namespace {

// The joint matrices of object `o`'s skin at the evaluator's pose, moved by `move` (none unskinned).
std::vector<glm::dmat4> movedJoints(const SceneEvaluator& evaluator, const SceneObject& o,
                                    const glm::dmat4& move) {
    std::vector<glm::dmat4> joints;
    if (o.skin >= 0)
        for (const glm::dmat4& j : evaluator.jointMatrices(size_t(o.skin)))
            joints.push_back(move * j);
    return joints;
}

} // namespace

std::vector<std::string> poseDecalSystem(DecalSystem& system, const Scene& scene, const DrawPose& pose) {
    std::vector<std::string> refused;
    if (scene.animation.animations.empty()) return refused;
    SceneEvaluator evaluator(scene);
    evaluator.evaluate(0, pose.time);
    const glm::dmat4 move = glm::translate(glm::dmat4(1.0), pose.offset);
    for (uint32_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& o = scene.objects[i];
        const CollisionObject* c = system.world().object(i);
        if (o.node < 0 || !o.dynamic || !c || !c->inWorld) continue;
        const glm::dmat4 transform = move * evaluator.objectTransform(i);
        const Result<TransformUpdate> r =
            system.world().deforms(i)
                ? system.setPose(i, transform, movedJoints(evaluator, o, move), evaluator.morphWeights(i))
                : system.setTransform(i, transform);
        if (!r) refused.push_back(r.error());
    }
    return refused;
}

} // namespace spatter
