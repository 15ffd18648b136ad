#include "spatter/core/GalleryScene.hpp"
#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SkinnedArm.hpp"
#include "spatter/core/SkinnedDummy.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

using namespace spatter;

namespace {

// The largest distance between the object's rest mesh placed by its transform and its mesh skinned
// at time t, in world space.
double restAgainstPosed(const Scene& scene, uint32_t object, int animation, double t) {
    SceneEvaluator evaluator(scene);
    evaluator.evaluate(animation, t);
    const std::vector<glm::dvec3> posed = posedPositions(scene, object, evaluator);
    const SceneObject& o = scene.objects[object];
    double worst = 0.0;
    for (size_t v = 0; v < posed.size(); ++v) {
        const glm::dvec3 rest(o.transform * glm::dvec4(glm::dvec3(o.mesh->positions[v]), 1.0));
        const glm::dvec3 now(evaluator.objectTransform(object) * glm::dvec4(posed[v], 1.0));
        worst = std::max(worst, glm::length(rest - now));
    }
    return worst;
}

} // namespace

TEST(SkinnedFigures, ArmIsValidAndBendsAwayFromItsRestPose) {
    const Scene arm = makeSkinnedArm();
    ASSERT_TRUE(validateScene(arm).ok()) << validateScene(arm).error();
    EXPECT_LT(restAgainstPosed(arm, 0, 0, 0.0), 1e-6);
    EXPECT_GT(restAgainstPosed(arm, 0, 0, 1.0), 0.3);
}

TEST(SkinnedFigures, DummyJoinsAGalleryAsAValidAnimatedTarget) {
    Scene scene = makeGalleryScene(GallerySettings{1, 0, 1, 0});
    const size_t before = scene.objects.size();
    const glm::dmat4 at = glm::translate(glm::dmat4(1.0), glm::dvec3(-2.5, 0.0, 1.0));
    const uint32_t dummy = addSkinnedDummy(scene, at);
    ASSERT_EQ(dummy, before);
    ASSERT_TRUE(validateScene(scene).ok()) << validateScene(scene).error();
    const SceneObject& o = scene.objects[dummy];
    EXPECT_TRUE(o.dynamic);
    EXPECT_GT(o.mesh->triangleCount(), 1000u);
    const Bounds b = o.mesh->bounds();
    EXPECT_NEAR(b.max.y - b.min.y, 1.71, 0.05);
    // At rest the skin puts every vertex where the mesh has it; half a swing later the arms have moved.
    EXPECT_LT(restAgainstPosed(scene, dummy, 0, 0.0), 1e-6);
    EXPECT_GT(restAgainstPosed(scene, dummy, 0, 0.75), 0.2);
}
