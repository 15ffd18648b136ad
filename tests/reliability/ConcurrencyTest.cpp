// Concurrency: the threading model of docs/PLACEMENT.md. Several threads spawn through every entry
// point while one moves the targets and another ages and removes decals; spawnBatch traces single
// rays and packets on several threads. Built with ThreadSanitizer by `./spatter test` (build-tsan),
// where a data race fails it.

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <atomic>
#include <cmath>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

using namespace spatter;

namespace {

constexpr int kTargets = 4;

glm::dmat4 targetTransform(int i, double time) {
    glm::dmat4 t =
        glm::translate(glm::dmat4(1.0), glm::dvec3(-3.0 + 2.0 * i + 0.5 * std::sin(time), 1.0, 0.0));
    t = glm::rotate(t, time + i, glm::dvec3(0.0, 1.0, 0.0));
    return glm::scale(t, glm::dvec3(1.0 + 0.25 * std::sin(time + i)));
}

// A static floor and wall, and kTargets dynamic unit boxes ([-0.5, 0.5]^3 in object space).
Scene rangeScene() {
    Scene s;
    s.source = "test:concurrency";
    s.objects.push_back(makeSceneObject("floor", makeBox(glm::vec3(8.0f, 0.1f, 8.0f), 4),
                                        glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, -0.1, 0.0))));
    s.objects.push_back(makeSceneObject("wall", makeBox(glm::vec3(8.0f, 2.0f, 0.1f), 4),
                                        glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 2.0, -4.0))));
    for (int i = 0; i < kTargets; ++i)
        s.objects.push_back(makeSceneObject("target_" + std::to_string(i), makeBox(glm::vec3(0.5f), 2),
                                            targetTransform(i, 0.0), true));
    return s;
}

// The system of the tests. Embree builds and commits its BVHs with TBB worker threads that
// synchronise in uninstrumented library code, which ThreadSanitizer cannot see (it reports their
// hand-offs as races); with one Embree thread every build runs in the calling thread, under the
// system's lock, and what ThreadSanitizer checks is spatter's own synchronisation.
Result<DecalSystem> makeSystem(const DecalSettings& settings) {
    WorldSettings world;
    world.deviceConfig = "threads=1";
    Result<CollisionWorld> built = CollisionWorld::build(rangeScene(), {}, world);
    if (!built) return fail(built.error());
    return DecalSystem::create(std::move(built).value(), settings);
}

Ray randomShot(Rng& rng) {
    const glm::dvec3 eye(rng.uniform(-4.0f, 4.0f), rng.uniform(0.5f, 2.5f), 6.0);
    const glm::dvec3 aim(rng.uniform(-4.0f, 4.0f), rng.uniform(0.0f, 2.0f), rng.uniform(-4.0f, 0.5f));
    return Ray{eye, aim - eye};
}

// `count` shots in groups of 8: every other group a shotgun burst, 8 rays from one point within about
// 2 degrees (spawnBatch traces those as Embree packets), the others 8 single shots.
std::vector<Ray> shotsAndBursts(Rng& rng, size_t count) {
    std::vector<Ray> rays(count);
    for (size_t i = 0; i < count; ++i) {
        const bool burst = (i / 8) % 2 == 1 && i % 8 != 0;
        if (!burst) {
            rays[i] = randomShot(rng);
            continue;
        }
        const Ray& first = rays[i - i % 8];
        const glm::dvec3 jitter(rng.uniform(-0.01f, 0.01f), rng.uniform(-0.01f, 0.01f),
                                rng.uniform(-0.01f, 0.01f));
        rays[i] = Ray{first.origin, glm::normalize(first.direction) + jitter};
    }
    return rays;
}

// What one spawning thread saw.
struct Tally {
    uint64_t placed = 0, rejected = 0, removed = 0;
    void add(const SpawnResult& r) { r.placed() ? placed++ : rejected++; }
};

} // namespace

TEST(Concurrency, ThreadsSpawnWhileObjectsMoveAndDecalsAge) {
    DecalSettings settings;
    settings.seed = 5;
    settings.maxPerCell = 8;
    settings.budget = 1500;
    settings.batchThreads = 2;
    Result<DecalSystem> created = makeSystem(settings);
    ASSERT_TRUE(created) << created.error();
    DecalSystem& sys = created.value();
    DecalType hole, splat;
    hole.name = "hole";
    hole.lifetime = 0.5f;
    hole.fadeOutTime = 0.1f;
    splat.name = "splat";
    splat.size = {0.4f, 0.4f};
    splat.sizeJitter = 0.2f;
    const uint16_t holeType = sys.registerType(hole).value();
    const uint16_t splatType = sys.registerType(splat).value();

    constexpr int kSpawners = 3;
    constexpr int kRounds = 600;
    std::vector<Tally> tallies(kSpawners);
    std::atomic<int> spawnersDone{0};
    std::atomic<uint64_t> moves{0};
    std::vector<std::thread> threads;
    for (int k = 0; k < kSpawners; ++k) {
        threads.emplace_back([&, k] {
            Rng rng(100 + uint64_t(k));
            Tally& tally = tallies[size_t(k)];
            std::vector<Ray> rays;
            std::vector<SpawnResult> results;
            std::vector<DecalHandle> mine;
            for (int round = 0; round < kRounds; ++round) {
                if (round == kRounds / 2) // make sure the objects move while spawning goes on
                    while (moves.load() < 2)
                        std::this_thread::yield();
                const uint16_t type = (round + k) % 2 ? holeType : splatType;
                const SpawnResult shot = sys.spawn(randomShot(rng), type);
                tally.add(shot);
                if (shot.placed()) mine.push_back(shot.handle);
                const uint32_t target = 2 + rng.below(kTargets);
                tally.add(sys.spawnAttached(target,
                                            {0.5f, rng.uniform(-0.4f, 0.4f), rng.uniform(-0.4f, 0.4f)},
                                            {1.0f, 0.0f, 0.0f}, type));
                tally.add(sys.spawnAt({rng.uniform(-6.0f, 6.0f), 0.0, rng.uniform(-3.0f, 3.0f)},
                                      {0.0, 1.0, 0.0}, type));
                if (round % 10 == 0) {
                    rays = shotsAndBursts(rng, 64);
                    sys.spawnBatch(rays, type, results);
                    for (const SpawnResult& r : results)
                        tally.add(r);
                }
                if (round % 7 == 0 && !mine.empty()) {
                    tally.removed += sys.remove(mine[rng.below(uint32_t(mine.size()))]) ? 1 : 0;
                }
            }
            spawnersDone++;
        });
    }
    threads.emplace_back([&] { // the mover
        double time = 0.0;
        do {
            time += 0.01;
            for (int i = 0; i < kTargets; ++i)
                EXPECT_TRUE(sys.setTransform(uint32_t(2 + i), targetTransform(i, time)).ok());
            moves++;
            std::this_thread::yield();
        } while (spawnersDone.load() < kSpawners);
    });
    threads.emplace_back([&] { // the game loop's clock
        while (spawnersDone.load() < kSpawners) {
            EXPECT_TRUE(sys.update(1.0 / 60.0).ok());
            std::this_thread::yield();
        }
    });
    for (std::thread& t : threads)
        t.join();

    // Every mutation is done: the const calls may look now.
    uint64_t placed = 0, rejected = 0;
    for (const Tally& t : tallies) {
        placed += t.placed;
        rejected += t.rejected;
    }
    const DecalStats& st = sys.stats();
    EXPECT_GE(moves.load(), 2u);
    EXPECT_GT(placed, uint64_t(kSpawners * kRounds));
    EXPECT_EQ(st.placed, placed);
    EXPECT_EQ(st.rejectedTotal(), rejected);
    EXPECT_EQ(st.alive, sys.decals().size());
    EXPECT_EQ(st.placed, st.alive - st.fading + st.evicted + st.expired + st.removed);
    EXPECT_LE(st.alive - st.fading, settings.budget);
    size_t onTargets = 0;
    for (const Decal& d : sys.decals()) {
        ASSERT_LT(d.object, 2u + kTargets);
        EXPECT_LT(frameError(d.frame()), 1e-4f);
        EXPECT_TRUE(std::isfinite(d.size.x) && d.size.x > 0.0f && std::isfinite(d.halfDepth) &&
                    d.halfDepth > 0.0f);
        if (d.object < 2) continue;
        // A decal on a target lies on the box surface in the target's space, wherever the target was
        // when the decal landed (the spawn traced and placed under one lock).
        const glm::vec3 a = glm::abs(d.center);
        EXPECT_NEAR(std::max({a.x, a.y, a.z}), 0.5f, 1e-4f)
            << d.center.x << " " << d.center.y << " " << d.center.z;
        onTargets++;
    }
    EXPECT_GT(onTargets, 0u);
}

TEST(Concurrency, ThreadedSpawnBatchEqualsSerialBitForBit) {
    Rng rng(9);
    const std::vector<Ray> rays = shotsAndBursts(rng, 20000);
    std::vector<std::vector<Decal>> decals;
    std::vector<DecalStats> stats;
    for (uint32_t threads : {1u, 0u, 3u}) {
        DecalSettings settings;
        settings.seed = 3;
        settings.maxPerCell = 4;
        settings.budget = 5000;
        settings.batchThreads = threads;
        Result<DecalSystem> sys = makeSystem(settings);
        ASSERT_TRUE(sys) << sys.error();
        DecalType t;
        t.name = "t";
        t.sizeJitter = 0.3f;
        const uint16_t type = sys->registerType(t).value();
        std::vector<SpawnResult> results;
        sys->spawnBatch(rays, type, results);
        ASSERT_EQ(results.size(), rays.size());
        decals.push_back(sys->decals());
        stats.push_back(sys->stats());
    }
    for (size_t k = 1; k < decals.size(); ++k) {
        EXPECT_EQ(stats[k], stats[0]);
        ASSERT_EQ(decals[k].size(), decals[0].size());
        for (size_t i = 0; i < decals[0].size(); ++i) {
            const Decal &a = decals[0][i], &b = decals[k][i];
            ASSERT_EQ(a.packedFrame, b.packedFrame) << i;
            ASSERT_EQ(std::memcmp(&a.center, &b.center, sizeof a.center), 0) << i;
            ASSERT_EQ(a.id, b.id) << i;
            ASSERT_EQ(a.size, b.size) << i;
            ASSERT_EQ(a.halfDepth, b.halfDepth) << i;
        }
    }
    EXPECT_GT(stats[0].placed, 10000u);
}
