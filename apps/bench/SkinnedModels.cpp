#include "SkinnedModels.hpp"

#include "BenchSupport.hpp"

#include "spatter/core/SceneLoader.hpp"
#include "spatter/core/SkinnedArm.hpp"
#include "spatter/core/SkinnedDummy.hpp"

#include <algorithm>
#include <utility>

namespace spatter::bench {

namespace {

SkinnedArmSettings armSettings() {
    SkinnedArmSettings s;
    s.rings = 50; // 49 bands of 50 quads and the two end fans: 5,000 triangles
    s.segments = 50;
    return s;
}

Result<Scene> loadModelScene(const std::string& spec) {
    if (spec == kSkinnedArmSpec) return makeSkinnedArm(armSettings());
    if (spec == kSkinnedDummySpec) {
        Scene dummy;
        dummy.source = kSkinnedDummySpec;
        addSkinnedDummy(dummy, glm::dmat4(1.0));
        return dummy;
    }
    const std::string path = resolveInput(spec);
    if (path.empty())
        return fail("'" + spec + "' not found (nor in the shared data '" + sharedDataDir() + "')");
    return loadScene(path);
}

} // namespace

ModelPose modelPoseAt(const SkinnedModel& m, SceneEvaluator& evaluator, double t) {
    evaluator.evaluate(0, t);
    ModelPose p{evaluator.objectTransform(m.object), {}, evaluator.morphWeights(m.object)};
    p.joints = evaluator.jointMatrices(size_t(m.scene.objects[m.object].skin));
    return p;
}

double cycleTime(const SkinnedModel& m, double phase) {
    return m.duration * phase;
}

std::vector<glm::dvec3> worldPositionsAt(const SkinnedModel& m, SceneEvaluator& evaluator, double t) {
    evaluator.evaluate(0, t);
    return worldPositionsOf(m.scene, m.object, evaluator);
}

std::vector<glm::dvec3> worldPositionsOf(const Scene& scene, uint32_t object,
                                         const SceneEvaluator& evaluator) {
    const glm::dmat4& toWorld = evaluator.objectTransform(object);
    std::vector<glm::dvec3> p = posedPositions(scene, object, evaluator);
    for (glm::dvec3& v : p)
        v = glm::dvec3(toWorld * glm::dvec4(v, 1.0));
    return p;
}

Mesh meshAt(const SkinnedModel& m, const std::vector<glm::dvec3>& positions) {
    return withPositions(*m.scene.objects[m.object].mesh, positions);
}

Result<SkinnedModel> loadSkinnedModel(const std::string& spec) {
    Result<Scene> scene = loadModelScene(spec);
    if (!scene) return fail(scene.error());
    SkinnedModel m{spec, std::move(scene).value()};
    const auto& animations = m.scene.animation.animations;
    if (animations.empty() || !(animations[0].duration > 0.0)) return fail(spec + ": no animation to loop");
    m.duration = animations[0].duration;
    const auto& objects = m.scene.objects;
    const auto skinned = std::find_if(objects.begin(), objects.end(), [](const SceneObject& o) {
        return o.skin != -1 && o.dynamic && o.receivesDecals;
    });
    if (skinned == objects.end()) return fail(spec + ": no skinned object receives decals");
    m.object = uint32_t(skinned - objects.begin());
    SceneEvaluator evaluator(m.scene);
    m.diagonal = referencedDiagonal(meshAt(m, worldPositionsAt(m, evaluator, 0.0)));
    m.decalSize = kSkinnedDecalSizeFraction * m.diagonal;
    return m;
}

WorldSettings oneThreadWorld() {
    WorldSettings s;
    s.useColliders = false;
    s.deviceConfig = "threads=1";
    return s;
}

Result<CollisionWorld> skinnedWorld(const SkinnedModel& m, const std::optional<Proxy>& proxy) {
    std::vector<std::shared_ptr<const Proxy>> proxies;
    if (proxy) {
        proxies.resize(m.scene.objects.size());
        proxies[m.object] = shareProxy(*proxy);
    }
    return CollisionWorld::build(m.scene, proxies, oneThreadWorld());
}

Result<DecalSystem> holeSystem(Result<CollisionWorld> world, double size, size_t decals) {
    if (!world) return fail(world.error());
    DecalSettings settings;
    settings.maxPerCell = settings.budget = settings.maxPerObject = uint32_t(decals);
    Result<DecalSystem> system = DecalSystem::create(std::move(world).value(), settings);
    if (!system) return system;
    DecalType type;
    type.name = "hole";
    type.size = glm::vec2(float(size));
    if (Result<uint16_t> index = system->registerType(type); !index) return fail(index.error());
    return system;
}

Status poseSystem(DecalSystem& system, const SkinnedModel& m, const ModelPose& pose) {
    Result<TransformUpdate> u = system.setPose(m.object, pose.transform, pose.joints, pose.weights);
    if (!u) return fail(m.name + ": " + u.error());
    return {};
}

} // namespace spatter::bench
