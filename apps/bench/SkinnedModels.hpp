#pragma once
// SkinnedModels: the models `spatter-bench skinned` measures, and the worlds and decal systems it
// measures them in. A model is a scene with an animation and the first skinned object that receives
// decals, posed by animation 0 looped over its duration: builtin:skinned-arm (50 rings of 50
// vertices), the gallery's dummy, or a glTF file (found as the other benchmarks find their inputs).

#include "spatter/core/Mesh.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/placement/CollisionWorld.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

namespace spatter::bench {

constexpr const char* kSkinnedArmSpec = "builtin:skinned-arm";
constexpr const char* kSkinnedDummySpec = "gallery dummy";
constexpr double kSkinnedDecalSizeFraction = 0.05; // decals a twentieth of the model's diagonal

struct SkinnedModel {
    std::string name;
    Scene scene;
    uint32_t object = 0;    // the first skinned receiver: the object every row measures
    double duration = 0.0;  // of animation 0, seconds
    double diagonal = 0.0;  // of the render mesh posed at time 0, world units
    double decalSize = 0.0; // world units
};

// One pose of the model's object as a host hands it to setPose.
struct ModelPose {
    glm::dmat4 transform{1.0};
    std::vector<glm::dmat4> joints;
    std::vector<double> weights;
};

// Loads the model `spec` names. Fails when it cannot be found or loaded, has no animation of
// positive duration, or no skinned dynamic object that receives decals.
Result<SkinnedModel> loadSkinnedModel(const std::string& spec);

// The object's pose at time `t` of animation 0 (leaves `evaluator` at t).
ModelPose modelPoseAt(const SkinnedModel& m, SceneEvaluator& evaluator, double t);
// The time at `phase` (a fraction) of the cycle.
double cycleTime(const SkinnedModel& m, double phase);
// The render mesh's vertices at time t, in world space (leaves `evaluator` at t).
std::vector<glm::dvec3> worldPositionsAt(const SkinnedModel& m, SceneEvaluator& evaluator, double t);
// The render mesh of `scene.objects[object]` posed as `evaluator` stands, in world space.
std::vector<glm::dvec3> worldPositionsOf(const Scene& scene, uint32_t object,
                                         const SceneEvaluator& evaluator);
// The object's render mesh with `positions`.
Mesh meshAt(const SkinnedModel& m, const std::vector<glm::dvec3>& positions);

// Embree commits and refits on the calling thread alone, so that the thread's CPU time is all the
// work of a call.
WorldSettings oneThreadWorld();
// The model's world: the render mesh as the skinned object's collision mesh, or `proxy`.
Result<CollisionWorld> skinnedWorld(const SkinnedModel& m, const std::optional<Proxy>& proxy);
// A system over `world` with one decal type (index 0), "hole", of `size`, and room for `decals`
// decals everywhere, so that no limit evicts or rejects.
Result<DecalSystem> holeSystem(Result<CollisionWorld> world, double size, size_t decals);
// Gives `system` the model's object at `pose`.
Status poseSystem(DecalSystem& system, const SkinnedModel& m, const ModelPose& pose);

} // namespace spatter::bench
