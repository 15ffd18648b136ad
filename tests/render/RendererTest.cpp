#include "RenderTestSupport.hpp"

#include "ReferenceGeometry.hpp"
#include "TestData.hpp"

#include "spatter/core/GalleryScene.hpp"
#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/SceneLoader.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <set>

using namespace spatter;
using namespace spatter::test;

namespace {

SceneObject box(const std::string& name, glm::vec3 half, glm::dvec3 position, int material = -1,
                bool dynamic = false) {
    SceneObject o;
    o.name = name;
    o.mesh = shareMesh(makeBox(half, 2));
    if (material >= 0) o.editMesh().submeshes = {Submesh{0, uint32_t(o.mesh->indices.size()), material}};
    o.transform = glm::translate(glm::dmat4(1.0), position);
    o.dynamic = dynamic;
    return o;
}

// An orange material and a floor of it (or of the default material), top at y = 0.
Scene orangeFloor(int floorMaterial) {
    Scene scene;
    Material orange;
    orange.baseColorFactor = {0.8f, 0.3f, 0.05f, 1.0f};
    scene.materials = {orange};
    scene.objects.push_back(box("floor", {10.0f, 0.1f, 10.0f}, {0.0, -0.1, 0.0}, floorMaterial));
    return scene;
}

const uint8_t* at(const Image& im, int x, int y) {
    return &im.rgba[(size_t(y) * size_t(im.width) + size_t(x)) * 4];
}

// Pixel where the world point p appears.
glm::ivec2 project(const Camera& cam, int w, int h, const glm::dvec3& p) {
    const glm::dvec4 clip = projection(cam, double(w) / h) * viewRotation(cam) * glm::dvec4(p - cam.eye, 1.0);
    const double x = clip.x / clip.w, y = clip.y / clip.w;
    return {int(std::floor((x * 0.5 + 0.5) * w)), int(std::floor((0.5 - y * 0.5) * h))};
}

} // namespace

TEST(Renderer, RendersGalleryWithoutGlErrors) {
    SPATTER_REQUIRE_GL(gl);
    const size_t errorsBefore = gl.debugErrorCount();
    Result<Renderer> r = test::makeRenderer(160, 90);
    ASSERT_TRUE(r.ok()) << r.error();
    GallerySettings gs;
    gs.detail = 0;
    ASSERT_TRUE(r->setScene(makeGalleryScene(gs)).ok());
    Camera cam;
    cam.eye = {0.0, 1.7, 6.0};
    cam.target = {0.0, 1.2, -3.0};
    for (View v : {View::Final, View::Albedo, View::Normal, View::Depth, View::Ids, View::Coverage}) {
        const Image im = test::renderView(r.value(), cam, v);
        test::dumpImage(std::string("gallery-") + toString(v), im);
        std::set<uint32_t> colours;
        for (size_t i = 0; i < im.rgba.size(); i += 4)
            colours.insert(uint32_t(im.rgba[i]) << 16 | im.rgba[i + 1] << 8 | im.rgba[i + 2]);
        if (v == View::Coverage) {
            EXPECT_EQ(colours.size(), 1u); // no decals: all black
        } else if (v == View::Ids) {
            EXPECT_EQ(colours.size(), 2u); // no IDs set: every object 0, and the background
        } else {
            EXPECT_GT(colours.size(), 3u) << toString(v);
        }
    }
    EXPECT_EQ(gl.debugErrorCount(), errorsBefore);
}

TEST(Renderer, ViewsShowWhatTheyName) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene scene = orangeFloor(0);
    scene.objects.push_back(box("near", {0.3f, 0.3f, 0.3f}, {-0.8, 0.3, 1.0}, -1, true));
    scene.objects.push_back(box("far", {0.3f, 0.3f, 0.3f}, {0.8, 0.3, -3.0}));
    ASSERT_TRUE(r->setScene(scene).ok());
    ASSERT_TRUE(r->setObjectIds({0, 200, 0}).ok());
    Camera cam;
    cam.eye = {0.0, 1.5, 4.0};
    cam.target = {0.0, 0.3, 0.0};
    const glm::ivec2 floorPx = project(cam, kW, kH, {0.0, 0.0, -1.0});
    const glm::ivec2 nearPx = project(cam, kW, kH, {-0.8, 0.3, 1.3});
    const glm::ivec2 farPx = project(cam, kW, kH, {0.8, 0.3, -2.7});
    const glm::ivec2 skyPx{kW / 2, 0};

    const Image albedo = test::renderView(r.value(), cam, View::Albedo);
    // sRGB of (0.8, 0.3, 0.05): 231, 149, 63.
    EXPECT_NEAR(at(albedo, floorPx.x, floorPx.y)[0], 231, 2);
    EXPECT_NEAR(at(albedo, floorPx.x, floorPx.y)[1], 149, 2);
    EXPECT_NEAR(at(albedo, floorPx.x, floorPx.y)[2], 63, 2);

    const Image normal = test::renderView(r.value(), cam, View::Normal);
    EXPECT_NEAR(at(normal, floorPx.x, floorPx.y)[0], 128, 2); // (0, 1, 0) * 0.5 + 0.5
    EXPECT_NEAR(at(normal, floorPx.x, floorPx.y)[1], 255, 2);
    EXPECT_NEAR(at(normal, floorPx.x, floorPx.y)[2], 128, 2);
    EXPECT_EQ(at(normal, skyPx.x, skyPx.y)[1], 0);

    const Image depth = test::renderView(r.value(), cam, View::Depth);
    EXPECT_GT(at(depth, nearPx.x, nearPx.y)[0], at(depth, floorPx.x, floorPx.y)[0]);
    EXPECT_GT(at(depth, floorPx.x, floorPx.y)[0], at(depth, farPx.x, farPx.y)[0]);
    EXPECT_EQ(at(depth, skyPx.x, skyPx.y)[0], 0);

    const Image ids = test::renderView(r.value(), cam, View::Ids);
    EXPECT_EQ(at(ids, floorPx.x, floorPx.y)[0], 64); // static: dark grey
    EXPECT_EQ(at(ids, farPx.x, farPx.y)[0], 64);
    const uint8_t* dyn = at(ids, nearPx.x, nearPx.y);
    EXPECT_TRUE(dyn[0] != 64 || dyn[1] != 64 || dyn[2] != 64);
    EXPECT_EQ(at(ids, skyPx.x, skyPx.y)[0], 0);

    const Image final = test::renderView(r.value(), cam, View::Final);
    EXPECT_GT(at(final, skyPx.x, skyPx.y)[2], 100);                                    // a sky, not black
    EXPECT_GT(at(final, floorPx.x, floorPx.y)[0], at(final, floorPx.x, floorPx.y)[2]); // orange floor, lit
}

TEST(Renderer, RejectsBadInputWithErrors) {
    SPATTER_REQUIRE_GL(gl);
    RendererSettings bad;
    bad.fadeStart = 1.0f;
    EXPECT_FALSE(Renderer::create(gl, bad).ok());
    bad = {};
    bad.width = 0;
    EXPECT_FALSE(Renderer::create(gl, bad).ok());
    bad = {};
    bad.decalTextureSize = 100;
    EXPECT_FALSE(Renderer::create(gl, bad).ok());

    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    EXPECT_FALSE(r->readback().ok()); // nothing rendered yet
    Scene good;
    good.objects.push_back(box("a", {1.0f, 1.0f, 1.0f}, {0.0, 0.0, 0.0}));
    ASSERT_TRUE(r->setScene(good).ok());
    Scene broken = good;
    broken.objects[0].editMesh().indices.push_back(999);
    const Status s = r->setScene(broken);
    EXPECT_FALSE(s.ok());
    EXPECT_NE(s.error().find("object 0"), std::string::npos) << s.error();
    EXPECT_FALSE(r->setObjectIds({1, 2}).ok()); // the good scene (one object) is still there
    EXPECT_TRUE(r->setObjectIds({0}).ok());

    Camera cam;
    cam.eye = {0.0, 0.0, 5.0};
    cam.target = {0.0, 0.0, 5.0};
    EXPECT_FALSE(r->render(cam).ok());
    cam.target = {0.0, 0.0, 0.0};
    EXPECT_TRUE(r->render(cam).ok());
    EXPECT_FALSE(r->resize(-1, 10).ok());
    ASSERT_TRUE(r->resize(40, 30).ok());
    ASSERT_TRUE(r->render(cam).ok());
    Result<Image> im = r->readback();
    ASSERT_TRUE(im.ok());
    EXPECT_EQ(im->width, 40);
    EXPECT_EQ(im->height, 30);
    EXPECT_EQ(gl.debugErrorCount(), 0u);
}

TEST(Renderer, CoverageHoldsFarFromTheOrigin) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    GallerySettings gs;
    gs.detail = 0;
    const Scene base = makeGalleryScene(gs);
    Result<DecalSystem> sys = DecalSystem::create(base);
    ASSERT_TRUE(sys.ok()) << sys.error();
    DecalType t;
    t.name = "t";
    t.size = {0.6f, 0.6f};
    const uint16_t type = sys->registerType(t).value();
    Camera cam;
    cam.eye = {0.5, 1.8, 5.0};
    cam.target = {0.0, 1.2, -3.0};
    for (int s = 0; s < 40; ++s)
        sys->spawn(Ray{cam.eye, pixelDirection(cam, kW, kH, (s * 37) % kW, (s * 53) % kH)}, type);
    ASSERT_GT(sys->decals().size(), 30u);
    const std::vector<uint8_t> ids = sys->objectIds();

    std::vector<uint8_t> reference;
    for (double offset : {0.0, 1e3, 1e4, 1e5}) {
        Scene moved = base;
        moved.translate({offset, -0.5 * offset, offset});
        Camera c = cam;
        c.eye += glm::dvec3(offset, -0.5 * offset, offset);
        c.target += glm::dvec3(offset, -0.5 * offset, offset);
        ASSERT_TRUE(r->setScene(moved).ok());
        ASSERT_TRUE(r->setObjectIds(ids).ok());
        r->setDecalTypes({t});
        r->setDecals(sys->decals()); // object space: unchanged by the move
        const std::vector<uint8_t> mask = test::whiteMask(test::renderView(r.value(), c, View::Coverage));
        if (offset == 0.0) {
            reference = mask;
            ASSERT_GT(test::countSet(reference), size_t(kW * kH) / 20);
        } else {
            EXPECT_GE(test::iou(mask, reference), 0.97) << offset;
        }
    }
}

TEST(Renderer, RendersTexturedSharedGltfScenes) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    for (const char* file : {"gltf/Duck/Duck.glb", "gltf/DamagedHelmet/DamagedHelmet.glb"}) {
        SPATTER_REQUIRE_SHARED(path, file);
        Result<Scene> scene = loadScene(path);
        ASSERT_TRUE(scene.ok()) << scene.error();
        ASSERT_FALSE(scene->images.empty()) << file;
        ASSERT_TRUE(r->setScene(scene.value()).ok());
        const DBounds b = scene->worldBounds();
        Camera cam;
        cam.target = b.center();
        cam.eye = b.center() + glm::dvec3(0.3, 0.2, 1.0) * b.diagonal();
        cam.nearPlane = b.diagonal() * 1e-3;
        const Image albedo = test::renderView(r.value(), cam, View::Albedo);
        test::dumpImage(std::string(file).substr(5, 4) + "-albedo", albedo);
        // Textured: many different colours where the model is.
        std::set<uint32_t> colours;
        for (size_t i = 0; i < albedo.rgba.size(); i += 4)
            colours.insert(uint32_t(albedo.rgba[i]) << 16 | albedo.rgba[i + 1] << 8 | albedo.rgba[i + 2]);
        EXPECT_GT(colours.size(), 50u) << file;
    }
    EXPECT_EQ(gl.debugErrorCount(), 0u);
}

// The renderer's projector leaves the GL state as its passes set it (ProjectorSettings::restoreGlState
// off), since each of the renderer's passes sets what it uses: a second frame of a view draws the
// pixels of the first, whose passes ran before any decal pass. (A sampler of the projector's left on a
// texture unit samples the floor's checkers without their mipmaps; its depth clamp left on draws what
// lies before the near plane.)
TEST(Renderer, DrawsTheSameFrameAfterItsDecalPass) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene scene = orangeFloor(0);
    Image checker{64, 64, {}, "checker"};
    for (int y = 0; y < checker.height; ++y)
        for (int x = 0; x < checker.width; ++x) {
            const uint8_t v = (x / 4 + y / 4) % 2 != 0 ? 255 : 0;
            checker.rgba.insert(checker.rgba.end(), {v, v, v, 255});
        }
    scene.images = {checker};
    scene.materials[0].baseColorTexture = 0;
    ASSERT_TRUE(r->setScene(scene).ok());
    Result<DecalSystem> sys = DecalSystem::create(scene);
    ASSERT_TRUE(sys.ok()) << sys.error();
    DecalType t;
    t.name = "t";
    t.size = {1.0f, 1.0f};
    const uint16_t type = sys->registerType(t).value();
    Camera cam = lookAt({0.0, 1.0, 6.0}, {0.0, 0.0, -4.0});
    cam.nearPlane = 2.0; // the floor's nearest part lies before it
    for (int s = 0; s < 5; ++s)
        ASSERT_TRUE(sys->spawn(Ray{cam.eye, glm::normalize(glm::dvec3(s - 2.0, -1.0, -5.0))}, type).placed());
    r->setDecalTypes({t});
    r->setDecals(sys->decals());
    FrameStats stats;
    const Image first = renderView(r.value(), cam, View::Final, &stats);
    ASSERT_GT(stats.decalsDrawn, 0u);
    const Image second = renderView(r.value(), cam, View::Final);
    EXPECT_TRUE(first.rgba == second.rgba);
    EXPECT_EQ(gl.debugErrorCount(), 0u);
}

// Objects placed with one mesh share its upload: each still draws at its own transform and with its
// own object ID, pixel for pixel as copies that differ by an unused vertex (distinct meshes) draw.
TEST(Renderer, DrawsCopiesOfAMeshAsItDrawsDistinctMeshes) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene copies = orangeFloor(-1);
    for (int i = 0; i < 4; ++i) {
        SceneObject o = box("crate_" + std::to_string(i), {0.3f, 0.3f, 0.3f}, {-1.2 + 0.8 * i, 0.3, -0.5 * i},
                            0, i % 2 == 1);
        o.transform = glm::rotate(o.transform, 0.4 * i, glm::dvec3(0.0, 1.0, 0.0));
        copies.objects.push_back(std::move(o));
    }
    Scene distinct = copies;
    for (size_t i = 1; i < distinct.objects.size(); ++i)
        distinct.objects[i].mesh = shareMesh(withUnusedVertices(*distinct.objects[i].mesh, i));
    Camera cam;
    cam.eye = {0.0, 1.5, 4.0};
    cam.target = {0.0, 0.3, -0.5};
    std::vector<Image> images[2];
    for (int k = 0; k < 2; ++k) {
        ASSERT_TRUE(r->setScene(k == 0 ? copies : distinct).ok());
        ASSERT_TRUE(r->setObjectIds({0, 0, 7, 0, 9}).ok());
        for (View v : {View::Final, View::Normal, View::Depth, View::Ids})
            images[k].push_back(test::renderView(r.value(), cam, v));
    }
    for (size_t v = 0; v < images[0].size(); ++v)
        EXPECT_EQ(images[0][v].rgba, images[1][v].rgba) << "view " << v;
    size_t crates = 0; // the crates are in the picture
    const Image& lit = images[0][0];
    for (size_t i = 0; i < lit.rgba.size(); i += 4)
        crates += lit.rgba[i] > 2 * lit.rgba[i + 2] + 40;
    EXPECT_GT(crates, 200u);
}
