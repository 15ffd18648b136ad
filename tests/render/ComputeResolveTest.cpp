// The G-buffer blend resolved by one compute pass over the forward path's tiles
// (DeferredResolve::Compute) against the boxes (DeferredResolve::Boxes): the same decals give the
// same albedo and normals, and frames the compute pass does not take go to the boxes.

#include "HostedWall.hpp"
#include "RenderTestSupport.hpp"
#include "ShotDecals.hpp"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>

using namespace spatter;

namespace {

constexpr int kResolveWidth = 160;
constexpr int kResolveHeight = 120;

struct Rendered {
    Image albedo, normal, coverage;
    std::string variant, coverageVariant;
    ProjectorMemory memory;
};

// The gallery's shots (test::galleryShots) drawn with `resolve`, culled on the GPU from
// `gpuCullingFrom` decals.
Rendered renderGallery(DeferredResolve resolve, std::optional<size_t> gpuCullingFrom = {}) {
    const test::GalleryShots g = test::galleryShots();
    EXPECT_GT(g.placed.placed, 40u);
    RendererSettings settings;
    settings.deferredResolve = resolve;
    settings.gpuCullingFrom = gpuCullingFrom;
    Result<Renderer> r = test::makeRenderer(kResolveWidth, kResolveHeight, settings);
    EXPECT_TRUE(r.ok()) << r.error();
    if (!r) return {};
    EXPECT_TRUE(r->setScene(g.scene).ok());
    EXPECT_TRUE(r->setObjectIds(g.placed.inputs.objectIds).ok());
    r->setDecalTypes(g.placed.inputs.types);
    r->setDecals(g.placed.inputs.decals);
    Rendered out;
    FrameStats st;
    out.albedo = test::renderView(r.value(), g.camera, View::Albedo, &st);
    out.variant = st.decalVariant;
    out.normal = test::renderView(r.value(), g.camera, View::Normal);
    out.coverage = test::renderView(r.value(), g.camera, View::Coverage, &st);
    out.coverageVariant = st.decalVariant;
    out.memory = r->decalMemory();
    return out;
}

// The largest difference of the first `channels` channels between `a` and `b`, and how many pixels
// differ by more than `tolerance` in one of them.
std::pair<int, size_t> difference(const Image& a, const Image& b, int tolerance, size_t channels = 3) {
    int largest = 0;
    size_t over = 0;
    for (size_t p = 0; p + 3 < a.rgba.size() && p + 3 < b.rgba.size(); p += 4) {
        int worst = 0;
        for (size_t c = 0; c < channels; ++c)
            worst = std::max(worst, std::abs(int(a.rgba[p + c]) - int(b.rgba[p + c])));
        largest = std::max(largest, worst);
        over += worst > tolerance;
    }
    return {largest, over};
}

// `decals` and thirty overlapping decals a quarter wide across the wall.
std::vector<Decal> withThirtyOverlapping(std::vector<Decal> decals) {
    for (int i = 0; i < 30; ++i) {
        Decal d = test::WallScene::decalAt(0, {-0.9f + 0.06f * float(i), 0.1f * float(i % 4), 0.05f});
        d.size = glm::vec2(0.25f);
        decals.push_back(d);
    }
    return decals;
}

// Texture `texture` of the wall host's size as RGBA floats (the DBuffer's normals are signed).
std::vector<float> readFloats(GLuint texture) {
    std::vector<float> texels(size_t(test::kWallWidth) * test::kWallHeight * 4);
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(texels.size() * sizeof(float)), texels.data());
    return texels;
}

// How many texels of `a` and `b` differ by more than `tolerance` in a channel.
size_t texelsApart(const std::vector<float>& a, const std::vector<float>& b, float tolerance) {
    size_t over = 0;
    for (size_t t = 0; t + 3 < a.size() && t + 3 < b.size(); t += 4) {
        bool apart = false;
        for (size_t c = 0; c < 4; ++c)
            apart = apart || std::abs(a[t + c] - b[t + c]) > tolerance;
        over += apart;
    }
    return over;
}

// How many texels of `t` some decal covers (A below 1: less of the surface shows through).
size_t coveredTexels(const std::vector<float>& t) {
    size_t covered = 0;
    for (size_t i = 3; i < t.size(); i += 4)
        covered += t[i] < 0.99f;
    return covered;
}

// The compute resolve of decals the GPU culls, the counts of each draw read at its end.
ProjectorSettings culledCompute() {
    ProjectorSettings settings;
    settings.deferredResolve = DeferredResolve::Compute;
    settings.gpuCullingFrom = 0;
    settings.waitForTimers = true;
    return settings;
}

// `count` decals on the wall a hundredth apart, overlapping over one spot.
std::vector<Decal> stackedOnWall(int count) {
    std::vector<Decal> decals;
    for (int i = 0; i < count; ++i)
        decals.push_back(test::WallScene::decalAt(0, {0.01f * float(i), 0.0f, 0.05f}));
    return decals;
}

} // namespace

// Culled on the CPU, and on the GPU, whose short tile runs (a fullest tile of a few decals) have the
// resolve test a pixel against the boxes before it reads its neighbours and targets.
class ComputeResolveCulling : public ::testing::TestWithParam<bool> {};

TEST_P(ComputeResolveCulling, BlendsTheGBufferAsTheBoxesDo) {
    SPATTER_REQUIRE_GL(gl);
    const std::optional<size_t> from = GetParam() ? std::optional<size_t>(0) : std::nullopt;
    const Rendered boxes = renderGallery(DeferredResolve::Boxes, from);
    const Rendered compute = renderGallery(DeferredResolve::Compute, from);
    ASSERT_EQ(boxes.albedo.rgba.size(), compute.albedo.rgba.size());
    EXPECT_EQ(boxes.variant.find("COMPUTE"), std::string::npos) << boxes.variant;
    EXPECT_NE(compute.variant.find("COMPUTE"), std::string::npos) << compute.variant;
    test::dumpImage("compute-resolve-albedo-boxes", boxes.albedo);
    test::dumpImage("compute-resolve-albedo-compute", compute.albedo);
    // Blending in float where the boxes round to the target after each decal moves a channel by a
    // step or two; texture derivatives from the neighbouring pixels where the boxes take them across
    // their pixel quad pick another mip level on a silhouette (the arch's top edge here), so a few
    // pixels there differ more.
    const size_t pixels = boxes.albedo.rgba.size() / 4;
    const auto [albedoLargest, albedoOver] = difference(boxes.albedo, compute.albedo, 4);
    const auto [normalLargest, normalOver] = difference(boxes.normal, compute.normal, 4);
    EXPECT_LT(albedoOver, pixels / 100) << "largest difference " << albedoLargest;
    EXPECT_LT(normalOver, pixels / 100) << "largest difference " << normalLargest;
    // The decals changed the frame: the comparison is not of two undecorated walls.
    const size_t covered = test::countSet(test::whiteMask(compute.coverage));
    EXPECT_GT(covered, pixels / 20);
}

INSTANTIATE_TEST_SUITE_P(CpuAndGpu, ComputeResolveCulling, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& p) {
                             return p.param ? "GpuCulled" : "CpuCulled";
                         });

TEST(ComputeResolve, CoverageModeDrawsTheBoxes) {
    SPATTER_REQUIRE_GL(gl);
    const Rendered boxes = renderGallery(DeferredResolve::Boxes);
    const Rendered compute = renderGallery(DeferredResolve::Compute);
    EXPECT_EQ(compute.coverageVariant.find("COMPUTE"), std::string::npos) << compute.coverageVariant;
    EXPECT_EQ(boxes.coverage.rgba, compute.coverage.rgba);
}

TEST(ComputeResolve, CountsItsScreenTilesAndTheNormalCopyAsMemorySizedByTheViewport) {
    SPATTER_REQUIRE_GL(gl);
    const ProjectorMemory boxes = renderGallery(DeferredResolve::Boxes).memory;
    const ProjectorMemory compute = renderGallery(DeferredResolve::Compute).memory;
    // Culled on the CPU, the boxes need no depth pyramid and no tiles: the copy of the renderer's
    // normals (4 bytes a texel) is all they hold by the viewport.
    EXPECT_EQ(boxes.gpuScreenBytes, size_t(kResolveWidth) * kResolveHeight * 4);
    EXPECT_GT(compute.gpuScreenBytes, 0u);
    // The same decals take the same buffers either way.
    EXPECT_EQ(compute.gpuBufferBytes - compute.gpuScreenBytes, boxes.gpuBufferBytes - boxes.gpuScreenBytes);
}

// In a foreign host's frame (standard Z, RGBA8 albedo, RGB10_A2 world normals, object IDs), with
// roughness in the G channel of its own target or in the albedo's alpha: the crate's deep decal stays
// off the wall behind it, and the targets are the boxes' within a few steps.
TEST(ComputeResolve, BlendsAHostsFrameAsTheBoxesDo) {
    SPATTER_REQUIRE_GL(gl);
    for (const bool alphaRoughness : {false, true}) {
        std::vector<Image> albedo, normal, material;
        std::vector<std::string> variants;
        for (const DeferredResolve resolve : {DeferredResolve::Boxes, DeferredResolve::Compute}) {
            ProjectorSettings settings;
            settings.deferredResolve = resolve;
            std::optional<test::HostedWall> h = test::HostedWall::make(settings);
            ASSERT_TRUE(h);
            h->projector.setDecals(withThirtyOverlapping(h->wall.decals));
            HostFrame f = h->host.frame(h->wall.camera, true);
            if (alphaRoughness) f.roughness = {f.albedoTexture, 3};
            Result<ProjectorStats> st = h->projector.draw(f);
            ASSERT_TRUE(st.ok()) << st.error();
            variants.push_back(st->variant);
            albedo.push_back(h->host.read(f.albedoTexture));
            normal.push_back(h->host.read(f.normals.texture));
            material.push_back(h->host.read(f.roughness.texture));
        }
        EXPECT_EQ(variants[0].find("COMPUTE"), std::string::npos) << variants[0];
        EXPECT_NE(variants[1].find("COMPUTE"), std::string::npos) << variants[1];
        const size_t pixels = albedo[0].rgba.size() / 4;
        for (const auto* targets : {&albedo, &normal, &material}) {
            const auto [largest, over] = difference((*targets)[0], (*targets)[1], 4, 4);
            EXPECT_LT(over, pixels / 100)
                << "largest difference " << largest << (alphaRoughness ? " (alpha)" : "");
        }
    }
}

// The DBuffer path resolved in compute fills the projector's decal buffers as its boxes do, culled on
// the CPU and on the GPU: thirty overlapping normal-mapped decals on the wall (and the crate's, kept
// off the wall by object IDs) give the same albedo, normals and roughness, each with how much of the
// surface shows through; a later draw with nothing in view clears what the compute pass wrote.
class ComputeResolveDBuffer : public ::testing::TestWithParam<bool> {};

TEST_P(ComputeResolveDBuffer, FillsTheDecalBuffersAsTheBoxesDo) {
    SPATTER_REQUIRE_GL(gl);
    std::vector<std::vector<float>> buffers[3];
    std::vector<std::string> variants;
    for (const DeferredResolve resolve : {DeferredResolve::Boxes, DeferredResolve::Compute}) {
        ProjectorSettings settings;
        settings.deferredResolve = resolve;
        if (GetParam()) settings.gpuCullingFrom = 0;
        std::optional<test::HostedWall> h = test::HostedWall::make(settings);
        ASSERT_TRUE(h);
        h->projector.setDecals(withThirtyOverlapping(h->wall.decals));
        ProjectorDraw dbuffer;
        dbuffer.path = ProjectorPath::DBuffer;
        Result<ProjectorStats> st = h->projector.draw(h->host.frame(h->wall.camera, true), dbuffer);
        ASSERT_TRUE(st.ok()) << st.error();
        variants.push_back(st->variant);
        const ProjectorResources r = h->projector.resources();
        const GLuint textures[3] = {r.dbufferAlbedo, r.dbufferNormal, r.dbufferMaterial};
        for (int b = 0; b < 3; ++b)
            buffers[b].push_back(readFloats(textures[b]));
        const Camera away = test::lookAt({0.0, 1.0, 4.0}, {0.0, 1.0, 8.0});
        ASSERT_TRUE(h->projector.draw(h->host.frame(away, true), dbuffer).ok());
        for (const GLuint t : textures)
            EXPECT_EQ(coveredTexels(readFloats(t)), 0u) << "texture " << t;
    }
    EXPECT_EQ(variants[0].find("COMPUTE"), std::string::npos) << variants[0];
    EXPECT_NE(variants[1].find("DBUFFER"), std::string::npos) << variants[1];
    EXPECT_NE(variants[1].find("COMPUTE"), std::string::npos) << variants[1];
    const size_t texels = buffers[0][0].size() / 4;
    const char* names[3] = {"albedo", "normal", "material"};
    for (int b = 0; b < 3; ++b) {
        EXPECT_GT(coveredTexels(buffers[b][0]), texels / 40) << names[b];
        EXPECT_LT(texelsApart(buffers[b][0], buffers[b][1], 4.0f / 255.0f), texels / 100) << names[b];
    }
}

INSTANTIATE_TEST_SUITE_P(CpuAndGpu, ComputeResolveDBuffer, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& p) {
                             return p.param ? "GpuCulled" : "CpuCulled";
                         });

// Culled on the GPU, a tile holds at most forwardTileCapacity decals: 40 decals over one spot, with a
// capacity of 16, are reported as left out (ProjectorStats::tilesLeftOut); 8 are not.
TEST(ComputeResolve, ReportsDecalsLeftOutOfAFullTile) {
    SPATTER_REQUIRE_GL(gl);
    for (const int count : {8, 40}) {
        ProjectorSettings settings = culledCompute();
        settings.forwardTileCapacity = 16;
        std::optional<test::HostedWall> h = test::HostedWall::make(settings);
        ASSERT_TRUE(h);
        h->projector.setDecals(stackedOnWall(count));
        Result<ProjectorStats> st = h->projector.draw(h->host.frame(h->wall.camera, true));
        ASSERT_TRUE(st.ok()) << st.error();
        EXPECT_TRUE(st->gpuCulled);
        EXPECT_NE(st->variant.find("COMPUTE"), std::string::npos) << st->variant;
        EXPECT_EQ(st->tilesLeftOut, count > 16) << count << " decals";
    }
}

// Culled on the GPU, the tiles' runs are sized by the fullest tile of an earlier binning; a tile with
// more decals than its run holds (up to forwardTileCapacity) walks every decal in view. 40 overlapping
// decals over one spot blend to the same pixels drawn after a draw of two decals (runs of 16: the
// whole list) as drawn a second time (runs of 128), and nothing is reported left out.
TEST(ComputeResolve, ATileFullerThanItsRunBlendsEveryDecalInOrder) {
    SPATTER_REQUIRE_GL(gl);
    std::vector<Image> albedo, normal;
    for (const bool afterFew : {false, true}) {
        std::optional<test::HostedWall> h = test::HostedWall::make(culledCompute());
        ASSERT_TRUE(h);
        const std::vector<Decal> decals = stackedOnWall(40);
        if (!afterFew) h->projector.setDecals(decals);
        ASSERT_TRUE(h->projector.draw(h->host.frame(h->wall.camera, true)).ok());
        h->host.draw(h->wall.transforms, h->wall.ids, h->wall.camera);
        h->projector.setDecals(decals);
        const HostFrame f = h->host.frame(h->wall.camera, true);
        Result<ProjectorStats> st = h->projector.draw(f);
        ASSERT_TRUE(st.ok()) << st.error();
        EXPECT_TRUE(st->gpuCulled);
        EXPECT_NE(st->variant.find("COMPUTE"), std::string::npos) << st->variant;
        EXPECT_FALSE(st->tilesLeftOut) << afterFew;
        albedo.push_back(h->host.read(f.albedoTexture));
        normal.push_back(h->host.read(f.normals.texture));
    }
    EXPECT_EQ(test::differingPixels(albedo[0], albedo[1]), 0u);
    EXPECT_EQ(test::differingPixels(normal[0], normal[1]), 0u);
}

// The tiles' runs are sized by the fullest tile the GPU reported: a thousand decals over one spot
// take runs of 2048 from the second draw on (runs of 32 before any report), and the wall's two
// decals after them runs of 16, in an item list made anew, smaller.
TEST(ComputeResolve, SizesTheTilesRunsByTheFullestTile) {
    SPATTER_REQUIRE_GL(gl);
    ProjectorSettings settings = culledCompute();
    settings.forwardTileSize = 8;
    settings.forwardTileCapacity = 4096;
    std::optional<test::HostedWall> h = test::HostedWall::make(settings);
    ASSERT_TRUE(h);
    std::vector<Decal> stacked;
    for (int i = 0; i < 1000; ++i)
        stacked.push_back(test::WallScene::decalAt(0, {0.0005f * float(i), 0.0f, 0.05f}));
    std::vector<size_t> screenBytes;
    for (int draw = 0; draw < 4; ++draw) {
        h->projector.setDecals(draw < 2 ? stacked : h->wall.decals);
        h->host.draw(h->wall.transforms, h->wall.ids, h->wall.camera);
        Result<ProjectorStats> st = h->projector.draw(h->host.frame(h->wall.camera, true));
        ASSERT_TRUE(st.ok()) << st.error();
        EXPECT_FALSE(st->tilesLeftOut) << "draw " << draw;
        screenBytes.push_back(h->projector.memory().gpuScreenBytes);
    }
    const size_t tiles = size_t(test::kWallWidth / 8) * size_t(test::kWallHeight / 8);
    EXPECT_GT(screenBytes[1], screenBytes[0] + tiles * 1024 * 4) << "runs of 2048 items of 4 bytes";
    EXPECT_EQ(screenBytes[2], screenBytes[1]);
    EXPECT_LT(screenBytes[3], screenBytes[1] / 4);
}

// With ProjectorSettings::stageTimers the pass's time splits into its stages, of the same frame as
// its GPU time: the compute resolve bins and draws; the boxes bin nothing, and their stages add up
// to the pass's time; without the setting no stage is timed.
TEST(ComputeResolve, StageTimersSplitThePassIntoItsStages) {
    SPATTER_REQUIRE_GL(gl);
    for (const DeferredResolve resolve : {DeferredResolve::Compute, DeferredResolve::Boxes}) {
        ProjectorSettings settings = culledCompute();
        settings.deferredResolve = resolve;
        settings.stageTimers = true;
        std::optional<test::HostedWall> h = test::HostedWall::make(settings);
        ASSERT_TRUE(h);
        h->projector.setDecals(stackedOnWall(40));
        for (int draw = 0; draw < 3; ++draw) {
            h->host.draw(h->wall.transforms, h->wall.ids, h->wall.camera);
            Result<ProjectorStats> st = h->projector.draw(h->host.frame(h->wall.camera, true));
            ASSERT_TRUE(st.ok()) << st.error();
            const ProjectorStageTimes& s = st->stages;
            EXPECT_EQ(s.frame, st->gpuFrame);
            EXPECT_GE(s.cullMs, 0.0);
            EXPECT_GE(s.readBackMs, 0.0);
            EXPECT_GT(s.drawMs, 0.0);
            if (resolve == DeferredResolve::Compute) {
                EXPECT_GT(s.binMs, 0.0);
                continue;
            }
            EXPECT_EQ(s.binMs, 0.0);
            const double sum = s.cullMs + s.drawMs + s.readBackMs;
            EXPECT_NEAR(sum, st->gpuMs, 0.5 * st->gpuMs + 0.05) << "draw " << draw;
        }
    }
    std::optional<test::HostedWall> h = test::HostedWall::make(culledCompute());
    ASSERT_TRUE(h);
    h->projector.setDecals(stackedOnWall(4));
    Result<ProjectorStats> st = h->projector.draw(h->host.frame(h->wall.camera, true));
    ASSERT_TRUE(st.ok()) << st.error();
    EXPECT_EQ(st->stages.frame, -1);
}
