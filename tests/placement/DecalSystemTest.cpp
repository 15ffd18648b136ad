#include "PlacementTestUtil.hpp"

#include "spatter/core/SceneLoader.hpp"
#include "spatter/placement/DecalPersistence.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/placement/ObjectIds.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <set>

using namespace spatter;
using namespace spatter::test;

namespace {

// The decal's frame is orthonormal and right-handed, in object and in world space.
void expectGoodFrames(const DecalSystem& s, const Decal& d) {
    EXPECT_LE(frameError(d.frame()), 1e-6f);
    EXPECT_LE(frameError(s.worldBox(d).frame), 1e-6f);
}

// Spawns `rays` (type 0) one by one on `one` and as one spawnBatch on `many`: the results (status,
// handle, reason), the decals and the stats must agree.
::testing::AssertionResult batchEqualsOneByOne(DecalSystem& one, DecalSystem& many,
                                               const std::vector<Ray>& rays) {
    std::vector<SpawnResult> single;
    for (const Ray& r : rays)
        single.push_back(one.spawn(r, 0));
    std::vector<SpawnResult> batch;
    many.spawnBatch(rays, 0, batch);
    if (batch.size() != rays.size()) return ::testing::AssertionFailure() << batch.size() << " results";
    for (size_t i = 0; i < rays.size(); ++i)
        if (batch[i].status != single[i].status || batch[i].handle != single[i].handle ||
            batch[i].reason != single[i].reason)
            return ::testing::AssertionFailure()
                   << "ray " << i << ": " << toString(batch[i].status) << " in the batch, "
                   << toString(single[i].status) << " alone";
    if (::testing::AssertionResult same = sameDecals(one.decals(), many.decals()); !same) return same;
    if (!(one.stats() == many.stats())) return ::testing::AssertionFailure() << "stats differ";
    return ::testing::AssertionSuccess();
}

} // namespace

TEST(DecalSystem, FramesOnEveryFaceOfABox) {
    DecalSystem s = makeSystem(boxScene());
    const uint16_t type = addType(s, plainType());
    const glm::dvec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    Rng rng(3);
    for (const glm::dvec3& n : normals) {
        for (int k = 0; k < 40; ++k) {
            // A point on the face and a ray towards it within 70 degrees of the normal.
            glm::dvec3 p = 0.5 * n;
            glm::dvec3 off(rng.uniform(-0.4f, 0.4f), rng.uniform(-0.4f, 0.4f), rng.uniform(-0.4f, 0.4f));
            p += off - n * glm::dot(off, n);
            glm::dvec3 d;
            do {
                d = -n + 2.5 * glm::dvec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
            } while (glm::dot(glm::normalize(d), -n) < std::cos(70.0 * kPi / 180.0));
            const SpawnResult r = s.spawn(ray(p - 3.0 * d, d), type);
            ASSERT_TRUE(r.placed()) << r.reason;
            const Decal& decal = *s.get(r.handle);
            expectGoodFrames(s, decal);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(decal.frame().normal[c], n[c], kPackedFrameError);
                EXPECT_NEAR(decal.center[c], p[c], 1e-6);
            }
            EXPECT_NEAR(glm::dot(glm::dvec3(decal.frame().tangent), n), 0.0, kPackedFrameError);
        }
    }
    EXPECT_EQ(s.stats().placed, 240u);
}

TEST(DecalSystem, TangentFollowsTheProjectedRayWithoutRotation) {
    DecalSystem s = makeSystem(boxScene());
    DecalType t = plainType("aligned");
    t.randomRotation = false;
    const uint16_t type = addType(s, t);
    const glm::dvec3 d(0.6, -0.3, -1.0);
    const SpawnResult r = s.spawn(ray(glm::dvec3(0.1, 0.1, 0.5) - 2.0 * d, d), type);
    ASSERT_TRUE(r.placed()) << r.reason;
    const Decal& decal = *s.get(r.handle);
    const glm::dvec3 expected = glm::normalize(glm::dvec3(0.6, -0.3, 0.0));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(decal.frame().tangent[c], expected[c], kPackedFrameError);
    expectGoodFrames(s, decal);

    // Straight on: the projection vanishes, the tangent falls back to world X.
    const SpawnResult straight = s.spawn(ray({0.2, 0.1, 4.0}, {0.0, 0.0, -1.0}), type);
    ASSERT_TRUE(straight.placed());
    EXPECT_NEAR(s.get(straight.handle)->frame().tangent.x, 1.0, kPackedFrameError);
    // Straight down onto the top face along X: world X lies in the plane too.
    const SpawnResult down = s.spawn(ray({0.2, 4.0, 0.1}, {0.0, -1.0, 0.0}), type);
    ASSERT_TRUE(down.placed());
    EXPECT_NEAR(s.get(down.handle)->frame().tangent.x, 1.0, kPackedFrameError);
    // Straight onto the +X face: X is the normal, Duff et al. gives the frame.
    const SpawnResult side = s.spawn(ray({4.0, 0.1, 0.2}, {-1.0, 0.0, 0.0}), type);
    ASSERT_TRUE(side.placed());
    const Frame duff = basisFromNormal(glm::vec3(1, 0, 0));
    EXPECT_NEAR(glm::length(s.get(side.handle)->frame().tangent - duff.tangent), 0.0, kPackedFrameError);
    expectGoodFrames(s, *s.get(side.handle));
}

TEST(DecalSystem, FramesOnASphereSweep) {
    DecalSystem s = makeSystem(sphereScene());
    DecalType t = plainType();
    t.maxAngleDeg = 90.0f;
    const uint16_t type = addType(s, t);
    size_t placed = 0;
    // Rays from every direction around the sphere, aimed at offsets from the centre up to 0.9.
    for (int i = 0; i < 24; ++i)
        for (int j = 0; j < 12; ++j)
            for (double aim : {0.0, 0.5, 0.9}) {
                const double theta = kPi * (j + 0.5) / 12.0, phi = 2.0 * kPi * i / 24.0;
                const glm::dvec3 from = 4.0 * glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                                         std::sin(theta) * std::sin(phi));
                const glm::dvec3 side = glm::normalize(glm::cross(from, glm::dvec3(0.3, 1.0, 0.2)));
                const glm::dvec3 d = (side * aim) - from;
                const SpawnResult r = s.spawn(ray(from, d), type);
                ASSERT_TRUE(r.placed()) << r.reason;
                ++placed;
                const Decal& decal = *s.get(r.handle);
                expectGoodFrames(s, decal);
                // On the faceted sphere: within the chord sag of the unit sphere; normal close to radial.
                EXPECT_NEAR(glm::length(decal.center), 1.0, 3e-3);
                EXPECT_GT(glm::dot(glm::normalize(decal.center), decal.frame().normal), std::cos(0.1));
                // The normal faces the shooter.
                EXPECT_LT(glm::dot(glm::dvec3(decal.frame().normal), d), 0.0);
            }
    EXPECT_EQ(placed, 24u * 12u * 3u);
}

TEST(DecalSystem, HalfDepthIsTheErrorBoundPlusAMarginOrTheOverride) {
    Scene scene = rangeScene(1);
    std::vector<std::shared_ptr<const Proxy>> proxies(scene.objects.size());
    proxies[1] = shareProxy(makeProxy(makeBox(glm::vec3(10.0f, 2.0f, 0.1f), 1), 0.2f));
    Result<CollisionWorld> world = CollisionWorld::build(scene, proxies);
    ASSERT_TRUE(world.ok()) << world.error();
    DecalSettings settings;
    settings.depthMargin = 0.5f;
    Result<DecalSystem> sys = DecalSystem::create(std::move(world).value(), settings);
    ASSERT_TRUE(sys.ok());
    DecalSystem& s = sys.value();
    const uint16_t automatic = addType(s, plainType("auto", glm::vec2(0.2f, 0.4f)));
    DecalType deep = plainType("deep", glm::vec2(0.2f, 0.4f));
    deep.halfDepth = 1.0f;
    const uint16_t overridden = addType(s, deep);

    const Ray atWall = ray({3.0, 1.5, 0.0}, {0.0, 0.0, -1.0});
    const SpawnResult a = s.spawn(atWall, automatic);
    ASSERT_TRUE(a.placed()) << a.reason;
    EXPECT_FLOAT_EQ(s.get(a.handle)->halfDepth, 0.2f + 0.5f * 0.4f);
    const SpawnResult b = s.spawn(atWall, overridden);
    ASSERT_TRUE(b.placed());
    EXPECT_FLOAT_EQ(s.get(b.handle)->halfDepth, 1.0f);
    // On the floor (h = 0) only the margin remains.
    const SpawnResult c = s.spawn(ray({3.0, 2.0, 3.0}, {0.0, -1.0, 0.1}), automatic);
    ASSERT_TRUE(c.placed());
    EXPECT_FLOAT_EQ(s.get(c.handle)->halfDepth, 0.5f * 0.4f);
}

TEST(DecalSystem, RenderSurfaceLiesInsideTheBoxOfASimplifiedProxy) {
    // A bumpy render mesh, its simplified proxy from the proxy builder, decals placed on the proxy:
    // along each decal's normal through its centre, the render surface lies within the half-depth.
    Scene scene;
    scene.source = "test:bumpy";
    Mesh bumpy = makeSphere(1.0f, 64, 128);
    displace(bumpy, [](const glm::vec3& p, const glm::vec3&) {
        return 0.03f * std::sin(9.0f * p.x) * std::cos(7.0f * p.y);
    });
    glm::dmat4 t = glm::translate(glm::dmat4(1.0), glm::dvec3(5.0, 1.0, -2.0));
    t = glm::scale(glm::rotate(t, 0.6, glm::dvec3(0.0, 0.0, 1.0)), glm::dvec3(1.5));
    scene.objects.push_back(makeSceneObject("bumpy", bumpy, t, true));
    ProxySettings ps;
    ps.tolerance = 0.04f;
    ps.toleranceRelative = false;
    Result<Proxy> proxy = buildProxy(bumpy, ps);
    ASSERT_TRUE(proxy.ok()) << proxy.error();
    ASSERT_LT(proxy->mesh.triangleCount(), bumpy.triangleCount());
    ASSERT_GT(proxy->errorBound, 0.0);
    std::vector<std::shared_ptr<const Proxy>> proxies = {shareProxy(std::move(proxy).value())};
    Result<CollisionWorld> world = CollisionWorld::build(scene, proxies);
    ASSERT_TRUE(world.ok()) << world.error();
    const double h = world->worldErrorBound(0);
    EXPECT_NEAR(h, 1.5 * proxies[0]->errorBound, 1e-12);
    Result<DecalSystem> sys = DecalSystem::create(std::move(world).value());
    ASSERT_TRUE(sys.ok());
    DecalSystem& s = sys.value();
    DecalType small = plainType("small", glm::vec2(0.05f));
    small.maxAngleDeg = 60.0f;
    const uint16_t type = addType(s, small);
    Result<CollisionWorld> renderWorld = CollisionWorld::build(scene); // the render mesh itself
    ASSERT_TRUE(renderWorld.ok());
    const std::vector<Ray> rays = rayFan(500, glm::dvec3(5.0, 1.0, -2.0), 6.0, 0.5, 31);
    size_t checked = 0;
    for (const Ray& r : rays) {
        const SpawnResult placed = s.spawn(r, type);
        if (!placed.placed()) continue;
        const WorldDecal w = *s.worldBox(placed.handle);
        EXPECT_GE(w.halfDepth, float(h));
        Ray probe;
        probe.origin = w.center + glm::dvec3(w.frame.normal) * double(w.halfDepth);
        probe.direction = -glm::dvec3(w.frame.normal);
        probe.tfar = 2.0 * w.halfDepth;
        EXPECT_TRUE(renderWorld->intersect(probe).has_value()) << "render surface outside the decal box";
        ++checked;
    }
    EXPECT_GT(checked, 200u);
}

TEST(DecalSystem, ScaledObjectsGetObjectSpaceSizesThatMatchTheWorld) {
    DecalSystem s = makeSystem(rangeScene(3)); // target_1 (object 3) is scaled by 0.75
    const uint16_t type = addType(s, plainType("t", glm::vec2(0.2f, 0.1f)));
    const SpawnResult r = s.spawn(ray({2.0, 1.0, 5.0}, {0.0, 0.0, -1.0}), type);
    ASSERT_TRUE(r.placed()) << r.reason;
    const Decal& d = *s.get(r.handle);
    EXPECT_EQ(d.object, 3u);
    EXPECT_NEAR(d.size.x, 0.2 / 0.75, 1e-6);
    EXPECT_NEAR(d.size.y, 0.1 / 0.75, 1e-6);
    const WorldDecal w = s.worldBox(d);
    EXPECT_NEAR(w.size.x, 0.2, 1e-6);
    EXPECT_NEAR(w.size.y, 0.1, 1e-6);
    EXPECT_NEAR(w.halfDepth, 0.25 * 0.2, 1e-6);
    expectGoodFrames(s, d);
}

TEST(DecalSystem, SizeJitterStaysInRange) {
    DecalSystem s = makeSystem(boxScene());
    DecalType t = plainType("jitter", glm::vec2(0.2f, 0.1f));
    t.sizeJitter = 0.25f;
    const uint16_t type = addType(s, t);
    float lo = 10.0f, hi = 0.0f;
    for (int i = 0; i < 200; ++i) {
        const SpawnResult r = s.spawn(ray({-0.4 + 0.004 * i, 0.0, 3.0}, {0.0, 0.0, -1.0}), type);
        ASSERT_TRUE(r.placed()) << r.reason;
        const Decal& d = *s.get(r.handle);
        EXPECT_FLOAT_EQ(d.size.x / d.size.y, 2.0f);
        lo = std::min(lo, d.size.x);
        hi = std::max(hi, d.size.x);
    }
    EXPECT_GE(lo, 0.2f * 0.75f);
    EXPECT_LE(hi, 0.2f * 1.25f);
    EXPECT_LT(lo, 0.2f * 0.8f); // the range is used
    EXPECT_GT(hi, 0.2f * 1.2f);
}

TEST(DecalSystem, RejectsGrazingHits) {
    DecalSystem s = makeSystem(boxScene());
    DecalType t = plainType();
    t.maxAngleDeg = 60.0f;
    const uint16_t type = addType(s, t);
    // 59 and 61 degrees from the +Z face normal.
    for (double deg : {59.0, 61.0}) {
        const double a = deg * kPi / 180.0;
        const glm::dvec3 d(std::sin(a), 0.0, -std::cos(a));
        const SpawnResult r = s.spawn(ray(glm::dvec3(0.0, 0.0, 0.5) - d, d), type);
        EXPECT_EQ(r.placed(), deg < 60.0) << deg << ": " << r.reason;
        if (!r.placed()) {
            EXPECT_EQ(r.status, SpawnStatus::GrazingAngle);
            EXPECT_NE(r.reason.find("61"), std::string::npos) << r.reason;
        }
    }
}

TEST(DecalSystem, EveryBadInputIsRejectedWithItsReasonAndNoStateChange) {
    Scene scene = rangeScene(2);
    DecalSettings settings;
    settings.policy = LimitPolicy::Reject;
    settings.maxPerCell = 2;
    const DecalType hole = plainType("hole");
    DecalType staticOnly = plainType("static-only");
    staticOnly.onDynamic = false;
    const Ray good = ray({-3.0, 1.0, 3.0}, {0.1, 0.05, -1.0});
    const Ray crowded = ray({3.0, 1.0, 3.0}, {0.0, 0.0, -1.0});

    // The history every test run shares: two decals in the crowded cell, one elsewhere.
    auto history = [&](DecalSystem& s) {
        ASSERT_EQ(addType(s, hole), 0);
        ASSERT_EQ(addType(s, staticOnly), 1);
        ASSERT_TRUE(s.spawn(crowded, 0).placed());
        ASSERT_TRUE(s.spawn(crowded, 0).placed());
        ASSERT_TRUE(s.spawn(ray({-5.0, 1.0, 3.0}, {0.0, 0.0, -1.0}), 0).placed());
    };
    DecalSystem reference = makeSystem(scene, settings);
    history(reference);
    const SpawnResult expectedNext = reference.spawn(good, 0);
    ASSERT_TRUE(expectedNext.placed());

    Ray nanOrigin = good;
    nanOrigin.origin.y = std::numeric_limits<double>::quiet_NaN();
    Ray infDir = good;
    infDir.direction.x = std::numeric_limits<double>::infinity();
    Ray zeroDir = good;
    zeroDir.direction = glm::dvec3(0.0);
    Ray denormalDir = good;
    denormalDir.direction = glm::dvec3(0.0, 0.0, -4e-320);
    Ray negativeNear = good;
    negativeNear.tnear = -0.5;
    Ray emptyRange = good;
    emptyRange.tnear = 2.0;
    emptyRange.tfar = 1.0;
    Ray nanFar = good;
    nanFar.tfar = std::numeric_limits<double>::quiet_NaN();
    const double nan = std::numeric_limits<double>::quiet_NaN();

    struct Case {
        const char* name;
        SpawnStatus status;
        std::function<SpawnResult(DecalSystem&)> call;
    };
    const std::vector<Case> cases = {
        {"NaN origin", SpawnStatus::InvalidRay, [&](DecalSystem& s) { return s.spawn(nanOrigin, 0); }},
        {"infinite direction", SpawnStatus::InvalidRay, [&](DecalSystem& s) { return s.spawn(infDir, 0); }},
        {"zero direction", SpawnStatus::InvalidRay, [&](DecalSystem& s) { return s.spawn(zeroDir, 0); }},
        {"denormal direction", SpawnStatus::InvalidRay,
         [&](DecalSystem& s) { return s.spawn(denormalDir, 0); }},
        {"negative tnear", SpawnStatus::InvalidRay, [&](DecalSystem& s) { return s.spawn(negativeNear, 0); }},
        {"empty range", SpawnStatus::InvalidRay, [&](DecalSystem& s) { return s.spawn(emptyRange, 0); }},
        {"NaN tfar", SpawnStatus::InvalidRay, [&](DecalSystem& s) { return s.spawn(nanFar, 0); }},
        {"unknown type", SpawnStatus::InvalidType, [&](DecalSystem& s) { return s.spawn(good, 7); }},
        {"miss", SpawnStatus::Missed,
         [&](DecalSystem& s) {
             return s.spawn(ray({0, 1, 3}, {0, 1, 0}), 0);
         }},
        {"grazing", SpawnStatus::GrazingAngle,
         [&](DecalSystem& s) {
             return s.spawn(ray({-3.0, 0.5, 3.0}, {0.0, -0.1, -1.0}), 0);
         }},
        {"dynamic target, static-only type", SpawnStatus::NotReceiver,
         [&](DecalSystem& s) {
             return s.spawn(ray({0.0, 1.0, 3.0}, {0.0, 0.0, -1.0}), 1);
         }},
        {"full cell", SpawnStatus::AreaLimit, [&](DecalSystem& s) { return s.spawn(crowded, 0); }},
        {"batch of bad rays", SpawnStatus::InvalidRay,
         [&](DecalSystem& s) {
             std::vector<SpawnResult> rs;
             s.spawnBatch({nanOrigin}, 0, rs);
             return rs.at(0);
         }},
        {"spawnAt NaN position", SpawnStatus::InvalidArgument,
         [&](DecalSystem& s) {
             return s.spawnAt({nan, 0, 0}, {0, 1, 0}, 0);
         }},
        {"spawnAt zero normal", SpawnStatus::InvalidArgument,
         [&](DecalSystem& s) {
             return s.spawnAt({0, 0, 0}, {0, 0, 0}, 0);
         }},
        {"spawnAt in the air", SpawnStatus::Missed,
         [&](DecalSystem& s) {
             return s.spawnAt({0, 8, 0}, {0, 1, 0}, 0);
         }},
        {"spawnAt tilted", SpawnStatus::GrazingAngle,
         [&](DecalSystem& s) {
             return s.spawnAt({-3, 0, 3}, {1, 0.1, 0}, 0);
         }},
        {"spawnAt unknown type", SpawnStatus::InvalidType,
         [&](DecalSystem& s) {
             return s.spawnAt({-3, 0, 3}, {0, 1, 0}, 9);
         }},
        {"spawnAttached out of range", SpawnStatus::InvalidArgument,
         [&](DecalSystem& s) {
             return s.spawnAttached(99, {0, 0, 0}, {0, 1, 0}, 0);
         }},
        {"spawnAttached NaN normal", SpawnStatus::InvalidArgument,
         [&](DecalSystem& s) {
             return s.spawnAttached(2, {0, 0, 0}, {0, float(nan), 1}, 0);
         }},
        {"spawnAttached static-only type", SpawnStatus::NotReceiver,
         [&](DecalSystem& s) {
             return s.spawnAttached(2, {0, 0, 0.5f}, {0, 0, 1}, 1);
         }},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        DecalSystem s = makeSystem(scene, settings);
        history(s);
        const std::vector<Decal> decalsBefore = s.decals();
        const DecalStats statsBefore = s.stats();
        const SpawnResult r = c.call(s);
        EXPECT_EQ(r.status, c.status) << r.reason;
        EXPECT_FALSE(r.reason.empty());
        EXPECT_EQ(r.handle, DecalHandle());
        EXPECT_TRUE(sameDecals(s.decals(), decalsBefore));
        DecalStats expectedStats = statsBefore;
        expectedStats.rejected[size_t(c.status)]++;
        EXPECT_EQ(s.stats(), expectedStats);
        // No random number was drawn: the next spawn is exactly the reference's.
        const SpawnResult next = s.spawn(good, 0);
        ASSERT_TRUE(next.placed());
        EXPECT_EQ(next.handle, expectedNext.handle);
        EXPECT_TRUE(sameDecals(s.decals(), reference.decals()));
    }
}

TEST(DecalSystem, FullCellsEvictTheOldest) {
    DecalSettings settings;
    settings.maxPerCell = 3;
    settings.cellSize = 1.0f;
    DecalSystem s = makeSystem(rangeScene(0), settings);
    const uint16_t type = addType(s, plainType());
    std::vector<DecalHandle> handles;
    for (int i = 0; i < 5; ++i) {
        const SpawnResult r = s.spawn(ray({0.2 + 0.1 * i, 1.3, 0.0}, {0.0, 0.0, -1.0}), type);
        ASSERT_TRUE(r.placed()) << r.reason;
        handles.push_back(r.handle);
    }
    EXPECT_EQ(s.decals().size(), 3u);
    EXPECT_EQ(s.stats().evicted, 2u);
    EXPECT_EQ(s.stats().placed, 5u);
    EXPECT_EQ(s.get(handles[0]), nullptr);
    EXPECT_EQ(s.get(handles[1]), nullptr);
    for (int i = 2; i < 5; ++i)
        EXPECT_NE(s.get(handles[i]), nullptr);
    // Another cell is unaffected.
    ASSERT_TRUE(s.spawn(ray({4.2, 1.3, 0.0}, {0.0, 0.0, -1.0}), type).placed());
    EXPECT_EQ(s.decals().size(), 4u);
    EXPECT_EQ(s.stats().evicted, 2u);
}

// A cell's list is singly linked up to kSmallCellLimit decals and doubly linked above:
// removals from its middle and its end must leave the oldest-first order of evictions intact either way.
TEST(DecalSystem, RemovalsFromAFullCellKeepItsEvictionOrder) {
    for (const uint32_t cap : {5u, kSmallCellLimit + 36}) {
        SCOPED_TRACE("maxPerCell " + std::to_string(cap));
        DecalSettings settings;
        settings.maxPerCell = cap;
        settings.cellSize = 1.0f;
        DecalSystem s = makeSystem(rangeScene(0), settings);
        const uint16_t type = addType(s, plainType());
        std::vector<DecalHandle> handles;
        auto spawnOne = [&] {
            const double x = 0.1 + 0.8 * double(handles.size() % 97) / 97.0;
            const SpawnResult r = s.spawn(ray({x, 1.3, 0.0}, {0.0, 0.0, -1.0}), type);
            ASSERT_TRUE(r.placed()) << r.reason;
            handles.push_back(r.handle);
        };
        for (uint32_t i = 0; i < cap; ++i)
            spawnOne();
        // Out of the middle, the newest (the list's end) and the second oldest.
        const std::set<uint32_t> removed = {cap / 2, cap - 1, 1};
        for (uint32_t k : removed)
            ASSERT_TRUE(s.remove(handles[k]));
        // Three spawns fill the cell again; the fourth and fifth evict the two oldest left.
        for (int i = 0; i < 5; ++i)
            spawnOne();
        EXPECT_EQ(s.stats().evicted, 2u);
        std::vector<uint32_t> left;
        for (uint32_t i = 0; i < cap; ++i)
            if (removed.count(i) == 0) left.push_back(i);
        for (uint32_t i = 0; i < handles.size(); ++i) {
            const bool gone = removed.count(i) != 0 || i == left[0] || i == left[1];
            EXPECT_EQ(s.get(handles[i]) == nullptr, gone) << "decal " << i;
        }
        EXPECT_EQ(s.decals().size(), size_t(cap));
    }
}

TEST(DecalSystem, FullCellsRejectUnderTheRejectPolicy) {
    DecalSettings settings;
    settings.maxPerCell = 3;
    settings.cellSize = 1.0f;
    settings.policy = LimitPolicy::Reject;
    DecalSystem s = makeSystem(rangeScene(0), settings);
    const uint16_t type = addType(s, plainType());
    for (int i = 0; i < 5; ++i) {
        const SpawnResult r = s.spawn(ray({0.2 + 0.1 * i, 1.3, 0.0}, {0.0, 0.0, -1.0}), type);
        EXPECT_EQ(r.placed(), i < 3);
        if (i >= 3) {
            EXPECT_EQ(r.status, SpawnStatus::AreaLimit);
            EXPECT_NE(r.reason.find("maxPerCell 3"), std::string::npos) << r.reason;
        }
    }
    EXPECT_EQ(s.decals().size(), 3u);
    EXPECT_EQ(s.stats().rejected[size_t(SpawnStatus::AreaLimit)], 2u);
    EXPECT_EQ(s.stats().evicted, 0u);
}

TEST(DecalSystem, FadeOldestFadesTheEvictedDecalThenRemovesIt) {
    DecalSettings settings;
    settings.maxPerCell = 2;
    settings.cellSize = 1.0f;
    settings.policy = LimitPolicy::FadeOldest;
    DecalSystem s = makeSystem(rangeScene(0), settings);
    DecalType t = plainType();
    t.fadeOutTime = 2.0f;
    const uint16_t type = addType(s, t);
    std::vector<DecalHandle> h;
    for (int i = 0; i < 3; ++i)
        h.push_back(s.spawn(ray({0.2 + 0.1 * i, 1.3, 0.0}, {0.0, 0.0, -1.0}), type).handle);
    EXPECT_EQ(s.decals().size(), 3u); // the evicted one is still fading
    EXPECT_EQ(s.stats().evicted, 1u);
    ASSERT_TRUE(s.update(0.5).ok());
    EXPECT_EQ(s.get(h[0])->opacity.bits(), Opacity(0.75f).bits());
    EXPECT_FLOAT_EQ(s.get(h[1])->opacity, 1.0f);
    // The fading decal no longer counts: one more fits only after evicting h[1].
    ASSERT_TRUE(s.spawn(ray({0.6, 1.3, 0.0}, {0.0, 0.0, -1.0}), type).placed());
    EXPECT_EQ(s.stats().evicted, 2u);
    ASSERT_TRUE(s.update(1.5).ok());
    EXPECT_EQ(s.get(h[0]), nullptr);
    EXPECT_EQ(s.get(h[1])->opacity.bits(), Opacity(0.25f).bits());
    EXPECT_EQ(s.decals().size(), 3u);
    EXPECT_EQ(s.stats().expired, 0u);
}

TEST(DecalSystem, GlobalBudgetAndPerObjectCap) {
    DecalSettings settings;
    settings.budget = 4;
    settings.maxPerObject = 2;
    settings.cellSize = 100.0f;
    settings.maxPerCell = 1000;
    DecalSystem s = makeSystem(rangeScene(0), settings);
    const uint16_t type = addType(s, plainType());
    const Ray atFloor = ray({0.0, 3.0, 1.0}, {0.0, -1.0, 0.0});
    const Ray atWall = ray({0.0, 1.0, 1.0}, {0.0, 0.0, -1.0});
    std::vector<DecalHandle> floor, wall;
    for (int i = 0; i < 3; ++i)
        floor.push_back(s.spawn(atFloor, type).handle);
    EXPECT_EQ(s.get(floor[0]), nullptr); // object cap 2
    EXPECT_EQ(s.stats().evicted, 1u);
    for (int i = 0; i < 2; ++i)
        wall.push_back(s.spawn(atWall, type).handle);
    EXPECT_EQ(s.decals().size(), 4u);
    ASSERT_TRUE(s.spawn(ray({0.0, 1.0, 1.0}, {0.0, -0.1, -1.0}), type).placed()); // the wall's cap first
    EXPECT_EQ(s.get(wall[0]), nullptr);
    EXPECT_EQ(s.decals().size(), 4u);

    DecalSettings reject = settings;
    reject.policy = LimitPolicy::Reject;
    reject.maxPerObject = 10;
    DecalSystem r = makeSystem(rangeScene(0), reject);
    addType(r, plainType());
    for (int i = 0; i < 4; ++i)
        ASSERT_TRUE(r.spawn(atFloor, 0).placed());
    const SpawnResult over = r.spawn(atWall, 0);
    EXPECT_EQ(over.status, SpawnStatus::AreaLimit);
    EXPECT_NE(over.reason.find("budget 4"), std::string::npos) << over.reason;
}

TEST(DecalSystem, DynamicCellsFollowTheirObject) {
    DecalSettings settings;
    settings.maxPerCell = 1;
    settings.policy = LimitPolicy::Reject;
    DecalSystem s = makeSystem(rangeScene(1), settings);
    const uint16_t type = addType(s, plainType());
    ASSERT_TRUE(s.spawn(ray({0.0, 1.0, 3.0}, {0.0, 0.0, -1.0}), type).placed());
    // Move the target: the same spot on it is still the same (full) cell.
    const glm::dmat4 t0 = s.world().object(2)->transform;
    ASSERT_TRUE(s.setTransform(2, glm::translate(glm::dmat4(1.0), glm::dvec3(3.0, 0.0, 0.0)) * t0).ok());
    EXPECT_EQ(s.spawn(ray({3.0, 1.0, 3.0}, {0.0, 0.0, -1.0}), type).status, SpawnStatus::AreaLimit);
}

TEST(DecalSystem, NeighbouringDynamicObjectsGetDifferentIds) {
    Scene scene = rangeScene(0);
    // A 6 x 6 grid of crates 0.8 apart (bounds 0.3 apart, within the default separation).
    for (int i = 0; i < 36; ++i)
        scene.objects.push_back(makeSceneObject(
            "crate_" + std::to_string(i), makeBox(glm::vec3(0.25f), 1),
            glm::translate(glm::dmat4(1.0), glm::dvec3(0.8 * (i % 6), 1.0, 0.8 * (i / 6))), true));
    const DecalSystem s = makeSystem(scene);
    EXPECT_EQ(s.objectId(0), 0);
    EXPECT_EQ(s.objectId(1), 0);
    EXPECT_EQ(s.stats().sharedObjectIds, 0u);
    for (uint32_t a = 2; a < scene.objects.size(); ++a) {
        EXPECT_NE(s.objectId(a), 0);
        for (uint32_t b = a + 1; b < scene.objects.size(); ++b)
            if (boundsDistance(s.world().worldBounds(a), s.world().worldBounds(b)) <= 1.0) {
                EXPECT_NE(s.objectId(a), s.objectId(b)) << a << " and " << b;
            }
    }
    // Decals carry their object's ID.
    DecalSystem s2 = makeSystem(scene);
    const uint16_t type = addType(s2, plainType());
    const SpawnResult r = s2.spawn(ray({0.0, 5.0, 0.0}, {0.0, -1.0, 0.0}), type);
    ASSERT_TRUE(r.placed());
    EXPECT_EQ(s2.get(r.handle)->object, 2u);
    EXPECT_EQ(s2.get(r.handle)->objectId, s2.objectId(2));
}

TEST(DecalSystem, DecalFollowsItsMovingObject) {
    DecalSystem s = makeSystem(rangeScene(2));
    const uint16_t type = addType(s, plainType());
    const uint32_t target = 3; // target_1, at x = 2
    const SpawnResult r = s.spawn(ray({2.1, 1.05, 4.0}, {0.0, 0.0, -1.0}), type);
    ASSERT_TRUE(r.placed()) << r.reason;
    ASSERT_EQ(s.get(r.handle)->object, target);
    const Decal before = *s.get(r.handle);
    const WorldDecal w0 = *s.worldBox(r.handle);

    glm::dmat4 move = glm::translate(glm::dmat4(1.0), glm::dvec3(-1.0, 2.0, 0.5));
    move = glm::rotate(move, 1.1, glm::normalize(glm::dvec3(0.2, 1.0, -0.4)));
    const glm::dmat4 t1 = move * s.world().object(target)->transform;
    ASSERT_TRUE(s.setTransform(target, t1).ok());
    EXPECT_TRUE(sameDecal(*s.get(r.handle), before)); // stored in object space: unchanged
    const WorldDecal w1 = *s.worldBox(r.handle);
    const glm::dvec3 expectedCenter = glm::dvec3(move * glm::dvec4(w0.center, 1.0));
    EXPECT_LT(glm::length(w1.center - expectedCenter), 1e-6);
    EXPECT_LT(glm::length(glm::dvec3(w1.frame.normal) - glm::dmat3(move) * glm::dvec3(w0.frame.normal)),
              1e-6);
    EXPECT_LE(frameError(w1.frame), 1e-6f);
    // A new shot at the moved decal lands on the target again.
    const SpawnResult again =
        s.spawn(ray(w1.center + 2.0 * glm::dvec3(w1.frame.normal), -glm::dvec3(w1.frame.normal)), type);
    ASSERT_TRUE(again.placed()) << again.reason;
    EXPECT_EQ(s.get(again.handle)->object, target);
    EXPECT_LT(glm::length(s.get(again.handle)->center - before.center), 1e-5);

    // Removing the object removes its decals.
    ASSERT_TRUE(s.removeObject(target).ok());
    EXPECT_EQ(s.get(r.handle), nullptr);
    EXPECT_EQ(s.get(again.handle), nullptr);
    EXPECT_TRUE(s.decals().empty());
    EXPECT_EQ(s.stats().removed, 2u);
    EXPECT_EQ(s.spawnAttached(target, {0, 0, 0.5f}, {0, 0, 1}, type).status, SpawnStatus::NotReceiver);
}

TEST(DecalSystem, SameSeedSameCallsGiveBitIdenticalDecals) {
    const Scene scene = rangeScene(3);
    const std::vector<Ray> rays = rayFan(600, glm::dvec3(2.0, 1.0, -2.0), 8.0, 4.0, 9);
    auto run = [&](uint64_t seed) {
        DecalSettings settings;
        settings.seed = seed;
        settings.maxPerCell = 4;
        DecalSystem s = makeSystem(scene, settings);
        DecalType t = plainType("jittery");
        t.sizeJitter = 0.3f;
        t.lifetime = 3.0f;
        addType(s, t);
        addType(s, plainType("plain"));
        for (size_t i = 0; i < rays.size(); ++i) {
            s.spawn(rays[i], uint16_t(i % 2));
            if (i % 50 == 0) s.update(0.25);
            if (i % 97 == 0) s.spawnAt({1.0, 0.0, 1.0}, {0.0, 1.0, 0.0}, 0);
        }
        return s;
    };
    const DecalSystem a = run(42), b = run(42), c = run(43);
    EXPECT_GT(a.decals().size(), 100u);
    EXPECT_TRUE(sameDecals(a.decals(), b.decals()));
    EXPECT_EQ(a.stats(), b.stats());
    ASSERT_EQ(a.decals().size(), c.decals().size()); // same placement, other random draws
    size_t sameIds = 0;
    for (size_t i = 0; i < a.decals().size(); ++i)
        sameIds += a.decals()[i].id == c.decals()[i].id;
    EXPECT_LT(sameIds, 3u);
}

TEST(DecalSystem, BatchSpawnEqualsSpawningOneByOne) {
    const Scene scene = rangeScene(4);
    std::vector<Ray> rays = rayFan(3000, glm::dvec3(3.0, 1.0, -2.0), 9.0, 5.0, 13);
    rays[10].direction = glm::dvec3(0.0); // an invalid ray in the middle
    rays[11].tnear = -1.0;
    for (LimitPolicy policy : {LimitPolicy::EvictOldest, LimitPolicy::FadeOldest, LimitPolicy::Reject}) {
        DecalSettings settings;
        settings.policy = policy;
        settings.maxPerCell = 3; // limits act inside the batch
        settings.budget = 900;
        DecalSystem one = makeSystem(scene, settings), many = makeSystem(scene, settings);
        DecalType t = plainType();
        t.sizeJitter = 0.2f;
        t.maxAngleDeg = 70.0f;
        addType(one, t);
        addType(many, t);
        ASSERT_TRUE(batchEqualsOneByOne(one, many, rays));
        EXPECT_GT(one.stats().placed, 500u);
        EXPECT_GT(one.stats().rejectedTotal(), 100u);
        // Both continue identically.
        EXPECT_EQ(one.spawn(rays[5], 0).handle, many.spawn(rays[5], 0).handle);
        EXPECT_TRUE(sameDecals(one.decals(), many.decals()));
    }
    DecalSystem s = makeSystem(scene);
    std::vector<SpawnResult> out;
    s.spawnBatch(rays, 3, out);
    ASSERT_EQ(out.size(), rays.size());
    for (const SpawnResult& r : out)
        EXPECT_EQ(r.status, SpawnStatus::InvalidType);
    EXPECT_EQ(s.stats().rejected[size_t(SpawnStatus::InvalidType)], rays.size());
}

TEST(DecalSystem, BatchSpawnOfShotgunBurstsEqualsSpawningOneByOne) {
    Result<Scene> scene = loadScene("builtin:gallery");
    ASSERT_TRUE(scene.ok()) << scene.error();
    for (const double cone : {2.0, 10.0}) {
        DecalSettings settings;
        settings.maxPerCell = 4; // limits act inside the batch
        DecalSystem one = makeSystem(scene.value(), settings), many = makeSystem(scene.value(), settings);
        addType(one, plainType());
        addType(many, plainType());
        for (uint32_t i = 0; i < one.world().objectCount(); ++i) {
            const CollisionObject& o = *one.world().object(i);
            if (!o.dynamic || !o.inWorld) continue;
            const glm::dmat4 moved =
                glm::translate(glm::dmat4(1.0), glm::dvec3(0.2, 0.0, 0.1 * i)) * o.transform;
            ASSERT_TRUE(one.setTransform(i, moved).ok());
            ASSERT_TRUE(many.setTransform(i, moved).ok());
        }
        std::vector<Ray> rays = bursts(150, 16, glm::dvec3(0.0, 1.5, -1.0), 6.0, 3.0, cone, 41);
        rays[21].direction = glm::dvec3(0.0); // invalid rays inside bursts
        rays[100].tnear = -1.0;
        ASSERT_TRUE(batchEqualsOneByOne(one, many, rays)) << "cone " << cone;
        EXPECT_EQ(one.stats().rejected[size_t(SpawnStatus::InvalidRay)], 2u) << "cone " << cone;
        EXPECT_GT(one.stats().placed, 1000u) << "cone " << cone;
    }
}

TEST(DecalSystem, LifetimeFadesThenExpires) {
    DecalSystem s = makeSystem(boxScene());
    DecalType t = plainType();
    t.lifetime = 2.0f;
    t.fadeOutTime = 1.0f;
    const uint16_t type = addType(s, t);
    const uint16_t permanent = addType(s, plainType("permanent"));
    const DecalHandle h = s.spawn(ray({0.0, 0.0, 3.0}, {0.0, 0.0, -1.0}), type).handle;
    const DecalHandle p = s.spawn(ray({0.2, 0.0, 3.0}, {0.0, 0.0, -1.0}), permanent).handle;
    ASSERT_TRUE(s.update(0.5).ok());
    EXPECT_FLOAT_EQ(s.get(h)->opacity, 1.0f);
    ASSERT_TRUE(s.update(1.0).ok());
    EXPECT_EQ(s.get(h)->opacity.bits(), Opacity(0.5f).bits());
    EXPECT_FALSE(s.update(-1.0).ok());
    EXPECT_FALSE(s.update(std::numeric_limits<double>::quiet_NaN()).ok());
    EXPECT_DOUBLE_EQ(s.time(), 1.5);
    ASSERT_TRUE(s.update(0.5).ok());
    EXPECT_EQ(s.get(h), nullptr);
    EXPECT_EQ(s.stats().expired, 1u);
    ASSERT_TRUE(s.update(1000.0).ok());
    EXPECT_NE(s.get(p), nullptr);
    EXPECT_FLOAT_EQ(s.get(p)->opacity, 1.0f);
    EXPECT_EQ(s.stats().alive, 1u);
}

// Each step is finite, the clock they would sum to is not: the step is refused and the clock stays
// where it was, so that the system's save (which holds the clock) can still be loaded.
TEST(DecalSystem, UpdateRefusesAStepThatWouldTakeTheClockPastTheLargestFiniteTime) {
    DecalSystem s = makeSystem(boxScene());
    const double largest = std::numeric_limits<double>::max();
    ASSERT_TRUE(s.update(largest).ok());
    const Status past = s.update(largest);
    EXPECT_FALSE(past.ok());
    EXPECT_NE(past.error().find("clock"), std::string::npos) << past.error();
    EXPECT_EQ(s.time(), largest);
    const std::vector<uint8_t> bytes = saveDecals(s);
    DecalSystem other = makeSystem(boxScene());
    EXPECT_TRUE(loadDecals(other, bytes.data(), bytes.size()).ok());
}

TEST(DecalSystem, StaleHandlesAreDetected) {
    DecalSystem s = makeSystem(boxScene());
    const uint16_t type = addType(s, plainType());
    const DecalHandle a = s.spawn(ray({0.0, 0.0, 3.0}, {0.0, 0.0, -1.0}), type).handle;
    const DecalHandle b = s.spawn(ray({0.2, 0.0, 3.0}, {0.0, 0.0, -1.0}), type).handle;
    EXPECT_TRUE(s.remove(a));
    EXPECT_FALSE(s.remove(a));
    EXPECT_EQ(s.get(a), nullptr);
    EXPECT_FALSE(s.worldBox(a).has_value());
    const DecalHandle c = s.spawn(ray({0.1, 0.0, 3.0}, {0.0, 0.0, -1.0}), type).handle;
    EXPECT_EQ(c.slot, a.slot); // the slot is reused...
    EXPECT_NE(c, a);           // ...under a new generation
    EXPECT_EQ(s.get(a), nullptr);
    EXPECT_NE(s.get(b), nullptr);
    EXPECT_NEAR(s.get(c)->center.x, 0.1f, 1e-6f);
    EXPECT_EQ(s.get(DecalHandle()), nullptr);
    EXPECT_EQ(s.get(DecalHandle{12345, 1}), nullptr);
    EXPECT_EQ(s.stats().removed, 1u);
    EXPECT_EQ(s.decals().size(), 2u);
}

TEST(DecalSystem, RegisterTypeRejectsBadTypes) {
    DecalSystem s = makeSystem(boxScene());
    ASSERT_EQ(addType(s, plainType("hole")), 0);
    EXPECT_FALSE(s.registerType(plainType("hole")).ok());
    EXPECT_FALSE(s.registerType(plainType("")).ok());
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<std::function<void(DecalType&)>> breakers = {
        [](DecalType& t) { t.size.x = 0.0f; },
        [&](DecalType& t) { t.size.y = nan; },
        [](DecalType& t) { t.size.x = std::numeric_limits<float>::infinity(); },
        [](DecalType& t) { t.sizeJitter = 1.0f; },
        [](DecalType& t) { t.sizeJitter = -0.1f; },
        [](DecalType& t) { t.maxAngleDeg = 0.0f; },
        [](DecalType& t) { t.maxAngleDeg = 91.0f; },
        [&](DecalType& t) { t.maxAngleDeg = nan; },
        [](DecalType& t) { t.lifetime = -1.0f; },
        [&](DecalType& t) { t.fadeOutTime = nan; },
        [](DecalType& t) { t.halfDepth = -0.1f; },
        [](DecalType& t) { t.texture = -1; },
        [&](DecalType& t) { t.tint.w = nan; },
        [](DecalType& t) { t.tint.x = -1.0f; },
        [](DecalType& t) { t.tint.w = 1.5f; },
        [](DecalType& t) { t.roughness = 1e30f; },
        [](DecalType& t) { t.depthFade = DepthFade(7); },
        [](DecalType& t) { t.projection = Projection(9); },
    };
    for (size_t i = 0; i < breakers.size(); ++i) {
        DecalType t = plainType("bad" + std::to_string(i));
        breakers[i](t);
        const Result<uint16_t> r = s.registerType(t);
        EXPECT_FALSE(r.ok()) << "breaker " << i;
        if (!r.ok()) {
            EXPECT_NE(r.error().find(t.name), std::string::npos) << r.error();
        }
    }
    EXPECT_EQ(s.typeCount(), 1u);
    EXPECT_EQ(s.typeIndex("hole").value(), 0);
    EXPECT_FALSE(s.typeIndex("nope").ok());
    EXPECT_EQ(s.type(0)->name, "hole");
    EXPECT_EQ(s.type(1), nullptr);
}

TEST(DecalSystem, RejectsBadSettings) {
    const Scene scene = boxScene();
    std::vector<std::function<void(DecalSettings&)>> breakers = {
        [](DecalSettings& s) { s.cellSize = 0.0f; },
        [](DecalSettings& s) { s.cellSize = std::numeric_limits<float>::quiet_NaN(); },
        [](DecalSettings& s) { s.maxPerCell = 0; },
        [](DecalSettings& s) { s.budget = 0; },
        [](DecalSettings& s) { s.maxPerObject = 0; },
        [](DecalSettings& s) { s.idSeparation = -1.0; },
        [](DecalSettings& s) { s.depthMargin = -0.5f; },
    };
    for (size_t i = 0; i < breakers.size(); ++i) {
        DecalSettings settings;
        breakers[i](settings);
        EXPECT_FALSE(DecalSystem::create(scene, settings).ok()) << "breaker " << i;
    }
}

TEST(DecalSystem, SpawnAtSnapsToTheSurface) {
    DecalSystem s = makeSystem(rangeScene(1));
    DecalType t = plainType();
    t.randomRotation = false;
    const uint16_t type = addType(s, t);
    const SpawnResult r = s.spawnAt({3.0, 0.04, 2.0}, {0.0, 2.0, 0.0}, type);
    ASSERT_TRUE(r.placed()) << r.reason;
    const WorldDecal w = *s.worldBox(r.handle);
    EXPECT_NEAR(w.center.x, 3.0, 1e-9);
    EXPECT_NEAR(w.center.y, 0.0, 1e-6);
    EXPECT_NEAR(w.center.z, 2.0, 1e-9);
    EXPECT_NEAR(w.frame.normal.y, 1.0, kPackedFrameError);
    EXPECT_NEAR(w.frame.tangent.x, 1.0, kPackedFrameError); // world X
    EXPECT_EQ(s.get(r.handle)->object, 0u);
}

TEST(DecalSystem, SpawnAttachedPlacesInObjectSpace) {
    DecalSystem s = makeSystem(rangeScene(2));
    DecalType t = plainType();
    t.randomRotation = false;
    const uint16_t type = addType(s, t);
    const SpawnResult r = s.spawnAttached(3, {0.1f, 0.2f, 0.5f}, {0.0f, 0.0f, 3.0f}, type);
    ASSERT_TRUE(r.placed()) << r.reason;
    const Decal& d = *s.get(r.handle);
    EXPECT_EQ(d.center, glm::vec3(0.1f, 0.2f, 0.5f));
    EXPECT_NEAR(d.frame().normal.z, 1.0f, float(kPackedFrameError));
    EXPECT_NEAR(d.frame().tangent.x, 1.0f, float(kPackedFrameError)); // the object's X axis
    EXPECT_EQ(d.objectId, s.objectId(3));
    expectGoodFrames(s, d);
}
