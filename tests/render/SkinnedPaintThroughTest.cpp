// No painting through on a skinned character: a deep decal shot at the dummy's arm from the side,
// drawn by the renderer on the GPU-skinned mesh, covers pixels of the arm and none of the body behind
// it. Each covered pixel is traced on the CPU through the posed render mesh to find what it shows.

#include "RenderTestSupport.hpp"
#include "TestData.hpp"

#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SkinnedDummy.hpp"
#include "spatter/core/VertexDeformation.hpp"
#include "spatter/placement/CollisionWorld.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace spatter;
using namespace spatter::test;

namespace {

constexpr int kSize = 192;

// The dummy's render mesh posed at t, as a static object: what the renderer draws.
Scene drawnDummy(const Scene& scene, const SceneEvaluator& evaluator) {
    Scene drawn;
    drawn.source = "test:drawn-dummy";
    drawn.objects.push_back(
        makeSceneObject("dummy", withPositions(*scene.objects[0].mesh, posedPositions(scene, 0, evaluator)),
                        evaluator.objectTransform(0)));
    return drawn;
}

struct Shown {
    size_t arm = 0, body = 0;
};

// What the covered pixels of `mask` show: the arms or the rest of the body (vertices the hips alone
// carry), by a ray through each pixel's centre against the drawn mesh.
Shown whatIsCovered(const std::vector<uint8_t>& mask, const Scene& scene, const Scene& drawn,
                    const Camera& camera) {
    const CollisionWorld world = CollisionWorld::build(drawn).value();
    const CameraBasis basis = cameraBasis(camera);
    const double t = std::tan(glm::radians(camera.fovYDeg) * 0.5);
    const SkinWeights& w = scene.objects[0].skinWeights;
    Shown shown;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            if (!mask[size_t(y) * kSize + size_t(x)]) continue;
            Ray r;
            r.origin = camera.eye;
            r.direction = -basis.back + basis.right * ((2.0 * (x + 0.5) / kSize - 1.0) * t) +
                          basis.up * ((1.0 - 2.0 * (y + 0.5) / kSize) * t);
            const std::optional<Hit> hit = world.intersect(r);
            if (!hit) continue;
            bool body = true;
            for (int k = 0; k < 3; ++k) {
                const uint32_t v = scene.objects[0].mesh->indices[3 * size_t(hit->primitive) + size_t(k)];
                body = body && w.joints[2 * v] == 0 && w.weights[2 * v] >= 1.0;
            }
            ++(body ? shown.body : shown.arm);
        }
    return shown;
}

} // namespace

TEST(SkinnedPaintThrough, ADeepDecalOnTheArmCoversNoPixelOfTheBodyBehindIt) {
    SPATTER_REQUIRE_GL(gl);
    Scene scene;
    scene.source = "test:dummy";
    addSkinnedDummy(scene, glm::dmat4(1.0));
    SceneEvaluator evaluator(scene);
    evaluator.evaluate(0, 0.2);
    DecalSettings settings;
    settings.maxPerCell = 64;
    Result<DecalSystem> system = DecalSystem::create(scene, settings);
    ASSERT_TRUE(system.ok()) << system.error();
    DecalType deep;
    deep.name = "deep";
    deep.size = glm::vec2(0.15f);
    deep.halfDepth = 1.8f; // the dummy's height
    deep.randomRotation = false;
    const uint16_t type = system->registerType(deep).value();
    ASSERT_TRUE(system->setPose(0, evaluator.objectTransform(0), evaluator.jointMatrices(0), {}).ok());

    // Posed a little (hips, shoulders and elbows turned 5 to 16 degrees), shot from the dummy's left
    // (+X) at its left arm about the elbow, the torso right behind.
    const std::vector<glm::dvec3> posed = posedPositions(scene, 0, evaluator);
    glm::dvec3 aim(0.0);
    for (size_t v = 0; v < posed.size(); ++v)
        if (scene.objects[0].skinWeights.joints[2 * v] != 0 && std::abs(posed[v].y - 1.12) < 0.05 &&
            posed[v].x > aim.x)
            aim = posed[v];
    Ray shot;
    shot.origin = aim + glm::dvec3(3.0, 0.0, 0.0);
    shot.direction = glm::dvec3(-1.0, 0.0, 0.0);
    const SpawnResult placed = system->spawn(shot, type);
    ASSERT_TRUE(placed.placed()) << placed.reason;
    // The same decal as an engine attaches one: its box keeps the type's depth.
    const Decal skinned = *system->get(placed.handle);
    Decal deepBox = skinned;
    deepBox.halfDepth = deep.halfDepth;

    Result<Renderer> r = makeRenderer(kSize, kSize);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r->setScene(scene).ok());
    r->setDecalTypes({deep});
    ASSERT_TRUE(r->setObjectIds({system->objectId(0)}).ok());
    ASSERT_TRUE(r->setPose(evaluator).ok());
    const Camera camera = lookAt(aim + glm::dvec3(2.5, 0.0, 0.0), aim);
    const Scene drawn = drawnDummy(scene, evaluator);

    r->setDecals({skinned});
    const Shown onSkin =
        whatIsCovered(whiteMask(renderView(r.value(), camera, View::Coverage)), scene, drawn, camera);
    EXPECT_GT(onSkin.arm, 50u);
    EXPECT_EQ(onSkin.body, 0u) << "the skinned decal paints the body behind the arm";

    r->setDecals({deepBox});
    const Shown deepShown =
        whatIsCovered(whiteMask(renderView(r.value(), camera, View::Coverage)), scene, drawn, camera);
    EXPECT_GT(deepShown.body, 20u) << "a box of the type's depth reaches the body: the test can see it";
}
