// Skinning and morph targets on the GPU (Renderer::setPose): a posed model drawn by the geometry pass
// against the same model whose meshes are replaced by the CPU reference of its pose (posedPositions,
// in double) and drawn as static geometry. Both draw the same triangles; their vertices differ only
// by float rounding (the GPU blends float joint matrices; measured: at most 2e-6 of the model's
// diagonal), far below a pixel. So coverage may differ only where a pixel's centre lies on an edge,
// and depth by the rounding: at most 0.5% of the covered pixels (plus two) may differ in coverage or
// by more than 1e-4 of the diagonal in depth, fifty times the rounding. The normal views are compared
// the same way against normals posed here in double (posedNormals). The rest pose, drawn for
// comparison, differs from the pose on hundreds of pixels: the check can fail.

#include "RenderTestSupport.hpp"

#include "TestData.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SceneLoader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

using namespace spatter;
using namespace spatter::test;

namespace {

// Normals of object `object` at the evaluator's pose, in double, in the object's space at that pose:
// morph target normal deltas added with the weights, then for a skinned object the normal mapped by
// the inverse transpose of its blended joint matrix and brought back into the object's space (by the
// transpose of the object's transform, the inverse of its normal matrix). Not normalised.
std::vector<glm::dvec3> posedNormals(const Scene& scene, size_t object, const SceneEvaluator& evaluator) {
    const SceneObject& o = scene.objects[object];
    std::vector<glm::dvec3> out(o.mesh->normals.begin(), o.mesh->normals.end());
    const std::vector<double>& weights = evaluator.morphWeights(object);
    for (size_t t = 0; t < o.morphTargets.size(); ++t)
        for (size_t v = 0; v < out.size() && v < o.morphTargets[t].normals.size(); ++v)
            out[v] += weights[t] * glm::dvec3(o.morphTargets[t].normals[v]);
    if (o.skin == -1) return out;
    const std::vector<glm::dmat4>& joints = evaluator.jointMatrices(size_t(o.skin));
    const glm::dmat3 toObject = glm::transpose(glm::dmat3(evaluator.objectTransform(object)));
    const size_t stride = size_t(o.skinWeights.influences);
    for (size_t v = 0; v < out.size(); ++v) {
        glm::dmat3 blended(0.0);
        for (size_t k = 0; k < stride; ++k)
            blended += o.skinWeights.weights[v * stride + k] *
                       glm::dmat3(joints[o.skinWeights.joints[v * stride + k]]);
        out[v] = toObject * (glm::transpose(glm::inverse(blended)) * out[v]);
    }
    return out;
}

// `scene` with every mesh replaced by its positions and normals at the evaluator's pose, placed by
// the object's transform at that pose, with no skin, morph targets or node: static geometry.
Scene cpuPosed(const Scene& scene, const SceneEvaluator& evaluator) {
    Scene out = scene;
    for (size_t i = 0; i < out.objects.size(); ++i) {
        SceneObject& o = out.objects[i];
        Mesh& mesh = o.editMesh();
        const std::vector<glm::dvec3> posed = posedPositions(scene, i, evaluator);
        for (size_t v = 0; v < posed.size(); ++v)
            mesh.positions[v] = glm::vec3(posed[v]);
        const std::vector<glm::dvec3> normals = posedNormals(scene, i, evaluator);
        for (size_t v = 0; v < normals.size(); ++v)
            mesh.normals[v] = glm::vec3(glm::normalize(normals[v]));
        o.transform = evaluator.objectTransform(i);
        o.node = o.skin = -1;
        o.skinWeights = {};
        o.morphTargets.clear();
        o.dynamic = false;
    }
    return out;
}

// A camera that sees all of `b` from the front, above and to the side.
Camera frame(const DBounds& b) {
    const glm::dvec3 centre = 0.5 * (b.min + b.max);
    const double diagonal = glm::length(b.max - b.min);
    Camera cam = test::lookAt(centre + diagonal * glm::dvec3(0.4, 0.25, 0.75), centre);
    cam.nearPlane = std::max(kMinNearPlane, 0.01 * diagonal);
    return cam;
}

std::vector<float> depthOf(Renderer& r, const Camera& cam) {
    test::renderView(r, cam, View::Final);
    Result<std::vector<float>> d = r.readbackDepth();
    EXPECT_TRUE(d.ok()) << d.error();
    return d.ok() ? d.value() : std::vector<float>(size_t(kW) * kH, 0.0f);
}

// Pixels covered in both depth images whose normal views differ by more than `levels` in a channel.
size_t normalsDiffering(const Image& a, const Image& b, const std::vector<float>& da,
                        const std::vector<float>& db, int levels) {
    size_t n = 0;
    for (size_t i = 0;
         i < da.size() && i < db.size() && 4 * i + 2 < a.rgba.size() && 4 * i + 2 < b.rgba.size(); ++i) {
        if (da[i] <= 0.0f || db[i] <= 0.0f) continue;
        for (size_t c = 0; c < 3; ++c)
            if (std::abs(int(a.rgba[4 * i + c]) - int(b.rgba[4 * i + c])) > levels) {
                ++n;
                break;
            }
    }
    return n;
}

struct DepthAgreement {
    size_t covered = 0;         // pixels covered in both
    size_t coverageDiffers = 0; // pixels covered in one only
    size_t depthDiffers = 0;    // pixels covered in both, depths further apart than the tolerance
    double worstDepth = 0.0;    // largest depth difference where both are covered
};

DepthAgreement compare(const std::vector<float>& a, const std::vector<float>& b, double tolerance) {
    DepthAgreement out;
    for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
        const bool ca = a[i] > 0.0f, cb = b[i] > 0.0f;
        if (ca != cb) ++out.coverageDiffers;
        if (!ca || !cb) continue;
        ++out.covered;
        const double d = std::abs(double(a[i]) - double(b[i]));
        out.worstDepth = std::max(out.worstDepth, d);
        if (d > tolerance) ++out.depthDiffers;
    }
    return out;
}

// Renders `scene` posed at (animation, t) on the GPU and its CPU-posed twin, and checks that they
// agree while the rest pose does not.
void expectGpuPoseMatchesCpu(Scene scene, int animation, double t) {
    for (Material& m : scene.materials)
        m.normalTexture = -1; // the normal views compare the posed vertex normals, not normal maps
    SceneEvaluator evaluator(scene);
    evaluator.evaluate(animation, t);
    const Scene reference = cpuPosed(scene, evaluator);
    const DBounds bounds = reference.worldBounds();
    const double diagonal = glm::length(bounds.max - bounds.min);
    const Camera cam = frame(bounds);

    Result<Renderer> gpu = test::makeRenderer(kW, kH);
    Result<Renderer> cpu = test::makeRenderer(kW, kH);
    ASSERT_TRUE(gpu.ok() && cpu.ok());
    ASSERT_TRUE(gpu->setScene(scene).ok());
    ASSERT_TRUE(cpu->setScene(reference).ok());
    const std::vector<float> rest = depthOf(gpu.value(), cam);
    Status posed = gpu->setPose(evaluator);
    ASSERT_TRUE(posed.ok()) << posed.error();
    const std::vector<float> a = depthOf(gpu.value(), cam);
    const std::vector<float> b = depthOf(cpu.value(), cam);
    const Image normalsA = test::renderView(gpu.value(), cam, View::Normal);
    const Image normalsB = test::renderView(cpu.value(), cam, View::Normal);
    const size_t normalDiffers = normalsDiffering(normalsA, normalsB, a, b, 3);

    const double tolerance = 1e-4 * diagonal;
    const DepthAgreement posedAgreement = compare(a, b, tolerance);
    const DepthAgreement restAgreement = compare(rest, b, tolerance);
    const size_t pixels = size_t(kW) * kH;
    std::printf("[pose] %s t=%.3f: covered %zu, coverage differs %zu, depth differs %zu (worst %.3g of "
                "the diagonal), normal differs %zu; rest pose: coverage differs %zu, depth differs %zu\n",
                scene.source.c_str(), t, posedAgreement.covered, posedAgreement.coverageDiffers,
                posedAgreement.depthDiffers, posedAgreement.worstDepth / diagonal, normalDiffers,
                restAgreement.coverageDiffers, restAgreement.depthDiffers);
    EXPECT_GT(posedAgreement.covered, pixels / 50);
    EXPECT_LE(posedAgreement.coverageDiffers, posedAgreement.covered / 200 + 2);
    EXPECT_LE(posedAgreement.depthDiffers, posedAgreement.covered / 200 + 2);
    EXPECT_LE(normalDiffers, posedAgreement.covered / 200 + 2);
    // The pose is not the rest pose: the check above could fail.
    EXPECT_GT(restAgreement.coverageDiffers + restAgreement.depthDiffers,
              20 * (posedAgreement.coverageDiffers + posedAgreement.depthDiffers) + 20);
}

SceneNode node(const glm::dvec3& translation, int parent = -1) {
    SceneNode n;
    n.translation = translation;
    n.parent = parent;
    return n;
}

// A scene written here: a bar bent by a two-joint skin (four influences per vertex, two of them 0)
// and a box with one morph target (position and normal deltas), both `offset` from the origin, at
// rest as the pose to draw (the upper joint turned by 50 degrees, the morph weight 0.7).
Scene bentBarAndMorphedBox(const glm::dvec3& offset) {
    Scene scene;
    scene.source = "written";
    SceneAnimation& a = scene.animation;
    a.nodes = {node(offset), node({0.0, 1.0, 0.0}, 0), node(offset),
               node(offset + glm::dvec3(1.5, 0.0, 0.0))};
    a.nodes[1].rotation = glm::angleAxis(glm::radians(50.0), glm::dvec3(0.0, 0.0, 1.0));
    a.nodes[3].weights = {0.7};
    Skin skin;
    skin.joints = {0, 1};
    skin.inverseBindMatrices = {glm::dmat4(1.0), glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, -1.0, 0.0))};
    a.skins.push_back(skin);

    SceneObject bar =
        makeSceneObject("bar", makeBox({0.15f, 1.0f, 0.15f}, 8), glm::translate(glm::dmat4(1.0), offset));
    bar.node = 2;
    bar.skin = 0;
    bar.skinWeights.influences = 4;
    for (glm::vec3& p : bar.editMesh().positions) {
        p.y += 1.0f;
        const double upper = std::clamp(double(p.y) - 0.5, 0.0, 1.0);
        bar.skinWeights.joints.insert(bar.skinWeights.joints.end(), {0, 1, 0, 1});
        bar.skinWeights.weights.insert(bar.skinWeights.weights.end(), {1.0 - upper, upper, 0.0, 0.0});
    }
    scene.objects.push_back(bar);

    SceneObject box = makeSceneObject("box", makeBox(glm::vec3(0.4f), 2),
                                      glm::translate(glm::dmat4(1.0), a.nodes[3].translation));
    box.node = 3;
    MorphTarget target;
    for (const glm::vec3& p : box.mesh->positions) {
        target.positions.push_back(p.y > 0.0f ? glm::vec3(0.2f, 0.6f, 0.0f) : glm::vec3(0.0f));
        target.normals.push_back(p.y > 0.0f ? glm::vec3(-0.6f, 0.0f, 0.3f) : glm::vec3(0.0f));
    }
    box.morphTargets.push_back(target);
    scene.objects.push_back(box);
    return scene;
}

Scene load(const std::string& path) {
    Result<Scene> scene = loadScene(path);
    EXPECT_TRUE(scene.ok()) << scene.error();
    return scene.ok() ? std::move(scene.value()) : Scene{};
}

// The shared model at `path`, posed at `fraction` of its first animation, drawn as the CPU poses it.
void expectSharedModelMatchesCpu(const std::string& path, double fraction) {
    const Scene scene = load(path);
    ASSERT_FALSE(scene.animation.animations.empty());
    expectGpuPoseMatchesCpu(scene, 0, fraction * scene.animation.animations[0].duration);
}

} // namespace

TEST(Pose, SkinnedCesiumManMatchesCpuPose) {
    SPATTER_REQUIRE_GL(gl);
    SPATTER_REQUIRE_SHARED(path, "gltf/CesiumMan/CesiumMan.glb");
    expectSharedModelMatchesCpu(path, 0.37);
}

TEST(Pose, SkinnedRiggedSimpleMatchesCpuPose) {
    SPATTER_REQUIRE_GL(gl);
    SPATTER_REQUIRE_SHARED(path, "gltf/RiggedSimple/RiggedSimple.glb");
    expectSharedModelMatchesCpu(path, 0.6);
}

TEST(Pose, MorphedCubeMatchesCpuPose) {
    SPATTER_REQUIRE_GL(gl);
    SPATTER_REQUIRE_SHARED(path, "gltf/AnimatedMorphCube/AnimatedMorphCube.glb");
    expectSharedModelMatchesCpu(path, 0.3);
}

TEST(Pose, AnimatedNodesMatchCpuPose) {
    SPATTER_REQUIRE_GL(gl);
    SPATTER_REQUIRE_SHARED(path, "gltf/BoxAnimated/BoxAnimated.glb");
    expectSharedModelMatchesCpu(path, 0.45);
}

TEST(Pose, WrittenSkinAndMorphMatchCpuPose) {
    SPATTER_REQUIRE_GL(gl);
    const Scene scene = bentBarAndMorphedBox(glm::dvec3(0.0));
    ASSERT_TRUE(validateScene(scene).ok()) << validateScene(scene).error();
    expectGpuPoseMatchesCpu(scene, -1, 0.0);
}

// Joint matrices reach the GPU camera-relative: 300 km from the origin the pose draws as it does at
// the origin.
TEST(Pose, WrittenSkinAndMorphMatchCpuPoseFarFromOrigin) {
    SPATTER_REQUIRE_GL(gl);
    const Scene scene = bentBarAndMorphedBox(glm::dvec3(3.0e5, 20.0, -2.0e5));
    ASSERT_TRUE(validateScene(scene).ok()) << validateScene(scene).error();
    expectGpuPoseMatchesCpu(scene, -1, 0.0);
}

TEST(Pose, RefusesBadPosesAndChangesNothing) {
    SPATTER_REQUIRE_GL(gl);
    const Scene scene = bentBarAndMorphedBox(glm::dvec3(0.0));
    SceneEvaluator evaluator(scene);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok());
    ASSERT_TRUE(r->setScene(scene).ok());
    ASSERT_TRUE(r->setPose(evaluator).ok());
    const Camera cam = frame(scene.worldBounds());
    const std::vector<float> before = depthOf(r.value(), cam);

    ScenePose good;
    good.objectTransforms = {evaluator.objectTransform(0), evaluator.objectTransform(1)};
    good.jointMatrices = {evaluator.jointMatrices(0)};
    good.morphWeights = {{}, {0.7}};
    const double nan = std::numeric_limits<double>::quiet_NaN();
    struct Case {
        const char* expected;
        ScenePose pose;
    };
    std::vector<Case> cases(8, Case{"", good});
    cases[0].expected = "1 object transforms for 2 objects";
    cases[0].pose.objectTransforms.pop_back();
    cases[1].expected = "0 joint matrix lists for 1 skins";
    cases[1].pose.jointMatrices.clear();
    cases[2].expected = "skin 0: 1 joint matrices for 2 joints";
    cases[2].pose.jointMatrices[0].pop_back();
    cases[3].expected = "skin 0 joint 1: transform is not finite";
    cases[3].pose.jointMatrices[0][1][3][0] = nan;
    cases[4].expected = "object 1: transform is not affine";
    cases[4].pose.objectTransforms[1][0][3] = 0.5;
    cases[5].expected = "object 1: morph weight is not finite";
    cases[5].pose.morphWeights[1][0] = nan;
    cases[6].expected = "object 1: 2 morph weights for 1 morph targets";
    cases[6].pose.morphWeights[1].push_back(0.1);
    cases[7].expected = "1 morph weight lists for 2 objects";
    cases[7].pose.morphWeights.pop_back();
    for (const Case& c : cases) {
        const Status s = r->setPose(c.pose);
        ASSERT_FALSE(s.ok()) << c.expected;
        EXPECT_NE(s.error().find(c.expected), std::string::npos) << s.error();
    }
    Scene other = scene;
    other.animation.nodes.push_back(node(glm::dvec3(0.0)));
    SceneEvaluator foreign(other);
    const Status s = r->setPose(foreign);
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().find("the evaluator has 5 nodes, the scene 4"), std::string::npos) << s.error();
    EXPECT_EQ(depthOf(r.value(), cam), before);
    ASSERT_TRUE(r->setPose(good).ok());
    EXPECT_EQ(depthOf(r.value(), cam), before);
}
