// Decals projected along the shot: the axis placement gives them, the calls that keep the normal, and
// the footprint landing where the shot meets a drawn surface that lies off the collision proxy.

#include "PlacementTestUtil.hpp"

#include "spatter/core/DecalRefit.hpp"

#include <cmath>

using namespace spatter;
using namespace spatter::test;

namespace {

// A drawn plane y = 0 (4 x 4) whose collision proxy is the plane y = offset, with h = |offset|.
CollisionWorld offsetFloorWorld(float offset) {
    Scene scene;
    scene.source = "test:offset floor";
    scene.objects.push_back(makeSceneObject("floor", makeGrid({-2.0f, 2.0f}, {-2.0f, 2.0f})));
    Mesh proxy = makeGrid({-2.0f, 2.0f}, {-2.0f, 2.0f});
    for (glm::vec3& p : proxy.positions)
        p.y = offset;
    std::vector<std::shared_ptr<const Proxy>> proxies;
    proxies.push_back(shareProxy(makeProxy(std::move(proxy), std::fabs(double(offset)))));
    Result<CollisionWorld> w = CollisionWorld::build(scene, proxies);
    EXPECT_TRUE(w.ok()) << w.error();
    return std::move(w).value();
}

// The plane y = z tan(tiltDeg) (object space; the floor y = 0 for 0) of an object turned and scaled
// unevenly.
Scene turnedFloor(double tiltDeg = 0.0) {
    Scene scene;
    scene.source = "test:turned floor";
    scene.objects.push_back(makeSceneObject("floor", tiltedPlane(tiltDeg), turnedTransform()));
    return scene;
}

// A decal system over turnedFloor(tiltDeg), traced on its own mesh.
DecalSystem turnedFloorSystem(double tiltDeg) {
    Result<DecalSystem> s = DecalSystem::create(buildWorld(turnedFloor(tiltDeg)));
    EXPECT_TRUE(s.ok()) << s.error();
    return std::move(s).value();
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

// A decal placed on a plane tilted against the floor, laid again where the line along its projection
// axis meets the floor (relaidDecal), is the decal placement lays on the floor with the same shot: the
// same centre, frame (its random rotation included), slant and size, for shots 10 to 60 degrees off
// the normal, in an object turned and scaled unevenly.
TEST(ShotProjection, ADecalRelaidOnTheDrawnSurfaceIsTheOnePlacementLaysThere) {
    const glm::dmat4 toWorld = turnedFloor().objects[0].transform;
    for (double degrees : {10.0, 35.0, 60.0})
        for (double azimuth : {0.3, 2.0, 4.1}) {
            const glm::dvec3 target(toWorld * glm::dvec4(0.2, 0.0, 0.3, 1.0));
            const glm::dvec3 back = glm::normalize(glm::dmat3(toWorld) * shotFrom(degrees, azimuth));
            const Ray shot = ray(target + 3.0 * back, -back);
            DecalSystem onTilted = turnedFloorSystem(6.0), onFloor = turnedFloorSystem(0.0);
            const SpawnResult a = onTilted.spawn(shot, addType(onTilted, plainType()));
            const SpawnResult b = onFloor.spawn(shot, addType(onFloor, plainType()));
            ASSERT_TRUE(a.placed() && b.placed()) << a.reason << b.reason;
            const Decal tiltPlaced = *onTilted.get(a.handle), drawn = *onFloor.get(b.handle);
            const glm::vec3 axis = tiltPlaced.projectionAxis();
            const glm::vec3 meet = tiltPlaced.center - axis * (tiltPlaced.center.y / axis.y);
            const std::optional<Decal> relaid = relaidDecal(tiltPlaced, glm::dmat3(toWorld), meet,
                                                            glm::vec3(0.0f, 1.0f, 0.0f), drawn.halfDepth);
            ASSERT_TRUE(relaid.has_value());
            const std::string where =
                std::to_string(degrees) + " degrees, azimuth " + std::to_string(azimuth);
            EXPECT_LT(glm::length(relaid->center - drawn.center), 1e-4f) << where;
            const Frame f = relaid->frame(), g = drawn.frame();
            EXPECT_LT(glm::length(f.tangent - g.tangent), 2e-3f) << where;
            EXPECT_LT(glm::length(f.bitangent - g.bitangent), 2e-3f) << where;
            EXPECT_LT(glm::length(f.normal - g.normal), 1e-5f) << where;
            EXPECT_LT(glm::length(unpackSlant(relaid->slant) - unpackSlant(drawn.slant)), 2e-3f) << where;
            EXPECT_LT(glm::length(relaid->size - drawn.size), 1e-4f * glm::length(drawn.size)) << where;
            EXPECT_EQ(relaid->halfDepth, drawn.halfDepth);
            // The decal on the tilted plane is off: its frame lies in that plane.
            EXPECT_GT(glm::length(tiltPlaced.frame().normal - g.normal), 0.05f) << where;
        }
}

TEST(ShotProjection, RelaidDecalRefusesWhatCannotBeLaidAndTurnsANormalDecalTheLeastWay) {
    DecalSystem s = turnedFloorSystem(0.0);
    const uint16_t t = addType(s, plainType());
    const SpawnResult r = s.spawnAt(glm::dvec3(turnedFloor().objects[0].transform * glm::dvec4(0, 0, 0, 1)),
                                    glm::dvec3(0.0, 1.0, 0.0), t);
    ASSERT_TRUE(r.placed()) << r.reason;
    const Decal d = *s.get(r.handle);
    ASSERT_EQ(d.slant, 0u);
    const glm::dmat3 m(1.0);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const Frame f = d.frame();
    const glm::vec3 across = glm::normalize(glm::cross(f.normal, f.tangent));
    EXPECT_FALSE(relaidDecal(d, m, glm::vec3(nan, 0.0f, 0.0f), f.normal, 0.1f).has_value());
    EXPECT_FALSE(relaidDecal(d, m, glm::vec3(0.0f), glm::vec3(0.0f), 0.1f).has_value());
    EXPECT_FALSE(relaidDecal(d, m, glm::vec3(0.0f), glm::vec3(nan, 1.0f, 0.0f), 0.1f).has_value());
    EXPECT_FALSE(relaidDecal(d, m, glm::vec3(0.0f), across, 0.1f).has_value());
    EXPECT_FALSE(relaidDecal(d, m, glm::vec3(0.0f), f.normal, -0.1f).has_value());
    EXPECT_FALSE(relaidDecal(d, glm::dmat3(0.0), glm::vec3(0.0f), f.normal, 0.1f).has_value());
    Decal none = d;
    none.packedFrame = kNoOrientation;
    EXPECT_FALSE(relaidDecal(none, m, glm::vec3(0.0f), f.normal, 0.1f).has_value());
    // Along its normal: turned about the tangent by 20 degrees, the tangent stays.
    const glm::vec3 tilted = glm::normalize(f.normal + float(std::tan(20.0 * kPi / 180.0)) * f.bitangent);
    const std::optional<Decal> turned = relaidDecal(d, m, d.center, tilted, d.halfDepth);
    ASSERT_TRUE(turned.has_value());
    EXPECT_LT(glm::length(turned->frame().normal - tilted), 1e-5f);
    EXPECT_LT(glm::length(turned->frame().tangent - f.tangent), 1e-5f);
    EXPECT_EQ(turned->slant, 0u);
    EXPECT_EQ(turned->size, d.size);
}
