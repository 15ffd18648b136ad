#include "spatter/core/VertexDeformation.hpp"
#include "spatter/core/DeformingProxy.hpp"
#include "spatter/core/HausdorffBound.hpp"
#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/PoseBound.hpp"
#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SkinnedArm.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace spatter;

namespace {

// One triangle whose corners are bound to joints 0, 1 and 2 alone, and one morph target moving
// corner k by (k + 1) along +Z.
struct Triangle {
    Mesh mesh;
    VertexDeformation deformation;
};

Triangle boundTriangle() {
    Triangle t;
    t.mesh.positions = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    t.mesh.indices = {0, 1, 2};
    computeNormals(t.mesh);
    t.deformation.skin.influences = 2;
    t.deformation.skin.joints = {0, 1, 1, 0, 2, 0};
    t.deformation.skin.weights = {1.0, 0.0, 1.0, 0.0, 1.0, 0.0};
    t.deformation.morphs = {{{0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 2.0f}, {0.0f, 0.0f, 3.0f}}};
    return t;
}

Mesh points(std::vector<glm::vec3> p) {
    Mesh m;
    m.positions = std::move(p);
    return m;
}

} // namespace

TEST(VertexDeformation, TransferGivesACornerItsOwnWeightsAndDeltas) {
    const Triangle t = boundTriangle();
    Result<VertexDeformation> d = transferDeformation(t.mesh, t.deformation, points({{1.0f, 0.0f, 0.5f}}));
    ASSERT_TRUE(d.ok()) << d.error();
    EXPECT_EQ(d->skin.influences, 2);
    EXPECT_EQ(d->skin.joints[0], 1);
    EXPECT_EQ(d->skin.weights[0], 1.0);
    EXPECT_EQ(d->skin.weights[1], 0.0);
    EXPECT_EQ(d->morphs[0][0], glm::vec3(0.0f, 0.0f, 2.0f));
}

TEST(VertexDeformation, TransferBlendsByBarycentricCoordinatesAndKeepsTheLargestInfluences) {
    const Triangle t = boundTriangle();
    // Above the midpoint of the edge from corner 0 to corner 1: half joint 0, half joint 1.
    // Inside at (0.2, 0.2): corners weigh 0.6, 0.2 and 0.2; of joints 0, 1 and 2 the two largest
    // stay (0.6 for joint 0, then joint 1 before joint 2 on the tie), renormalised to 0.75 and 0.25.
    Result<VertexDeformation> d =
        transferDeformation(t.mesh, t.deformation, points({{0.5f, 0.0f, 0.3f}, {0.2f, 0.2f, -0.1f}}));
    ASSERT_TRUE(d.ok()) << d.error();
    EXPECT_EQ(d->skin.joints[0], 0);
    EXPECT_EQ(d->skin.joints[1], 1);
    EXPECT_NEAR(d->skin.weights[0], 0.5, 1e-12);
    EXPECT_NEAR(d->skin.weights[1], 0.5, 1e-12);
    EXPECT_NEAR(d->morphs[0][0].z, 1.5f, 1e-6f);
    EXPECT_EQ(d->skin.joints[2], 0);
    EXPECT_EQ(d->skin.joints[3], 1);
    EXPECT_NEAR(d->skin.weights[2], 0.75, 1e-6);
    EXPECT_NEAR(d->skin.weights[3], 0.25, 1e-6);
    EXPECT_NEAR(d->morphs[0][1].z, 0.6f + 0.4f + 0.6f, 1e-5f);
}

TEST(VertexDeformation, TransferRejectsADeformationThatDoesNotFitItsMesh) {
    Triangle t = boundTriangle();
    t.deformation.morphs[0].pop_back();
    Result<VertexDeformation> d = transferDeformation(t.mesh, t.deformation, points({{0.0f, 0.0f, 0.0f}}));
    ASSERT_FALSE(d.ok());
    EXPECT_NE(d.error().find("morph target"), std::string::npos) << d.error();
}

TEST(VertexDeformation, PosingTheRenderMeshGivesTheEvaluatorsPose) {
    const Scene arm = makeSkinnedArm();
    SceneEvaluator evaluator(arm);
    evaluator.evaluate(0, 0.7);
    const std::vector<glm::dvec3> want = posedPositions(arm, 0, evaluator);
    const std::vector<glm::dvec3> got =
        posePositions(arm.objects[0].mesh->positions, deformationOf(arm.objects[0]),
                      evaluator.jointMatrices(0), {}, glm::inverse(evaluator.objectTransform(0)));
    ASSERT_EQ(got.size(), want.size());
    for (size_t v = 0; v < got.size(); ++v)
        ASSERT_EQ(got[v], want[v]) << "vertex " << v;
}

TEST(VertexDeformation, PoseProblemNamesWhatDoesNotFit) {
    const Triangle t = boundTriangle();
    const std::vector<glm::dmat4> three(3, glm::dmat4(1.0));
    EXPECT_EQ(poseProblem(t.deformation, 3, three, {0.5}), "");
    EXPECT_EQ(poseProblem(t.deformation, 3, {glm::dmat4(1.0)}, {0.5}),
              "1 joint matrices for a skin of 3 joints");
    EXPECT_EQ(poseProblem(t.deformation, 3, three, {}), "0 morph weights for 1 morph targets");
    EXPECT_EQ(poseProblem(t.deformation, 3, three, {std::nan("")}), "morph weight 0 is not finite");
    std::vector<glm::dmat4> projective = three;
    projective[2][2][3] = 1.0;
    EXPECT_EQ(poseProblem(t.deformation, 3, projective, {0.5}), "joint matrix 2 is not finite and affine");
}

TEST(PoseBound, RenderMeshAsItsOwnCollisionMeshIsWithinItsMotionAllowance) {
    const Scene arm = makeSkinnedArm();
    const SceneObject& o = arm.objects[0];
    Result<PoseBound> b = boundOverPoses(arm, 0, *o.mesh, deformationOf(o), 8, 1e-4);
    ASSERT_TRUE(b.ok()) << b.error();
    EXPECT_EQ(b->poses, 9u);
    EXPECT_LE(b->sampledMax, 1e-4 * 1.001) << "the same surface at every pose";
    EXPECT_GT(b->motion, 0.0);
    EXPECT_LE(b->bound, b->sampledMax + b->motion);
}

// Between its sampled poses the bound still holds: the arm's proxy simplified at rest, which strays
// most where the elbow bends most, half-way through the swing, sampled at thirds of it, so that the
// worst pose lies between two samples; at poses inside every interval, the distance measured between
// the arm and the proxy stays within the bound, and somewhere exceeds every sampled one.
TEST(PoseBound, HoldsBetweenItsSampledPoses) {
    const Scene arm = makeSkinnedArm();
    const SceneObject& o = arm.objects[0];
    ProxySettings settings;
    settings.tolerance = 0.02f;
    settings.toleranceRelative = true;
    Result<Proxy> proxy = buildProxy(*o.mesh, settings);
    ASSERT_TRUE(proxy.ok()) << proxy.error();
    Result<VertexDeformation> d = transferDeformation(*o.mesh, deformationOf(o), proxy->mesh);
    ASSERT_TRUE(d.ok()) << d.error();
    constexpr int kSamples = 3;
    Result<PoseBound> b = boundOverPoses(arm, 0, proxy->mesh, d.value(), kSamples, 1e-3);
    ASSERT_TRUE(b.ok()) << b.error();
    SceneEvaluator evaluator(arm);
    const double period = arm.animation.animations[0].duration;
    double largest = 0.0;
    for (int i = 0; i < kSamples; ++i)
        for (double f : {0.25, 0.5, 0.75}) {
            evaluator.evaluate(0, period * (i + f) / kSamples);
            const Mesh render = withPositions(*o.mesh, posedPositions(arm, 0, evaluator));
            const Mesh posed = withPositions(
                proxy->mesh,
                posePositions(proxy->mesh.positions, d.value(), evaluator.jointMatrices(0),
                              evaluator.morphWeights(0), glm::inverse(evaluator.objectTransform(0))));
            Result<HausdorffSurface> r = HausdorffSurface::create(render),
                                     c = HausdorffSurface::create(posed);
            ASSERT_TRUE(r.ok() && c.ok());
            HausdorffSettings sharp;
            sharp.margin = 1e-3;
            Result<HausdorffResult> h = boundHausdorff(r.value(), c.value(), sharp);
            ASSERT_TRUE(h.ok()) << h.error();
            EXPECT_LE(h->lower, b->bound) << "at " << (i + f) / kSamples << " of the swing";
            largest = std::max(largest, h->lower);
        }
    EXPECT_GT(largest, b->sampledMax) << "the worst pose lies between two samples";
    EXPECT_GT(b->motion, 0.0);
}

// Surfaces that one motion carries together add nothing to the bound, however far they travel: the
// arm sliding 2 m along x without turning, its render mesh as its own collision mesh.
TEST(PoseBound, SurfacesThatMoveTogetherAddNoMotion) {
    SkinnedArmSettings still;
    still.swingDeg = 0.0;
    still.bendDeg = 0.0;
    Scene arm = makeSkinnedArm(still);
    AnimationChannel slide;
    slide.node = 1; // the shoulder, which carries the elbow
    slide.path = AnimationPath::Translation;
    slide.times = {0.0, arm.animation.animations[0].duration};
    slide.width = 3;
    slide.values = {0.0, 0.0, 0.0, 2.0, 0.0, 0.0};
    arm.animation.animations[0].channels = {slide};
    ASSERT_TRUE(validateScene(arm).ok());
    const SceneObject& o = arm.objects[0];
    Result<PoseBound> b = boundOverPoses(arm, 0, *o.mesh, deformationOf(o), 8, 1e-4);
    ASSERT_TRUE(b.ok()) << b.error();
    EXPECT_LT(b->motion, 1e-9) << "each interval moves every vertex 0.25 m the same way";
    EXPECT_LE(b->bound, b->sampledMax + 1e-9);
}

TEST(PoseBound, RejectsBadArguments) {
    const Scene arm = makeSkinnedArm();
    const SceneObject& o = arm.objects[0];
    EXPECT_FALSE(boundOverPoses(arm, 3, *o.mesh, deformationOf(o), 8, 1e-4).ok());
    EXPECT_FALSE(boundOverPoses(arm, 0, *o.mesh, deformationOf(o), 0, 1e-4).ok());
    EXPECT_FALSE(boundOverPoses(arm, 0, *o.mesh, deformationOf(o), 8, 0.0).ok());
    EXPECT_FALSE(boundOverPoses(arm, 0, *o.mesh, VertexDeformation{}, 8, 1e-4).ok());
}

TEST(DeformingProxy, HoldsItsBoundOverThePosesWhereARestProxyCutsAcrossTheBend) {
    const Scene arm = makeSkinnedArm();
    ProxySettings settings;
    settings.tolerance = 0.02f;
    settings.toleranceRelative = true;
    Result<DeformingProxy> p = buildDeformingProxy(arm, 0, settings, 32);
    ASSERT_TRUE(p.ok()) << p.error();
    EXPECT_TRUE(p->simplifiedPosed);
    EXPECT_FALSE(p->restCertified) << "it certifies below the rest proxy's sampled distances";
    EXPECT_LT(p->proxy.proxyTriangles, arm.objects[0].mesh->triangleCount() / 4);
    EXPECT_EQ(p->proxy.errorBound, p->poses.bound);
    EXPECT_TRUE(p->proxy.drawnNormals.empty()) << "they would face one pose's drawn surface";
    EXPECT_LT(p->poses.sampledMax, 2.0 * p->proxy.tolerance);
    EXPECT_GT(p->restPoses.sampledMax, 10.0 * p->poses.sampledMax)
        << "a proxy simplified at rest keeps no rings at the elbow";
    ASSERT_EQ(p->deformation.skin.joints.size(), p->proxy.mesh.positions.size() * 2);
}

// The bound over the poses (certificates and the relative motion between samples) does not depend on
// the number of threads.
TEST(DeformingProxy, SameBoundOverThePosesOnAnyNumberOfThreads) {
    const Scene arm = makeSkinnedArm();
    ProxySettings settings;
    settings.tolerance = 0.02f;
    std::vector<DeformingProxy> built;
    for (const unsigned threads : {1u, 3u}) {
        settings.threads = threads;
        Result<DeformingProxy> p = buildDeformingProxy(arm, 0, settings, 8);
        ASSERT_TRUE(p.ok()) << p.error();
        built.push_back(std::move(p).value());
    }
    EXPECT_EQ(built[1].proxy.mesh.indices, built[0].proxy.mesh.indices);
    EXPECT_EQ(built[1].poses.bound, built[0].poses.bound);
    EXPECT_EQ(built[1].poses.motion, built[0].poses.motion);
    EXPECT_EQ(built[1].restPoses.bound, built[0].restPoses.bound);
}

TEST(DeformingProxy, RejectsAnObjectThatDoesNotDeform) {
    Scene scene;
    scene.source = "test:static";
    scene.objects.push_back(makeSceneObject("box", makeBox(glm::vec3(0.5f), 2)));
    Result<DeformingProxy> p = buildDeformingProxy(scene, 0, ProxySettings{}, 8);
    ASSERT_FALSE(p.ok());
    EXPECT_NE(p.error().find("neither skinned nor morphed"), std::string::npos) << p.error();
}
