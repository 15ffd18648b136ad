// Animation read from small glTF files written by each test, and posed by SceneEvaluator: keyframes
// are exact, each interpolation is followed between them, skinned and morphed positions agree with
// GltfReference (an independent reading in double), and what moves becomes dynamic.

#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SceneLoader.hpp"

#include "AnimatedGltf.hpp"
#include "GltfLoading.hpp"
#include "GltfReference.hpp"
#include "TestData.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace spatter;
using namespace spatter::test;

namespace {

// Scene of `g` written as a .glb, and its path in `path`.
Scene loadedGlb(const GltfBuilder& g, std::string& path) {
    path = writeGlb(g, scratchForTest("anim-"), "scene");
    return loaded(path);
}

// The quad's translation under "base" (0, 0, 5) at time t of animation 0.
glm::dvec3 quadTranslation(SceneEvaluator& evaluator, double t) {
    evaluator.evaluate(0, t);
    return glm::dvec3(evaluator.objectTransform(0)[3]) - glm::dvec3(0, 0, 5);
}

// Largest distance between the posed world positions of every object and the reference's, over
// `times` of animation 0.
double worstDistance(const Scene& scene, const GltfReference& reference, const std::vector<double>& times) {
    SceneEvaluator evaluator(scene);
    double worst = 0.0;
    for (double t : times) {
        evaluator.evaluate(0, t);
        for (size_t o = 0; o < scene.objects.size(); ++o) {
            const std::vector<glm::dvec3> posed = posedPositions(scene, o, evaluator);
            const std::vector<glm::dvec3> expected = reference.worldPositions(scene.objects[o].node, 0, t);
            EXPECT_EQ(posed.size(), expected.size());
            for (size_t v = 0; v < std::min(posed.size(), expected.size()); ++v) {
                const glm::dvec3 world(evaluator.objectTransform(o) * glm::dvec4(posed[v], 1.0));
                worst = std::max(worst, glm::length(world - expected[v]));
            }
        }
    }
    return worst;
}

const std::vector<double> kTimes = {-1.0, 0.0, 0.25, 0.5, 0.999, 1.0, 1.3, 1.75, 2.0, 3.0};

} // namespace

TEST(GltfAnimation, AFileWithoutAnimationDataLoadsAsBefore) {
    GltfBuilder g = animatedQuad();
    g.doc.erase("animations");
    Scene scene = loaded(g.writeGltf(scratchForTest("anim-"), "still"));
    EXPECT_TRUE(scene.animation.empty());
    for (const SceneObject& o : scene.objects) {
        EXPECT_EQ(o.node, -1);
        EXPECT_EQ(o.skin, -1);
        EXPECT_FALSE(o.dynamic);
    }
    SceneEvaluator evaluator(scene);
    evaluator.evaluate(0, 1.0);
    EXPECT_EQ(evaluator.objectTransform(0), scene.objects[0].transform);
}

TEST(GltfAnimation, AnimatedNodeAndItsDescendantsBecomeDynamicByThemselves) {
    GltfBuilder g = animatedQuad();
    g.doc["animations"][0]["channels"][0]["target"]["node"] = 1; // animate "base", the quad's parent
    g.doc["nodes"][1]["translation"] = {0, 0, 0};
    Scene scene = loaded(g.writeGltf(scratchForTest("anim-"), "parent"));
    ASSERT_EQ(scene.objects.size(), 2u);
    EXPECT_EQ(scene.objects[0].name, "quad");
    EXPECT_TRUE(scene.objects[0].dynamic);
    EXPECT_FALSE(scene.objects[1].dynamic); // "still" is beside, not below
    ASSERT_EQ(scene.animation.animations.size(), 1u);
    EXPECT_EQ(scene.animation.animations[0].name, "move");
    EXPECT_DOUBLE_EQ(scene.animation.animations[0].duration, 2.0);
}

TEST(GltfAnimation, LinearTranslationIsExactAtKeysAndLinearBetween) {
    Scene scene = loaded(animatedQuad().writeGltf(scratchForTest("anim-"), "linear"));
    SceneEvaluator evaluator(scene);
    EXPECT_EQ(quadTranslation(evaluator, 0.0), glm::dvec3(0, 0, 0));
    EXPECT_EQ(quadTranslation(evaluator, 1.0), glm::dvec3(1, 2, 3));
    EXPECT_EQ(quadTranslation(evaluator, 2.0), glm::dvec3(4, 4, 4));
    const glm::dvec3 mid = quadTranslation(evaluator, 1.25);
    EXPECT_NEAR(glm::length(mid - glm::dvec3(1.75, 2.5, 3.25)), 0.0, 1e-15);
    EXPECT_EQ(quadTranslation(evaluator, -3.0), glm::dvec3(0, 0, 0)); // before the first key
    EXPECT_EQ(quadTranslation(evaluator, 9.0), glm::dvec3(4, 4, 4));  // after the last key
    evaluator.evaluate(-1, 0.0);
    EXPECT_EQ(evaluator.objectTransform(0), scene.objects[0].transform); // the rest pose
}

TEST(GltfAnimation, StepHoldsEachKeyUntilTheNext) {
    GltfBuilder g = animatedQuad();
    g.doc["animations"][0]["samplers"][0]["interpolation"] = "STEP";
    Scene scene = loaded(g.writeGltf(scratchForTest("anim-"), "step"));
    SceneEvaluator evaluator(scene);
    EXPECT_EQ(quadTranslation(evaluator, 0.5), glm::dvec3(0, 0, 0));
    EXPECT_EQ(quadTranslation(evaluator, 0.9999), glm::dvec3(0, 0, 0));
    EXPECT_EQ(quadTranslation(evaluator, 1.0), glm::dvec3(1, 2, 3));
    EXPECT_EQ(quadTranslation(evaluator, 1.999), glm::dvec3(1, 2, 3));
    EXPECT_EQ(quadTranslation(evaluator, 2.0), glm::dvec3(4, 4, 4));
}

TEST(GltfAnimation, CubicSplineFollowsTheHermiteCurveWithTangentsScaledByTheKeyInterval) {
    GltfBuilder g = animatedQuad();
    g.doc.erase("animations");
    // Keys at 0 and 2 s: value 0 then 1 in x; out-tangent 3 at key 0, in-tangent -1 at key 1.
    addChannel(g, 0, "translation", {0, 2}, {9, 9, 9, 0, 0, 0, 3, 0, 0, -1, 0, 0, 1, 0, 0, 9, 9, 9}, "VEC3",
               "CUBICSPLINE");
    std::string path;
    Scene scene = loadedGlb(g, path);
    SceneEvaluator evaluator(scene);
    EXPECT_EQ(quadTranslation(evaluator, 0.0), glm::dvec3(0, 0, 0));
    EXPECT_EQ(quadTranslation(evaluator, 2.0), glm::dvec3(1, 0, 0));
    for (double t : {0.3, 1.0, 1.7}) {
        const double s = t / 2.0, td = 2.0;
        const double expected = (-2 * s * s * s + 3 * s * s) * 1.0 + td * (s * s * s - 2 * s * s + s) * 3.0 +
                                td * (s * s * s - s * s) * -1.0;
        EXPECT_NEAR(quadTranslation(evaluator, t).x, expected, 1e-15) << t;
    }
    const GltfReference reference(path);
    EXPECT_LT(worstDistance(scene, reference, kTimes), 1e-12);
}

TEST(GltfAnimation, LinearRotationSlerpsAlongTheShorterArc) {
    GltfBuilder g = animatedQuad();
    g.doc.erase("animations");
    // Identity, then 170 degrees about +Z written with the opposite sign (the same rotation).
    const glm::dquat turn = glm::angleAxis(glm::radians(170.0), glm::dvec3(0, 0, 1));
    addChannel(g, 0, "rotation", {0, 1},
               {0, 0, 0, 1, -float(turn.x), -float(turn.y), -float(turn.z), -float(turn.w)}, "VEC4");
    std::string path;
    Scene scene = loadedGlb(g, path);
    SceneEvaluator evaluator(scene);
    evaluator.evaluate(0, 0.5);
    const glm::dmat4 expected = glm::mat4_cast(glm::angleAxis(glm::radians(85.0), glm::dvec3(0, 0, 1)));
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            EXPECT_NEAR(evaluator.objectTransform(0)[c][r], expected[c][r], 1e-7); // the key is a float
    const GltfReference reference(path);
    EXPECT_LT(worstDistance(scene, reference, kTimes), 1e-12);
}

TEST(GltfAnimation, ScaleChannelsScaleTheNode) {
    GltfBuilder g = animatedQuad();
    g.doc.erase("animations");
    addChannel(g, 0, "scale", {0, 1}, {1, 1, 1, 3, 2, 1}, "VEC3");
    Scene scene = loaded(g.writeGltf(scratchForTest("anim-"), "scale"));
    SceneEvaluator evaluator(scene);
    evaluator.evaluate(0, 0.5);
    EXPECT_EQ(evaluator.objectTransform(0)[0][0], 2.0);
    EXPECT_EQ(evaluator.objectTransform(0)[1][1], 1.5);
}

TEST(GltfAnimation, EvaluatingTheSameTimeTwiceKeepsThePose) {
    Scene scene = loaded(animatedQuad().writeGltf(scratchForTest("anim-"), "cache"));
    SceneEvaluator evaluator(scene);
    evaluator.evaluate(0, 1.5);
    const glm::dmat4 first = evaluator.objectTransform(0);
    evaluator.evaluate(0, 1.5);
    EXPECT_EQ(evaluator.objectTransform(0), first);
    evaluator.evaluate(0, std::nan(""));
    EXPECT_EQ(evaluator.objectTransform(0), scene.objects[0].transform); // a NaN time gives the rest pose
    evaluator.evaluate(7, 1.5);
    EXPECT_EQ(evaluator.objectTransform(0), scene.objects[0].transform); // so does an unknown animation
}

TEST(GltfAnimation, SkinnedPositionsMatchTheReferenceWithEveryJointAndWeightType) {
    std::string path;
    Scene scene = loadedGlb(skinnedStrip(), path);
    ASSERT_EQ(scene.objects.size(), 1u);
    const SceneObject& strip = scene.objects[0];
    EXPECT_EQ(strip.skin, 0);
    EXPECT_EQ(strip.skinWeights.influences, 12); // three sets of four
    EXPECT_TRUE(strip.dynamic);
    for (size_t v = 0; v < strip.mesh->vertexCount(); ++v) {
        double sum = 0.0;
        for (size_t k = 0; k < 12; ++k)
            sum += strip.skinWeights.weights[v * 12 + k];
        EXPECT_NEAR(sum, 1.0, 1e-15) << v;
    }
    const GltfReference reference(path);
    // The strip is 2 long: 1e-6 of its diagonal is about 2e-6.
    EXPECT_LT(worstDistance(scene, reference, kTimes), 1e-12);
    // At 1 s the tip joint has turned 90 degrees: vertex 2 (fully on the tip) swings from (2, 0)
    // to (1, 1) about the tip at (1, 0), and the root has moved up by 1.
    SceneEvaluator evaluator(scene);
    evaluator.evaluate(0, 1.0);
    const glm::dvec3 p = posedPositions(scene, 0, evaluator)[2];
    EXPECT_NEAR(glm::length(p - glm::dvec3(1, 2, 0)), 0.0, 1e-7);
}

TEST(GltfAnimation, MorphedPositionsFollowCubicSplineWeights) {
    std::string path;
    Scene scene = loadedGlb(morphQuad(), path);
    ASSERT_EQ(scene.objects.size(), 1u);
    const SceneObject& quad = scene.objects[0];
    ASSERT_EQ(quad.morphTargets.size(), 2u);
    EXPECT_EQ(quad.morphTargets[0].normals.size(), 4u);
    EXPECT_TRUE(quad.morphTargets[1].normals.empty());
    EXPECT_TRUE(quad.dynamic);
    SceneEvaluator evaluator(scene);
    EXPECT_EQ(evaluator.morphWeights(0), (std::vector<double>{0.5, 0.0})); // the mesh's weights at rest
    EXPECT_EQ(posedPositions(scene, 0, evaluator)[0], glm::dvec3(0, 0, 0.5));
    evaluator.evaluate(0, 2.0);
    EXPECT_EQ(evaluator.morphWeights(0), (std::vector<double>{1.0, 0.25}));
    const GltfReference reference(path);
    EXPECT_LT(worstDistance(scene, reference, kTimes), 1e-12);
}

TEST(GltfAnimation, SparseMorphTargetsOverZerosAndOverDenseDeltas) {
    GltfBuilder g = morphQuad();
    makeSparse(g, 1, "POSITION", true);  // bufferless: zeros but for vertices 1 and 2
    makeSparse(g, 0, "POSITION", false); // over the dense (0, 0, 1) of every vertex
    std::string path;
    Scene scene = loadedGlb(g, path);
    ASSERT_EQ(scene.objects.size(), 1u);
    const std::vector<MorphTarget>& targets = scene.objects[0].morphTargets;
    ASSERT_EQ(targets.size(), 2u);
    EXPECT_EQ(targets[1].positions, (std::vector<glm::vec3>{{0, 0, 0}, {0, 0, 2}, {0, 3, 0}, {0, 0, 0}}));
    EXPECT_EQ(targets[0].positions, (std::vector<glm::vec3>{{0, 0, 1}, {0, 0, 2}, {0, 3, 0}, {0, 0, 1}}));
    const GltfReference reference(path);
    EXPECT_LT(worstDistance(scene, reference, kTimes), 1e-12);
}
