#include "PlacementTestUtil.hpp"
#include "TestData.hpp"

#include "spatter/core/SceneLoader.hpp"
#include "spatter/placement/CollisionWorld.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

using namespace spatter;
using namespace spatter::test;

namespace {

// A bumpy sphere and a box: curved and flat geometry, two objects, no symmetry to hide behind.
Scene rawComparisonScene() {
    Scene s;
    s.source = "test:raw";
    Mesh bumpy = makeSphere(1.0f, 40, 80);
    displace(bumpy, [](const glm::vec3& p, const glm::vec3&) {
        return 0.08f * std::sin(7.0f * p.x) * std::cos(5.0f * p.y + 2.0f * p.z);
    });
    s.objects.push_back(makeSceneObject("bumpy", std::move(bumpy)));
    glm::dmat4 t = glm::translate(glm::dmat4(1.0), glm::dvec3(2.2, -0.3, 0.4));
    t = glm::rotate(t, 0.7, glm::normalize(glm::dvec3(1.0, 2.0, 0.5)));
    s.objects.push_back(makeSceneObject("box", makeBox(glm::vec3(0.6f, 0.4f, 0.8f), 3), t));
    return s;
}

// Every element of intersectBatch(rays) equals intersect() of its ray bit for bit, front face
// included; `hits` counts the rays that hit.
::testing::AssertionResult batchEqualsSingle(const CollisionWorld& w, const std::vector<Ray>& rays,
                                             size_t& hits) {
    const std::vector<std::optional<Hit>> batch = w.intersectBatch(rays);
    if (batch.size() != rays.size()) return ::testing::AssertionFailure() << batch.size() << " results";
    hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const std::optional<Hit> single = w.intersect(rays[i]);
        if (::testing::AssertionResult same = sameHit(single, batch[i]); !same)
            return same << " (ray " << i << ")";
        if (single && single->frontFace != batch[i]->frontFace)
            return ::testing::AssertionFailure() << "front faces differ (ray " << i << ")";
        hits += single.has_value();
    }
    return ::testing::AssertionSuccess();
}

// Rays that cannot be traced: a zero direction, a NaN origin, a negative tnear, tfar below tnear.
std::vector<Ray> invalidRays(const Ray& like) {
    std::vector<Ray> bad(4, like);
    bad[0].direction = glm::dvec3(0.0);
    bad[1].origin.x = std::numeric_limits<double>::quiet_NaN();
    bad[2].tnear = -1.0;
    bad[3].tnear = 2.0;
    bad[3].tfar = 1.0;
    return bad;
}

// The gallery with every dynamic object moved away from where it was built.
CollisionWorld movedGallery() {
    Result<Scene> scene = loadScene("builtin:gallery");
    EXPECT_TRUE(scene.ok()) << scene.error();
    CollisionWorld w = buildWorld(scene.value());
    for (uint32_t i = 0; i < w.objectCount(); ++i) {
        const CollisionObject& o = *w.object(i);
        if (!o.dynamic || !o.inWorld) continue;
        const glm::dmat4 moved = glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(0.3 * i, 0.1, -0.2)),
                                             0.2 + 0.1 * i, glm::normalize(glm::dvec3(0.2, 1.0, 0.1)));
        EXPECT_TRUE(w.setTransform(i, moved * o.transform).ok());
    }
    return w;
}

} // namespace

TEST(CollisionWorld, HitsAxisAlignedBoxAtExactPositions) {
    const CollisionWorld w = buildWorld(boxScene());
    struct Case {
        glm::dvec3 o, d, p, n;
        double t;
    } cases[] = {
        {{0.1, 0.2, 5.0}, {0.0, 0.0, -1.0}, {0.1, 0.2, 0.5}, {0.0, 0.0, 1.0}, 4.5},
        {{0.1, 0.2, 5.0}, {0.0, 0.0, -3.0}, {0.1, 0.2, 0.5}, {0.0, 0.0, 1.0}, 1.5},
        {{3.0, 0.1, 0.2}, {-1.0, 0.0, 0.0}, {0.5, 0.1, 0.2}, {1.0, 0.0, 0.0}, 2.5},
        {{0.2, 3.0, -0.1}, {0.1, -1.0, 0.05}, {0.45, 0.5, 0.025}, {0.0, 1.0, 0.0}, 2.5},
        {{0.3, -0.2, -4.0}, {0.0, 0.0, 2.0}, {0.3, -0.2, -0.5}, {0.0, 0.0, -1.0}, 1.75},
    };
    for (const Case& c : cases) {
        const std::optional<Hit> h = w.intersect(ray(c.o, c.d));
        ASSERT_TRUE(h.has_value());
        EXPECT_EQ(h->object, 0u);
        EXPECT_NEAR(h->t, c.t, 1e-12);
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(h->position[k], c.p[k], 1e-12);
            EXPECT_NEAR(h->localPosition[k], c.p[k], 1e-12);
            EXPECT_NEAR(h->normal[k], c.n[k], 1e-12);
            EXPECT_NEAR(h->localNormal[k], c.n[k], 1e-12);
        }
    }
}

TEST(CollisionWorld, HitsTransformedBoxAtExactPositions) {
    Scene s = boxScene();
    glm::dmat4 t = glm::translate(glm::dmat4(1.0), glm::dvec3(10.0, -2.0, 3.0));
    t = glm::rotate(t, 0.5 * 3.14159265358979323846, glm::dvec3(0.0, 1.0, 0.0)); // local +Z -> world +X
    t = glm::scale(t, glm::dvec3(2.0));
    s.objects[0].transform = t;
    const CollisionWorld w = buildWorld(s);
    const std::optional<Hit> h = w.intersect(ray({20.0, -1.8, 3.4}, {-1.0, 0.0, 0.0}));
    ASSERT_TRUE(h.has_value());
    EXPECT_NEAR(h->position.x, 11.0, 1e-12);
    EXPECT_NEAR(h->position.y, -1.8, 1e-12);
    EXPECT_NEAR(h->position.z, 3.4, 1e-12);
    EXPECT_NEAR(h->normal.x, 1.0, 1e-12);
    EXPECT_NEAR(h->localPosition.z, 0.5, 1e-12);
    EXPECT_NEAR(h->localPosition.y, 0.1, 1e-12);
    EXPECT_NEAR(h->localNormal.z, 1.0, 1e-12);
    EXPECT_NEAR(h->t, 9.0, 1e-12);
}

TEST(CollisionWorld, RespectsTheRayRange) {
    const CollisionWorld w = buildWorld(boxScene());
    Ray r = ray({0.1, 0.2, 5.0}, {0.0, 0.0, -1.0});
    r.tfar = 4.4;
    EXPECT_FALSE(w.intersect(r).has_value());
    r.tfar = 4.6;
    EXPECT_TRUE(w.intersect(r).has_value());
    r.tnear = 4.6; // past the front face: the back face at z = -0.5
    const std::optional<Hit> back = [&] {
        Ray b = r;
        b.tfar = 100.0;
        return w.intersect(b);
    }();
    ASSERT_TRUE(back.has_value());
    EXPECT_NEAR(back->position.z, -0.5, 1e-12);
    EXPECT_NEAR(back->normal.z, 1.0, 1e-12); // facing the ray, although the face points away
}

TEST(CollisionWorld, InvalidRaysHitNothing) {
    const CollisionWorld w = buildWorld(boxScene());
    Ray r = ray({0.1, 0.2, 5.0}, {0.0, 0.0, 0.0});
    EXPECT_FALSE(w.intersect(r).has_value());
    r.direction = glm::dvec3(0.0, std::numeric_limits<double>::quiet_NaN(), -1.0);
    EXPECT_FALSE(w.intersect(r).has_value());
    EXPECT_FALSE(w.intersectBatch({r})[0].has_value());
}

TEST(CollisionWorld, SameHitsAsRawEmbreeOnARayTable) {
    const Scene s = rawComparisonScene();
    const CollisionWorld w = buildWorld(s);
    const RawEmbree raw(s);
    // The decal system on the same scene: one decal per hit, centred on it.
    DecalSettings settings;
    settings.maxPerCell = 100000;
    Result<DecalSystem> sys = DecalSystem::create(s, settings);
    ASSERT_TRUE(sys.ok()) << sys.error();
    DecalType t = plainType();
    t.maxAngleDeg = 90.0f;
    ASSERT_TRUE(sys->registerType(t).ok());

    const std::vector<Ray> rays = rayFan(4000, glm::dvec3(1.0, 0.0, 0.2), 6.0, 1.8, 7);
    size_t hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const std::optional<Hit> h = w.intersect(rays[i]);
        const auto r = raw.intersect(rays[i]);
        const SpawnResult placed = sys->spawn(rays[i], 0);
        ASSERT_EQ(h.has_value(), r.has_value()) << "ray " << i;
        ASSERT_EQ(placed.placed(), r.has_value()) << "ray " << i << ": " << placed.reason;
        if (!h) continue;
        ++hits;
        EXPECT_EQ(h->object, r->object) << "ray " << i;
        EXPECT_EQ(h->primitive, r->primitive) << "ray " << i;
        EXPECT_NEAR(h->t, r->t, 1e-5 * r->t) << "ray " << i;
        EXPECT_LT(glm::length(h->position - r->position), 1e-5) << "ray " << i;
        // Embree's Ng is a float cross product; the world's is computed in double.
        EXPECT_LT(glm::length(h->normal - r->normal), 1e-4) << "ray " << i;
        const Decal& d = *sys->get(placed.handle);
        const WorldDecal box = sys->worldBox(d);
        EXPECT_EQ(d.object, r->object) << "ray " << i;
        EXPECT_LT(glm::length(box.center - r->position), 1e-5) << "ray " << i;
        EXPECT_LT(glm::length(glm::dvec3(box.frame.normal) - r->normal), 1e-4) << "ray " << i;
    }
    EXPECT_GT(hits, rays.size() / 3);
}

TEST(CollisionWorld, BatchGivesExactlyTheSingleRayHits) {
    Scene s = rangeScene(5);
    s.objects.push_back(rawComparisonScene().objects[0]);
    s.objects.back().transform = glm::translate(glm::dmat4(1.0), glm::dvec3(4.0, 1.5, -2.0));
    const CollisionWorld w = buildWorld(s);
    std::vector<Ray> rays = rayFan(6000, glm::dvec3(4.0, 1.0, -1.0), 12.0, 5.0, 11);
    Ray bad = rays[3];
    bad.direction = glm::dvec3(0.0);
    rays.insert(rays.begin() + 100, bad);
    bad = rays[5];
    bad.tnear = -1.0;
    rays.insert(rays.begin() + 2000, bad);
    const std::vector<std::optional<Hit>> batch = w.intersectBatch(rays);
    ASSERT_EQ(batch.size(), rays.size());
    size_t hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const std::optional<Hit> single = w.intersect(rays[i]);
        ASSERT_TRUE(sameHit(single, batch[i])) << "ray " << i;
        hits += single.has_value();
    }
    EXPECT_GT(hits, rays.size() / 3);
    EXPECT_FALSE(batch[100].has_value());
    EXPECT_FALSE(batch[2000].has_value());
}

TEST(CollisionWorld, BatchEqualsSingleOnEveryInstructionSet) {
    // Embree picks its kernels by instruction set; the equality must hold for each of them.
    Scene s = rangeScene(4);
    s.objects.push_back(rawComparisonScene().objects[0]);
    const std::vector<Ray> rays = rayFan(3000, glm::dvec3(3.0, 1.0, -1.0), 10.0, 5.0, 23);
    const std::vector<Ray> burstRays = bursts(100, 19, glm::dvec3(3.0, 1.0, -1.0), 10.0, 3.0, 2.0, 29);
    size_t tested = 0;
    for (const char* isa : {"isa=sse2", "isa=sse4.2", "isa=avx", "isa=avx2", "isa=avx512"}) {
        WorldSettings settings;
        settings.deviceConfig = isa;
        Result<CollisionWorld> built = CollisionWorld::build(s, {}, settings);
        if (!built.ok() && built.error().find("unsupported CPU") != std::string::npos)
            continue; // not on this CPU
        ASSERT_TRUE(built.ok()) << built.error();
        ++tested;
        const CollisionWorld& w = built.value();
        size_t hits = 0;
        ASSERT_TRUE(batchEqualsSingle(w, rays, hits)) << isa;
        ASSERT_TRUE(batchEqualsSingle(w, burstRays, hits)) << isa;
        EXPECT_GT(hits, burstRays.size() / 2) << isa;
    }
    EXPECT_GE(tested, 2u); // SSE2 and SSE4.2 at least, on any x86-64 CPU that runs Embree
    WorldSettings bad;
    bad.deviceConfig = "isa=no-such-isa,threads=banana";
    EXPECT_FALSE(CollisionWorld::build(s, {}, bad).ok());
}

TEST(CollisionWorld, CoincidentSurfacesResolveTheSameWayInEveryTraversal) {
    // Two identical static boxes and two identical dynamic boxes: every hit is an exact tie
    // between two objects, which Embree would settle by traversal order.
    Scene s;
    s.source = "test:coincident";
    s.objects.push_back(makeSceneObject("static_a", makeBox(glm::vec3(0.5f), 3)));
    s.objects.push_back(makeSceneObject("static_b", makeBox(glm::vec3(0.5f), 3)));
    const glm::dmat4 t = glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(30.0, 0.0, 0.0)), 0.4,
                                     glm::dvec3(0.0, 1.0, 0.0));
    s.objects.push_back(makeSceneObject("dynamic_a", makeBox(glm::vec3(0.5f), 3), t, true));
    s.objects.push_back(makeSceneObject("dynamic_b", makeBox(glm::vec3(0.5f), 3), t, true));
    const CollisionWorld w = buildWorld(s);
    for (const glm::dvec3 center : {glm::dvec3(0.0), glm::dvec3(30.0, 0.0, 0.0)}) {
        const std::vector<Ray> rays = rayFan(3000, center, 4.0, 0.3, 19);
        const std::vector<std::optional<Hit>> batch = w.intersectBatch(rays);
        for (size_t i = 0; i < rays.size(); ++i) {
            const std::optional<Hit> h = w.intersect(rays[i]);
            ASSERT_TRUE(h.has_value()) << "ray " << i;
            EXPECT_EQ(h->object, center.x == 0.0 ? 0u : 2u) << "ray " << i;
            ASSERT_TRUE(sameHit(h, batch[i])) << "ray " << i;
        }
    }
}

TEST(CollisionWorld, RaysThroughSharedEdgesAndVerticesAgreeInEveryTraversal) {
    const Scene s = boxScene();
    const CollisionWorld w = buildWorld(s);
    const Mesh& m = *s.objects[0].mesh;
    std::vector<Ray> rays;
    std::vector<std::vector<uint32_t>> containing;
    // Points on the +Z face (z = 0.5) on grid lines, diagonals and vertices, shot straight and slanted.
    for (double x : {-0.25, 0.0, 0.125, 0.25})
        for (double y : {-0.25, 0.0, 0.25, 0.375})
            for (const glm::dvec3 d : {glm::dvec3(0.0, 0.0, -1.0), glm::dvec3(0.25, -0.5, -1.0)}) {
                std::vector<uint32_t> tris; // every triangle of the face containing (x, y), borders included
                for (uint32_t t = 0; t < m.triangleCount(); ++t) {
                    const glm::dvec3 a(m.positions[m.indices[3 * t]]), b(m.positions[m.indices[3 * t + 1]]),
                        c(m.positions[m.indices[3 * t + 2]]);
                    if (a.z != 0.5 || b.z != 0.5 || c.z != 0.5) continue;
                    auto edge = [&](const glm::dvec3& p, const glm::dvec3& q) {
                        return (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x);
                    };
                    const double e0 = edge(a, b), e1 = edge(b, c), e2 = edge(c, a);
                    if ((e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0)) tris.push_back(t);
                }
                ASSERT_FALSE(tris.empty());
                rays.push_back(ray(glm::dvec3(x, y, 0.5) - 2.0 * d, d));
                containing.push_back(tris);
            }
    const std::vector<std::optional<Hit>> batch = w.intersectBatch(rays);
    for (size_t i = 0; i < rays.size(); ++i) {
        const std::optional<Hit> h = w.intersect(rays[i]);
        ASSERT_TRUE(h.has_value());
        EXPECT_NE(std::find(containing[i].begin(), containing[i].end(), h->primitive), containing[i].end())
            << "ray " << i << " hit triangle " << h->primitive;
        EXPECT_TRUE(sameHit(h, batch[i])) << "ray " << i;
    }
}

TEST(CollisionWorld, BatchTracesBurstsAsSingleRaysOnTheGallery) {
    const CollisionWorld w = movedGallery();
    // Narrow bursts go into packets, wide ones ray by ray; burst sizes that are no multiple of a
    // packet width, and a burst of one.
    for (const double cone : {0.5, 2.0, 4.0, 9.0, 30.0})
        for (const size_t perBurst : {1u, 3u, 5u, 16u, 17u, 31u}) {
            std::vector<Ray> rays =
                bursts(40, perBurst, glm::dvec3(0.0, 1.5, -1.0), 6.0, 3.0, cone, 7 + perBurst);
            size_t hits = 0;
            ASSERT_TRUE(batchEqualsSingle(w, rays, hits)) << "cone " << cone << ", bursts of " << perBurst;
            EXPECT_GT(hits, rays.size() / 2) << "cone " << cone << ", bursts of " << perBurst;
        }
}

TEST(CollisionWorld, BatchSkipsInvalidRaysInsideBursts) {
    const CollisionWorld w = movedGallery();
    std::vector<Ray> rays = bursts(60, 16, glm::dvec3(0.0, 1.5, -1.0), 6.0, 3.0, 2.0, 5);
    std::vector<size_t> badAt;
    for (size_t at = 3; at < rays.size(); at += 37) {
        const std::vector<Ray> bad = invalidRays(rays[at]);
        rays.insert(rays.begin() + std::ptrdiff_t(at), bad.begin(), bad.end());
        for (size_t k = 0; k < bad.size(); ++k)
            badAt.push_back(at + k);
    }
    size_t hits = 0;
    ASSERT_TRUE(batchEqualsSingle(w, rays, hits));
    const std::vector<std::optional<Hit>> batch = w.intersectBatch(rays);
    for (size_t i : badAt)
        EXPECT_FALSE(batch[i].has_value()) << "ray " << i;
    EXPECT_GT(hits, rays.size() / 2);
}

TEST(CollisionWorld, BatchOfScatteredRaysEqualsSingleRaysOnTheGallery) {
    const CollisionWorld w = movedGallery();
    size_t hits = 0;
    ASSERT_TRUE(batchEqualsSingle(w, rayFan(5000, glm::dvec3(0.0, 1.5, -1.0), 8.0, 4.0, 31), hits));
    EXPECT_GT(hits, 2000u);
}

TEST(CollisionWorld, BatchEqualsSingleRaysOnASharedMesh) {
    SPATTER_REQUIRE_SHARED(path, "meshes/stanford-bunny.obj");
    Result<Scene> scene = loadScene(path);
    ASSERT_TRUE(scene.ok()) << scene.error();
    const CollisionWorld w = buildWorld(scene.value());
    const DBounds b = w.worldBounds(0);
    const double size = glm::length(b.max - b.min);
    for (const double cone : {1.0, 3.0, 10.0}) {
        size_t hits = 0;
        ASSERT_TRUE(batchEqualsSingle(w, bursts(200, 16, b.center(), 0.75 * size, 0.2 * size, cone, 3), hits))
            << "cone " << cone;
        EXPECT_GT(hits, 1600u) << "cone " << cone;
    }
    size_t hits = 0;
    ASSERT_TRUE(batchEqualsSingle(w, rayFan(3000, b.center(), 0.75 * size, 0.3 * size, 9), hits));
    EXPECT_GT(hits, 1000u);
}

TEST(CollisionWorld, BurstsAimedAtSharedVerticesAndEdgesNeverLeak) {
    // A closed sphere seen from near and far: bursts aimed exactly at the vertices of a triangle fan
    // and at the midpoints of its edges all hit, in the batch as alone.
    const Scene s = sphereScene(40, 80);
    const CollisionWorld w = buildWorld(s);
    const Mesh& m = *s.objects[0].mesh;
    size_t rays = 0;
    for (const double distance : {4.0, 50.0, 3e3})
        for (uint32_t centre = 0; centre < m.positions.size(); centre += 97) {
            const glm::dvec3 c(m.positions[centre]);
            const glm::dvec3 from = glm::normalize(c + glm::dvec3(0.05, -0.03, 0.02)) * distance;
            std::vector<Ray> burst;
            for (uint32_t t = 0; t < m.triangleCount(); ++t) {
                const uint32_t* tri = &m.indices[3 * t];
                if (tri[0] != centre && tri[1] != centre && tri[2] != centre) continue;
                for (int k = 0; k < 3; ++k) {
                    const glm::dvec3 a(m.positions[tri[k]]), b(m.positions[tri[(k + 1) % 3]]);
                    burst.push_back(ray(from, a - from));
                    burst.push_back(ray(from, 0.5 * (a + b) - from));
                }
            }
            size_t hits = 0;
            ASSERT_TRUE(batchEqualsSingle(w, burst, hits))
                << "vertex " << centre << ", distance " << distance;
            EXPECT_EQ(hits, burst.size()) << "vertex " << centre << ", distance " << distance;
            rays += burst.size();
        }
    EXPECT_GT(rays, 1000u);
}

TEST(CollisionWorld, EmptyBatchGivesNoHits) {
    const CollisionWorld w = buildWorld(boxScene());
    EXPECT_TRUE(w.intersectBatch({}).empty());
}

TEST(CollisionWorld, MovingADynamicObjectMovesItsHits) {
    CollisionWorld w = buildWorld(rangeScene(1));
    const uint32_t target = 2;
    const Ray atTarget = ray({0.0, 1.0, 5.0}, {0.0, 0.0, -1.0});
    std::optional<Hit> before = w.intersect(atTarget);
    ASSERT_TRUE(before.has_value());
    EXPECT_EQ(before->object, target);

    const glm::dmat4 moved = glm::translate(glm::dmat4(1.0), glm::dvec3(5.0, 1.0, 0.0)) *
                             (glm::inverse(glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 1.0, 0.0))) *
                              w.object(target)->transform);
    ASSERT_TRUE(w.setTransform(target, moved).ok());
    const std::optional<Hit> nowWall = w.intersect(atTarget);
    ASSERT_TRUE(nowWall.has_value());
    EXPECT_EQ(nowWall->object, 1u);
    const std::optional<Hit> after = w.intersect(ray({5.0, 1.0, 5.0}, {0.0, 0.0, -1.0}));
    ASSERT_TRUE(after.has_value());
    EXPECT_EQ(after->object, target);
    EXPECT_EQ(after->primitive, before->primitive);
    EXPECT_LT(glm::length(after->localPosition - before->localPosition), 1e-9);
    EXPECT_LT(glm::length(after->position - before->position - glm::dvec3(5.0, 0.0, 0.0)), 1e-9);
    EXPECT_TRUE(sameHit(after, w.intersectBatch({ray({5.0, 1.0, 5.0}, {0.0, 0.0, -1.0})})[0]));
}

TEST(CollisionWorld, SetTransformRejectsBadRequests) {
    CollisionWorld w = buildWorld(rangeScene(1));
    EXPECT_FALSE(w.setTransform(0, glm::dmat4(1.0)).ok()); // static floor
    EXPECT_FALSE(w.setTransform(7, glm::dmat4(1.0)).ok()); // out of range
    glm::dmat4 nan(1.0);
    nan[3][0] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(w.setTransform(2, nan).ok());
    EXPECT_FALSE(w.setTransform(2, glm::dmat4(0.0)).ok());
    glm::dmat4 projective(1.0);
    projective[0][3] = 0.5;
    EXPECT_FALSE(w.setTransform(2, projective).ok());
    const auto s = w.setTransform(0, glm::dmat4(1.0));
    EXPECT_NE(s.error().find("floor"), std::string::npos) << s.error();
}

TEST(CollisionWorld, RemovedObjectsLetRaysThrough) {
    CollisionWorld w = buildWorld(rangeScene(1));
    const Ray r = ray({0.0, 1.0, 5.0}, {0.0, 0.0, -1.0});
    ASSERT_EQ(w.intersect(r)->object, 2u);
    ASSERT_TRUE(w.removeObject(2).ok());
    EXPECT_EQ(w.intersect(r)->object, 1u);
    ASSERT_TRUE(w.removeObject(1).ok());
    EXPECT_FALSE(w.intersect(r).has_value());
    EXPECT_FALSE(w.removeObject(1).ok());
    EXPECT_FALSE(w.object(1)->inWorld);
    EXPECT_EQ(w.triangleCount(), w.object(0)->triangles);
}

TEST(CollisionWorld, NonReceiversAreNotInTheWorld) {
    Scene s = rangeScene(1);
    s.objects[2].receivesDecals = false;
    CollisionWorld w = buildWorld(s);
    EXPECT_FALSE(w.object(2)->inWorld);
    EXPECT_EQ(w.object(2)->triangles, 0u);
    EXPECT_EQ(w.intersect(ray({0.0, 1.0, 5.0}, {0.0, 0.0, -1.0}))->object, 1u);
    EXPECT_FALSE(w.setTransform(2, glm::dmat4(1.0)).ok());
    EXPECT_FALSE(w.worldBounds(2).empty()); // still known, from its render mesh
}

TEST(CollisionWorld, KeepsPrecisionFarFromTheOrigin) {
    const Scene near = rangeScene(3);
    const CollisionWorld wn = buildWorld(near);
    const std::vector<Ray> rays = rayFan(1500, glm::dvec3(2.0, 1.0, -1.0), 9.0, 4.0, 5);
    for (const glm::dvec3 offset :
         {glm::dvec3(1e5, 0.0, -2e5), glm::dvec3(1e7, 3e6, -4e7), glm::dvec3(-3e9, 1e8, 2e9)}) {
        Scene far = near;
        far.translate(offset);
        const CollisionWorld wf = buildWorld(far);
        size_t compared = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
            Ray r = rays[i];
            r.origin += offset;
            const std::optional<Hit> a = wn.intersect(rays[i]);
            const std::optional<Hit> b = wf.intersect(r);
            ASSERT_EQ(a.has_value(), b.has_value()) << "ray " << i;
            if (!a) continue;
            // Rays near an edge may pick the neighbouring triangle; they still land on the surface.
            ++compared;
            EXPECT_EQ(a->object, b->object) << "ray " << i;
            const double tolerance = 1e-5 + 4e-16 * glm::length(offset);
            EXPECT_LT(glm::length((b->position - offset) - a->position), tolerance) << "ray " << i;
            EXPECT_LT(glm::length(b->localPosition - a->localPosition), tolerance) << "ray " << i;
            EXPECT_LT(glm::length(b->normal - a->normal), 1e-4) << "ray " << i;
        }
        EXPECT_GT(compared, rays.size() / 3);
    }
}

TEST(CollisionWorld, RaysFromVeryFarAwayHitTheSamePoint) {
    const CollisionWorld w = buildWorld(rangeScene(2));
    const Ray nearRay = ray({0.3, 1.1, 6.0}, {0.0, 0.0, -1.0});
    const std::optional<Hit> a = w.intersect(nearRay);
    ASSERT_TRUE(a.has_value());
    Ray farRay = nearRay;
    farRay.origin.z += std::ldexp(1.0, 30); // 1e9 away, the sum exactly representable
    const std::optional<Hit> b = w.intersect(farRay);
    ASSERT_TRUE(b.has_value());
    EXPECT_EQ(a->object, b->object);
    EXPECT_EQ(a->primitive, b->primitive);
    EXPECT_LT(glm::length(a->position - b->position), 1e-6);
}

TEST(CollisionWorld, UsesAuthoredCollidersWithAMeasuredBound) {
    Scene s = boxScene();
    s.objects[0].collider = makeBox(glm::vec3(0.55f), 1);
    const CollisionWorld w = buildWorld(s);
    // The collider's corners lie sqrt(3) * 0.05 from the render box: the certified bound is at
    // least that, and at most 1% of the render box's diagonal (sqrt(3)) above it.
    EXPECT_GE(w.object(0)->errorBound, std::sqrt(3.0) * 0.05 - 1e-9);
    EXPECT_LE(w.object(0)->errorBound, std::sqrt(3.0) * (0.05 + 0.01) + 1e-6);
    EXPECT_EQ(w.object(0)->triangles, 12u);
    EXPECT_NEAR(w.intersect(ray({0.0, 0.1, 5.0}, {0.0, 0.0, -1.0}))->position.z, 0.55, 1e-6);

    WorldSettings renderOnly;
    renderOnly.useColliders = false;
    const CollisionWorld r = buildWorld(s, {}, renderOnly);
    EXPECT_EQ(r.object(0)->errorBound, 0.0);
    EXPECT_NEAR(r.intersect(ray({0.0, 0.1, 5.0}, {0.0, 0.0, -1.0}))->position.z, 0.5, 1e-12);
}

TEST(CollisionWorld, ProxiesReplaceMeshesAndCarryTheirBound) {
    Scene s = rangeScene(1);
    std::vector<std::shared_ptr<const Proxy>> proxies(s.objects.size());
    proxies[2] = shareProxy(makeProxy(makeSphere(0.8f, 8, 16), 0.125f));
    const CollisionWorld w = buildWorld(s, proxies);
    EXPECT_EQ(w.object(2)->errorBound, 0.125);
    EXPECT_EQ(w.object(2)->triangles, makeSphere(0.8f, 8, 16).triangleCount());
    // Target 0 is scaled by 0.5: h in world units halves.
    EXPECT_NEAR(w.worldErrorBound(2), 0.0625, 1e-12);
    EXPECT_EQ(w.worldErrorBound(0), 0.0);
    const std::optional<Hit> h = w.intersect(ray({0.0, 1.0, 5.0}, {0.0, 0.0, -1.0}));
    ASSERT_TRUE(h.has_value());
    EXPECT_EQ(h->object, 2u);
    EXPECT_NEAR(glm::length(h->localPosition), 0.8, 0.02);
}

// Under a shear (x moves by y) a distance in the object grows up to 1.618 times, farther than the
// longest column of the matrix (1.414) says: the bound in world units covers the stretch that power
// iteration finds.
TEST(CollisionWorld, WorldErrorBoundCoversTheStretchOfAShear) {
    Scene s = rangeScene(1);
    glm::dmat4 shear(1.0);
    shear[1][0] = 1.0;
    s.objects[2].transform = shear * s.objects[2].transform;
    std::vector<std::shared_ptr<const Proxy>> proxies(s.objects.size());
    proxies[2] = shareProxy(makeProxy(makeSphere(0.8f, 8, 16), 0.125f));
    const CollisionWorld w = buildWorld(s, proxies);
    const glm::dmat3 m(s.objects[2].transform);
    glm::dvec3 v(1.0, 0.3, 0.2);
    for (int i = 0; i < 200; ++i)
        v = glm::normalize(glm::transpose(m) * (m * v));
    const double stretch = glm::length(m * v);
    EXPECT_GT(stretch, 1.001 * std::max({glm::length(m[0]), glm::length(m[1]), glm::length(m[2])}));
    EXPECT_GE(w.worldErrorBound(2), 0.125 * stretch);
    EXPECT_LE(w.worldErrorBound(2), 0.125 * std::sqrt(3.0) * stretch);
}

TEST(CollisionWorld, RejectsBadProxiesAndScenes) {
    const Scene s = rangeScene(1);
    std::vector<std::shared_ptr<const Proxy>> wrongCount(2);
    EXPECT_FALSE(CollisionWorld::build(s, wrongCount).ok());

    std::vector<std::shared_ptr<const Proxy>> proxies(s.objects.size());
    proxies[1] = shareProxy(makeProxy(makeBox(glm::vec3(1.0f), 1), std::numeric_limits<float>::quiet_NaN()));
    Result<CollisionWorld> w = CollisionWorld::build(s, proxies);
    ASSERT_FALSE(w.ok());
    EXPECT_NE(w.error().find("wall"), std::string::npos) << w.error();

    Proxy badIndex = makeProxy(makeBox(glm::vec3(1.0f), 1), 0.0f);
    badIndex.mesh.indices[4] = 9999;
    proxies[1] = shareProxy(badIndex);
    w = CollisionWorld::build(s, proxies);
    ASSERT_FALSE(w.ok());
    EXPECT_NE(w.error().find("wall"), std::string::npos) << w.error();

    Scene bad = s;
    bad.objects[0].transform[1][1] = std::numeric_limits<double>::infinity();
    EXPECT_FALSE(CollisionWorld::build(bad).ok());
}

TEST(CollisionWorld, EmptyWorldHitsNothing) {
    Scene s = boxScene();
    s.objects[0].receivesDecals = false;
    const CollisionWorld w = buildWorld(s);
    EXPECT_EQ(w.triangleCount(), 0u);
    EXPECT_FALSE(w.intersect(ray({0.0, 0.0, 5.0}, {0.0, 0.0, -1.0})).has_value());
    EXPECT_FALSE(w.intersectBatch({ray({0.0, 0.0, 5.0}, {0.0, 0.0, -1.0})})[0].has_value());
}

TEST(CollisionWorld, ConcurrentQueriesAgreeWithSerialOnes) {
    const CollisionWorld w = buildWorld(rangeScene(4));
    const std::vector<Ray> rays = rayFan(2000, glm::dvec3(3.0, 1.0, 0.0), 10.0, 4.0, 3);
    std::vector<std::optional<Hit>> serial;
    for (const Ray& r : rays)
        serial.push_back(w.intersect(r));
    std::vector<std::vector<std::optional<Hit>>> out(4);
    std::vector<std::thread> threads;
    for (int k = 0; k < 4; ++k)
        threads.emplace_back([&, k] {
            if (k % 2 == 0)
                for (const Ray& r : rays)
                    out[k].push_back(w.intersect(r));
            else
                out[k] = w.intersectBatch(rays);
        });
    for (std::thread& t : threads)
        t.join();
    for (int k = 0; k < 4; ++k)
        for (size_t i = 0; i < rays.size(); ++i)
            ASSERT_TRUE(sameHit(serial[i], out[k][i])) << "thread " << k << " ray " << i;
}
