// Culling on the GPU (ProjectorSettings::gpuCullingFrom) is exact: the same decals give the same
// coverage, bit for bit, and the same counts as culling on the CPU, with the camera inside boxes,
// boxes across the frustum's edges and its near plane, on a sheared object, and far from the world's
// origin. Its occlusion test (ProjectorSettings::occlusionCulling) culls the boxes hidden behind the
// scene and changes no pixel.

#include "ForeignHost.hpp"
#include "HostedWall.hpp"
#include "RenderTestSupport.hpp"
#include "TestData.hpp"

#include "spatter/core/Random.hpp"
#include "spatter/render/DecalProjector.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

using namespace spatter;
using namespace spatter::test;

namespace {

// `count` decals on the wall (object 0) scattered over an area wider than the view and the wall,
// some deep enough to reach the camera, in three sizes, one in five projected along a slanted axis.
std::vector<Decal> scatteredDecals(int count, uint64_t seed) {
    Rng rng(seed);
    std::vector<Decal> decals;
    for (int i = 0; i < count; ++i) {
        Decal d = test::WallScene::decalAt(0, {rng.uniform(-6.0f, 6.0f), rng.uniform(-4.0f, 4.0f), 0.05f});
        d.size = glm::vec2(0.2f + 0.3f * float(i % 3));
        d.halfDepth = i % 7 == 0 ? 4.0f : 0.2f; // deep boxes reach the eye at the close views
        if (i % 5 == 0) d.setProjectionAxis({0.7f, -0.4f, 1.0f}); // slanted boxes
        decals.push_back(d);
    }
    // Deep boxes around the close views' eye, (0.2, 1, 0.6) in the world, and beside it.
    for (const glm::vec3& c : {glm::vec3(0.2f, 0.0f, 0.05f), glm::vec3(-0.2f, 0.1f, 0.05f)}) {
        Decal d = test::WallScene::decalAt(0, c);
        d.size = glm::vec2(0.5f);
        d.halfDepth = 4.0f;
        decals.push_back(d);
    }
    return decals;
}

struct Culled {
    std::vector<uint8_t> coverage;
    ProjectorStats stats;
    std::vector<uint8_t> albedo; // the host's albedo target, the decals blended into it in draw order
};

// How a coverage run differs from the plain wall.
struct Variant {
    bool occlusion = true;               // the GPU's occlusion test
    glm::dmat4 shape{1.0};               // the wall's shape (before it moves)
    std::vector<DecalType> types;        // types after the wall's own
    std::vector<uint8_t> hostDrawn;      // types the host draws (DecalProjector::setHostDrawn)
    std::vector<glm::dmat4> moreObjects; // the projector's objects after the wall's (moved with it)
    std::optional<Camera> earlier;       // a view drawn first, whose counts size the culling's passes
};

// The coverage of `decals` on the wall shaped by `variant.shape` and moved by `offset`, seen by
// `camera` (moved too), culled on the CPU or on the GPU.
Culled coverage(const std::vector<Decal>& decals, const glm::dvec3& offset, Camera camera, bool onGpu,
                const Variant& variant = {}) {
    test::WallScene wall;
    wall.types.insert(wall.types.end(), variant.types.begin(), variant.types.end());
    const glm::dmat4 move = glm::translate(glm::dmat4(1.0), offset) * variant.shape;
    for (size_t i = 0; i < wall.scene.objects.size(); ++i) {
        wall.scene.objects[i].transform = move * wall.scene.objects[i].transform;
        wall.transforms[i] = wall.scene.objects[i].transform;
    }
    std::vector<glm::dmat4> transforms = wall.transforms;
    std::vector<uint8_t> ids = wall.ids;
    for (const glm::dmat4& t : variant.moreObjects)
        transforms.push_back(move * t);
    ids.resize(transforms.size(), 0);
    camera.eye += offset;
    camera.target += offset;
    Result<test::ForeignHost> host = test::ForeignHost::create(kWallWidth, kWallHeight);
    ProjectorSettings settings;
    settings.gpuCullingFrom = onGpu ? 0 : std::numeric_limits<size_t>::max();
    settings.waitForTimers = true; // this draw's counts
    settings.occlusionCulling = variant.occlusion;
    Result<DecalProjector> projector = DecalProjector::create(settings);
    EXPECT_TRUE(host.ok() && projector.ok());
    if (!host || !projector) return {};
    host->setScene(wall.scene);
    EXPECT_TRUE(projector->setObjects(transforms, ids).ok());
    projector->setDecalTypes(wall.types);
    projector->setHostDrawn(variant.hostDrawn, {});
    projector->setDecals(decals);
    ProjectorDraw draw;
    draw.coverageTexture = host->coverageTexture();
    if (variant.earlier) {
        Camera earlier = *variant.earlier;
        earlier.eye += offset;
        earlier.target += offset;
        host->draw(wall.transforms, wall.ids, earlier);
        EXPECT_TRUE(projector->draw(host->frame(earlier, true), draw).ok());
    }
    host->draw(wall.transforms, wall.ids, camera);
    host->clearCoverage();
    Result<ProjectorStats> st = projector->draw(host->frame(camera, true), draw);
    EXPECT_TRUE(st.ok()) << st.error();
    if (!st) return {};
    EXPECT_EQ(st->gpuCulled, onGpu);
    return {test::whiteMask(host->read(host->coverageTexture())), st.value(),
            host->read(host->albedoTexture()).rgba};
}

// The GPU's culling covers the same pixels as the CPU's; its float test keeps a margin: it may draw a
// box the CPU culls (which then covers no pixel), never the reverse.
void expectSameCoverage(const char* name, const Culled& cpu, const Culled& gpu) {
    EXPECT_GT(test::countSet(cpu.coverage), 0u) << name;
    size_t differing = 0;
    for (size_t i = 0; i < gpu.coverage.size() && i < cpu.coverage.size(); ++i)
        if (gpu.coverage[i] != cpu.coverage[i]) {
            if (++differing <= 8)
                std::printf("  pixel (%zu, %zu): %s\n", i % kWallWidth, i / kWallWidth,
                            cpu.coverage[i] ? "CPU only" : "GPU only");
        }
    EXPECT_EQ(differing, 0u) << name << ": pixels whose coverage differs";
    EXPECT_EQ(gpu.coverage.size(), cpu.coverage.size()) << name;
    EXPECT_GE(gpu.stats.drawn, cpu.stats.drawn) << name;
    EXPECT_LE(gpu.stats.drawn, cpu.stats.drawn + 2) << name;
}

void expectSameAsCpu(const char* name, const std::vector<Decal>& decals, const glm::dvec3& offset,
                     const Camera& camera, bool occlusion, const glm::dmat4& shape = glm::dmat4(1.0)) {
    Variant variant;
    variant.shape = shape;
    const Culled cpu = coverage(decals, offset, camera, false, variant);
    variant.occlusion = occlusion;
    const Culled gpu = coverage(decals, offset, camera, true, variant);
    std::printf("%s: %zu drawn (%zu inside), %zu culled; %zu covered pixels\n", name, cpu.stats.drawn,
                cpu.stats.inside, cpu.stats.culled, test::countSet(cpu.coverage));
    expectSameCoverage(name, cpu, gpu);
    EXPECT_EQ(gpu.stats.drawn + gpu.stats.culled, cpu.stats.drawn + cpu.stats.culled) << name;
}

// The CPU's and the GPU's culling of `decals` under `variant` give the same coverage and counts of
// the host's decals and of those that cannot be drawn.
void expectSameCounts(const std::vector<Decal>& decals, const Variant& variant) {
    const Camera camera = test::lookAt({0.0, 1.0, 4.0}, {0.0, 1.0, 0.0});
    const Culled cpu = coverage(decals, {}, camera, false, variant);
    const Culled gpu = coverage(decals, {}, camera, true, variant);
    std::printf("%zu drawn, %zu the host's, %zu that cannot be drawn; %zu covered pixels\n", cpu.stats.drawn,
                cpu.stats.hostDrawn, cpu.stats.invalid, test::countSet(cpu.coverage));
    expectSameCoverage("counts", cpu, gpu);
    EXPECT_EQ(gpu.stats.hostDrawn, cpu.stats.hostDrawn);
    EXPECT_EQ(gpu.stats.invalid, cpu.stats.invalid);
}

// The same with the occlusion test on the GPU (the first draw tries it) and without it.
void expectSameAsCpu(const char* name, const std::vector<Decal>& decals, const glm::dvec3& offset,
                     const Camera& camera) {
    for (const bool occlusion : {true, false}) {
        SCOPED_TRACE(occlusion ? "with the occlusion test" : "without the occlusion test");
        expectSameAsCpu(name, decals, offset, camera, occlusion);
    }
}

} // namespace

TEST(GpuCulling, MatchesTheCpuWithBoxesAcrossTheFrustumEdges) {
    SPATTER_REQUIRE_GL(gl);
    const std::vector<Decal> decals = scatteredDecals(300, 7);
    expectSameAsCpu("edges", decals, glm::dvec3(0.0), test::lookAt({0.0, 1.0, 4.0}, {0.0, 1.0, 0.0}));
    expectSameAsCpu("oblique", decals, glm::dvec3(0.0), test::lookAt({2.5, 2.0, 2.0}, {-1.0, 0.5, 0.0}));
}

TEST(GpuCulling, MatchesTheCpuWithTheCameraInsideBoxesAndBoxesAcrossTheNearPlane) {
    SPATTER_REQUIRE_GL(gl);
    const std::vector<Decal> decals = scatteredDecals(300, 11);
    expectSameAsCpu("close", decals, glm::dvec3(0.0), test::lookAt({0.2, 1.0, 0.6}, {0.0, 1.0, 0.0}));
    expectSameAsCpu("grazing", decals, glm::dvec3(0.0), test::lookAt({-2.0, 1.0, 0.3}, {2.0, 1.0, 0.0}));
}

// Thousands of decals: the visible places lie in many groups of 256 of the draw order, among groups
// with none, so that each group's first place in the visible list sums the groups before it.
TEST(GpuCulling, MatchesTheCpuOverManyGroupsOfTheDrawOrder) {
    SPATTER_REQUIRE_GL(gl);
    const std::vector<Decal> decals = scatteredDecals(4000, 17);
    expectSameAsCpu("many", decals, glm::dvec3(0.0), test::lookAt({0.0, 1.0, 2.0}, {0.5, 1.0, 0.0}));
}

// Past 65,536 places the groups form several blocks of 256, whose visible places the scatter sums
// before those of its own block's groups: 300 decals on the wall, each followed by 499 far out of
// view, put visible places in every block of the draw order's 150,300.
TEST(GpuCulling, MatchesTheCpuOverManyBlocksOfTheDrawOrder) {
    SPATTER_REQUIRE_GL(gl);
    std::vector<Decal> decals;
    for (const Decal& d : scatteredDecals(300, 31)) {
        decals.push_back(d);
        Decal away = d;
        away.center.x += 500.0f;
        decals.insert(decals.end(), 499, away);
    }
    // Without the occlusion test, which hides a box behind the crate here that the CPU counts drawn.
    expectSameAsCpu("blocks", decals, glm::dvec3(0.0), test::lookAt({0.0, 1.0, 4.0}, {0.0, 1.0, 0.0}), false);
}

// The same view drawn twice over 600 decals in view, each followed by 255 far out of view, so that
// nearly every group of three blocks holds a visible place: the second draw tests every group in one
// pass (most were tested in the first), and each block's visible places are counted from nothing
// again, not added to the first draw's.
TEST(GpuCulling, MatchesTheCpuOverManyBlocksDrawnAgain) {
    SPATTER_REQUIRE_GL(gl);
    Rng rng(37);
    std::vector<Decal> decals;
    for (int i = 0; i < 600; ++i) {
        Decal d = test::WallScene::decalAt(0, {rng.uniform(-1.0f, 1.0f), rng.uniform(0.4f, 1.6f), 0.05f});
        d.size = glm::vec2(0.1f);
        decals.push_back(d);
        Decal away = d;
        away.center.x += 500.0f;
        decals.insert(decals.end(), 255, away);
    }
    const Camera camera = test::lookAt({0.0, 1.0, 4.0}, {0.0, 1.0, 0.0});
    Variant variant;
    variant.occlusion = false;
    const Culled cpu = coverage(decals, {}, camera, false, variant);
    variant.earlier = camera;
    const Culled again = coverage(decals, {}, camera, true, variant);
    std::printf("%zu drawn, %zu groups tested by place; %zu covered pixels\n", again.stats.drawn,
                size_t(again.stats.groupsTested), test::countSet(again.coverage));
    EXPECT_GE(again.stats.groupsTested, 590u);
    expectSameCoverage("drawn again", cpu, again);
}

// The GPU's passes are sized by the counts of an earlier draw: a view that takes in thousands of
// decals after one that took in none still culls every box, its passes' invocations striding over
// more candidates and groups than they were sized for: the same boxes as a first draw, in the same order
// (the same albedo, where overlapping decals blend), the same pixels as the CPU. (Without the
// occlusion test, whose depth pyramid the earlier draw changes.)
TEST(GpuCulling, MatchesTheCpuWhenTheViewTakesInFarMoreThanTheDrawBefore) {
    SPATTER_REQUIRE_GL(gl);
    // Each scattered decal followed by a tiny one between the eye and the near plane: the sphere test
    // passes it, the corner test culls it, so that the candidates are not the visible decals and a
    // group the scatter skipped would draw the wrong ones.
    std::vector<Decal> decals;
    for (const Decal& d : scatteredDecals(10000, 23)) {
        decals.push_back(d);
        decals.push_back(test::WallScene::decalAt(0, {0.0f, 0.0f, 4.03f})); // 0.02 in front of the eye
        decals.back().size = glm::vec2(0.004f);
        decals.back().halfDepth = 0.004f;
    }
    const Camera camera = test::lookAt({0.0, 1.0, 4.0}, {0.0, 1.0, 0.0});
    Variant variant;
    variant.occlusion = false;
    const Culled cpu = coverage(decals, {}, camera, false, variant);
    const Culled first = coverage(decals, {}, camera, true, variant);
    variant.earlier = test::lookAt({0.0, 1.0, 4.0}, {0.0, 1.0, 8.0}); // facing away from the wall
    const Culled after = coverage(decals, {}, camera, true, variant);
    std::printf("%zu drawn, %zu culled; %zu covered pixels\n", after.stats.drawn, after.stats.culled,
                test::countSet(after.coverage));
    EXPECT_GT(after.stats.drawn, 4096u); // past what the earlier counts size the corner test for
    EXPECT_EQ(after.stats.drawn, first.stats.drawn);
    EXPECT_EQ(after.stats.culled, first.stats.culled);
    EXPECT_TRUE(after.coverage == first.coverage);
    EXPECT_TRUE(after.albedo == first.albedo);
    EXPECT_TRUE(after.coverage == cpu.coverage);
    EXPECT_TRUE(after.albedo == cpu.albedo);
    EXPECT_GT(test::countSet(after.coverage), 0u);
}

// The wall sheared (x moves by y) stretches a box up to 1.618 times, more than its longest column
// (1.414) says: both culling paths size their bounding spheres by a bound that holds for a shear.
// Rows of decals, whose corners point the way the shear stretches most across the side planes of a
// narrow view rolled to face that way, cross its left and right sides, so that some lie just
// outside it.
TEST(GpuCulling, MatchesTheCpuOnAShearedObject) {
    SPATTER_REQUIRE_GL(gl);
    const double roll = std::atan2(0.526, 0.851); // the direction the shear stretches most
    const glm::dvec2 across(std::cos(roll), std::sin(roll));
    std::vector<Decal> decals = scatteredDecals(300, 19);
    for (int i = -750; i <= 750; ++i) {
        const glm::dvec2 world = glm::dvec2(0.0, 0.5) + across * (0.004 * double(i));
        Decal d = test::WallScene::decalAt(0, {float(world.x - world.y), float(world.y), 0.05f});
        d.size = glm::vec2(0.1236f, 0.2f); // corners along (0.829, 1.341, 0.225) before the shear
        d.halfDepth = 0.0168f;
        decals.push_back(d);
    }
    glm::dmat4 shear(1.0);
    shear[1][0] = 1.0;
    Camera camera = test::lookAt({0.0, 0.5, 3.0}, {0.0, 0.5, 0.0});
    camera.up = glm::dvec3(-across.y, across.x, 0.0);
    camera.fovYDeg = 20.0;
    expectSameAsCpu("sheared", decals, glm::dvec3(0.0), camera, true, shear);
}

TEST(GpuCulling, MatchesTheCpuFarFromTheOrigin) {
    SPATTER_REQUIRE_GL(gl);
    const std::vector<Decal> decals = scatteredDecals(300, 13);
    const glm::dvec3 far(1.0e6, -2.0e5, 3.0e6);
    expectSameAsCpu("far", decals, far, test::lookAt({0.0, 1.0, 4.0}, {0.0, 1.0, 0.0}));
    expectSameAsCpu("far close", decals, far, test::lookAt({0.2, 1.0, 0.6}, {0.0, 1.0, 0.0}));
}

// Decals of a type the host draws, of a type that cannot be drawn, and naming a type or an object
// that does not exist, in view and out of it: the GPU counts them as the CPU does and draws none (its
// first pass then reads each decal's type, which it skips while every type is the projector's). Among
// the objects that do not exist, 65,536 and 65,537, whose low 16 bits (all the culling reads of an
// object's index while there are at most 65,536 objects) name the wall.
TEST(GpuCulling, CountsTheHostsDecalsAndThoseThatCannotBeDrawnAsTheCpuDoes) {
    SPATTER_REQUIRE_GL(gl);
    const test::WallScene wall;
    Variant variant;
    variant.types = {wall.types.at(0), wall.types.at(0)};
    variant.types[1].texture = 99; // no such layer
    const uint16_t host = uint16_t(wall.types.size()), none = uint16_t(host + 1);
    variant.hostDrawn.assign(host + 1, 0);
    variant.hostDrawn[host] = 1;
    std::vector<Decal> decals = scatteredDecals(400, 23);
    for (size_t i = 0; i < decals.size(); ++i) {
        const uint16_t kinds[4] = {0, host, none, uint16_t(none + 5)};
        decals[i].type = kinds[i % 4];
        if (i % 9 == 0) decals[i].object = 7; // no such object
        if (i % 9 == 1) decals[i].object = 65536 + uint32_t(i % 2);
    }
    expectSameCounts(decals, variant);
}

// The decals' bounds hold the low 16 bits of their object's index and their bodies the next 8,
// which the culling reads while there are more than 65,536 objects: decals on objects on either side
// of that line are culled as the CPU culls them, and one whose index does not fit in 24 bits names no
// object. The objects they name are the wall; the others lie 50 m aside, where a decal given the
// wrong object (70,000 cut to 16 bits, 2^24 + 3 cut to 24) would be culled or counted otherwise.
TEST(GpuCulling, FindsTheObjectsOfDecalsPastTheBoundsObjectBits) {
    SPATTER_REQUIRE_GL(gl);
    const test::WallScene wall;
    const uint32_t objects[5] = {0, 65535, 65536, 70000, (1u << 24) + 3u};
    Variant variant;
    variant.moreObjects.assign(70001 - wall.transforms.size(),
                               glm::translate(glm::dmat4(1.0), glm::dvec3(50.0, 0.0, 0.0)) *
                                   wall.transforms[0]);
    for (const uint32_t o : objects)
        if (o >= wall.transforms.size() && o <= 70000)
            variant.moreObjects[o - wall.transforms.size()] = wall.transforms[0];
    std::vector<Decal> decals = scatteredDecals(300, 29);
    for (size_t i = 0; i < decals.size(); ++i)
        decals[i].object = objects[i % 5];
    expectSameCounts(decals, variant);
}

// Below gpuCullingFrom the projector culls on the GPU while many decals are in view
// (gpuCullingInViewFrom, here 8): the first draw culls on the CPU and finds more than that in view,
// the next takes the GPU and covers the same pixels; turned away from the wall, one more draw stays
// on the GPU (its latest count was high), finds none, and the draw after it is back on the CPU.
TEST(GpuCulling, TakesOverWhileManyDecalsAreInViewAndHandsBackWhenFew) {
    SPATTER_REQUIRE_GL(gl);
    test::WallScene wall;
    Result<test::ForeignHost> host = test::ForeignHost::create(kWallWidth, kWallHeight);
    ProjectorSettings settings;
    settings.gpuCullingInViewFrom = 8;
    settings.waitForTimers = true; // each draw's counts
    Result<DecalProjector> projector = DecalProjector::create(settings);
    ASSERT_TRUE(host.ok() && projector.ok());
    host->setScene(wall.scene);
    ASSERT_TRUE(projector->setObjects(wall.transforms, wall.ids).ok());
    projector->setDecalTypes(wall.types);
    projector->setDecals(scatteredDecals(300, 7));
    auto drawWith = [&](const Camera& camera, ProjectorStats& stats) {
        host->draw(wall.transforms, wall.ids, camera);
        host->clearCoverage();
        ProjectorDraw draw;
        draw.coverageTexture = host->coverageTexture();
        Result<ProjectorStats> st = projector->draw(host->frame(camera, true), draw);
        EXPECT_TRUE(st.ok()) << st.error();
        if (st) stats = st.value();
        return test::whiteMask(host->read(host->coverageTexture()));
    };
    const Camera facing = test::lookAt({0.0, 1.0, 4.0}, {0.0, 1.0, 0.0});
    const Camera away = test::lookAt({0.0, 1.0, 4.0}, {0.0, 1.0, 8.0});
    ProjectorStats stats;
    const std::vector<uint8_t> onCpu = drawWith(facing, stats);
    EXPECT_FALSE(stats.gpuCulled);
    EXPECT_GE(stats.drawn, 8u);
    const size_t inView = stats.drawn;
    const std::vector<uint8_t> onGpu = drawWith(facing, stats);
    EXPECT_TRUE(stats.gpuCulled);
    EXPECT_EQ(stats.drawn, inView);
    EXPECT_GT(test::countSet(onCpu), 0u);
    EXPECT_EQ(onGpu, onCpu) << "the GPU's culling covers other pixels than the CPU's";
    drawWith(away, stats);
    EXPECT_TRUE(stats.gpuCulled);
    EXPECT_EQ(stats.drawn, 0u);
    drawWith(away, stats);
    EXPECT_FALSE(stats.gpuCulled);
    EXPECT_EQ(stats.drawn, 0u);
    EXPECT_EQ(drawWith(facing, stats), onCpu); // from the CPU again
    EXPECT_FALSE(stats.gpuCulled);
}

// Decals on the wall behind the crate, hidden from the camera, and decals beside it: the occlusion
// test culls exactly the hidden ones, and the coverage stays the same bit for bit.
TEST(GpuCulling, OcclusionCullsTheBoxesHiddenBehindTheSceneAndNoPixelChanges) {
    SPATTER_REQUIRE_GL(gl);
    std::vector<Decal> decals;
    // The camera faces the crate (x and y 0.5 to 1.1, z 0.2 to 0.8) from 2.5 m: it hides the wall from
    // 0.36 to 1.24 in x and y.
    const Camera camera = test::lookAt({0.8, 0.8, 2.5}, {0.8, 0.8, 0.0});
    for (int i = 0; i < 6; ++i) { // hidden behind it, at least five pixels inside its shadow
        Decal d =
            test::WallScene::decalAt(0, {0.65f + 0.15f * float(i % 3), -0.3f + 0.2f * float(i / 3), 0.05f});
        d.size = glm::vec2(0.08f);
        d.halfDepth = 0.05f;
        decals.push_back(d);
    }
    for (int i = 0; i < 4; ++i) { // in plain view
        Decal d = test::WallScene::decalAt(
            0, {i < 2 ? -1.0f + 0.4f * float(i) : 1.6f + 0.4f * float(i), 0.3f, 0.05f});
        d.size = glm::vec2(0.3f);
        decals.push_back(d);
    }
    Variant noOcclusion;
    noOcclusion.occlusion = false;
    const Culled open = coverage(decals, glm::dvec3(0.0), camera, true, noOcclusion);
    const Culled occluded = coverage(decals, glm::dvec3(0.0), camera, true);
    EXPECT_EQ(open.stats.drawn, decals.size());
    EXPECT_EQ(occluded.stats.drawn, 4u) << "the six boxes behind the crate are culled";
    EXPECT_EQ(occluded.stats.culled, 6u);
    ASSERT_EQ(occluded.coverage.size(), open.coverage.size());
    EXPECT_GT(test::countSet(open.coverage), 0u);
    EXPECT_EQ(occluded.coverage, open.coverage);
    // Far from the origin too, where the depth of a box and of the crate differ by little.
    const glm::dvec3 far(1.0e5, -2.0e4, 3.0e5);
    const Culled openFar = coverage(decals, far, camera, true, noOcclusion);
    const Culled occludedFar = coverage(decals, far, camera, true);
    EXPECT_EQ(occludedFar.coverage, openFar.coverage);
    EXPECT_LE(occludedFar.stats.drawn, openFar.stats.drawn);
}
