#include "PlacementTestUtil.hpp"

#include "spatter/core/DeformingProxy.hpp"
#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SkinnedArm.hpp"
#include "spatter/placement/CollisionWorld.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace spatter;
using namespace spatter::test;

namespace {

// The arm and a static floor below it. The floor fixes the origin of the world's float frame, so that
// two worlds of it trace rays in the same frame whatever pose the arm was built in.
Scene armOverFloor(Scene arm) {
    arm.objects.push_back(makeSceneObject("floor", makeBox(glm::vec3(2.0f, 0.05f, 2.0f), 1),
                                          glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, -1.0, 0.0))));
    return arm;
}

// The arm's render mesh posed at time t of its animation, as an object of its own that does not
// deform, over the floor: what the drawn surface is at t.
Scene drawnPose(const Scene& arm, double t) {
    SceneEvaluator evaluator(arm);
    evaluator.evaluate(0, t);
    Scene posed;
    posed.source = "test:posed-arm";
    posed.objects.push_back(
        makeSceneObject("arm", withPositions(*arm.objects[0].mesh, posedPositions(arm, 0, evaluator)),
                        evaluator.objectTransform(0), true));
    return armOverFloor(posed);
}

Status poseAt(CollisionWorld& world, const Scene& arm, double t) {
    SceneEvaluator evaluator(arm);
    evaluator.evaluate(0, t);
    Result<TransformUpdate> r =
        world.setPose(0, evaluator.objectTransform(0), evaluator.jointMatrices(0), evaluator.morphWeights(0));
    if (!r) return fail(r.error());
    return {};
}

// Rays from a sphere of radius 3 around the arm aimed at the centroid of every 5th triangle of
// `target`'s arm (centroids, so that no ray grazes an edge, where the float frame would decide).
std::vector<Ray> raysAt(const Scene& target) {
    std::vector<Ray> rays;
    const SceneObject& o = target.objects[0];
    const size_t triangles = o.mesh->triangleCount();
    for (size_t i = 0; i < triangles; i += 5) {
        glm::dvec3 c(0.0);
        for (int k = 0; k < 3; ++k)
            c += glm::dvec3(o.mesh->positions[o.mesh->indices[3 * i + size_t(k)]]) / 3.0;
        const glm::dvec3 p(o.transform * glm::dvec4(c, 1.0));
        const double a = 2.399963 * double(i), z = 1.0 - 2.0 * double(i) / double(triangles);
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        const glm::dvec3 from =
            glm::dvec3(0.0, 0.5, 0.0) + 3.0 * glm::dvec3(r * std::cos(a), z, r * std::sin(a));
        rays.push_back(ray(from, glm::normalize(p - from)));
    }
    return rays;
}

// The hits of raysAt(drawn) in `world` and the largest distance of one from the drawn surface.
struct SurfaceHits {
    size_t hits = 0;
    double worst = 0.0;
};

SurfaceHits hitsAgainst(const CollisionWorld& world, const Scene& drawn) {
    const ClosestPointQuery surface = ClosestPointQuery::create(*drawn.objects[0].mesh).value();
    const glm::dmat4 toObject = glm::inverse(drawn.objects[0].transform);
    SurfaceHits out;
    for (const Ray& r : raysAt(drawn))
        if (const std::optional<Hit> hit = world.intersect(r)) {
            ++out.hits;
            const glm::dvec3 local(toObject * glm::dvec4(hit->position, 1.0));
            out.worst = std::max(out.worst, surface.closest(local)->distance);
        }
    return out;
}

} // namespace

TEST(PosedCollision, PosedRenderMeshTracesExactlyAsAWorldBuiltAtThatPose) {
    const Scene arm = makeSkinnedArm();
    CollisionWorld world = buildWorld(armOverFloor(arm));
    for (double t : {0.3, 1.0, 1.7}) {
        ASSERT_TRUE(poseAt(world, arm, t).ok());
        const Scene drawn = drawnPose(arm, t);
        const CollisionWorld reference = buildWorld(drawn);
        size_t hits = 0;
        for (const Ray& r : raysAt(drawn)) {
            const std::optional<Hit> got = world.intersect(r), want = reference.intersect(r);
            EXPECT_TRUE(sameHit(got, want)) << "t " << t;
            hits += want.has_value();
        }
        EXPECT_GT(hits, 60u);
    }
}

TEST(PosedCollision, ShotsAtTheBentForearmHitItAndNotWhereItRested) {
    const Scene arm = makeSkinnedArm();
    CollisionWorld world = buildWorld(arm);
    // At rest the hand end of the bar stands at (0, 0.9, 0); shot from the front it is hit.
    const Ray atRestingHand = ray({0.0, 0.9, 3.0}, {0.0, 0.0, -1.0});
    ASSERT_TRUE(world.intersect(atRestingHand).has_value());
    ASSERT_TRUE(poseAt(world, arm, 1.0).ok()); // elbow bent 90 degrees, shoulder swung 30
    EXPECT_FALSE(world.intersect(atRestingHand).has_value()) << "the collision mesh stayed at rest";
    const SurfaceHits on = hitsAgainst(world, drawnPose(arm, 1.0));
    EXPECT_GT(on.hits, 60u);
    EXPECT_LT(on.worst, 1e-6);
}

TEST(PosedCollision, SetPoseRejectsWhatDoesNotFitAndChangesNothing) {
    Scene scene = makeSkinnedArm();
    Scene withStatic = scene;
    withStatic.objects.push_back(makeSceneObject("box", makeBox(glm::vec3(0.2f), 1),
                                                 glm::translate(glm::dmat4(1.0), glm::dvec3(2.0, 0.0, 0.0))));
    withStatic.objects.push_back(makeSceneObject("crate", makeBox(glm::vec3(0.2f), 1),
                                                 glm::translate(glm::dmat4(1.0), glm::dvec3(-2.0, 0.0, 0.0)),
                                                 true));
    CollisionWorld world = buildWorld(withStatic);
    SceneEvaluator evaluator(scene);
    evaluator.evaluate(0, 1.0);
    const std::vector<glm::dmat4> joints = evaluator.jointMatrices(0);
    const std::vector<Ray> rays = raysAt(scene);
    std::vector<std::optional<Hit>> before;
    for (const Ray& r : rays)
        before.push_back(world.intersect(r));

    const auto expectRefused = [&](uint32_t object, const glm::dmat4& transform,
                                   const std::vector<glm::dmat4>& j, const std::vector<double>& w,
                                   const std::string& says) {
        Result<TransformUpdate> r = world.setPose(object, transform, j, w);
        ASSERT_FALSE(r.ok()) << says;
        EXPECT_NE(r.error().find(says), std::string::npos) << r.error();
    };
    expectRefused(7, glm::dmat4(1.0), joints, {}, "out of range");
    expectRefused(1, glm::dmat4(1.0), joints, {}, "'box' is static");
    expectRefused(2, glm::dmat4(1.0), joints, {}, "'crate' has no skin");
    expectRefused(0, glm::dmat4(1.0), {joints[0]}, {}, "1 joint matrices for a skin of 2 joints");
    expectRefused(0, glm::dmat4(1.0), joints, {0.5}, "1 morph weights for 0 morph targets");
    std::vector<glm::dmat4> nan = joints;
    nan[1][3][0] = std::numeric_limits<double>::quiet_NaN();
    expectRefused(0, glm::dmat4(1.0), nan, {}, "joint matrix 1 is not finite");
    glm::dmat4 projective(1.0);
    projective[0][3] = 0.5;
    expectRefused(0, projective, joints, {}, "not affine");
    glm::dmat4 infinite(1.0);
    infinite[3][1] = std::numeric_limits<double>::infinity();
    expectRefused(0, infinite, joints, {}, "not finite");

    for (size_t i = 0; i < rays.size(); ++i)
        EXPECT_TRUE(sameHit(before[i], world.intersect(rays[i]))) << "ray " << i;
}

TEST(PosedCollision, DeformingProxyHitsStayWithinItsBoundOfTheDrawnSurface) {
    const Scene arm = makeSkinnedArm();
    Result<DeformingProxy> proxy = deformingProxy(arm, 0.02f, 32);
    ASSERT_TRUE(proxy.ok()) << proxy.error();
    CollisionWorld world = buildWorld(arm, {shareProxy(proxy->proxy)});
    EXPECT_EQ(world.object(0)->errorBound, proxy->proxy.errorBound);
    for (double t : {0.0, 0.4, 1.0, 1.33, 1.9}) { // sampled poses and poses between samples
        ASSERT_TRUE(poseAt(world, arm, t).ok());
        const SurfaceHits on = hitsAgainst(world, drawnPose(arm, t));
        EXPECT_GT(on.hits, 40u) << "t " << t;
        EXPECT_LE(on.worst, proxy->proxy.errorBound) << "t " << t;
    }
}

TEST(PosedCollision, ShotsThroughADeformingProxyAnchorWhereTheyMeetTheDrawnSurface) {
    // A shot anchors where its line meets the drawn surface first, as the render mesh posed and built
    // static is hit by the same ray. The arm's lathe repeats the vertices of its UV seam, so shots near
    // the seam test that the search walks across it. Every anchor lies within the search's reach of
    // the proxy's hit (where a coarse proxy misses a thin part of the drawn surface the ray meets
    // first, the proxy's hit and its anchor lie farther on).
    const Scene arm = makeSkinnedArm();
    Result<DeformingProxy> proxy = deformingProxy(arm, 0.02f, 32);
    ASSERT_TRUE(proxy.ok()) << proxy.error();
    CollisionWorld world = buildWorld(arm, {shareProxy(proxy->proxy)});
    for (double t : {0.4, 1.0}) {
        ASSERT_TRUE(poseAt(world, arm, t).ok());
        const Scene drawn = drawnPose(arm, t);
        const CollisionWorld reference = buildWorld(drawn);
        const glm::dmat4 toWorld = drawn.objects[0].transform, toObject = glm::inverse(toWorld);
        size_t shots = 0, onTheDrawnHit = 0;
        for (const Ray& r : raysAt(drawn)) {
            const std::optional<Hit> hit = world.intersect(r), want = reference.intersect(r);
            if (!hit || hit->object != 0 || !want || want->object != 0) continue;
            const glm::dvec3 direction(toObject * glm::dvec4(r.direction, 0.0));
            const std::optional<SurfaceLocation> at =
                world.anchorAt(0, hit->primitive, hit->localPosition, direction);
            ASSERT_TRUE(at.has_value()) << "t " << t;
            const glm::dvec3 point(toWorld * glm::dvec4(glm::dvec3(at->frame[3]), 1.0));
            EXPECT_LE(glm::length(point - hit->position), 8.0 * proxy->proxy.errorBound) << "t " << t;
            ++shots;
            onTheDrawnHit += glm::length(point - want->position) < 1e-5;
        }
        EXPECT_GT(shots, 40u) << "t " << t;
        EXPECT_GE(double(onTheDrawnHit), 0.95 * double(shots)) << "t " << t;
    }
}
