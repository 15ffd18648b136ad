// Soak: a long session of spawns under area limits, budgets and lifetimes, with moving targets.
// The stats must stay consistent at every frame and memory must stop growing once the budget is
// reached. SPATTER_SOAK_SPAWNS sets the number of spawns (default: a CI-sized run);
// docs/RELIABILITY.md records a run of ten million.

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/ProcessMemory.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#ifdef SPATTER_ASAN
#include <sanitizer/lsan_interface.h>
#endif

using namespace spatter;

namespace {

uint64_t soakSpawns(uint64_t ciDefault) {
    const char* env = std::getenv("SPATTER_SOAK_SPAWNS");
    if (env && *env) return std::strtoull(env, nullptr, 10);
#ifdef SPATTER_ASAN
    return ciDefault / 4;
#else
    return ciDefault;
#endif
}

glm::dmat4 targetTransform(int i, double time) {
    glm::dmat4 t =
        glm::translate(glm::dmat4(1.0), glm::dvec3(-6.0 + 3.0 * i + std::sin(time + i), 1.0, -2.0));
    return glm::rotate(t, 0.7 * time + i, glm::dvec3(0.0, 1.0, 0.0));
}

// A floor, a back wall, and four dynamic targets that move every frame.
Scene soakScene() {
    Scene s;
    s.source = "test:soak";
    s.objects.push_back(makeSceneObject("floor", makeBox(glm::vec3(12.0f, 0.1f, 12.0f), 8),
                                        glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, -0.1, 0.0)), false));
    s.objects.push_back(makeSceneObject("wall", makeBox(glm::vec3(12.0f, 3.0f, 0.1f), 8),
                                        glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 3.0, -8.0)), false));
    for (int i = 0; i < 4; ++i)
        s.objects.push_back(makeSceneObject("target_" + std::to_string(i), makeSphere(0.6f, 12, 24),
                                            targetTransform(i, 0.0), true));
    return s;
}

struct SoakFigures {
    uint64_t spawns = 0;
    uint64_t frames = 0;
    size_t maxAlive = 0;
    size_t maxCounted = 0;   // alive - fading
    size_t residentWarm = 0; // resident size once the budget had been reached
    size_t residentPeak = 0; // largest resident size sampled after that
    size_t heapWarm = 0;     // heap in use once the budget had been reached
    size_t heapPeak = 0;     // largest heap in use sampled after that
    double seconds = 0.0;
};

// Runs `spawns` spawns (batches of 512 rays from a moving shooter, a few single spawns) at 60
// frames per second of simulated time with `perFrame` spawns a frame, checking the stats every frame.
SoakFigures soak(DecalSystem& sys, const std::vector<uint16_t>& types, uint64_t spawns, uint64_t perFrame) {
    SoakFigures f;
    Rng rng(7);
    const DecalSettings& settings = sys.settings();
    std::vector<Ray> rays;
    std::vector<SpawnResult> results;
    const auto start = std::chrono::steady_clock::now();
    bool warm = false;
    double time = 0.0;
    while (f.spawns < spawns) {
        const uint64_t n = std::min<uint64_t>(perFrame, spawns - f.spawns);
        const glm::dvec3 eye(rng.uniform(-8.0f, 8.0f), rng.uniform(0.5f, 3.0f), 8.0);
        rays.resize(size_t(n));
        for (Ray& r : rays) {
            const glm::dvec3 aim(rng.uniform(-12.0f, 12.0f), rng.uniform(-0.5f, 4.0f),
                                 rng.uniform(-8.0f, 0.0f));
            r = Ray{eye, aim - eye};
        }
        const uint16_t type = types[size_t(f.frames % types.size())];
        sys.spawnBatch(rays, type, results);
        for (int k = 0; k < 4 && k < int(n); ++k) // single spawns alongside the batches
            (void)sys.spawn(rays[size_t(k)], types[size_t(k) % types.size()]);
        f.spawns += n;
        time += 1.0 / 60.0;
        for (uint32_t i = 0; i < 4; ++i)
            EXPECT_TRUE(sys.setTransform(2 + i, targetTransform(int(i), time)).ok());
        EXPECT_TRUE(sys.update(1.0 / 60.0).ok());
        f.frames++;

        const DecalStats& st = sys.stats();
        if (st.placed != st.alive - st.fading + st.evicted + st.expired + st.removed ||
            st.alive != sys.decals().size() || st.fading > st.alive) {
            ADD_FAILURE() << "stats inconsistent at frame " << f.frames << ": placed " << st.placed
                          << ", alive " << st.alive << ", fading " << st.fading << ", evicted " << st.evicted
                          << ", expired " << st.expired << ", removed " << st.removed;
            break;
        }
        const size_t counted = st.alive - st.fading;
        if (counted > settings.budget) {
            ADD_FAILURE() << counted << " decals count against a budget of " << settings.budget;
            break;
        }
        f.maxAlive = std::max(f.maxAlive, st.alive);
        f.maxCounted = std::max(f.maxCounted, counted);
        if (f.frames % 64 == 0) {
            const size_t rss = residentBytes(), heap = heapBytes();
            if (!warm && f.spawns >= spawns / 10) {
                warm = true;
                f.residentWarm = rss;
                f.heapWarm = heap;
            }
            if (warm) {
                f.residentPeak = std::max(f.residentPeak, rss);
                f.heapPeak = std::max(f.heapPeak, heap);
            }
        }
    }
    f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return f;
}

void report(const char* name, const DecalSystem& sys, const SoakFigures& f) {
    const DecalStats& st = sys.stats();
    std::printf(
        "[soak %s] %llu spawns in %llu frames, %.2f s (%.0f spawns/s): placed %llu, rejected %llu, "
        "evicted %llu, expired %llu, removed %llu, alive %zu (max %zu, counted max %zu); resident "
        "%.1f MiB once warm, peak after %.1f MiB (growth %+.2f MiB), process peak %.1f MiB; heap in use "
        "%.2f MiB once warm, peak after %.2f MiB (growth %+.3f MiB)\n",
        name, (unsigned long long)f.spawns, (unsigned long long)f.frames, f.seconds,
        double(f.spawns) / f.seconds, (unsigned long long)st.placed, (unsigned long long)st.rejectedTotal(),
        (unsigned long long)st.evicted, (unsigned long long)st.expired, (unsigned long long)st.removed,
        st.alive, f.maxAlive, f.maxCounted, double(f.residentWarm) / 1048576.0,
        double(f.residentPeak) / 1048576.0, (double(f.residentPeak) - double(f.residentWarm)) / 1048576.0,
        double(peakResidentBytes()) / 1048576.0, double(f.heapWarm) / 1048576.0,
        double(f.heapPeak) / 1048576.0, (double(f.heapPeak) - double(f.heapWarm)) / 1048576.0);
    std::fflush(stdout);
}

void expectBoundedMemory(const SoakFigures& f) {
    ASSERT_GT(f.heapWarm, 0u);
    // Once the budget is reached every decal that comes replaces one that goes: the heap in use stays
    // put whatever the number of spawns, and the resident size within a few MiB of allocator slack.
    EXPECT_LT(double(f.heapPeak) - double(f.heapWarm), 1048576.0)
        << "heap in use grew from " << f.heapWarm << " to " << f.heapPeak << " bytes";
#ifndef SPATTER_ASAN // ASan's quarantine keeps freed memory resident for a while
    EXPECT_LT(double(f.residentPeak) - double(f.residentWarm), 8.0 * 1048576.0)
        << "resident size grew from " << f.residentWarm << " to " << f.residentPeak << " bytes";
#endif
}

void expectNoLeak() {
#ifdef SPATTER_ASAN
    EXPECT_EQ(__lsan_do_recoverable_leak_check(), 0) << "LeakSanitizer found leaks (see above)";
#endif
}

} // namespace

TEST(Soak, EvictingLimitsAndLifetimesKeepStatsConsistentAndMemoryBounded) {
    const uint64_t spawns = soakSpawns(1'000'000);
    {
        DecalSettings settings;
        settings.seed = 11;
        settings.cellSize = 0.5f;
        settings.maxPerCell = 6;
        settings.maxPerObject = 600;
        settings.budget = 3000;
        settings.policy = LimitPolicy::EvictOldest;
        Result<DecalSystem> sys = DecalSystem::create(soakScene(), settings);
        ASSERT_TRUE(sys) << sys.error();
        DecalType shortLived, longLived, permanent;
        shortLived.name = "short";
        shortLived.lifetime = 0.05f; // shorter than the time the limits give a decal here
        shortLived.fadeOutTime = 0.02f;
        longLived.name = "long";
        longLived.lifetime = 20.0f;
        longLived.sizeJitter = 0.3f;
        permanent.name = "permanent";
        permanent.size = {0.3f, 0.2f};
        const std::vector<uint16_t> types = {sys->registerType(shortLived).value(),
                                             sys->registerType(longLived).value(),
                                             sys->registerType(permanent).value()};
        const SoakFigures f = soak(sys.value(), types, spawns, 512);
        report("evict-oldest", sys.value(), f);
        const DecalStats& st = sys->stats();
        EXPECT_GE(f.spawns, spawns);
        EXPECT_GT(st.placed, spawns / 2);
        EXPECT_GT(st.evicted, 0u);
        EXPECT_GT(st.expired, 0u);
        EXPECT_EQ(st.fading, 0u);
        EXPECT_LE(f.maxAlive, settings.budget);
        expectBoundedMemory(f);
    }
    expectNoLeak();
}

TEST(Soak, FadingEvictionsStayBoundedWhileUpdated) {
    const uint64_t spawns = soakSpawns(500'000);
    {
        DecalSettings settings;
        settings.seed = 12;
        settings.maxPerCell = 4;
        settings.budget = 1500;
        settings.policy = LimitPolicy::FadeOldest;
        Result<DecalSystem> sys = DecalSystem::create(soakScene(), settings);
        ASSERT_TRUE(sys) << sys.error();
        DecalType fading, quick;
        fading.name = "fading";
        fading.fadeOutTime = 0.25f;
        quick.name = "quick";
        quick.lifetime = 0.05f;
        quick.fadeOutTime = 0.02f;
        const std::vector<uint16_t> types = {sys->registerType(fading).value(),
                                             sys->registerType(quick).value()};
        const uint64_t perFrame = 256;
        const SoakFigures f = soak(sys.value(), types, spawns, perFrame);
        report("fade-oldest", sys.value(), f);
        const DecalStats& st = sys->stats();
        EXPECT_GT(st.evicted, 0u);
        EXPECT_GT(st.expired, 0u);
        // Fading decals come on top of the budget: at most the spawns of one fade-out time.
        const double fadeFrames = 0.25 * 60.0 + 1.0;
        EXPECT_LE(double(f.maxAlive), double(settings.budget) + (perFrame + 4) * fadeFrames);
        expectBoundedMemory(f);
        // Everything fades out once spawning stops.
        for (int i = 0; i < 120; ++i)
            ASSERT_TRUE(sys->update(1.0 / 60.0).ok());
        EXPECT_EQ(sys->stats().fading, 0u);
        EXPECT_EQ(sys->stats().placed,
                  sys->stats().alive + sys->stats().evicted + sys->stats().expired + sys->stats().removed);
    }
    expectNoLeak();
}
