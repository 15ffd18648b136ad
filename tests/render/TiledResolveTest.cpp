// The tiled resolve (DeferredResolve::Tiles) blends what the boxes blend: the same decals on the
// gallery, with normal maps, wrap-around, depth fades and roughness, overlapping, give the same
// albedo, normals and lit image within the rounding of blending once instead of once per decal.

#include "HostedWall.hpp"
#include "RenderTestSupport.hpp"
#include "ShotDecals.hpp"
#include "TestData.hpp"

#include "spatter/core/GalleryScene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

using namespace spatter;

namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 120;

struct Resolved {
    Image albedo, normal, final;
    FrameStats stats;
};

Resolved render(const Scene& scene, const test::Placed& placed, const Camera& cam, DeferredResolve resolve) {
    RendererSettings settings;
    settings.deferredResolve = resolve;
    settings.normalFrame = DecalNormalFrame::DepthDerivatives;
    Result<Renderer> r = test::makeRenderer(kWidth, kHeight, settings);
    EXPECT_TRUE(r.ok()) << r.error();
    if (!r) return {};
    EXPECT_TRUE(r->setScene(scene).ok());
    EXPECT_TRUE(r->setObjectIds(placed.inputs.objectIds).ok());
    r->setDecalTypes(placed.inputs.types);
    r->setDecals(placed.inputs.decals);
    Resolved out;
    out.albedo = test::renderView(r.value(), cam, View::Albedo);
    out.normal = test::renderView(r.value(), cam, View::Normal);
    out.final = test::renderView(r.value(), cam, View::Final, &out.stats);
    return out;
}

// Pixels whose channels (alpha included) differ by more than `tolerance`, and the largest difference.
struct Difference {
    size_t pixels = 0;
    int largest = 0;
};

Difference compare(const Image& a, const Image& b, int tolerance) {
    Difference d;
    EXPECT_EQ(a.rgba.size(), b.rgba.size());
    for (size_t i = 0; i + 4 <= a.rgba.size() && i + 4 <= b.rgba.size(); i += 4) {
        int worst = 0;
        for (size_t c = 0; c < 4; ++c)
            worst = std::max(worst, std::abs(int(a.rgba[i + c]) - int(b.rgba[i + c])));
        d.largest = std::max(d.largest, worst);
        d.pixels += worst > tolerance;
    }
    return d;
}

std::vector<DecalType> overlappingTypes() {
    std::vector<DecalType> types = {test::makeType("hole", {0.5f, 0.5f}, DecalTexture::BulletHole),
                                    test::makeType("blood", {1.0f, 0.8f}, DecalTexture::Blood, true),
                                    test::makeType("scorch", {1.4f, 1.4f}, DecalTexture::Scorch, false, 0.8f),
                                    test::makeType("paint", {0.9f, 0.9f}, DecalTexture::Paint)};
    types[2].roughness = 0.9f;
    types[3].depthFade = DepthFade::Linear;
    types[3].normalMap = false;
    types[3].tint = glm::vec4(0.2f, 0.6f, 1.0f, 0.7f);
    return types;
}

} // namespace

TEST(TiledResolve, BlendsWhatTheBoxesBlendOnTheGallery) {
    SPATTER_REQUIRE_GL(gl);
    GallerySettings gs;
    gs.detail = 1;
    const Scene scene = makeGalleryScene(gs);
    Camera cam;
    cam.eye = {1.5, 2.2, 4.5};
    cam.target = {-0.5, 1.0, -3.0};
    const test::Placed placed = test::shootFromCamera(scene, cam, overlappingTypes(), 160, 23);
    ASSERT_GT(placed.placed, 100u);
    const Resolved boxes = render(scene, placed, cam, DeferredResolve::Boxes);
    const Resolved tiles = render(scene, placed, cam, DeferredResolve::Tiles);
    ASSERT_GT(boxes.stats.decalsDrawn, 100u);
    EXPECT_EQ(tiles.stats.decalsDrawn, boxes.stats.decalsDrawn);
    test::dumpImage("tiles-albedo", tiles.albedo);
    test::dumpImage("boxes-albedo", boxes.albedo);
    struct Case {
        const char* name;
        const Image &a, &b;
    };
    // Blending each decal into an 8-bit target rounds once per decal; the tiles round once.
    for (const Case& c :
         {Case{"albedo", boxes.albedo, tiles.albedo}, Case{"normal", boxes.normal, tiles.normal},
          Case{"final", boxes.final, tiles.final}}) {
        const Difference d = compare(c.a, c.b, 4);
        std::printf("%s: %zu pixels differ by more than 4 (largest %d)\n", c.name, d.pixels, d.largest);
        EXPECT_LE(d.pixels, size_t(kWidth * kHeight) / 1000) << c.name;
        EXPECT_LE(d.largest, 8) << c.name;
    }
}

namespace {

// The host's targets after a draw of `decals` on the wall, by boxes or tiles: the G-buffer blend
// (albedo, normals, roughness in the material texture), then again with roughness in the albedo's
// alpha channel, and the DBuffer's three textures.
std::vector<Image> wallTargets(const std::vector<Decal>& decals, DeferredResolve resolve) {
    ProjectorSettings settings;
    settings.deferredResolve = resolve;
    std::optional<test::HostedWall> h = test::HostedWall::make(settings);
    EXPECT_TRUE(h);
    if (!h) return {};
    h->projector.setDecals(decals);
    const HostFrame f = h->host.frame(h->wall.camera, true);
    std::vector<Image> out;
    Result<ProjectorStats> st = h->projector.draw(f);
    EXPECT_TRUE(st.ok()) << st.error();
    for (GLuint t : {f.albedoTexture, f.normals.texture, f.roughness.texture})
        out.push_back(h->host.read(t));
    h->host.draw(h->wall.transforms, h->wall.ids, h->wall.camera);
    HostFrame alpha = f;
    alpha.roughness = {f.albedoTexture, 3};
    st = h->projector.draw(alpha);
    EXPECT_TRUE(st.ok()) << st.error();
    out.push_back(h->host.read(f.albedoTexture));
    ProjectorDraw dbuffer;
    dbuffer.path = ProjectorPath::DBuffer;
    st = h->projector.draw(f, dbuffer);
    EXPECT_TRUE(st.ok()) << st.error();
    const ProjectorResources r = h->projector.resources();
    for (GLuint t : {r.dbufferAlbedo, r.dbufferNormal, r.dbufferMaterial})
        out.push_back(h->host.read(t));
    return out;
}

} // namespace

// Forty overlapping decals with roughness on a foreign host's wall: every target the boxes write,
// the tiles write alike.
TEST(TiledResolve, WritesWhatTheBoxesWriteInEveryTargetOfAForeignHost) {
    SPATTER_REQUIRE_GL(gl);
    const test::WallScene wall;
    std::vector<Decal> decals = wall.decals;
    for (int i = 0; i < 40; ++i) {
        Decal d = test::WallScene::decalAt(0, {-0.9f + 0.03f * float(i), 0.1f * float(i % 4), 0.05f});
        d.size = glm::vec2(0.25f);
        decals.push_back(d);
    }
    const std::vector<Image> boxes = wallTargets(decals, DeferredResolve::Boxes);
    const std::vector<Image> tiles = wallTargets(decals, DeferredResolve::Tiles);
    ASSERT_EQ(boxes.size(), 7u);
    ASSERT_EQ(tiles.size(), 7u);
    size_t decalled = 0; // pixels of the DBuffer that show less of the surface than all of it
    for (size_t i = 3; i < boxes[4].rgba.size(); i += 4)
        decalled += boxes[4].rgba[i] < 250;
    ASSERT_GT(decalled, 200u) << "the decals show";
    const char* names[7] = {
        "albedo",         "normal",         "material",        "albedo with roughness in alpha",
        "DBuffer albedo", "DBuffer normal", "DBuffer material"};
    for (size_t i = 0; i < 7; ++i) {
        const Difference d = compare(boxes[i], tiles[i], 3);
        std::printf("%s: %zu pixels differ by more than 3 (largest %d)\n", names[i], d.pixels, d.largest);
        EXPECT_EQ(d.pixels, 0u) << names[i];
    }
}
