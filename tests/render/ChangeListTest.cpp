// The persistent decal store: a projector fed DecalSystem's change list (updateDecals) draws exactly
// what one given every decal each frame (setDecals) draws, with culling on the CPU and on the GPU,
// through spawns, removals, evictions, fades, moving objects and a change of the types' priorities;
// and a long run of spawns keeps its GPU memory flat and never draws a removed decal.

#include "HostedWall.hpp"
#include "RenderTestSupport.hpp"
#include "TestData.hpp"

#include "spatter/core/Random.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/render/DecalProjector.hpp"

#include <epoxy/gl.h>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <deque>
#include <optional>

using namespace spatter;

namespace {

DecalType colourType(const char* name, const glm::vec3& colour, int priority, float lifetime) {
    DecalType t;
    t.name = name;
    t.size = glm::vec2(0.5f);
    t.texture = int(DecalTexture::Paint);
    t.tint = glm::vec4(colour, 1.0f);
    t.priority = priority;
    t.lifetime = lifetime;
    t.fadeOutTime = lifetime > 0.0f ? lifetime / 2.0f : 0.4f;
    return t;
}

struct StoreRun {
    std::optional<test::HostedWall> h;
    std::optional<DecalProjector> whole; // given every decal each frame
    std::optional<DecalSystem> sys;
    std::vector<DecalType> types;
    uint64_t version = 0;
};

std::optional<StoreRun> makeRun(std::optional<size_t> gpuCullingFrom, const DecalSettings& settings) {
    StoreRun r;
    r.h = test::HostedWall::make();
    if (!r.h) return std::nullopt;
    ProjectorSettings ps;
    ps.gpuCullingFrom = gpuCullingFrom;
    ps.waitForTimers = true; // this draw's counts
    Result<DecalProjector> a = DecalProjector::create(ps), b = DecalProjector::create(ps);
    Result<DecalSystem> sys = DecalSystem::create(r.h->wall.scene, settings);
    EXPECT_TRUE(a.ok() && b.ok() && sys.ok());
    if (!a || !b || !sys) return std::nullopt;
    r.h->projector = std::move(a).value();
    r.whole.emplace(std::move(b).value());
    r.sys.emplace(std::move(sys).value());
    r.types = {colourType("red", {1, 0, 0}, 1, 0.0f), colourType("green", {0, 1, 0}, 0, 0.0f),
               colourType("blue", {0, 0, 1}, 0, 0.6f)};
    for (const DecalType& t : r.types)
        EXPECT_TRUE(r.sys->registerType(t).ok());
    r.h->projector.setDecalTypes(r.types);
    r.whole->setDecalTypes(r.types);
    return r;
}

// Draws the run's decals through `p` and reads the albedo back.
Image drawThrough(StoreRun& r, DecalProjector& p, ProjectorStats* stats) {
    std::vector<glm::dmat4> transforms;
    for (uint32_t o = 0; o < r.sys->world().objectCount(); ++o)
        transforms.push_back(r.sys->world().object(o)->transform);
    const std::vector<uint8_t> ids = r.sys->objectIds();
    r.h->host.draw(transforms, ids, r.h->wall.camera);
    EXPECT_TRUE(p.setObjects(transforms, ids).ok());
    const HostFrame f = r.h->host.frame(r.h->wall.camera, true);
    Result<ProjectorStats> st = p.draw(f);
    EXPECT_TRUE(st.ok()) << st.error();
    if (st && stats) *stats = st.value();
    return r.h->host.read(f.albedoTexture);
}

// One frame of gameplay: spawns on the wall and the crate, a few removals, the crate moving, time.
void play(StoreRun& r, Rng& rng, std::deque<DecalHandle>& handles, int frame) {
    for (int k = 0; k < 6; ++k) {
        const uint16_t type = uint16_t(rng.next() % 3);
        const bool crate = rng.next() % 4 == 0;
        const glm::vec3 at = crate ? glm::vec3(rng.uniform(-0.3f, 0.3f), rng.uniform(-0.3f, 0.3f), 0.3f)
                                   : glm::vec3(rng.uniform(-2.0f, 2.0f), rng.uniform(-1.2f, 1.2f), 0.05f);
        const SpawnResult s = r.sys->spawnAttached(crate ? 1 : 0, at, {0, 0, 1}, type);
        if (s.placed()) handles.push_back(s.handle);
        // Decals of one spawn time draw in the order they reached the projector: by index when taken
        // whole, in spawn order through the change list. Apart in time, both agree.
        EXPECT_TRUE(r.sys->update(0.01).ok());
    }
    for (int k = 0; k < 2 && !handles.empty(); ++k) {
        const size_t i = rng.next() % handles.size();
        r.sys->remove(handles[i]);
        handles.erase(handles.begin() + std::ptrdiff_t(i));
    }
    const glm::dmat4 crate =
        glm::translate(glm::dmat4(1.0), glm::dvec3(0.8 - std::fmod(0.05 * frame, 1.0), 0.8, 0.5));
    EXPECT_TRUE(r.sys->setTransform(1, crate).ok());
    EXPECT_TRUE(r.sys->update(0.04).ok());
}

void expectUpdatesMatchWholeDecals(std::optional<size_t> gpuCullingFrom, const char* what) {
    DecalSettings settings;
    settings.budget = 48;
    settings.maxPerCell = 3;
    settings.policy = LimitPolicy::FadeOldest;
    std::optional<StoreRun> r = makeRun(gpuCullingFrom, settings);
    ASSERT_TRUE(r.has_value());
    Rng rng(7);
    std::deque<DecalHandle> handles;
    size_t drawnMost = 0;
    for (int frame = 0; frame < 30; ++frame) {
        play(*r, rng, handles, frame);
        if (frame == 20) { // the priorities change: the order is laid out afresh
            r->types[1].priority = 2;
            r->h->projector.setDecalTypes(r->types);
            r->whole->setDecalTypes(r->types);
        }
        const DecalChanges changes = r->sys->changesSince(r->version);
        r->version = changes.version;
        r->h->projector.updateDecals(r->sys->decals(), changes);
        r->whole->setDecals(r->sys->decals());
        ProjectorStats a, b;
        const Image updated = drawThrough(*r, r->h->projector, &a);
        const Image whole = drawThrough(*r, *r->whole, &b);
        EXPECT_EQ(test::differingPixels(updated, whole), 0u) << what << ", frame " << frame;
        EXPECT_EQ(a.decals, r->sys->decals().size()) << what;
        EXPECT_EQ(a.drawn, b.drawn) << what << ", frame " << frame;
        EXPECT_EQ(a.invalid, 0u);
        drawnMost = std::max(drawnMost, a.drawn);
    }
    std::printf("%s: %zu decals, at most %zu drawn, %llu evicted, %llu removed\n", what,
                r->sys->decals().size(), drawnMost, (unsigned long long)r->sys->stats().evicted,
                (unsigned long long)r->sys->stats().removed);
    EXPECT_GT(drawnMost, 20u);
    EXPECT_GT(r->sys->stats().evicted, 0u);
}

size_t bufferBytes(uint32_t buffer) {
    GLint64 size = 0;
    glGetNamedBufferParameteri64v(buffer, GL_BUFFER_SIZE, &size);
    return size_t(size);
}

} // namespace

TEST(ChangeList, UpdatesDrawExactlyWhatTheDecalsTakenWholeDraw) {
    SPATTER_REQUIRE_GL(gl);
    expectUpdatesMatchWholeDecals(std::nullopt, "culled on the CPU");
    expectUpdatesMatchWholeDecals(size_t(0), "culled on the GPU");
    // From 30 decals on: the CPU stops keeping the records and the draw order's entries mid-run.
    expectUpdatesMatchWholeDecals(size_t(30), "culled on the GPU from 30 decals");
}

TEST(ChangeList, ALongRunOfSpawnsKeepsGpuMemoryFlatAndNeverDrawsARemovedDecal) {
    SPATTER_REQUIRE_GL(gl);
    DecalSettings settings;
    settings.budget = 4000;
    settings.maxPerCell = 64;
    settings.maxPerObject = 4000;
    settings.policy = LimitPolicy::FadeOldest;
    std::optional<StoreRun> r = makeRun(size_t(0), settings);
    ASSERT_TRUE(r.has_value());
    Rng rng(11);
    constexpr int kFrames = 400, kPerFrame = 500; // 200,000 spawns, 50 times the budget
    size_t bufferAtBudget = 0, mostAlive = 0;
    std::deque<DecalHandle> handles;
    for (int frame = 0; frame < kFrames; ++frame) {
        for (int k = 0; k < kPerFrame; ++k) {
            const glm::vec3 at(rng.uniform(-2.5f, 2.5f), rng.uniform(-1.5f, 1.5f), 0.05f);
            const SpawnResult s = r->sys->spawnAttached(0, at, {0, 0, 1}, uint16_t(rng.next() % 3));
            if (s.placed()) handles.push_back(s.handle);
            if (handles.size() > 3000) handles.pop_front();
        }
        for (int k = 0; k < 20 && !handles.empty(); ++k) { // removals, some of decals already gone
            r->sys->remove(handles.front());
            handles.pop_front();
        }
        EXPECT_TRUE(r->sys->update(0.05).ok());
        const DecalChanges changes = r->sys->changesSince(r->version);
        r->version = changes.version;
        r->h->projector.updateDecals(r->sys->decals(), changes);
        mostAlive = std::max(mostAlive, r->sys->decals().size()); // the budget, and those fading out
        if (frame % 40 != 39) continue;
        ProjectorStats st;
        drawThrough(*r, r->h->projector, &st);
        const DecalStats& s = r->sys->stats();
        EXPECT_EQ(st.decals, r->sys->decals().size());
        EXPECT_EQ(s.placed, s.alive - s.fading + s.evicted + s.expired + s.removed);
        const ProjectorResources res = r->h->projector.resources();
        const size_t bytes = bufferBytes(res.decals) + bufferBytes(res.decalBounds);
        if (frame < kFrames / 2) continue; // the decals alive (the budget and those fading) settle
        if (bufferAtBudget == 0) bufferAtBudget = bytes;
        EXPECT_EQ(bytes, bufferAtBudget) << "frame " << frame << ": the decal buffers grew past the budget";
    }
    std::printf("%d spawns: %zu decals alive, decal buffers %zu bytes, %llu evicted, %llu expired\n",
                kFrames * kPerFrame, r->sys->decals().size(), bufferAtBudget,
                (unsigned long long)r->sys->stats().evicted, (unsigned long long)r->sys->stats().expired);
    EXPECT_LE(bufferAtBudget, mostAlive * 44 * 5 / 4); // 44 bytes a decal, grown by a quarter at a time

    // Every decal removed: nothing of them is drawn any more, by either projector.
    ASSERT_TRUE(r->sys->removeObject(0).ok());
    ASSERT_TRUE(r->sys->decals().empty());
    const DecalChanges changes = r->sys->changesSince(r->version);
    r->h->projector.updateDecals(r->sys->decals(), changes);
    r->whole->setDecals({});
    const Image updated = drawThrough(*r, r->h->projector, nullptr);
    const Image none = drawThrough(*r, *r->whole, nullptr);
    EXPECT_EQ(test::differingPixels(updated, none), 0u);
}
