// The projector's forward path: decals binned into screen tiles on the GPU (DecalProjector::bin) and
// applied in a forward host's fragment shader (forward.glsl) give what the G-buffer blend gives, in
// the same order; bad frames are refused naming the field.

#include "HostedWall.hpp"
#include "RenderTestSupport.hpp"
#include "TestData.hpp"

#include "spatter/render/DecalProjector.hpp"

#include <epoxy/gl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

using namespace spatter;
using ::testing::HasSubstr;

namespace {

// The wall's decals and a stack of `count` more over the first, alternating looks and offsets, so
// that many decals share tiles and their order shows; every third projected along a slanted shot.
std::vector<Decal> stackedDecals(const test::WallScene& wall, int count) {
    std::vector<Decal> decals = wall.decals;
    for (int i = 0; i < count; ++i) {
        Decal d = test::WallScene::decalAt(0, {-0.8f + 0.02f * float(i), 0.1f * float(i % 3), 0.05f});
        d.type = uint16_t(i % 2);
        const Frame f = d.frame();
        if (i % 3 == 0) d.setProjectionAxis(f.normal + 0.8f * f.tangent - 0.4f * f.bitangent);
        decals.push_back(d);
    }
    return decals;
}

std::vector<DecalType> twoLooks(const test::WallScene& wall) {
    std::vector<DecalType> types = wall.types;
    DecalType blood = types[0];
    blood.texture = int(DecalTexture::Blood);
    blood.roughness = 0.9f;
    types.push_back(blood);
    return types;
}

} // namespace

TEST(Forward, AppliedInTheHostsShaderGivesWhatTheGBufferBlendGivesInOrder) {
    SPATTER_REQUIRE_GL(gl);
    std::optional<test::HostedWall> h = test::HostedWall::make();
    ASSERT_TRUE(h);
    h->projector.setDecalTypes(twoLooks(h->wall));
    h->projector.setDecals(stackedDecals(h->wall, 40));
    const HostFrame f = h->host.frame(h->wall.camera, true);
    ASSERT_TRUE(h->projector.draw(f).ok());
    const Image blendAlbedo = h->host.read(f.albedoTexture),
                blendMaterial = h->host.read(f.roughness.texture);

    Result<ProjectorStats> st =
        h->host.drawForward(h->wall.transforms, h->wall.ids, h->wall.camera, h->projector);
    ASSERT_TRUE(st.ok()) << st.error();
    EXPECT_EQ(st->drawn, 42u);
    EXPECT_EQ(st->variant, "FORWARD");
    const Image albedo = h->host.read(f.albedoTexture), material = h->host.read(f.roughness.texture);
    const std::vector<uint8_t> covered = test::whiteMask(h->host.read(h->host.coverageTexture()));
    ASSERT_GT(test::countSet(covered), 300u);
    double sum = 0.0, roughnessSum = 0.0;
    int worst = 0;
    size_t n = 0, far = 0;
    for (size_t p = 0; p < covered.size(); ++p) {
        if (!covered[p]) continue;
        for (size_t c = 0; c < 3; ++c) {
            const int d = std::abs(int(albedo.rgba[p * 4 + c]) - int(blendAlbedo.rgba[p * 4 + c]));
            sum += d;
            worst = std::max(worst, d);
            far += d > 4 ? 1 : 0;
            ++n;
        }
        roughnessSum += std::abs(int(material.rgba[p * 4 + 1]) - int(blendMaterial.rgba[p * 4 + 1]));
    }
    const double mean = sum / double(n), roughnessMean = 3.0 * roughnessSum / double(n);
    std::printf("forward vs G-buffer blend under %zu decal pixels: albedo mean %.2f/255, largest %d/255, "
                "%zu of %zu channels > 4/255; roughness mean %.2f/255\n",
                n / 3, mean, worst, far, n, roughnessMean);
    // The blend rounds to 8 bits after each of up to 40 decals while the forward shader blends in float,
    // and the texture's level of detail comes from depth derivatives in one and from the position's in
    // the other, which differ at the decals' alpha edges. Drawn in reverse order the same decals
    // differ by 7/255 on average and in a quarter of the channels by more than 4/255.
    EXPECT_LE(mean, 1.5);
    EXPECT_LE(far, n / 20);
    EXPECT_LE(roughnessMean, 2.0);
}

// Culled on the GPU (no count on the CPU: tiles of a fixed length, filled as the rectangles are
// found on the GPU), the forward pass gives what it gives culled on the CPU, bit for bit, with the
// decals stacked in the same tiles and the wall's decals spread over the view.
// Culled on the GPU, the tiles' runs are sized by the fullest tile of an earlier binning; a tile with
// more walks every decal binned, in drawing order, to the same pixels: the 40 stacked decals binned a
// second time (runs of 128) and binned after the wall's two (runs of 16: the whole list).
TEST(Forward, CulledOnTheGpuGivesWhatCulledOnTheCpuGives) {
    SPATTER_REQUIRE_GL(gl);
    Image images[3];
    ProjectorStats stats[3];
    for (const int run : {0, 1, 2}) {
        const bool onGpu = run > 0;
        std::optional<test::HostedWall> h = test::HostedWall::make();
        ASSERT_TRUE(h);
        ProjectorSettings settings;
        settings.gpuCullingFrom = onGpu ? 0 : std::numeric_limits<size_t>::max();
        settings.waitForTimers = true; // this bin's counts
        Result<DecalProjector> p = DecalProjector::create(settings);
        ASSERT_TRUE(p.ok()) << p.error();
        h->projector = std::move(p).value();
        ASSERT_TRUE(h->projector.setObjects(h->wall.transforms, h->wall.ids).ok());
        h->projector.setDecalTypes(twoLooks(h->wall));
        if (run > 0) {
            h->projector.setDecals(run == 1 ? stackedDecals(h->wall, 40) : h->wall.decals);
            ASSERT_TRUE(
                h->host.drawForward(h->wall.transforms, h->wall.ids, h->wall.camera, h->projector).ok());
        }
        std::vector<Decal> decals = stackedDecals(h->wall, 40);
        for (int i = 0; i < 30; ++i) // some in view, some beyond its edges
            decals.push_back(
                test::WallScene::decalAt(0, {-4.0f + 0.3f * float(i), -1.0f + 0.1f * float(i % 7), 0.05f}));
        h->projector.setDecals(decals);
        Result<ProjectorStats> st =
            h->host.drawForward(h->wall.transforms, h->wall.ids, h->wall.camera, h->projector);
        ASSERT_TRUE(st.ok()) << st.error();
        EXPECT_EQ(st->gpuCulled, onGpu);
        EXPECT_FALSE(st->tilesLeftOut);
        stats[run] = st.value();
        images[run] = h->host.read(h->host.albedoTexture());
    }
    std::printf("forward, %zu decals: %zu drawn culled on the CPU, %zu on the GPU\n", stats[0].decals,
                stats[0].drawn, stats[1].drawn);
    EXPECT_GT(stats[0].drawn, 50u);
    EXPECT_GT(stats[0].culled, 0u);
    EXPECT_GE(stats[1].drawn, stats[0].drawn); // the GPU's float test keeps a margin
    EXPECT_EQ(test::differingPixels(images[0], images[1]), 0u);
    EXPECT_EQ(test::differingPixels(images[0], images[2]), 0u);
}

TEST(Forward, TilesAreEmptyWhenNoDecalIsInView) {
    SPATTER_REQUIRE_GL(gl);
    std::optional<test::HostedWall> h = test::HostedWall::make();
    ASSERT_TRUE(h);
    ASSERT_TRUE(h->host.drawForward(h->wall.transforms, h->wall.ids, h->wall.camera, h->projector).ok());
    ASSERT_GT(test::countSet(test::whiteMask(h->host.read(h->host.coverageTexture()))), 100u);
    const Camera turned = test::lookAt({0.0, 1.0, 4.0}, {0.0, 1.0, 8.0});
    Result<ProjectorStats> behind = h->projector.bin(h->host.forwardFrame(turned));
    ASSERT_TRUE(behind.ok()) << behind.error();
    EXPECT_TRUE(behind->skipped);
    EXPECT_EQ(behind->culled, 2u);
    // No decal left: the tiles of the earlier frame must not show.
    h->projector.setDecals({});
    Result<ProjectorStats> st =
        h->host.drawForward(h->wall.transforms, h->wall.ids, h->wall.camera, h->projector);
    ASSERT_TRUE(st.ok()) << st.error();
    EXPECT_TRUE(st->skipped);
    EXPECT_EQ(test::countSet(test::whiteMask(h->host.read(h->host.coverageTexture()))), 0u);
}

TEST(Forward, RefusesFramesThatDoNotFitNamingTheField) {
    SPATTER_REQUIRE_GL(gl);
    std::optional<test::HostedWall> h = test::HostedWall::make();
    ASSERT_TRUE(h);
    const ForwardFrame good = h->host.forwardFrame(h->wall.camera);
    ASSERT_TRUE(h->projector.bin(good).ok());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    struct Case {
        const char* field;
        ForwardFrame frame;
    };
    std::vector<Case> cases(6, Case{"", good});
    cases[0] = {"ForwardFrame viewport", good};
    cases[0].frame.width = 0;
    cases[1] = {"ForwardFrame viewport", good};
    cases[1].frame.height = 20000;
    cases[2] = {"ForwardFrame.projection", good};
    cases[2].frame.projection = glm::dmat4(0.0);
    cases[3] = {"ForwardFrame.view", good};
    cases[3].frame.view[1][1] = nan;
    cases[4] = {"ForwardFrame.eye", good};
    cases[4].frame.eye.x = std::numeric_limits<double>::infinity();
    cases[5] = {"ForwardFrame.reversedZ", good};
    cases[5].frame.reversedZ = true;
    for (const Case& c : cases) {
        Result<ProjectorStats> st = h->projector.bin(c.frame);
        ASSERT_FALSE(st.ok()) << c.field;
        EXPECT_THAT(st.error(), HasSubstr(c.field));
    }
    ProjectorSettings tiles;
    tiles.forwardTileSize = 12;
    Result<DecalProjector> bad = DecalProjector::create(tiles);
    ASSERT_FALSE(bad.ok());
    EXPECT_THAT(bad.error(), HasSubstr("forwardTileSize"));
    ProjectorSettings frame, resolve;
    frame.normalFrame = DecalNormalFrame(5);
    resolve.deferredResolve = DeferredResolve(9);
    for (const auto& [settings, field] :
         {std::pair{frame, "normalFrame"}, std::pair{resolve, "deferredResolve"}}) {
        Result<DecalProjector> none = DecalProjector::create(settings);
        ASSERT_FALSE(none.ok()) << field;
        EXPECT_THAT(none.error(), HasSubstr(field));
    }
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// Bindings past the context's limits, or two on one point or unit, are refused naming the field, and
// nothing is bound.
TEST(Forward, RefusesBindingsTheContextHasNotOrThatCollide) {
    SPATTER_REQUIRE_GL(gl);
    std::optional<test::HostedWall> h = test::HostedWall::make();
    ASSERT_TRUE(h);
    ASSERT_TRUE(h->projector.bin(h->host.forwardFrame(h->wall.camera)).ok());
    struct Case {
        const char* field;
        ForwardBindings bindings;
    };
    std::vector<Case> cases(4);
    cases[0].field = "ForwardBindings.albedoUnit";
    cases[0].bindings.albedoUnit = 100000;
    cases[1].field = "ForwardBindings.items";
    cases[1].bindings.items = 100000;
    cases[2].field = "ForwardBindings.tiles: the binding point of decals";
    cases[2].bindings.tiles = cases[2].bindings.decals;
    cases[3].field = "ForwardBindings.normalUnit: the texture unit of albedoUnit";
    cases[3].bindings.normalUnit = cases[3].bindings.albedoUnit;
    for (const Case& c : cases) {
        glBindTextureUnit(c.bindings.albedoUnit < 64 ? c.bindings.albedoUnit : 0, 0);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, c.bindings.decals, 0);
        const Status st = h->projector.bindForward(c.bindings);
        ASSERT_FALSE(st.ok()) << c.field;
        EXPECT_THAT(st.error(), HasSubstr(c.field));
        GLint texture = -1, buffer = -1;
        glActiveTexture(GL_TEXTURE0 + (c.bindings.albedoUnit < 64 ? c.bindings.albedoUnit : 0));
        glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &texture);
        glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, c.bindings.decals, &buffer);
        EXPECT_EQ(texture, 0) << c.field;
        EXPECT_EQ(buffer, 0) << c.field;
    }
    glActiveTexture(GL_TEXTURE0);
    EXPECT_TRUE(h->projector.bindForward().ok());
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}
