// Placement on real scenes: builtin:gallery and the third-party meshes in ../shared/data.

#include "PlacementTestUtil.hpp"
#include "TestData.hpp"

#include "spatter/core/SceneLoader.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <gtest/gtest.h>

using namespace spatter;
using namespace spatter::test;

namespace {

Scene load(const std::string& source) {
    Result<Scene> s = loadScene(source);
    EXPECT_TRUE(s.ok()) << s.error();
    return s.ok() ? std::move(s).value() : Scene{};
}

// Rays from a camera at `eye` through a w x h grid spanning `fovDeg` degrees around -Z.
std::vector<Ray> cameraRays(const glm::dvec3& eye, int w, int h, double fovDeg) {
    std::vector<Ray> rays;
    const double half = std::tan(0.5 * fovDeg * 3.14159265358979323846 / 180.0);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            Ray r;
            r.origin = eye;
            r.direction =
                glm::dvec3(half * (2.0 * (i + 0.5) / w - 1.0), half * (2.0 * (j + 0.5) / h - 1.0), -1.0);
            rays.push_back(r);
        }
    return rays;
}

} // namespace

TEST(PlacementOnGallery, ShotsFromTheCameraPlaceGoodDecals) {
    const Scene scene = load("builtin:gallery");
    ASSERT_FALSE(scene.objects.empty());
    DecalSettings settings;
    settings.maxPerCell = 1000;
    DecalSystem single = makeSystem(scene, settings), batch = makeSystem(scene, settings);
    DecalType t = plainType("hole", glm::vec2(0.15f));
    t.sizeJitter = 0.2f;
    single.registerType(t);
    batch.registerType(t);
    const std::vector<Ray> rays = cameraRays(glm::dvec3(0.0, 1.6, 7.0), 48, 32, 70.0);

    std::vector<SpawnResult> batchResults;
    batch.spawnBatch(rays, 0, batchResults);
    size_t placed = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const SpawnResult r = single.spawn(rays[i], 0);
        ASSERT_EQ(r.status, batchResults[i].status) << "ray " << i;
        if (!r.placed()) continue;
        ++placed;
        const Decal& d = *single.get(r.handle);
        const WorldDecal w = single.worldBox(d);
        EXPECT_LE(frameError(d.frame()), 1e-6f);
        EXPECT_LE(frameError(w.frame), 1e-6f);
        // The centre lies on the ray, the normal faces the camera.
        const glm::dvec3 u = glm::normalize(rays[i].direction);
        const glm::dvec3 toCenter = w.center - rays[i].origin;
        EXPECT_LT(glm::length(toCenter - u * glm::dot(toCenter, u)), 1e-4) << "ray " << i;
        EXPECT_LT(glm::dot(glm::dvec3(w.frame.normal), u), 0.0);
        const SceneObject& o = scene.objects[d.object];
        EXPECT_EQ(d.objectId, o.dynamic ? single.objectId(d.object) : 0);
    }
    EXPECT_GT(placed, rays.size() / 2);
    EXPECT_TRUE(sameDecals(single.decals(), batch.decals()));
    EXPECT_EQ(single.stats(), batch.stats());

    // Targets (the dynamic objects) have non-zero IDs; static objects 0; objectIds() lists them all.
    const std::vector<uint8_t> ids = single.objectIds();
    ASSERT_EQ(ids.size(), scene.objects.size());
    size_t dynamic = 0;
    for (uint32_t i = 0; i < scene.objects.size(); ++i) {
        EXPECT_EQ(ids[i], single.objectId(i)) << scene.objects[i].name;
        if (scene.objects[i].dynamic) {
            ++dynamic;
            EXPECT_NE(single.objectId(i), 0) << scene.objects[i].name;
        } else {
            EXPECT_EQ(single.objectId(i), 0) << scene.objects[i].name;
        }
    }
    EXPECT_GT(dynamic, 0u);
}

TEST(PlacementOnSharedData, FandiskHitsMatchRawEmbree) {
    SPATTER_REQUIRE_SHARED(path, "meshes/fandisk.obj");
    const Scene scene = load(path);
    ASSERT_EQ(scene.objects.size(), 1u);
    const RawEmbree tracer(scene);
    DecalSystem s = makeSystem(scene);
    DecalType t = plainType("hole", glm::vec2(0.02f));
    t.maxAngleDeg = 90.0f;
    s.registerType(t);
    const DBounds b = scene.worldBounds();
    const std::vector<Ray> rays = rayFan(3000, b.center(), 2.0 * b.diagonal(), 0.3 * b.diagonal(), 21);
    size_t hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const auto raw = tracer.intersect(rays[i]);
        const std::optional<Hit> h = s.world().intersect(rays[i]);
        ASSERT_EQ(h.has_value(), raw.has_value()) << "ray " << i;
        const SpawnResult r = s.spawn(rays[i], 0);
        ASSERT_EQ(r.placed(), h.has_value()) << "ray " << i << ": " << r.reason;
        if (!h) continue;
        ++hits;
        EXPECT_EQ(h->primitive, raw->primitive) << "ray " << i;
        EXPECT_NEAR(h->t, raw->t, 1e-5 * raw->t) << "ray " << i;
        const WorldDecal w = *s.worldBox(r.handle);
        EXPECT_LT(glm::length(w.center - h->position), 1e-5 * b.diagonal());
        EXPECT_LT(glm::length(glm::dvec3(w.frame.normal) - h->normal), kPackedFrameError);
        EXPECT_LE(frameError(w.frame), 1e-6f);
    }
    EXPECT_GT(hits, rays.size() / 4);
}

TEST(PlacementOnSharedData, DuckDecalsHaveWorldSizesDespiteTheRootScale) {
    SPATTER_REQUIRE_SHARED(path, "gltf/Duck/Duck.glb");
    const Scene scene = load(path);
    DecalSettings settings;
    settings.maxPerCell = 1000; // every decal stays alive
    DecalSystem s = makeSystem(scene, settings);
    s.registerType(plainType("hole", glm::vec2(0.05f, 0.03f)));
    const DBounds b = scene.worldBounds();
    const std::vector<Ray> rays = rayFan(400, b.center(), 3.0, 0.3, 4);
    std::vector<SpawnResult> results;
    s.spawnBatch(rays, 0, results);
    size_t placed = 0;
    for (const SpawnResult& r : results) {
        if (!r.placed()) continue;
        ++placed;
        ASSERT_NE(s.get(r.handle), nullptr);
        const Decal& d = *s.get(r.handle);
        const WorldDecal w = s.worldBox(d);
        EXPECT_NEAR(w.size.x, 0.05f, 1e-6f);
        EXPECT_NEAR(w.size.y, 0.03f, 1e-6f);
        EXPECT_NEAR(w.halfDepth, 0.25f * 0.05f, 1e-6f);
        EXPECT_NEAR(d.size.x, 5.0f, 1e-4f); // object space is 100 times larger
        EXPECT_LE(frameError(d.frame()), 1e-6f);
        EXPECT_LE(frameError(w.frame), 1e-6f);
    }
    EXPECT_GT(placed, 100u);
}
