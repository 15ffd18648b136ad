// Decal texture cutouts (DecalProjector::decalTextureCutouts): each layer's rectangle of visible
// texels, widened by a sixteenth of the layer, outside which its decals show nothing. Boxes are drawn
// over it alone; the compute resolve bins the boxes over it where the GPU culls (whole boxes where the
// CPU does), the forward path whole boxes, both testing each pixel, and all draw the same.

#include "HostedWall.hpp"
#include "RenderTestSupport.hpp"

#include "spatter/render/DecalProjector.hpp"
#include "spatter/render/DecalTextures.hpp"

#include <gtest/gtest.h>

#include <optional>

using namespace spatter;

namespace {

constexpr int kSize = 64; // texels a side of the test images

// A clear kSize x kSize image with the texels of columns [x0, x1] and rows [y0, y1] (row 0 at the
// top) opaque red.
Image redBlock(int x0, int x1, int y0, int y1) {
    Image im;
    im.width = im.height = kSize;
    im.name = "red block";
    im.rgba.assign(size_t(kSize) * kSize * 4, 0);
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            uint8_t* p = &im.rgba[(size_t(y) * kSize + size_t(x)) * 4];
            p[0] = 230;
            p[3] = 255;
        }
    return im;
}

// The cutout the projector gives a layer made of `albedo`.
std::optional<glm::vec4> cutoutOf(DecalProjector& projector, const Image& albedo) {
    Result<int> layer = projector.addDecalTexture(albedo);
    EXPECT_TRUE(layer.ok()) << layer.error();
    if (!layer) return std::nullopt;
    const std::vector<glm::vec4> cutouts = projector.decalTextureCutouts();
    EXPECT_EQ(int(cutouts.size()), projector.decalTextureLayers());
    return cutouts.at(size_t(layer.value()));
}

enum class CutoutPath { Boxes, Compute, ComputeGpuCulled, Forward };

// Two decals on the wall, one turned, with the red block's layer, drawn through `path`: the host's
// albedo.
Image drawRedBlock(CutoutPath path) {
    ProjectorSettings settings;
    settings.decalTextureSize = kSize;
    if (path == CutoutPath::Compute || path == CutoutPath::ComputeGpuCulled)
        settings.deferredResolve = DeferredResolve::Compute;
    if (path == CutoutPath::ComputeGpuCulled) settings.gpuCullingFrom = 0; // binned by the cutout
    std::optional<test::HostedWall> h = test::HostedWall::make(settings);
    if (!h) return {};
    // The top left of the texture: towards -u and +v.
    Result<int> layer = h->projector.addDecalTexture(redBlock(4, 39, 4, 39));
    EXPECT_TRUE(layer.ok()) << layer.error();
    if (!layer) return {};
    DecalType t = h->wall.types[0];
    t.texture = layer.value();
    t.normalMap = false;
    t.depthFade = DepthFade::None;
    h->projector.setDecalTypes({t});
    Decal upright = test::WallScene::decalAt(0, {-0.8f, 0.0f, 0.05f}), turned = upright;
    upright.size = turned.size = glm::vec2(1.2f);
    turned.center = {0.6f, 0.2f, 0.05f};
    EXPECT_TRUE(turned.setFrame({{0.6, 0.8, 0}, {-0.8, 0.6, 0}, {0, 0, 1}}));
    h->projector.setDecals({upright, turned});
    const HostFrame f = h->host.frame(h->wall.camera, true);
    if (path == CutoutPath::Forward) {
        Result<ProjectorStats> st =
            h->host.drawForward(h->wall.transforms, h->wall.ids, h->wall.camera, h->projector);
        EXPECT_TRUE(st.ok()) << st.error();
        return h->host.read(f.albedoTexture);
    }
    Result<ProjectorStats> st = h->projector.draw(f);
    EXPECT_TRUE(st.ok()) << st.error();
    return h->host.read(f.albedoTexture);
}

// Each pixel: 1 where it is red.
std::vector<uint8_t> redMask(const Image& image) {
    std::vector<uint8_t> mask;
    for (size_t i = 0; i + 3 < image.rgba.size(); i += 4)
        mask.push_back(image.rgba[i] > 150 && image.rgba[i + 1] < 60 && image.rgba[i + 2] < 60 ? 1 : 0);
    return mask;
}

} // namespace

TEST(DecalCutout, IsTheRectangleOfVisibleTexelsWidenedByASixteenthOfTheLayer) {
    SPATTER_REQUIRE_GL(gl);
    ProjectorSettings settings;
    settings.decalTextureSize = kSize; // the images are not resized
    Result<DecalProjector> p = DecalProjector::create(settings);
    ASSERT_TRUE(p.ok()) << p.error();
    // Columns 8-15 and rows 4-11 from the top: u over [8, 16] / 64, v (from the bottom row) over
    // [52, 60] / 64, each widened by 4 texels and rounded outward to 1/255.
    const std::optional<glm::vec4> c = cutoutOf(p.value(), redBlock(8, 15, 4, 11));
    ASSERT_TRUE(c);
    EXPECT_NEAR(c->x, 4.0f / 64.0f, 1.0f / 255.0f);
    EXPECT_NEAR(c->y, 48.0f / 64.0f, 1.0f / 255.0f);
    EXPECT_NEAR(c->z, 20.0f / 64.0f, 1.0f / 255.0f);
    EXPECT_NEAR(c->w, 1.0f, 1.0f / 255.0f);
    EXPECT_LE(c->x, 4.0f / 64.0f);
    EXPECT_LE(c->y, 48.0f / 64.0f);
    EXPECT_GE(c->z, 20.0f / 64.0f);

    Image opaque = redBlock(0, kSize - 1, 0, kSize - 1);
    EXPECT_EQ(cutoutOf(p.value(), opaque), glm::vec4(0.0f, 0.0f, 1.0f, 1.0f))
        << "an opaque layer shows whole";
    const std::optional<glm::vec4> clear = cutoutOf(p.value(), redBlock(1, 0, 1, 0));
    ASSERT_TRUE(clear);
    EXPECT_GT(clear->x, clear->z) << "a clear layer shows nothing";

    // The built-in bullet hole shows in less than half of its square.
    const glm::vec4 hole = p->decalTextureCutouts().at(size_t(DecalTexture::BulletHole));
    EXPECT_LT((hole.z - hole.x) * (hole.w - hole.y), 0.5f);
    EXPECT_GT(hole.z, hole.x);
}

TEST(DecalCutout, AnOffCentreTextureDrawsTheSameAsBoxesByTheComputeResolveAndForward) {
    SPATTER_REQUIRE_GL(gl);
    const std::vector<uint8_t> boxes = redMask(drawRedBlock(CutoutPath::Boxes));
    const size_t red = test::countSet(boxes);
    EXPECT_GT(red, 40u) << "the red corners are drawn";
    for (const CutoutPath path : {CutoutPath::Compute, CutoutPath::ComputeGpuCulled, CutoutPath::Forward}) {
        const std::vector<uint8_t> other = redMask(drawRedBlock(path));
        ASSERT_EQ(other.size(), boxes.size());
        size_t differ = 0;
        for (size_t i = 0; i < boxes.size(); ++i)
            differ += boxes[i] != other[i] ? 1 : 0;
        EXPECT_LE(differ, red / 50) << "path " << int(path) << ": " << test::countSet(other)
                                    << " red pixels against " << red;
    }
}
