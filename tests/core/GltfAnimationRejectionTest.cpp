// Bad animation data in small glTF files: each defect rejects the whole file with an error that
// names the file, the glTF part and the problem. Also the checks validateScene makes on animation
// data built by hand.

#include "spatter/core/SceneLoader.hpp"

#include "AnimatedGltf.hpp"
#include "TestData.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

using namespace spatter;
using namespace spatter::test;
using ::testing::HasSubstr;

namespace {

// The error of loading `g`, which must fail and name the file.
std::string rejection(GltfBuilder g) {
    const std::string dir =
        scratchDir(std::string("animbad-") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    const std::string path = g.writeGltf(dir, "bad");
    Result<Scene> scene = loadGltf(path);
    if (scene.ok()) {
        ADD_FAILURE() << "loaded but should have been rejected";
        return "";
    }
    EXPECT_THAT(scene.error(), HasSubstr(path));
    return scene.error();
}

// Replaces accessor `index` of `g` by float `values` of `type`.
void replaceFloats(GltfBuilder& g, int index, const std::vector<float>& values, const char* type) {
    const int fresh = addFloats(g, values, type);
    g.doc["accessors"][index] = g.doc["accessors"][fresh];
}

nlohmann::json& channel0(GltfBuilder& g) {
    return g.doc["animations"][0]["channels"][0];
}
nlohmann::json& sampler0(GltfBuilder& g) {
    return g.doc["animations"][0]["samplers"][0];
}
int inputOf(GltfBuilder& g) {
    return sampler0(g)["input"];
}
int outputOf(GltfBuilder& g) {
    return sampler0(g)["output"];
}

const float kNaN = std::numeric_limits<float>::quiet_NaN();

} // namespace

// --- channels and samplers -----------------------------------------------------------------------

TEST(GltfAnimationRejection, ChannelTargetingAMissingNode) {
    GltfBuilder g = animatedQuad();
    channel0(g)["target"]["node"] = 9;
    EXPECT_THAT(rejection(g), HasSubstr("animation 0 (move) channel 0 targets node 9, which does not exist"));
}

TEST(GltfAnimationRejection, ChannelWithAMissingSampler) {
    GltfBuilder g = animatedQuad();
    channel0(g)["sampler"] = 4;
    EXPECT_THAT(rejection(g), HasSubstr("channel 0 refers to sampler 4, which does not exist"));
}

TEST(GltfAnimationRejection, UnknownTargetPath) {
    GltfBuilder g = animatedQuad();
    channel0(g)["target"]["path"] = "colour";
    EXPECT_THAT(rejection(g), HasSubstr("target path \"colour\""));
}

TEST(GltfAnimationRejection, AnimatedNodeWithAMatrix) {
    GltfBuilder g = animatedQuad();
    g.doc["nodes"][0].erase("translation");
    g.doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    EXPECT_THAT(rejection(g), HasSubstr("animates node 0 (quad), which has a matrix"));
}

TEST(GltfAnimationRejection, WeightsChannelOnANodeWithoutMorphTargets) {
    GltfBuilder g = animatedQuad();
    channel0(g)["target"]["path"] = "weights";
    EXPECT_THAT(rejection(g),
                HasSubstr("animates the morph weights of node 0 (quad), which has no morph targets"));
}

TEST(GltfAnimationRejection, UnknownInterpolation) {
    GltfBuilder g = animatedQuad();
    sampler0(g)["interpolation"] = "CUBIC";
    EXPECT_THAT(rejection(g), HasSubstr("sampler 0 has interpolation \"CUBIC\""));
}

TEST(GltfAnimationRejection, NaNKeyTime) {
    GltfBuilder g = animatedQuad();
    replaceFloats(g, inputOf(g), {0, kNaN, 2}, "SCALAR");
    EXPECT_THAT(rejection(g), HasSubstr("sampler 0 has key time 1 that is not finite"));
}

TEST(GltfAnimationRejection, KeyTimesThatDoNotIncrease) {
    GltfBuilder g = animatedQuad();
    replaceFloats(g, inputOf(g), {0, 1, 1}, "SCALAR");
    EXPECT_THAT(rejection(g), HasSubstr("key times that do not increase (key 2"));
}

// The glTF schema of animation.sampler.input: "time[0] >= 0.0" (tinygltf does not check it).
TEST(GltfAnimationRejection, KeyTimesBeforeZero) {
    GltfBuilder g = animatedQuad();
    replaceFloats(g, inputOf(g), {-5, 1, 2}, "SCALAR");
    EXPECT_THAT(rejection(g), HasSubstr("sampler 0 has key time 0 at -5.000000 s, before 0"));
}

TEST(GltfAnimationRejection, SamplerWithoutKeys) {
    GltfBuilder g = animatedQuad();
    g.doc["accessors"][inputOf(g)]["count"] = 0;
    EXPECT_THAT(rejection(g), HasSubstr("sampler 0 has no keyframes"));
}

TEST(GltfAnimationRejection, OutputCountThatDoesNotMatchTheKeys) {
    GltfBuilder g = animatedQuad();
    g.doc["accessors"][outputOf(g)]["count"] = 2;
    EXPECT_THAT(rejection(g), HasSubstr("has 2 output values for 3 keys, expected 3"));
}

TEST(GltfAnimationRejection, CubicSplineWithoutTangents) {
    GltfBuilder g = animatedQuad();
    sampler0(g)["interpolation"] = "CUBICSPLINE";
    EXPECT_THAT(rejection(g), HasSubstr("has 3 output values for 3 keys, expected 9"));
}

TEST(GltfAnimationRejection, NaNOutputValue) {
    GltfBuilder g = animatedQuad();
    replaceFloats(g, outputOf(g), {0, 0, 0, 1, kNaN, 3, 4, 4, 4}, "VEC3");
    EXPECT_THAT(rejection(g), HasSubstr("has output value 1 that is not finite"));
}

TEST(GltfAnimationRejection, OutputOfTheWrongType) {
    GltfBuilder g = animatedQuad();
    channel0(g)["target"]["path"] = "rotation";
    EXPECT_THAT(rejection(g), HasSubstr("(sampler output) is VEC3, expected VEC4"));
}

TEST(GltfAnimationRejection, ZeroRotationKey) {
    GltfBuilder g = animatedQuad();
    g.doc.erase("animations");
    addChannel(g, 0, "rotation", {0, 1}, {0, 0, 0, 1, 0, 0, 0, 0}, "VEC4");
    EXPECT_THAT(rejection(g), HasSubstr("zero rotation quaternion at key 1"));
}

TEST(GltfAnimationRejection, IntegerRotationsThatAreNotNormalized) {
    GltfBuilder g = animatedQuad();
    g.doc.erase("animations");
    addChannel(g, 0, "rotation", {0, 1}, {0, 0, 0, 1, 0, 0, 0, 1}, "VEC4");
    const std::vector<int16_t> packed = {0, 0, 0, 32767, 0, 0, 0, 32767};
    g.doc["accessors"][outputOf(g)] = g.doc["accessors"][g.addAccessor(g.addView(packed), 5122, 2, "VEC4")];
    EXPECT_THAT(rejection(g), HasSubstr("integer output values that are not normalized"));
}

TEST(GltfAnimationRejection, TwoChannelsOnTheSameProperty) {
    GltfBuilder g = animatedQuad();
    addChannel(g, 0, "translation", {0, 1}, {0, 0, 0, 1, 1, 1}, "VEC3");
    EXPECT_THAT(rejection(g), HasSubstr("channel 1 animates the same property of node 0 as channel 0"));
}

// --- skins ---------------------------------------------------------------------------------------

TEST(GltfAnimationRejection, SkinWithoutJoints) {
    GltfBuilder g = skinnedStrip();
    g.doc["skins"][0]["joints"] = nlohmann::json::array();
    EXPECT_THAT(rejection(g), HasSubstr("skin 0 has no joints"));
}

TEST(GltfAnimationRejection, SkinWithoutTheJointsPropertyIsNamed) {
    GltfBuilder g = skinnedStrip();
    g.doc["skins"][0].erase("joints");
    EXPECT_THAT(rejection(g), HasSubstr("not valid glTF: skin 0 lacks the required property \"joints\""));
    const std::string glb = writeGlb(g, scratchDir("animbad-glb-joints"), "bad");
    Result<Scene> scene = loadGltf(glb);
    ASSERT_FALSE(scene.ok());
    EXPECT_THAT(scene.error(), HasSubstr("skin 0 lacks the required property \"joints\""));
}

TEST(GltfAnimationRejection, ChannelWithoutATarget) {
    GltfBuilder g = animatedQuad();
    channel0(g).erase("target");
    EXPECT_THAT(rejection(g), HasSubstr("animation 0 (move) channel 0 has no target"));
}

TEST(GltfAnimationRejection, ChannelTargetingNoNodeIsLeftToExtensions) {
    GltfBuilder g = animatedQuad();
    channel0(g)["target"] = {{"path", "pointer"}};
    Result<Scene> scene = loadGltf(g.writeGltf(scratchDir("anim-pointer"), "pointer"));
    ASSERT_TRUE(scene.ok()) << scene.error();
    EXPECT_TRUE(scene->animation.animations[0].channels.empty());
    EXPECT_FALSE(scene->objects[0].dynamic);
}

TEST(GltfAnimationRejection, SkinJointThatIsNotANode) {
    GltfBuilder g = skinnedStrip();
    g.doc["skins"][0]["joints"] = {1, 7};
    EXPECT_THAT(rejection(g), HasSubstr("skin 0 has joint node 7, which does not exist"));
}

TEST(GltfAnimationRejection, SkinListingAJointTwice) {
    GltfBuilder g = skinnedStrip();
    g.doc["skins"][0]["joints"] = {1, 1};
    EXPECT_THAT(rejection(g), HasSubstr("skin 0 lists joint node 1 twice"));
}

TEST(GltfAnimationRejection, FewerInverseBindMatricesThanJoints) {
    GltfBuilder g = skinnedStrip();
    g.doc["accessors"][g.doc["skins"][0]["inverseBindMatrices"].get<int>()]["count"] = 1;
    EXPECT_THAT(rejection(g), HasSubstr("skin 0 has 2 joints but 1 inverse bind matrices"));
}

TEST(GltfAnimationRejection, NaNInverseBindMatrix) {
    GltfBuilder g = skinnedStrip();
    std::vector<float> ibm(32, 0.0f);
    ibm[16 + 5] = kNaN;
    replaceFloats(g, g.doc["skins"][0]["inverseBindMatrices"], ibm, "MAT4");
    EXPECT_THAT(rejection(g), HasSubstr("skin 0: inverse bind matrix 1 is not finite"));
}

TEST(GltfAnimationRejection, NodeWithAMissingSkin) {
    GltfBuilder g = skinnedStrip();
    g.doc["nodes"][0]["skin"] = 3;
    EXPECT_THAT(rejection(g), HasSubstr("node 0 (strip) refers to skin 3, which does not exist"));
}

TEST(GltfAnimationRejection, SkinnedMeshWithoutJoints) {
    GltfBuilder g = skinnedStrip();
    for (const char* name : {"JOINTS_0", "WEIGHTS_0", "JOINTS_1", "WEIGHTS_1", "JOINTS_2", "WEIGHTS_2"})
        g.doc["meshes"][0]["primitives"][0]["attributes"].erase(name);
    EXPECT_THAT(rejection(g), HasSubstr("node 0 (strip) has a skin, but its mesh has no JOINTS_0"));
}

TEST(GltfAnimationRejection, JointsWithoutWeights) {
    GltfBuilder g = skinnedStrip();
    g.doc["meshes"][0]["primitives"][0]["attributes"].erase("WEIGHTS_1");
    EXPECT_THAT(rejection(g), HasSubstr("mesh 0 primitive 0: has JOINTS_1 but no WEIGHTS_1"));
}

TEST(GltfAnimationRejection, JointIndexPastTheSkin) {
    GltfBuilder g = skinnedStrip();
    const std::vector<uint8_t> joints(24, 5);
    g.doc["accessors"][g.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"].get<int>()]
         ["bufferView"] = g.addView(joints);
    EXPECT_THAT(rejection(g), HasSubstr("vertex 0 uses joint 5, the skin has 2"));
}

TEST(GltfAnimationRejection, NegativeWeight) {
    GltfBuilder g = skinnedStrip();
    std::vector<float> weights(24, 0.0f);
    weights[0] = -1.0f;
    replaceFloats(g, g.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_2"], weights, "VEC4");
    EXPECT_THAT(rejection(g), HasSubstr("(WEIGHTS_2) element 0 has a negative or non-finite weight"));
}

TEST(GltfAnimationRejection, SkinnedVertexWithoutWeight) {
    GltfBuilder g = skinnedStrip();
    const std::vector<uint8_t> zeros(24, 0);
    g.doc["accessors"][g.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"].get<int>()]
         ["bufferView"] = g.addView(zeros);
    EXPECT_THAT(rejection(g), HasSubstr("vertex 0 has joint weights summing to 0"));
}

TEST(GltfAnimationRejection, FloatJoints) {
    GltfBuilder g = skinnedStrip();
    replaceFloats(g, g.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"],
                  std::vector<float>(24, 0.0f), "VEC4");
    EXPECT_THAT(rejection(g), HasSubstr("(JOINTS_0) has component type 5126"));
}

TEST(GltfAnimationRejection, IntegerWeightsThatAreNotNormalized) {
    GltfBuilder g = skinnedStrip();
    g.doc["accessors"][g.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"].get<int>()]
         ["normalized"] = false;
    EXPECT_THAT(rejection(g), HasSubstr("(WEIGHTS_0) has integer components that are not normalized"));
}

TEST(GltfAnimationRejection, JointsOfAnotherVertexCount) {
    GltfBuilder g = skinnedStrip();
    g.doc["accessors"][g.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_1"].get<int>()]["count"] = 5;
    EXPECT_THAT(rejection(g), HasSubstr("(JOINTS_1) has 5 elements, the primitive has 6 vertices"));
}

// --- morph targets -------------------------------------------------------------------------------

TEST(GltfAnimationRejection, PrimitivesWithDifferentTargetCounts) {
    GltfBuilder g = morphQuad();
    nlohmann::json second = g.doc["meshes"][0]["primitives"][0];
    second["targets"].erase(1);
    g.doc["meshes"][0]["primitives"].push_back(second);
    EXPECT_THAT(rejection(g), HasSubstr("primitive 1: has 1 morph targets, an earlier primitive has 2"));
}

TEST(GltfAnimationRejection, NaNMorphDelta) {
    GltfBuilder g = morphQuad();
    replaceFloats(g, g.doc["meshes"][0]["primitives"][0]["targets"][1]["POSITION"],
                  {0, 0, 0, 0, 0, 0, kNaN, 0, 0, 0, 0, 0}, "VEC3");
    EXPECT_THAT(rejection(g), HasSubstr("(morph target 1 POSITION) element 2 is not finite"));
}

TEST(GltfAnimationRejection, MorphDeltasOfAnotherVertexCount) {
    GltfBuilder g = morphQuad();
    g.doc["accessors"][g.doc["meshes"][0]["primitives"][0]["targets"][0]["NORMAL"].get<int>()]["count"] = 3;
    EXPECT_THAT(rejection(g),
                HasSubstr("(morph target 0 NORMAL) has 3 elements, the primitive has 4 vertices"));
}

TEST(GltfAnimationRejection, MorphWeightsOfAnotherCount) {
    GltfBuilder g = morphQuad();
    g.doc["nodes"][0]["weights"] = {1, 0, 0};
    EXPECT_THAT(rejection(g), HasSubstr("node 0 (morph) has 3 morph weights for 2 morph targets"));
}

TEST(GltfAnimationRejection, WeightsChannelOfAnotherWidth) {
    GltfBuilder g = morphQuad();
    g.doc["accessors"][outputOf(g)]["count"] = 6;
    EXPECT_THAT(rejection(g), HasSubstr("has 6 output values for 2 keys, expected 12"));
}

TEST(GltfAnimationRejection, SparseIndexPastTheElements) {
    GltfBuilder g = morphQuad();
    const int sparse = makeSparse(g, 1, "POSITION", true);
    g.doc["accessors"][sparse]["sparse"]["indices"]["bufferView"] =
        g.addView(std::vector<uint8_t>{1, 4, 0, 0});
    EXPECT_THAT(rejection(g),
                HasSubstr("(morph target 1 POSITION) has sparse index 4 (entry 1) that is past the "
                          "elements or does not increase"));
}

TEST(GltfAnimationRejection, SparseIndicesThatDoNotIncrease) {
    GltfBuilder g = morphQuad();
    const int sparse = makeSparse(g, 1, "POSITION", true);
    g.doc["accessors"][sparse]["sparse"]["indices"]["bufferView"] =
        g.addView(std::vector<uint8_t>{2, 1, 0, 0});
    EXPECT_THAT(rejection(g),
                HasSubstr("has sparse index 1 (entry 1) that is past the elements or does not increase"));
}

TEST(GltfAnimationRejection, SparseCountAboveTheAccessorCount) {
    GltfBuilder g = morphQuad();
    const int sparse = makeSparse(g, 1, "POSITION", true);
    g.doc["accessors"][sparse]["sparse"]["count"] = 5;
    EXPECT_THAT(rejection(g), HasSubstr("has a sparse count of 5 for 4 elements"));
}

TEST(GltfAnimationRejection, SparseValuesPastTheirBufferView) {
    GltfBuilder g = morphQuad();
    const int sparse = makeSparse(g, 1, "POSITION", true);
    g.doc["accessors"][sparse]["sparse"]["values"]["byteOffset"] = 8;
    EXPECT_THAT(rejection(g), HasSubstr("its sparse values read past the end of buffer view"));
}

TEST(GltfAnimationRejection, SparseIndicesOfAFloatType) {
    GltfBuilder g = morphQuad();
    const int sparse = makeSparse(g, 1, "POSITION", true);
    g.doc["accessors"][sparse]["sparse"]["indices"]["componentType"] = kFloat;
    EXPECT_THAT(rejection(g), HasSubstr("has sparse indices of component type 5126"));
}

TEST(GltfAnimationRejection, NaNSparseMorphDelta) {
    GltfBuilder g = morphQuad();
    const int sparse = makeSparse(g, 1, "POSITION", true);
    g.doc["accessors"][sparse]["sparse"]["values"]["bufferView"] =
        g.addView(std::vector<float>{0, 0, kNaN, 0, 0, 0});
    EXPECT_THAT(rejection(g), HasSubstr("(morph target 1 POSITION) element 1 is not finite"));
}

// --- validateScene on animation data built by hand ----------------------------------------------

namespace {

Scene handMadeScene() {
    Scene scene;
    Mesh quad;
    quad.positions = kAnimQuad;
    quad.normals.assign(4, glm::vec3(0, 0, 1));
    quad.indices = kAnimQuadIndices;
    scene.objects.push_back(makeSceneObject("quad", quad));
    scene.objects[0].node = 0;
    scene.animation.nodes.resize(2);
    scene.animation.nodes[1].parent = 0;
    AnimationChannel ch;
    ch.node = 1;
    ch.times = {0.0, 1.0};
    ch.values = {0, 0, 0, 1, 1, 1};
    ch.width = 3;
    scene.animation.animations.push_back({"a", {ch}, 1.0});
    return scene;
}

} // namespace

TEST(AnimationValidation, AcceptsAConsistentHandMadeScene) {
    EXPECT_TRUE(validateScene(handMadeScene()).ok()) << validateScene(handMadeScene()).error();
}

TEST(AnimationValidation, RejectsAParentCycle) {
    Scene scene = handMadeScene();
    scene.animation.nodes[0].parent = 1;
    EXPECT_THAT(validateScene(scene).error(), HasSubstr("the node hierarchy has a cycle"));
}

TEST(AnimationValidation, RejectsAChannelOfTheWrongWidthOrValueCount) {
    Scene scene = handMadeScene();
    scene.animation.animations[0].channels[0].width = 4;
    EXPECT_THAT(validateScene(scene).error(), HasSubstr("channel 0 has width 4, the target needs 3"));
    scene = handMadeScene();
    scene.animation.animations[0].channels[0].values.pop_back();
    EXPECT_THAT(validateScene(scene).error(), HasSubstr("has 5 values for 2 keys"));
}

TEST(AnimationValidation, RejectsKeyTimesThatDoNotIncrease) {
    Scene scene = handMadeScene();
    scene.animation.animations[0].channels[0].times = {1.0, 1.0};
    EXPECT_THAT(validateScene(scene).error(), HasSubstr("strictly increasing"));
}

TEST(AnimationValidation, RejectsAnObjectOnAMissingNodeOrSkin) {
    Scene scene = handMadeScene();
    scene.objects[0].node = 5;
    EXPECT_THAT(validateScene(scene).error(), HasSubstr("object 0 (quad) refers to animation node 5"));
    scene = handMadeScene();
    scene.objects[0].skin = 0;
    EXPECT_THAT(validateScene(scene).error(), HasSubstr("refers to skin 0, which does not exist"));
}

TEST(AnimationValidation, RejectsInfluencesThatDoNotCoverTheMesh) {
    Scene scene = handMadeScene();
    scene.animation.skins.push_back({"s", {0}, {glm::dmat4(1.0)}});
    scene.objects[0].skin = 0;
    scene.objects[0].skinWeights.influences = 4;
    scene.objects[0].skinWeights.joints.assign(12, 0);
    scene.objects[0].skinWeights.weights.assign(12, 0.25);
    EXPECT_THAT(validateScene(scene).error(),
                HasSubstr("has joint influences for 3 vertices, its mesh has 4"));
}

TEST(AnimationValidation, RejectsMorphTargetsWithoutWeights) {
    Scene scene = handMadeScene();
    scene.objects[0].morphTargets.resize(1);
    scene.objects[0].morphTargets[0].positions.assign(4, glm::vec3(0.0f));
    EXPECT_THAT(validateScene(scene).error(),
                HasSubstr("has 1 morph targets but its node has no weight for each"));
}

// --- limits --------------------------------------------------------------------------------------

namespace {

// One mesh of `vertices` vertices with `targets` morph targets (all one accessor of zero deltas),
// placed by `instances` nodes.
GltfBuilder manyTargets(size_t vertices, size_t targets, size_t instances) {
    GltfBuilder g;
    std::vector<glm::vec3> positions(vertices, glm::vec3(0.0f));
    positions[1] = glm::vec3(1, 0, 0);
    positions[2] = glm::vec3(0, 1, 0);
    g.addMesh(positions, {0, 1, 2});
    const int zeros = addFloats(g, std::vector<float>(vertices * 3, 0.0f), "VEC3");
    g.doc["meshes"][0]["primitives"][0]["targets"] =
        nlohmann::json::array_t(targets, nlohmann::json{{"POSITION", zeros}});
    nlohmann::json roots = nlohmann::json::array();
    for (size_t i = 0; i < instances; ++i)
        roots.push_back(g.push("nodes", {{"mesh", 0}, {"translation", {double(i), 0, 0}}}));
    g.doc["scenes"] = {{{"nodes", roots}}};
    return g;
}

} // namespace

TEST(GltfAnimationRejection, MeshWithTooManyMorphTargetDeltas) {
    EXPECT_THAT(rejection(manyTargets(4096, 4097, 1)), HasSubstr("more morph target deltas than the limit"));
}

TEST(GltfAnimationRejection, SceneWhoseInstancesCopyTooManyMorphTargetDeltas) {
    EXPECT_THAT(rejection(manyTargets(2048, 2048, 17)),
                HasSubstr("more joint influences and morph target deltas in all than the limit"));
}
