// Texture-space decals and vertex animation: routing by object mode, splatting once, the seam
// dilation, agreement with the projected decal on a flat surface and beside a face the shot cannot
// reach, and decals that follow a deforming surface while projected ones slide.

#include "RenderTestSupport.hpp"
#include "ShotDecals.hpp"

#include "TestData.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/UvOverlap.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace spatter;
using namespace spatter::test;

namespace {

// A grid on y = 0 over x in [x0, x1], z in [-0.5, 0.5], with UVs mapped onto the rectangle
// [u0, u1] x [0.25, 0.75].
Mesh gridPatch(float x0, float x1, float u0, float u1, float step) {
    Mesh m = makeGrid(makeSamples(x0, x1, step), makeSamples(-0.5f, 0.5f, step));
    for (size_t i = 0; i < m.positions.size(); ++i) {
        const glm::vec3& p = m.positions[i];
        m.uvs[i] = {u0 + (p.x - x0) / (x1 - x0) * (u1 - u0), 0.25f + (p.z + 0.5f) * 0.5f};
    }
    computeTangents(m);
    return m;
}

Scene sceneWith(Mesh mesh) {
    Scene s;
    Material dark;
    dark.name = "dark";
    dark.baseColorFactor = glm::vec4(0.02f, 0.02f, 0.02f, 1.0f);
    s.materials.push_back(dark);
    mesh.submeshes = {{0, uint32_t(mesh.indices.size()), 0}};
    SceneObject o;
    o.name = "sheet";
    o.mesh = shareMesh(std::move(mesh));
    o.dynamic = true;
    s.objects.push_back(std::move(o));
    return s;
}

// Both halves of the sheet in one mesh, as separate UV islands: the vertices along x = 0 are
// duplicated, so the surface is continuous while its UVs are cut there.
Mesh seamSheet() {
    Mesh m = gridPatch(-1.0f, 0.0f, 0.02f, 0.47f, 0.25f);
    appendMesh(m, gridPatch(0.0f, 1.0f, 0.53f, 0.98f, 0.25f), glm::mat4(1.0f));
    return m;
}

Camera topDown() {
    Camera c;
    c.eye = {0.0, 2.2, 0.0};
    c.target = {0.0, 0.0, 0.0};
    c.up = {0.0, 0.0, -1.0}; // image right is +x
    c.nearPlane = 0.05;
    return c;
}

Decal decalAt(glm::vec3 center, glm::vec2 size) {
    Decal d;
    d.center = center;
    d.setFrame({{1, 0, 0}, {0, 0, -1}, {0, 1, 0}});
    d.size = size;
    d.halfDepth = 0.1f;
    d.id = 7;
    return d;
}

// A white, fully opaque decal texture and a type using it without fades or normal map.
DecalType whiteType(Renderer& r) {
    Image white;
    white.width = white.height = 16;
    white.rgba.assign(16 * 16 * 4, 255);
    white.name = "white";
    Result<int> layer = r.addDecalTexture(white);
    EXPECT_TRUE(layer) << layer.error();
    DecalType t;
    t.name = "white";
    t.texture = layer ? layer.value() : 0;
    t.normalMap = false;
    t.depthFade = DepthFade::None;
    return t;
}

Image albedo(Renderer& r, FrameStats* stats = nullptr) {
    return test::renderView(r, topDown(), View::Albedo, stats);
}

uint8_t red(const Image& im, int x, int y) {
    return im.rgba[(size_t(y) * size_t(im.width) + size_t(x)) * 4];
}

std::vector<uint8_t> brightMask(const Image& im) {
    std::vector<uint8_t> m(size_t(im.width) * size_t(im.height));
    for (size_t i = 0; i < m.size(); ++i)
        m[i] = im.rgba[i * 4] > 128 ? 1 : 0;
    return m;
}

// Mean column of the bright pixels, or -1 when there are none.
double centroidX(const Image& im) {
    double sum = 0.0;
    size_t n = 0;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x)
            if (red(im, x, y) > 128) {
                sum += x;
                ++n;
            }
    return n ? sum / double(n) : -1.0;
}

} // namespace

TEST(TextureSpaceDecals, RejectsObjectWithOverlappingUvs) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r) << r.error();
    Mesh box = makeBox(glm::vec3(0.5f), 2);
    fitUvsToUnitSquare(box);
    ASSERT_TRUE(r->setScene(sceneWith(box)));
    Status s = r->setObjectDecalMode(0, DecalMode::TextureSpace, 64);
    ASSERT_FALSE(s);
    EXPECT_NE(s.error().find("sheet"), std::string::npos) << s.error();
    EXPECT_NE(s.error().find("overlapping"), std::string::npos) << s.error();
    EXPECT_EQ(r->objectDecalMode(0), DecalMode::Projected);
    EXPECT_FALSE(r->setObjectDecalMode(1, DecalMode::TextureSpace, 64)); // no such object
}

TEST(TextureSpaceDecals, RejectsBadSizesAndDeformations) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r) << r.error();
    ASSERT_TRUE(r->setScene(sceneWith(seamSheet())));
    EXPECT_FALSE(r->setObjectDecalMode(0, DecalMode::TextureSpace, 100));
    EXPECT_FALSE(r->setObjectDecalMode(0, DecalMode::TextureSpace, 8));
    Deformation d;
    d.amplitude = std::nanf("");
    EXPECT_FALSE(r->setObjectDeformation(0, d));
    d.amplitude = 0.1f;
    d.displacement = glm::vec3(0.0f);
    EXPECT_FALSE(r->setObjectDeformation(0, d));
    EXPECT_FALSE(r->setObjectDeformation(3, Deformation{}));
    EXPECT_FALSE(r->setTime(std::nan("")));
    EXPECT_FALSE(r->clearObjectDecals(0)); // not in texture-space mode
}

TEST(TextureSpaceDecals, SplatsOnceAndMatchesTheProjectedDecal) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r) << r.error();
    ASSERT_TRUE(r->setScene(sceneWith(gridPatch(-1.0f, 1.0f, 0.02f, 0.98f, 0.25f))));
    r->setDecalTypes({whiteType(r.value())});
    const std::vector<Decal> decals = {decalAt({0.3f, 0.0f, 0.1f}, {0.5f, 0.4f})};

    r->setDecals(decals);
    FrameStats projectedStats;
    const std::vector<uint8_t> projected = brightMask(albedo(r.value(), &projectedStats));
    EXPECT_EQ(projectedStats.decalsDrawn, 1u);
    ASSERT_GT(test::countSet(projected), 100u);

    ASSERT_TRUE(r->setObjectDecalMode(0, DecalMode::TextureSpace, 256));
    r->setDecals(decals);
    FrameStats first, second;
    const std::vector<uint8_t> splatted = brightMask(albedo(r.value(), &first));
    EXPECT_EQ(first.decalsSplatted, 1u);
    EXPECT_EQ(first.decalsDrawn, 0u);
    EXPECT_TRUE(first.decalPassSkipped);
    EXPECT_EQ(first.decalsTextureSpace, 1u);
    EXPECT_EQ(first.textureSpaceObjects, 1u);
    EXPECT_EQ(first.textureSpaceBytes, size_t(256 * 256) * (9 + 8));
    EXPECT_GT(test::iou(projected, splatted), 0.9);

    r->setDecals(decals); // the same decal again: already in the texture
    const std::vector<uint8_t> again = brightMask(albedo(r.value(), &second));
    EXPECT_EQ(second.decalsSplatted, 0u);
    EXPECT_EQ(second.decalsTextureSpace, 1u);
    EXPECT_EQ(again, splatted);

    ASSERT_TRUE(r->clearObjectDecals(0));
    EXPECT_EQ(test::countSet(brightMask(albedo(r.value()))), 0u);
}

// A decal shot 60 degrees off the normal of one face of a ridge: the other face, 50 degrees from the
// decal's normal but 110 from the reversed shot, takes no paint, splatted or projected.
TEST(TextureSpaceDecals, ASplatLeavesAFaceTheShotCannotReachAsTheProjectedDecalDoes) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r) << r.error();
    const Scene scene = sceneWith(test::ridgeMesh(50.0));
    ASSERT_TRUE(r->setScene(scene));
    DecalType t = whiteType(r.value());
    t.size = glm::vec2(0.3f);
    t.randomRotation = false;
    r->setDecalTypes({t});
    const test::CoverageInputs in = test::shotFromTheRight(scene, t, glm::dvec3(0.04, 0.0, 0.0), 60.0);
    ASSERT_EQ(in.decals.size(), 1u);
    ASSERT_NE(in.decals[0].slant, 0u);
    const Camera cam = test::lookAt({-0.5, -0.2, 0.9}, {0.0, 0.0, -0.05});
    auto onFallingFace = [](const std::optional<Hit>& hit) { return hit && hit->normal.x < -0.1; };

    r->setDecals(in.decals);
    const std::vector<uint8_t> projected = brightMask(test::renderView(r.value(), cam, View::Albedo));
    ASSERT_TRUE(r->setObjectDecalMode(0, DecalMode::TextureSpace, 256));
    r->setDecals(in.decals);
    const std::vector<uint8_t> splatted = brightMask(test::renderView(r.value(), cam, View::Albedo));
    EXPECT_GT(test::countSet(splatted), 100u);
    EXPECT_EQ(test::coveredWhere(scene, projected, cam, onFallingFace), 0u);
    EXPECT_EQ(test::coveredWhere(scene, splatted, cam, onFallingFace), 0u);
    EXPECT_GT(test::iou(projected, splatted), 0.9);
}

TEST(TextureSpaceDecals, DecalAcrossUvSeamShowsNoGap) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r) << r.error();
    ASSERT_TRUE(r->setScene(sceneWith(seamSheet())));
    // A coarse texture (about 2.5 pixels a texel here) so that a seam gap would span pixels.
    ASSERT_TRUE(r->setObjectDecalMode(0, DecalMode::TextureSpace, 32));
    r->setDecalTypes({whiteType(r.value())});
    r->setDecals({decalAt({0.0f, 0.0f, 0.0f}, {1.0f, 0.6f})});
    const Image im = albedo(r.value());
    test::dumpImage("texture_space_seam", im);

    // The seam x = 0 falls between columns kW/2 - 1 and kW/2; compare with columns 0.2 away.
    const int seamL = kW / 2 - 1, seamR = kW / 2, besideL = kW / 2 - 9, besideR = kW / 2 + 8;
    for (int y = kH / 2 - 6; y <= kH / 2 + 6; ++y) {
        const int beside = std::min(red(im, besideL, y), red(im, besideR, y));
        EXPECT_GT(beside, 200) << "row " << y;
        EXPECT_GE(int(red(im, seamL, y)), beside - 6) << "row " << y;
        EXPECT_GE(int(red(im, seamR, y)), beside - 6) << "row " << y;
    }
}

TEST(TextureSpaceDecals, FollowsDeformingSurfaceWhileProjectedDecalSlides) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r) << r.error();
    // The sheet shears in its own plane: x moves by 0.2 sin(z + pi/2 t), so a point near z = 0 is
    // at rest at t = 0 and 0.2 along +x at t = 1.
    Deformation wave;
    wave.amplitude = 0.2f;
    wave.frequency = 1.0f;
    wave.speed = float(kPi / 2.0);
    wave.displacement = {1, 0, 0};
    wave.waveDirection = {0, 0, 1};
    const Camera cam = topDown();
    const double pixelsPerUnit = kH / (2.0 * cam.eye.y * std::tan(cam.fovYDeg * kPi / 360.0));
    const std::vector<Decal> decals = {decalAt({0.0f, 0.0f, 0.0f}, {0.3f, 0.3f})};

    double shift[2] = {0.0, 0.0};
    for (int textureSpace = 0; textureSpace < 2; ++textureSpace) {
        SCOPED_TRACE(textureSpace ? "texture-space" : "projected");
        ASSERT_TRUE(r->setScene(sceneWith(gridPatch(-1.0f, 1.0f, 0.02f, 0.98f, 0.05f))));
        if (textureSpace) {
            ASSERT_TRUE(r->setObjectDecalMode(0, DecalMode::TextureSpace, 256));
        }
        ASSERT_TRUE(r->setObjectDeformation(0, wave));
        r->setDecalTypes({whiteType(r.value())});
        r->setDecals(decals);
        ASSERT_TRUE(r->setTime(0.0));
        const Image rest = albedo(r.value());
        test::dumpImage(textureSpace ? "texture_space_rest" : "projected_rest", rest);
        const double x0 = centroidX(rest);
        ASSERT_TRUE(r->setTime(1.0));
        const Image moved = albedo(r.value());
        test::dumpImage(textureSpace ? "texture_space_deformed" : "projected_deformed", moved);
        const double x1 = centroidX(moved);
        ASSERT_GE(x0, 0.0);
        ASSERT_GE(x1, 0.0);
        shift[textureSpace] = (x1 - x0) / pixelsPerUnit;
    }
    EXPECT_LT(std::fabs(shift[0]), 0.03) << "the projected decal stays where its box is";
    EXPECT_NEAR(shift[1], 0.2, 0.04) << "the texture-space decal moves with the surface";
}
