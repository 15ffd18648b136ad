// The GPU culling culls a group of 256 places of the draw order whole when the box around its decals,
// in their object's space, lies out of view: it draws what the CPU's culling draws (far from the
// origin too), reads none of the group's decals, writes a group's box again when its decals change,
// follows an object that moves its groups into view, and counts the decals of an object the host
// takes over.

#include "HostedWall.hpp"
#include "RenderTestSupport.hpp"

#include "spatter/core/DecalChanges.hpp"
#include "spatter/core/Random.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <optional>
#include <utility>

using namespace spatter;
using namespace spatter::test;

namespace {

constexpr size_t kGroupPlaces = 256;

// A decal on the wall in view of the wall scene's camera, at random.
Decal inView(Rng& rng) {
    Decal d = WallScene::decalAt(0, {rng.uniform(-2.5f, 2.5f), rng.uniform(-1.5f, 1.5f), 0.05f});
    d.size = glm::vec2(rng.uniform(0.1f, 0.4f));
    return d;
}

// `before` decals in view, then `away` groups' worth 500 units to the right in the wall's space, then
// `after` in view again.
std::vector<Decal> wallDecals(size_t before, size_t away, size_t after, uint64_t seed) {
    Rng rng(seed);
    std::vector<Decal> decals;
    for (size_t i = 0; i < before + away * kGroupPlaces + after; ++i) {
        decals.push_back(inView(rng));
        if (i >= before && i < before + away * kGroupPlaces) decals.back().center.x += 500.0f;
    }
    return decals;
}

struct Drawn {
    std::vector<uint8_t> coverage;
    ProjectorStats stats;
};

// The wall scene's projector culling on the GPU or on the CPU, the wall drawn by the host where
// object 0 of the projector may be moved away from it.
struct Culler {
    HostedWall h;

    static std::optional<Culler> make(bool onGpu) {
        ProjectorSettings settings;
        settings.gpuCullingFrom = onGpu ? 0 : std::numeric_limits<size_t>::max();
        settings.waitForTimers = true;     // this draw's counts
        settings.occlusionCulling = false; // the counts of the frustum alone, as the CPU's
        std::optional<HostedWall> h = HostedWall::make(settings);
        if (!h) return std::nullopt;
        return Culler{std::move(*h)};
    }

    // A culler on the GPU holding `decals`; nothing when it cannot be made.
    static std::optional<Culler> holding(const std::vector<Decal>& decals) {
        std::optional<Culler> c = make(true);
        if (c) c->h.projector.setDecals(decals);
        return c;
    }

    Drawn draw() {
        ProjectorDraw options;
        options.coverageTexture = h.host.coverageTexture();
        h.host.clearCoverage();
        Result<ProjectorStats> st = h.projector.draw(h.host.frame(h.wall.camera, true), options);
        EXPECT_TRUE(st.ok()) << st.error();
        if (!st) return {};
        return {whiteMask(h.host.read(h.host.coverageTexture())), st.value()};
    }

    // The whole scene and the camera moved by `offset`, the host's frame drawn again.
    void moveWorld(const glm::dvec3& offset) {
        const glm::dmat4 move = glm::translate(glm::dmat4(1.0), offset);
        for (glm::dmat4& t : h.wall.transforms)
            t = move * t;
        h.wall.camera.eye += offset;
        h.wall.camera.target += offset;
        h.host.draw(h.wall.transforms, h.wall.ids, h.wall.camera);
        EXPECT_TRUE(h.projector.setObjects(h.wall.transforms, h.wall.ids).ok());
    }

    // The projector's object `object` moved by `offset`, the host's where it is.
    void moveObject(size_t object, const glm::dvec3& offset) {
        std::vector<glm::dmat4> transforms = h.wall.transforms;
        transforms[object] = glm::translate(glm::dmat4(1.0), offset) * transforms[object];
        EXPECT_TRUE(h.projector.setObjects(transforms, h.wall.ids).ok());
    }
};

// The decals as a CPU-culling projector draws them, with the scene moved by `world` and then the
// projector's object `object` by `offset`.
Drawn cpuDrawn(const std::vector<Decal>& decals, size_t object = 0,
               const glm::dvec3& offset = glm::dvec3(0.0), const glm::dvec3& world = glm::dvec3(0.0)) {
    std::optional<Culler> cpu = Culler::make(false);
    if (!cpu) return {};
    cpu->h.projector.setDecals(decals);
    cpu->moveWorld(world);
    cpu->moveObject(object, offset);
    Drawn d = cpu->draw();
    EXPECT_FALSE(d.stats.gpuCulled);
    return d;
}

void expectSameCoverage(const Drawn& gpu, const Drawn& cpu) {
    EXPECT_TRUE(gpu.stats.gpuCulled);
    EXPECT_GT(countSet(cpu.coverage), 0u);
    ASSERT_EQ(gpu.coverage.size(), cpu.coverage.size());
    size_t differing = 0;
    for (size_t i = 0; i < gpu.coverage.size(); ++i)
        differing += gpu.coverage[i] != cpu.coverage[i] ? 1 : 0;
    EXPECT_EQ(differing, 0u) << "pixels whose coverage differs";
    // The GPU's float tests keep margins: they may draw a box the CPU culls, never the reverse.
    EXPECT_GE(gpu.stats.drawn, cpu.stats.drawn);
    EXPECT_LE(gpu.stats.drawn, cpu.stats.drawn + 2);
}

// The GPU's frames before and after the projector's object `object` moves by `offset`, each drawing
// what the CPU draws.
std::pair<Drawn, Drawn> drawnAroundAMove(const std::vector<Decal>& decals, size_t object,
                                         const glm::dvec3& offset) {
    std::optional<Culler> gpu = Culler::holding(decals);
    EXPECT_TRUE(gpu);
    if (!gpu) return {};
    const Drawn before = gpu->draw();
    expectSameCoverage(before, cpuDrawn(decals));
    gpu->moveObject(object, offset);
    const Drawn moved = gpu->draw();
    std::printf("groups tested by place: %zu, then %zu with object %zu moved\n", before.stats.groupsTested,
                moved.stats.groupsTested, object);
    expectSameCoverage(moved, cpuDrawn(decals, object, offset));
    return {before, moved};
}

} // namespace

TEST(GroupCulling, CullsTheGroupsOutOfViewWholeAndDrawsWhatTheCpuDraws) {
    SPATTER_REQUIRE_GL(gl);
    const std::vector<Decal> decals = wallDecals(300, 12, 300, 3);
    std::optional<Culler> gpu = Culler::holding(decals);
    ASSERT_TRUE(gpu);
    const Drawn drawn = gpu->draw();
    std::printf("%zu drawn; %zu of %zu groups tested by place\n", drawn.stats.drawn, drawn.stats.groupsTested,
                (decals.size() + kGroupPlaces - 1) / kGroupPlaces);
    expectSameCoverage(drawn, cpuDrawn(decals));
    // The groups holding a decal in view: two at each end, and the one shared where each end meets
    // the decals away.
    EXPECT_GE(drawn.stats.groupsTested, 4u);
    EXPECT_LE(drawn.stats.groupsTested, 6u);
}

// A million units from the world's origin, the scene and the camera with it: the groups away are
// still culled whole, their boxes and the view meeting relative to the eye.
TEST(GroupCulling, CullsTheGroupsOutOfViewWholeFarFromTheOrigin) {
    SPATTER_REQUIRE_GL(gl);
    const std::vector<Decal> decals = wallDecals(300, 12, 300, 13);
    const glm::dvec3 far(1.0e6, -2.0e5, 3.0e6);
    std::optional<Culler> gpu = Culler::make(true);
    ASSERT_TRUE(gpu);
    gpu->moveWorld(far);
    gpu->h.projector.setDecals(decals);
    const Drawn drawn = gpu->draw();
    std::printf("%zu drawn; %zu groups tested by place\n", drawn.stats.drawn, drawn.stats.groupsTested);
    expectSameCoverage(drawn, cpuDrawn(decals, 0, glm::dvec3(0.0), far));
    EXPECT_LE(drawn.stats.groupsTested, 6u);
}

// Decals of groups culled whole move into view, are removed (the last decal moving into their
// places) and are added: each group whose places or decals changed gets its box again, and the
// frame draws what the CPU draws of the decals as they are now.
TEST(GroupCulling, WritesAGroupsBoxAgainWhenItsDecalsChange) {
    SPATTER_REQUIRE_GL(gl);
    std::vector<Decal> decals = wallDecals(300, 12, 0, 5);
    std::optional<Culler> gpu = Culler::holding(decals);
    ASSERT_TRUE(gpu);
    const size_t testedBefore = gpu->draw().stats.groupsTested;
    Rng rng(9);
    DecalChanges changes;
    for (uint32_t i = 1000; i < 1010; ++i) { // a group away from the view: moved into it
        decals[i].center.x -= 500.0f;
        changes.changes.push_back({i, i, DecalChangeKind::Changed});
    }
    for (uint32_t i : {2000u, 2600u}) { // a decal away removed; the last, away too, takes its place
        changes.changes.push_back({i, uint32_t(decals.size() - 1), DecalChangeKind::Removed});
        decals[i] = decals.back();
        decals.pop_back();
    }
    for (int k = 0; k < 5; ++k) { // added at the end of the draw order, in view
        decals.push_back(inView(rng));
        changes.changes.push_back({uint32_t(decals.size() - 1), uint32_t(decals.size() - 1)});
    }
    gpu->h.projector.updateDecals(decals, changes);
    const Drawn after = gpu->draw();
    std::printf("groups tested by place: %zu before the changes, %zu after\n", testedBefore,
                after.stats.groupsTested);
    expectSameCoverage(after, cpuDrawn(decals));
    EXPECT_GT(after.stats.groupsTested, testedBefore);
}

// The boxes lie in their object's space: the wall's projector object moved 500 units to the left
// brings the groups away into view and takes those in view out of it, with no decal changed.
TEST(GroupCulling, FollowsAnObjectThatMovesItsGroupsIntoView) {
    SPATTER_REQUIRE_GL(gl);
    const std::vector<Decal> decals = wallDecals(300, 12, 0, 7);
    const auto [before, moved] = drawnAroundAMove(decals, 0, glm::dvec3(-500.0, 0.0, 0.0));
    EXPECT_GE(moved.stats.groupsTested, 12u);
    EXPECT_LE(before.stats.groupsTested, 3u);
}

// Decals in view spread through the draw order, every other one away: every group is tested by place,
// so that after the first frame's count the test by place takes every group without the list; each
// frame draws what the CPU draws.
TEST(GroupCulling, DrawsWhatTheCpuDrawsWhenEveryGroupHoldsDecalsInView) {
    SPATTER_REQUIRE_GL(gl);
    std::vector<Decal> decals = wallDecals(3000, 0, 0, 11);
    for (size_t i = 1; i < decals.size(); i += 2)
        decals[i].center.x += 500.0f;
    std::optional<Culler> gpu = Culler::holding(decals);
    ASSERT_TRUE(gpu);
    const Drawn cpu = cpuDrawn(decals);
    for (int frame = 0; frame < 3; ++frame) {
        SCOPED_TRACE(frame);
        const Drawn drawn = gpu->draw();
        expectSameCoverage(drawn, cpu);
        EXPECT_EQ(drawn.stats.groupsTested, (decals.size() + kGroupPlaces - 1) / kGroupPlaces);
    }
}

// The wall's projector object moved 500 units to the left brings the groups away into view: the
// frames after the first test every group without the list, each culling its group whole or listing
// it itself. Moved back, most groups leave the view: that frame, which still tests every group, and the
// next, which takes the list again, test the few groups in view and draw what the CPU draws.
TEST(GroupCulling, TestsTheFewGroupsInViewAfterFramesThatTestedEveryGroup) {
    SPATTER_REQUIRE_GL(gl);
    const std::vector<Decal> decals = wallDecals(300, 12, 0, 23);
    const glm::dvec3 left(-500.0, 0.0, 0.0);
    std::optional<Culler> gpu = Culler::holding(decals);
    ASSERT_TRUE(gpu);
    gpu->moveObject(0, left);
    const Drawn cpuLeft = cpuDrawn(decals, 0, left);
    for (int frame = 0; frame < 2; ++frame) {
        const Drawn drawn = gpu->draw();
        expectSameCoverage(drawn, cpuLeft);
        EXPECT_GE(drawn.stats.groupsTested, 12u);
    }
    gpu->moveObject(0, glm::dvec3(0.0));
    const Drawn cpuBack = cpuDrawn(decals);
    for (int frame = 0; frame < 2; ++frame) {
        SCOPED_TRACE(frame);
        const Drawn drawn = gpu->draw();
        expectSameCoverage(drawn, cpuBack);
        EXPECT_LE(drawn.stats.groupsTested, 3u);
    }
}

// The host takes over the wall's decals after its groups away were culled whole: every decal is
// counted the host's, as the CPU counts them, none drawn; and back again.
TEST(GroupCulling, CountsTheDecalsOfAnObjectTheHostTakesOverInGroupsOutOfView) {
    SPATTER_REQUIRE_GL(gl);
    const std::vector<Decal> decals = wallDecals(300, 12, 0, 17);
    std::optional<Culler> gpu = Culler::holding(decals);
    ASSERT_TRUE(gpu);
    const Drawn before = gpu->draw();
    gpu->h.projector.setHostDrawn({}, {1, 0});
    const Drawn taken = gpu->draw();
    EXPECT_EQ(taken.stats.hostDrawn, decals.size());
    EXPECT_EQ(taken.stats.drawn, 0u);
    gpu->h.projector.setHostDrawn({}, {});
    const Drawn back = gpu->draw();
    EXPECT_EQ(back.stats.hostDrawn, 0u);
    EXPECT_EQ(back.coverage, before.coverage);
    expectSameCoverage(back, cpuDrawn(decals));
}

// Decals on the wall and on the crate in turn, in view and 500 units away in each object's space:
// a group holds a box for each of its two objects and is culled whole when both lie out of view.
// The crate's projector object then moves its decals away into view (and those in view away): drawn
// as the CPU draws them.
TEST(GroupCulling, CullsGroupsOfDecalsOnSeveralObjectsByABoxForEach) {
    SPATTER_REQUIRE_GL(gl);
    Rng rng(19);
    std::vector<Decal> decals;
    for (size_t i = 0; i < 13 * kGroupPlaces; ++i) {
        const bool away = i >= 2 * kGroupPlaces;
        Decal d = i % 2 == 0
                      ? inView(rng)
                      : WallScene::decalAt(1, {rng.uniform(-0.2f, 0.2f), rng.uniform(-0.2f, 0.2f), 0.3f});
        if (i % 2 == 1) d.size = glm::vec2(0.2f);
        if (away) d.center.x += 500.0f;
        decals.push_back(d);
    }
    const auto [before, moved] = drawnAroundAMove(decals, 1, glm::dvec3(-500.0, 0.0, 0.0));
    EXPECT_LE(before.stats.groupsTested, 2u);
    EXPECT_GE(moved.stats.groupsTested, 11u);
}
