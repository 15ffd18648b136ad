// The animated glTF models of the shared data (Khronos samples): what the loader reads of their skins,
// animations and morph targets, and their poses at sampled times against GltfReference, an
// independent reading of the same file in double. Skipped with a message when the data is absent.

#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SceneLoader.hpp"

#include "GltfReference.hpp"
#include "TestData.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace spatter;

namespace {

Scene load(const std::string& path) {
    Result<Scene> scene = loadScene(path);
    EXPECT_TRUE(scene.ok()) << scene.error();
    return scene.ok() ? std::move(scene.value()) : Scene{};
}

// Times spread over [0, duration] that fall between keys as well as on them, plus the ends.
std::vector<double> sampleTimes(double duration) {
    std::vector<double> times = {0.0, duration};
    for (int i = 1; i < 12; ++i)
        times.push_back(duration * i / 12.0 + 0.0137);
    return times;
}

// Largest distance between the evaluator's posed world positions and the reference's, for every
// object of every animation at the sample times, relative to the rest scene's diagonal.
double worstRelativeError(const Scene& scene, const test::GltfReference& reference) {
    const DBounds rest = scene.worldBounds();
    const double diagonal = glm::length(rest.max - rest.min);
    SceneEvaluator evaluator(scene);
    double worst = 0.0;
    for (int a = 0; a < int(scene.animation.animations.size()); ++a)
        for (double t : sampleTimes(scene.animation.animations[size_t(a)].duration)) {
            evaluator.evaluate(a, t);
            for (size_t o = 0; o < scene.objects.size(); ++o) {
                const std::vector<glm::dvec3> posed = posedPositions(scene, o, evaluator);
                const std::vector<glm::dvec3> expected =
                    reference.worldPositions(scene.objects[o].node, a, t);
                EXPECT_EQ(posed.size(), expected.size());
                for (size_t v = 0; v < std::min(posed.size(), expected.size()); ++v) {
                    const glm::dvec3 world(evaluator.objectTransform(o) * glm::dvec4(posed[v], 1.0));
                    worst = std::max(worst, glm::length(world - expected[v]) / diagonal);
                }
            }
        }
    return worst;
}

// Largest distance of a posed vertex from its rest place over the sample times of animation 0,
// relative to the rest scene's diagonal: shows that the poses compared above are not the rest pose.
double largestMotion(const Scene& scene) {
    const DBounds rest = scene.worldBounds();
    SceneEvaluator evaluator(scene);
    double largest = 0.0;
    for (double t : sampleTimes(scene.animation.animations[0].duration)) {
        evaluator.evaluate(0, t);
        for (size_t o = 0; o < scene.objects.size(); ++o) {
            const SceneObject& object = scene.objects[o];
            const std::vector<glm::dvec3> posed = posedPositions(scene, o, evaluator);
            for (size_t v = 0; v < posed.size(); ++v) {
                const glm::dvec3 world(evaluator.objectTransform(o) * glm::dvec4(posed[v], 1.0));
                const glm::dvec3 before(object.transform *
                                        glm::dvec4(glm::dvec3(object.mesh->positions[v]), 1.0));
                largest = std::max(largest, glm::length(world - before));
            }
        }
    }
    return largest / glm::length(rest.max - rest.min);
}

} // namespace

TEST(AnimatedAssets, CesiumManHasOneSkinOfNineteenJointsAndMovesByItself) {
    SPATTER_REQUIRE_SHARED(path, "gltf/CesiumMan/CesiumMan.glb");
    const Scene scene = load(path);
    ASSERT_EQ(scene.animation.skins.size(), 1u);
    EXPECT_EQ(scene.animation.skins[0].joints.size(), 19u);
    ASSERT_EQ(scene.animation.animations.size(), 1u);
    EXPECT_GT(scene.animation.animations[0].duration, 1.0);
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].skin, 0);
    EXPECT_EQ(scene.objects[0].skinWeights.influences, 4);
    EXPECT_TRUE(scene.objects[0].dynamic);
}

TEST(AnimatedAssets, CesiumManSkinnedPositionsMatchTheReferenceAtSampledTimes) {
    SPATTER_REQUIRE_SHARED(path, "gltf/CesiumMan/CesiumMan.glb");
    const Scene scene = load(path);
    const test::GltfReference reference(path);
    ASSERT_TRUE(reference.ok());
    EXPECT_LT(worstRelativeError(scene, reference), 1e-6);
    EXPECT_GT(largestMotion(scene), 0.1);
}

TEST(AnimatedAssets, RiggedSimpleSkinnedPositionsMatchTheReferenceAtSampledTimes) {
    SPATTER_REQUIRE_SHARED(path, "gltf/RiggedSimple/RiggedSimple.glb");
    const Scene scene = load(path);
    ASSERT_EQ(scene.animation.skins.size(), 1u);
    EXPECT_EQ(scene.animation.skins[0].joints.size(), 2u);
    const test::GltfReference reference(path);
    ASSERT_TRUE(reference.ok());
    EXPECT_LT(worstRelativeError(scene, reference), 1e-6);
    EXPECT_GT(largestMotion(scene), 0.1);
}

TEST(AnimatedAssets, BoxAnimatedMovesItsAnimatedNodeAsADynamicObject) {
    SPATTER_REQUIRE_SHARED(path, "gltf/BoxAnimated/BoxAnimated.glb");
    const Scene scene = load(path);
    ASSERT_EQ(scene.objects.size(), 2u);
    EXPECT_EQ(scene.dynamicObjectCount(), 1u); // the animated box; the inner box stands still
    const test::GltfReference reference(path);
    ASSERT_TRUE(reference.ok());
    EXPECT_LT(worstRelativeError(scene, reference), 1e-6);
    EXPECT_GT(largestMotion(scene), 0.1);
    SceneEvaluator evaluator(scene);
    const double duration = scene.animation.animations[0].duration;
    for (double t : sampleTimes(duration)) {
        evaluator.evaluate(0, t);
        for (size_t o = 0; o < scene.objects.size(); ++o) {
            const glm::dmat4 expected = reference.nodeWorld(scene.objects[o].node, 0, t);
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r)
                    EXPECT_NEAR(evaluator.objectTransform(o)[c][r], expected[c][r], 1e-12);
        }
    }
}

TEST(AnimatedAssets, AnimatedMorphCubeFollowsItsMorphWeights) {
    SPATTER_REQUIRE_SHARED(path, "gltf/AnimatedMorphCube/AnimatedMorphCube.glb");
    const Scene scene = load(path);
    ASSERT_EQ(scene.objects.size(), 1u);
    const SceneObject& cube = scene.objects[0];
    ASSERT_EQ(cube.morphTargets.size(), 2u);
    EXPECT_FALSE(cube.morphTargets[0].normals.empty());
    EXPECT_FALSE(cube.morphTargets[0].tangents.empty());
    EXPECT_TRUE(cube.dynamic);
    const test::GltfReference reference(path);
    ASSERT_TRUE(reference.ok());
    EXPECT_LT(worstRelativeError(scene, reference), 1e-6);
    EXPECT_GT(largestMotion(scene), 0.1);
    SceneEvaluator evaluator(scene);
    bool moved = false;
    for (double t : sampleTimes(scene.animation.animations[0].duration)) {
        evaluator.evaluate(0, t);
        const std::vector<double> expected = reference.morphWeights(cube.node, 0, t);
        ASSERT_EQ(evaluator.morphWeights(0).size(), expected.size());
        for (size_t k = 0; k < expected.size(); ++k) {
            EXPECT_NEAR(evaluator.morphWeights(0)[k], expected[k], 1e-12);
            moved = moved || expected[k] > 0.1;
        }
    }
    EXPECT_TRUE(moved);
}

TEST(AnimatedAssets, RestPoseOfTheEvaluatorIsTheLoadedScene) {
    for (const char* relative : {"gltf/CesiumMan/CesiumMan.glb", "gltf/BoxAnimated/BoxAnimated.glb",
                                 "gltf/RiggedSimple/RiggedSimple.glb"}) {
        SCOPED_TRACE(relative);
        SPATTER_REQUIRE_SHARED(path, relative);
        const Scene scene = load(path);
        SceneEvaluator evaluator(scene);
        for (size_t o = 0; o < scene.objects.size(); ++o)
            EXPECT_EQ(evaluator.objectTransform(o), scene.objects[o].transform);
    }
}
