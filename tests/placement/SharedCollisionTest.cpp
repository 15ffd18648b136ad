// The collision world's objects that place one mesh many times: they take the first one's collision
// mesh, measured bound and drawn normals, and dynamic ones, and static ones placed four times or more,
// trace one Embree scene. Each is compared with a world that measures and builds every object on its
// own (each render mesh given spare copies of a vertex that no triangle uses: the same surface, not
// the same input bit for bit).

#include "PlacementTestUtil.hpp"
#include "ReferenceGeometry.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/placement/CollisionWorld.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace spatter;
using namespace spatter::test;

namespace {

// `scene` with object i's render mesh given i + 1 unused copies of its first vertex.
Scene unshared(Scene scene) {
    for (size_t i = 0; i < scene.objects.size(); ++i)
        scene.objects[i].mesh = shareMesh(withUnusedVertices(*scene.objects[i].mesh, i + 1));
    return scene;
}

// A bumpy sphere with a coarse sphere as its authored collider, placed twice as static and three
// times as dynamic objects, turned and scaled, over a static floor, and a dynamic box of its own.
Scene bumpyInstances() {
    Scene s;
    s.source = "test:instances";
    s.objects.push_back(makeSceneObject("floor", makeBox(glm::vec3(12.0f, 0.1f, 4.0f), 2),
                                        glm::translate(glm::dmat4(1.0), glm::dvec3(5.0, -1.2, 0.0))));
    Mesh bumpy = makeSphere(1.0f, 24, 48);
    displace(bumpy, [](const glm::vec3& p, const glm::vec3&) {
        return 0.06f * std::sin(7.0f * p.x) * std::cos(5.0f * p.y + 2.0f * p.z);
    });
    for (int i = 0; i < 5; ++i) {
        glm::dmat4 t = glm::translate(glm::dmat4(1.0), glm::dvec3(2.5 * i, 0.0, 0.0));
        t = glm::rotate(t, 0.4 * i, glm::normalize(glm::dvec3(0.3, 1.0, 0.2)));
        t = glm::scale(t, glm::dvec3(0.8 + 0.1 * i));
        SceneObject o = makeSceneObject("bumpy_" + std::to_string(i), bumpy, t, i >= 2);
        o.collider = makeSphere(1.02f, 6, 12);
        s.objects.push_back(std::move(o));
    }
    s.objects.push_back(makeSceneObject("box", makeBox(glm::vec3(0.7f), 2),
                                        glm::translate(glm::dmat4(1.0), glm::dvec3(5.0, 2.5, 0.0)), true));
    return s;
}

// The proxy of bumpyInstances' sphere at `tolerance` (a fraction of its diagonal).
Result<Proxy> bumpyProxy(const Scene& scene, float tolerance) {
    ProxySettings ps;
    ps.tolerance = tolerance;
    ps.smallMeshTriangles = 0;
    return buildProxy(*scene.objects[1].mesh, ps);
}

// Every ray of `rays` hits `a` as it hits `b`, bit for bit, and where the drawn surface's normal is
// known it is the same; returns the hits.
size_t sameHitsAndNormals(const CollisionWorld& a, const CollisionWorld& b, const std::vector<Ray>& rays) {
    size_t hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const std::optional<Hit> ha = a.intersect(rays[i]), hb = b.intersect(rays[i]);
        EXPECT_TRUE(sameHit(ha, hb)) << "ray " << i;
        if (!ha || !hb) continue;
        ++hits;
        const std::optional<glm::dvec3> na = a.drawnNormalAt(ha->object, ha->primitive, ha->localPosition);
        const std::optional<glm::dvec3> nb = b.drawnNormalAt(hb->object, hb->primitive, hb->localPosition);
        EXPECT_EQ(na.has_value(), nb.has_value()) << "ray " << i;
        if (na && nb) {
            EXPECT_EQ(*na, *nb) << "ray " << i;
        }
    }
    return hits;
}

// Rays at object `object` of `w` from every side.
std::vector<Ray> raysAt(const CollisionWorld& w, uint32_t object, uint64_t seed) {
    return rayFan(400, w.worldBounds(object).center(), 6.0, 1.2, seed);
}

// A ray from in front of object `object` of `w` (+z) enters it, inside its own bounds: each object is
// traced with its own triangles, whatever it shares.
::testing::AssertionResult hitsFromTheFront(const CollisionWorld& w, uint32_t object) {
    const DBounds b = w.worldBounds(object);
    const std::optional<Hit> h = w.intersect(ray(b.center() + glm::dvec3(0.0, 0.0, 10.0), {0.0, 0.0, -1.0}));
    if (!h || h->object != object) return ::testing::AssertionFailure() << "object " << object << " not hit";
    if (!h->frontFace) return ::testing::AssertionFailure() << "object " << object << " entered from behind";
    const glm::dvec3 pad(1e-6);
    if (glm::any(glm::lessThan(h->position, b.min - pad)) ||
        glm::any(glm::greaterThan(h->position, b.max + pad)))
        return ::testing::AssertionFailure() << "object " << object << " hit outside its bounds";
    return ::testing::AssertionSuccess();
}

} // namespace

TEST(SharedCollision, InstancesOfAMeshAndColliderTraceAsIfEachWereMeasuredAlone) {
    const Scene scene = bumpyInstances();
    const CollisionWorld shared = buildWorld(scene);
    const CollisionWorld alone = buildWorld(unshared(scene));
    for (uint32_t i = 1; i <= 5; ++i) { // the bumpy spheres
        EXPECT_GT(shared.object(i)->errorBound, 0.0) << i;
        EXPECT_EQ(shared.object(i)->errorBound, alone.object(i)->errorBound) << i;
        EXPECT_EQ(shared.object(i)->meshHash, shared.object(1)->meshHash) << i;
        EXPECT_EQ(shared.object(i)->collisionMeshOf, 1u) << i;
        EXPECT_EQ(alone.object(i)->collisionMeshOf, i) << i;
        EXPECT_EQ(shared.object(i)->instanced, i >= 3) << i; // two static copies stay in the static scene
        EXPECT_EQ(shared.object(i)->triangles, alone.object(i)->triangles) << i;
        EXPECT_GT(sameHitsAndNormals(shared, alone, raysAt(shared, i, 40 + i)), 100u) << i;
    }
    for (uint32_t i = 1; i < shared.objectCount(); ++i) // the spheres and the box of its own
        EXPECT_TRUE(hitsFromTheFront(shared, i));
}

TEST(SharedCollision, InstancesGivenEqualProxiesTraceAsIfEachWereGivenItsOwn) {
    const Scene scene = bumpyInstances();
    Result<Proxy> built = bumpyProxy(scene, 0.005f);
    ASSERT_TRUE(built.ok()) << built.error();
    Result<Proxy> coarser = bumpyProxy(scene, 0.03f);
    ASSERT_TRUE(coarser.ok()) << coarser.error();
    ASSERT_NE(coarser->mesh.triangleCount(), built->mesh.triangleCount());
    // The bumpy spheres, each given a copy: the first three of one proxy, the last two of another.
    std::vector<std::shared_ptr<const Proxy>> proxies(scene.objects.size());
    for (size_t i = 1; i <= 5; ++i)
        proxies[i] = shareProxy(i <= 3 ? built.value() : coarser.value());
    const CollisionWorld shared = buildWorld(scene, proxies);
    const CollisionWorld alone = buildWorld(unshared(scene), proxies);
    for (uint32_t i = 1; i <= 5; ++i) {
        EXPECT_EQ(shared.object(i)->errorBound, proxies[i]->errorBound) << i;
        EXPECT_EQ(shared.object(i)->triangles, proxies[i]->mesh.triangleCount()) << i;
        EXPECT_GT(sameHitsAndNormals(shared, alone, raysAt(shared, i, 80 + i)), 100u) << i;
    }
}

TEST(SharedCollision, InstancesGivenOneProxyTraceAsIfEachWereGivenACopy) {
    const Scene scene = bumpyInstances();
    Result<Proxy> built = bumpyProxy(scene, 0.005f);
    ASSERT_TRUE(built.ok()) << built.error();
    // The bumpy spheres handed one entry, as proxySources hands it out, and each a copy of its own.
    const std::shared_ptr<const Proxy> one = shareProxy(built.value());
    std::vector<std::shared_ptr<const Proxy>> handed(scene.objects.size()), copies(scene.objects.size());
    for (size_t i = 1; i <= 5; ++i) {
        handed[i] = one;
        copies[i] = shareProxy(built.value());
    }
    const CollisionWorld shared = buildWorld(scene, handed);
    const CollisionWorld apart = buildWorld(unshared(scene), copies);
    for (uint32_t i = 1; i <= 5; ++i) {
        EXPECT_EQ(shared.object(i)->collisionMeshOf, 1u) << i;
        EXPECT_EQ(shared.object(i)->errorBound, one->errorBound) << i;
        EXPECT_EQ(shared.object(i)->triangles, one->mesh.triangleCount()) << i;
        EXPECT_GT(sameHitsAndNormals(shared, apart, raysAt(shared, i, 90 + i)), 100u) << i;
    }
}

TEST(SharedCollision, DynamicInstancesMoveAndLeaveTheirSharedSceneOneByOne) {
    const Scene scene = bumpyInstances();
    CollisionWorld shared = buildWorld(scene);
    CollisionWorld alone = buildWorld(unshared(scene));
    const std::vector<glm::dvec3> where = {shared.worldBounds(3).center(), shared.worldBounds(4).center(),
                                           shared.worldBounds(5).center()};
    // The first of the dynamic instances, whose triangles the others trace, goes far away (the
    // world's boxes grow for the rays that reach it there); the second leaves; the third turns.
    const glm::dmat4 far =
        glm::translate(glm::dmat4(1.0), glm::dvec3(4e4, 300.0, -2e4)) * scene.objects[3].transform;
    const glm::dmat4 turned = glm::rotate(scene.objects[5].transform, 0.9, glm::dvec3(0.0, 0.0, 1.0));
    for (CollisionWorld* w : {&shared, &alone}) {
        ASSERT_TRUE(w->setTransform(3, far).ok());
        ASSERT_TRUE(w->removeObject(4).ok());
        ASSERT_TRUE(w->setTransform(5, turned).ok());
    }
    EXPECT_GT(sameHitsAndNormals(shared, alone, raysAt(shared, 3, 7)), 100u);
    EXPECT_GT(sameHitsAndNormals(shared, alone, raysAt(shared, 5, 8)), 100u);
    for (size_t k = 0; k < where.size(); ++k)
        sameHitsAndNormals(shared, alone, rayFan(300, where[k], 6.0, 1.2, 20 + k));
    const std::optional<Hit> there =
        shared.intersect(ray(where[1] + glm::dvec3(0.0, 0.0, 5.0), {0.0, 0.0, -1.0}));
    EXPECT_TRUE(!there || there->object != 4u);
}

TEST(SharedCollision, StaticCopiesTracedAsInstancesHitWhereTheStaticSceneDoes) {
    Scene scene = bumpyInstances();
    for (SceneObject& o : scene.objects)
        o.dynamic = false;
    const CollisionWorld instanced = buildWorld(scene), flat = buildWorld(unshared(scene));
    for (uint32_t i = 1; i <= 5; ++i) { // the bumpy spheres
        EXPECT_EQ(instanced.object(i)->errorBound, flat.object(i)->errorBound) << i;
        EXPECT_TRUE(instanced.object(i)->instanced) << i;
        EXPECT_FALSE(flat.object(i)->instanced) << i;
        const std::vector<Ray> rays = raysAt(instanced, i, 60 + i);
        size_t hits = 0, samePrimitive = 0;
        for (size_t r = 0; r < rays.size(); ++r) {
            const std::optional<Hit> a = instanced.intersect(rays[r]), b = flat.intersect(rays[r]);
            ASSERT_EQ(a.has_value(), b.has_value()) << "object " << i << ", ray " << r;
            if (!a) continue;
            ++hits;
            EXPECT_EQ(a->object, b->object) << "object " << i << ", ray " << r;
            // Rays near an edge may take the neighbouring triangle: they land on the same surface.
            EXPECT_LT(glm::length(a->position - b->position), 1e-5) << "object " << i << ", ray " << r;
            if (a->primitive != b->primitive) continue;
            ++samePrimitive;
            EXPECT_LT(glm::length(a->localPosition - b->localPosition), 1e-12)
                << "object " << i << ", ray " << r;
        }
        EXPECT_GT(hits, 100u) << i;
        EXPECT_GT(samePrimitive, hits * 99 / 100) << i;
    }
    // Copies taken out of the world let rays through, the first one (whose triangles the scene
    // holds) too; the others stay.
    CollisionWorld w = buildWorld(scene);
    for (uint32_t gone : {2u, 1u}) {
        const Ray down = ray(w.worldBounds(gone).center() + glm::dvec3(0.0, 5.0, 0.0), {0.0, -1.0, 0.0});
        ASSERT_EQ(w.intersect(down)->object, gone);
        ASSERT_TRUE(w.removeObject(gone).ok());
        EXPECT_EQ(w.intersect(down)->object, 0u); // the floor under it
    }
    const Ray atAnother = ray(w.worldBounds(4).center() + glm::dvec3(0.0, 0.0, 5.0), {0.0, 0.0, -1.0});
    EXPECT_EQ(w.intersect(atAnother)->object, 4u);
    EXPECT_EQ(w.triangleCount(),
              flat.triangleCount() - flat.object(1)->triangles - flat.object(2)->triangles);
}
