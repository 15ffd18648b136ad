// Decals projected along the shot: the axis placement gives them, the calls that keep the normal, and
// the footprint landing where the shot meets a drawn surface that lies off the collision proxy.

#include "PlacementTestUtil.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

using namespace spatter;
using namespace spatter::test;

namespace {

// The reversed shot `degrees` from the +Y normal, turned about it by `azimuth` radians.
glm::dvec3 shotFrom(double degrees, double azimuth) {
    const double a = degrees * kPi / 180.0;
    return glm::dvec3(std::sin(a) * std::cos(azimuth), std::cos(a), std::sin(a) * std::sin(azimuth));
}

// A drawn plane y = 0 (4 x 4) whose collision proxy is the plane y = offset, with h = |offset|.
CollisionWorld offsetFloorWorld(float offset) {
    Scene scene;
    scene.source = "test:offset floor";
    scene.objects.push_back(makeSceneObject("floor", makeGrid({-2.0f, 2.0f}, {-2.0f, 2.0f})));
    Mesh proxy = makeGrid({-2.0f, 2.0f}, {-2.0f, 2.0f});
    for (glm::vec3& p : proxy.positions)
        p.y = offset;
    std::vector<std::optional<Proxy>> proxies;
    proxies.push_back(makeProxy(std::move(proxy), std::fabs(double(offset))));
    Result<CollisionWorld> w = CollisionWorld::build(scene, proxies);
    EXPECT_TRUE(w.ok()) << w.error();
    return std::move(w).value();
}

// `point` (object space) in the unit box of `d`.
glm::dvec3 inBox(const Decal& d, const glm::dvec3& point) {
    return glm::dvec3(glm::inverse(glm::dmat4(d.boxToObject())) * glm::dvec4(point, 1.0));
}

} // namespace

TEST(ShotProjection, SpawnProjectsAlongTheReversedShot) {
    DecalSystem s = makeSystem(boxScene());
    const uint16_t t = addType(s, plainType());
    for (double degrees : {0.0, 10.0, 45.0, 75.0}) {
        const glm::dvec3 back = shotFrom(degrees, 0.4);
        const SpawnResult r = s.spawn(ray(glm::dvec3(0.1, 0.5, -0.1) + 3.0 * back, -back), t);
        ASSERT_TRUE(r.placed()) << r.reason;
        const WorldDecal w = s.worldBox(*s.get(r.handle));
        EXPECT_LT(glm::length(glm::dvec3(w.projection) - back), 1e-3) << degrees << " degrees";
        EXPECT_LT(glm::length(w.frame.normal - glm::vec3(0, 1, 0)), 1e-5f) << "the frame keeps the normal";
    }
}

TEST(ShotProjection, CallsWithoutAShotAndTypesThatKeepTheNormalProjectAlongIt) {
    DecalSystem s = makeSystem(boxScene());
    DecalType normal = plainType("normal");
    normal.projection = Projection::Normal;
    DecalType crater = plainType("crater");
    crater.volumetric = true;
    const uint16_t shot = addType(s, plainType("shot")), n = addType(s, normal), v = addType(s, crater);
    const Ray slanted = ray(glm::dvec3(1.5, 2.5, 0.3), glm::dvec3(-1.5, -2.0, -0.3));
    const SpawnResult results[] = {s.spawnAt({0.0, 0.5, 0.0}, {0.0, 1.0, 0.0}, shot),
                                   s.spawnAttached(0, {0.1f, 0.5f, 0.1f}, {0.0f, 1.0f, 0.0f}, shot),
                                   s.spawn(slanted, n), s.spawn(slanted, v)};
    for (const SpawnResult& r : results) {
        ASSERT_TRUE(r.placed()) << r.reason;
        EXPECT_EQ(s.get(r.handle)->slant, 0u);
    }
    const SpawnResult r = s.spawn(slanted, shot);
    ASSERT_TRUE(r.placed());
    EXPECT_NE(s.get(r.handle)->slant, 0u);
}

// The proxy lies 0.02 above the drawn floor; the decal box, projected along the shot, holds the point
// where the shot meets the floor on its axis (the footprint centred on it) at 10, 45 and 75 degrees.
// Projected along the normal, the footprint's centre is off by 0.02 * tan(angle) along the floor.
TEST(ShotProjection, FootprintIsCentredWhereTheShotMeetsTheDrawnSurface) {
    for (float offset : {0.02f, -0.02f}) {
        DecalSettings settings;
        settings.depthMargin = 0.0f; // half-depth h itself: the drawn floor at the box's face at most
        Result<DecalSystem> created = DecalSystem::create(offsetFloorWorld(offset), settings);
        ASSERT_TRUE(created.ok()) << created.error();
        DecalSystem& s = created.value();
        DecalType normal = plainType("normal", glm::vec2(0.2f));
        normal.projection = Projection::Normal;
        const uint16_t shot = addType(s, plainType("shot", glm::vec2(0.2f))), n = addType(s, normal);
        for (double degrees : {10.0, 45.0, 75.0}) {
            SCOPED_TRACE(std::to_string(degrees) + " degrees, proxy at " + std::to_string(offset));
            const glm::dvec3 back = shotFrom(degrees, 1.1);
            const Ray r = ray(glm::dvec3(0.3, 0.0, -0.2) + 2.0 * back, -back);
            const glm::dvec3 drawnHit = r.origin + r.direction * (r.origin.y / -r.direction.y);
            const SpawnResult a = s.spawn(r, shot), b = s.spawn(r, n);
            ASSERT_TRUE(a.placed() && b.placed()) << a.reason << b.reason;
            const glm::dvec3 onShot = inBox(*s.get(a.handle), drawnHit);
            EXPECT_LT(std::max(std::fabs(onShot.x), std::fabs(onShot.y)), 1e-3);
            EXPECT_LE(std::fabs(onShot.z), 1.0 + 1e-4);
            const double expected = std::fabs(offset) * std::tan(degrees * kPi / 180.0) / 0.1; // half-widths
            const glm::dvec3 onNormal = inBox(*s.get(b.handle), drawnHit);
            EXPECT_NEAR(glm::length(glm::dvec2(onNormal)), expected, 1e-3);
        }
    }
}

// A shot beyond the largest slant: the axis turns to 85 degrees in the plane of the shot and the
// normal, so the box stays within 11.5 half-depths of its centre.
TEST(ShotProjection, GrazingShotTurnsTheAxisToTheLargestSlant) {
    DecalSystem s = makeSystem(boxScene());
    DecalType t = plainType();
    t.maxAngleDeg = 90.0f;
    const uint16_t type = addType(s, t);
    const glm::dvec3 back = shotFrom(88.0, 0.0);
    const SpawnResult r = s.spawn(ray(glm::dvec3(0.0, 0.5, 0.0) + 2.0 * back, -back), type);
    ASSERT_TRUE(r.placed()) << r.reason;
    const WorldDecal w = s.worldBox(*s.get(r.handle));
    EXPECT_LT(glm::length(glm::dvec3(w.projection) - shotFrom(kMaxSlantDeg, 0.0)), 1e-3);
}
