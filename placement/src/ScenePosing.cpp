#include "spatter/placement/ScenePosing.hpp"

#include "spatter/core/SceneEvaluator.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace spatter {

namespace {

bool deforms(const SceneObject& o) {
    return o.skin >= 0 || !o.morphTargets.empty();
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
        Result<TransformUpdate> r = TransformUpdate{};
        if (!deforms(o)) {
            r = system.setTransform(i, transform);
        } else {
            std::vector<glm::dmat4> joints;
            if (o.skin >= 0)
                for (const glm::dmat4& j : evaluator.jointMatrices(size_t(o.skin)))
                    joints.push_back(move * j);
            r = system.setPose(i, transform, joints, evaluator.morphWeights(i));
        }
        if (!r) refused.push_back(r.error());
    }
    return refused;
}

} // namespace spatter
