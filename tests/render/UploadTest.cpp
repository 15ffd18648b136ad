// What reaches the GPU when decals change (DecalSystem's change list given to updateDecals): a batch
// of 100,000 spawns goes up in one upload, a later batch in one upload of its own records, and one
// more spawn sends only its own record.

#include "ForeignHost.hpp"
#include "RenderTestSupport.hpp"
#include "TestData.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/render/DecalProjector.hpp"

#include <gtest/gtest.h>

#include <cstdio>

using namespace spatter;

namespace {

constexpr int kShots = 100000;

} // namespace

TEST(Upload, ABatchOf100000SpawnsReachesTheGpuInOneUpload) {
    SPATTER_REQUIRE_GL(gl);
    Scene scene;
    scene.objects.push_back(
        makeSceneObject("floor", makeGrid({-200.0f, 200.0f}, {-200.0f, 200.0f}), glm::dmat4(1.0)));
    DecalSettings settings;
    settings.budget = 2 * kShots;
    settings.maxPerCell = 2 * kShots;
    settings.maxPerObject = 2 * kShots;
    Result<DecalSystem> sys = DecalSystem::create(scene, settings);
    ASSERT_TRUE(sys.ok()) << sys.error();
    DecalType type;
    type.name = "mark";
    const uint16_t t = sys->registerType(type).value();
    std::vector<Ray> rays;
    for (int i = 0; i < kShots; ++i)
        rays.push_back(
            Ray{{-150.0 + 300.0 * (i % 316) / 316.0, 5.0, -150.0 + 300.0 * (i / 316) / 316.0}, {0, -1, 0}});
    std::vector<SpawnResult> results;
    sys->spawnBatch(rays, t, results);
    ASSERT_EQ(sys->decals().size(), size_t(kShots));

    Result<test::ForeignHost> host = test::ForeignHost::create(64, 48);
    ProjectorSettings projectorSettings;
    projectorSettings.waitForTimers = true; // this draw's counts, also when the GPU culls
    Result<DecalProjector> projector = DecalProjector::create(projectorSettings);
    ASSERT_TRUE(host.ok() && projector.ok());
    host->setScene(scene);
    const std::vector<glm::dmat4> transforms = {glm::dmat4(1.0)};
    const std::vector<uint8_t> ids = {0};
    const Camera camera = test::lookAt({0.0, 3.0, 0.5}, {0.0, 0.0, 0.0}); // a few decals in view
    host->draw(transforms, ids, camera);
    ASSERT_TRUE(projector->setObjects(transforms, ids).ok());
    projector->setDecalTypes({type});
    projector->updateDecals(sys->decals(), sys->changesSince(0));
    uint64_t version = sys->version();
    Result<ProjectorStats> first = projector->draw(host->frame(camera, false));
    ASSERT_TRUE(first.ok()) << first.error();
    ASSERT_GT(first->drawn, 0u);
    EXPECT_EQ(first->instanceUploads, 1u);
    EXPECT_GE(first->bytesUploaded, size_t(kShots) * 44u);

    // A second batch into a buffer that already has room: still one upload, of the new records only.
    std::vector<Ray> more(rays.begin(), rays.begin() + 20000);
    for (Ray& r : more)
        r.origin.x += 0.25;
    sys->spawnBatch(more, t, results);
    ASSERT_EQ(sys->decals().size(), size_t(kShots + 20000));
    projector->updateDecals(sys->decals(), sys->changesSince(version));
    version = sys->version();
    Result<ProjectorStats> batch = projector->draw(host->frame(camera, false));
    ASSERT_TRUE(batch.ok()) << batch.error();
    EXPECT_EQ(batch->instanceUploads, 1u);
    EXPECT_GE(batch->bytesUploaded, size_t(20000) * 44u);
    // The 44-byte records and their draw-order entries: 4 bytes each in a run, 8 (place and entry)
    // where the GPU culls and the order's changes go as writes.
    EXPECT_LT(batch->bytesUploaded, size_t(20000) * (44u + 8u) + 65536u);

    ASSERT_TRUE(sys->spawn(Ray{{0.1, 5.0, 0.1}, {0, -1, 0}}, t).placed());
    projector->updateDecals(sys->decals(), sys->changesSince(version));
    Result<ProjectorStats> second = projector->draw(host->frame(camera, false));
    ASSERT_TRUE(second.ok()) << second.error();
    EXPECT_EQ(second->instanceUploads, 1u);
    EXPECT_LT(second->bytesUploaded, 4096u) << "only the new record and the visible list";
    std::printf(
        "100,000 spawns: %zu upload(s), %zu bytes; 20,000 more: %zu, %zu bytes; one more: %zu, %zu bytes\n",
        first->instanceUploads, first->bytesUploaded, batch->instanceUploads, batch->bytesUploaded,
        second->instanceUploads, second->bytesUploaded);
}
