// The decal pass on scenes with known geometry: ID clipping, the camera inside a box, wrap-around,
// thin walls, culling, partial uploads, shader variants, and what decals write into the G-buffer.

#include "RenderTestSupport.hpp"

#include "TestData.hpp"

#include "spatter/core/MeshBuilder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

using namespace spatter;

namespace {

constexpr int kW = 128;
constexpr int kH = 96;

SceneObject object(const std::string& name, const glm::vec3& halfExtents, const glm::dvec3& position,
                   bool dynamic = false) {
    SceneObject o;
    o.name = name;
    o.mesh = makeBox(halfExtents, 4);
    o.transform = glm::translate(glm::dmat4(1.0), position);
    o.dynamic = dynamic;
    return o;
}

// A box with flat faces (four vertices of its own per face), so that each face has one normal.
Mesh flatBox(const glm::vec3& h) {
    Mesh m;
    for (int axis = 0; axis < 3; ++axis)
        for (float sign : {-1.0f, 1.0f}) {
            glm::vec3 n(0.0f);
            n[axis] = sign;
            const glm::vec3 u = axis == 0 ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
            const glm::vec3 v = glm::cross(n, u);
            const uint32_t base = uint32_t(m.positions.size());
            for (int k = 0; k < 4; ++k) {
                const float a = (k == 1 || k == 2) ? 1.0f : -1.0f, b = (k >= 2) ? 1.0f : -1.0f;
                m.positions.push_back((n + a * u + b * v) * h);
                m.normals.push_back(n);
            }
            // Counter-clockwise seen from outside: u x v = n.
            m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
        }
    return m;
}

Decal decal(uint32_t objectIndex, glm::vec3 center, glm::vec3 normal, glm::vec3 tangent, glm::vec2 size,
            float halfDepth, uint16_t type = 0, uint8_t objectId = 0) {
    Decal d;
    d.object = objectIndex;
    d.center = center;
    d.frame.normal = glm::normalize(normal);
    d.frame.tangent = glm::normalize(tangent);
    d.frame.bitangent = glm::cross(d.frame.normal, d.frame.tangent);
    d.size = size;
    d.halfDepth = halfDepth;
    d.type = type;
    d.objectId = objectId;
    return d;
}

DecalType type(DecalTexture tex = DecalTexture::Paint, bool wrap = false, float maxAngle = 80.0f) {
    DecalType t;
    t.name = "t";
    t.texture = int(tex);
    t.wrapAround = wrap;
    t.maxAngleDeg = maxAngle;
    return t;
}

Camera camera(glm::dvec3 eye, glm::dvec3 target) {
    Camera c;
    c.eye = eye;
    c.target = target;
    c.nearPlane = 0.05;
    return c;
}

Image renderView(Renderer& r, const Camera& cam, View view, FrameStats* stats = nullptr) {
    Result<FrameStats> st = r.render(cam, view);
    EXPECT_TRUE(st.ok()) << st.error();
    if (stats && st) *stats = st.value();
    Result<Image> im = r.readback();
    EXPECT_TRUE(im.ok()) << im.error();
    return im ? im.value() : Image{};
}

const uint8_t* px(const Image& im, size_t i) {
    return &im.rgba[i * 4];
}

// Scene: a static wall whose front face is the plane z = 0 and a dynamic target plate in front.
Scene wallAndTarget(bool targetDynamic) {
    Scene s;
    s.objects.push_back(object("wall", {2.0f, 1.5f, 0.1f}, {0.0, 1.5, -0.1}));
    s.objects.push_back(object("target", {0.3f, 0.3f, 0.05f}, {0.0, 1.5, 0.4}, targetDynamic));
    return s;
}

} // namespace

TEST(DecalPass, IdClippingKeepsTheWallBehindAMovingTargetClean) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    const Camera cam = camera({0.4, 1.8, 3.0}, {0.0, 1.5, 0.0});
    // A decal on the target's front face (z = 0.45 in the world) whose box reaches back through the
    // wall's face at z = 0, and overhangs the target on every side.
    const std::vector<Decal> decals = {
        decal(1, {0.0f, 0.0f, 0.05f}, {0, 0, 1}, {1, 0, 0}, {1.4f, 1.4f}, 0.6f, 0, 9)};

    // Pixel classes from the ID view of the scene with a dynamic target: ID 0 (the wall) is dark grey.
    ASSERT_TRUE(r->setScene(wallAndTarget(true)).ok());
    ASSERT_TRUE(r->setObjectIds({0, 9}).ok());
    const Image ids = renderView(r.value(), cam, View::Ids);
    std::vector<uint8_t> wall(size_t(kW * kH)), target(size_t(kW * kH));
    for (size_t i = 0; i < wall.size(); ++i) {
        const uint8_t* id = px(ids, i);
        wall[i] = (id[0] == 64 && id[1] == 64 && id[2] == 64) ? 1 : 0;
        target[i] = (id[0] > 70 || id[1] > 70 || id[2] > 70) ? 1 : 0;
    }
    ASSERT_GT(test::countSet(wall), size_t(kW * kH) / 3);
    ASSERT_GT(test::countSet(target), 250u);

    for (bool dynamic : {true, false}) {
        SCOPED_TRACE(dynamic ? "dynamic target" : "static target");
        ASSERT_TRUE(r->setScene(wallAndTarget(dynamic)).ok());
        ASSERT_TRUE(r->setObjectIds({0, uint8_t(dynamic ? 9 : 0)}).ok());
        r->setDecalTypes({type()});
        const Image cleanFinal = renderView(r.value(), cam, View::Final);
        r->setDecals(decals);
        FrameStats st;
        const std::vector<uint8_t> cov = test::whiteMask(renderView(r.value(), cam, View::Coverage, &st));
        const Image final = renderView(r.value(), cam, View::Final);
        EXPECT_EQ(st.decalVariant.find("IDS") != std::string::npos, dynamic) << st.decalVariant;

        size_t wallCovered = 0, targetCovered = 0, wallChanged = 0;
        for (size_t i = 0; i < cov.size(); ++i) {
            if (wall[i] && cov[i]) ++wallCovered;
            if (target[i] && cov[i]) ++targetCovered;
            if (wall[i] && std::memcmp(px(final, i), px(cleanFinal, i), 4) != 0) ++wallChanged;
        }
        test::dumpImage(dynamic ? "idclip-dynamic" : "idclip-static", final);
        EXPECT_GT(targetCovered, 250u);
        if (dynamic) {
            EXPECT_EQ(wallCovered, 0u);
            EXPECT_EQ(wallChanged, 0u);
        } else {
            // Without IDs the same box does reach the wall: the clipping above is the IDs' doing.
            EXPECT_GT(wallCovered, 200u);
            EXPECT_GT(wallChanged, 100u);
        }
    }
}

TEST(DecalPass, IdClippingOffLetsADecalOnATargetReachTheWallBehind) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    const Camera cam = camera({0.4, 1.8, 3.0}, {0.0, 1.5, 0.0});
    ASSERT_TRUE(r->setScene(wallAndTarget(true)).ok());
    ASSERT_TRUE(r->setObjectIds({0, 9}).ok());
    r->setDecalTypes({type()});
    const Image ids = renderView(r.value(), cam, View::Ids);
    std::vector<uint8_t> wall(size_t(kW * kH));
    for (size_t i = 0; i < wall.size(); ++i)
        wall[i] = (px(ids, i)[0] == 64 && px(ids, i)[1] == 64 && px(ids, i)[2] == 64) ? 1 : 0;
    ASSERT_GT(test::countSet(wall), size_t(kW * kH) / 3);
    const Image cleanFinal = renderView(r.value(), cam, View::Final);
    // The decal of IdClippingKeepsTheWallBehindAMovingTargetClean: on the target, its box reaching
    // back through the wall's face.
    r->setDecals({decal(1, {0.0f, 0.0f, 0.05f}, {0, 0, 1}, {1, 0, 0}, {1.4f, 1.4f}, 0.6f, 0, 9)});

    for (bool clipping : {true, false}) {
        SCOPED_TRACE(clipping ? "ID clipping on" : "ID clipping off");
        RenderOptions options;
        options.decals.idClipping = clipping;
        options.view = View::Coverage;
        Result<FrameStats> st = r->render(cam, options);
        ASSERT_TRUE(st.ok()) << st.error();
        const std::vector<uint8_t> cov = test::whiteMask(r->readback().value());
        options.view = View::Final;
        ASSERT_TRUE(r->render(cam, options).ok());
        const Image final = r->readback().value();
        size_t wallCovered = 0, wallChanged = 0;
        for (size_t i = 0; i < cov.size(); ++i) {
            wallCovered += (wall[i] && cov[i]) ? 1 : 0;
            wallChanged += (wall[i] && std::memcmp(px(final, i), px(cleanFinal, i), 4) != 0) ? 1 : 0;
        }
        EXPECT_EQ(st->decalVariant.find("IDS") != std::string::npos, clipping) << st->decalVariant;
        if (clipping) {
            EXPECT_EQ(wallCovered, 0u);
            EXPECT_EQ(wallChanged, 0u);
        } else {
            EXPECT_GT(wallCovered, 200u);
            EXPECT_GT(wallChanged, 100u);
        }
    }
}

TEST(DecalPass, CameraInsideADecalBoxStillDrawsIt) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene scene;
    scene.objects.push_back(object("wall", {3.0f, 3.0f, 0.1f}, {0.0, 1.5, -0.1}));
    ASSERT_TRUE(r->setScene(scene).ok());
    test::CoverageInputs in;
    in.types = {type(DecalTexture::Blood)};
    in.decals = {decal(0, {0.0f, 0.0f, 0.1f}, {0, 0, 1}, {1, 0, 0}, {1.6f, 1.6f}, 1.2f)};
    r->setDecalTypes(in.types);
    r->setDecals(in.decals);

    // Walk towards the wall, through the box's front face at z = 1.2, to 0.3 from the wall.
    size_t insideFrames = 0;
    for (double z : {3.0, 1.5, 1.2 + 0.02, 1.2, 0.9, 0.6, 0.3}) {
        SCOPED_TRACE(z);
        const Camera cam = camera({0.15, 1.6, z}, {0.0, 1.45, z - 2.0});
        FrameStats st;
        const Image cov = renderView(r.value(), cam, View::Coverage, &st);
        const std::vector<uint8_t> gpu = test::whiteMask(cov);
        const std::vector<uint8_t> cpu = test::referenceCoverage(scene, in, cam, kW, kH);
        ASSERT_GT(test::countSet(cpu), 500u);
        EXPECT_GE(test::iou(gpu, cpu), 0.99);
        EXPECT_EQ(st.decalsDrawn, 1u);
        insideFrames += st.decalsInside;
        if (z < 1.2) {
            EXPECT_EQ(st.decalsInside, 1u); // the eye is in the box
        }
        if (z > 2.0) {
            EXPECT_EQ(st.decalsInside, 0u);
        }
    }
    EXPECT_GE(insideFrames, 4u);
}

TEST(DecalPass, WrapAroundCoversBothFacesOfACorner) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene scene;
    scene.objects.push_back(object("cube", {0.5f, 0.5f, 0.5f}, {0.0, 0.0, 0.0}));
    scene.objects[0].mesh = flatBox({0.5f, 0.5f, 0.5f});
    ASSERT_TRUE(r->setScene(scene).ok());
    const Camera cam = camera({1.9, 0.5, 1.9}, {0.35, 0.0, 0.35});
    // Face classes from the normals before any decal: +X side face and +Z front face.
    const Image normals = renderView(r.value(), cam, View::Normal);
    std::vector<uint8_t> side(size_t(kW * kH)), front(size_t(kW * kH));
    for (size_t i = 0; i < side.size(); ++i) {
        side[i] = px(normals, i)[0] > 245 ? 1 : 0;
        front[i] = px(normals, i)[2] > 245 ? 1 : 0;
    }
    ASSERT_GT(test::countSet(side), 300u);
    ASSERT_GT(test::countSet(front), 500u);

    // A decal on the front face whose centre is 0.15 from the edge with the side face.
    test::CoverageInputs in;
    in.decals = {decal(0, {0.35f, 0.0f, 0.5f}, {0, 0, 1}, {1, 0, 0}, {0.7f, 0.7f}, 0.45f)};
    for (bool wrap : {true, false}) {
        SCOPED_TRACE(wrap ? "wrap" : "flat");
        in.types = {type(DecalTexture::Blood, wrap)};
        r->setDecalTypes(in.types);
        r->setDecals(in.decals);
        FrameStats st;
        const std::vector<uint8_t> cov = test::whiteMask(renderView(r.value(), cam, View::Coverage, &st));
        size_t onSide = 0, onFront = 0;
        for (size_t i = 0; i < cov.size(); ++i) {
            onSide += (cov[i] && side[i]) ? 1 : 0;
            onFront += (cov[i] && front[i]) ? 1 : 0;
        }
        EXPECT_GT(onFront, 250u);
        if (wrap) {
            EXPECT_GT(onSide, 100u);
            EXPECT_NE(st.decalVariant.find("WRAP"), std::string::npos);
        } else {
            EXPECT_EQ(onSide, 0u);
            EXPECT_EQ(st.decalVariant.find("WRAP"), std::string::npos);
        }
        const std::vector<uint8_t> cpu = test::referenceCoverage(scene, in, cam, kW, kH);
        EXPECT_GE(test::iou(cov, cpu), 0.97);
        test::dumpImage(wrap ? "wrap-final" : "flat-final", renderView(r.value(), cam, View::Final));
    }
}

TEST(DecalPass, BackSideOfAThinWallStaysClean) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene scene;
    scene.objects.push_back(object("thin wall", {1.0f, 1.0f, 0.01f}, {0.0, 0.0, 0.0}));
    ASSERT_TRUE(r->setScene(scene).ok());
    // On the front face (+Z); the box goes right through the 2 cm wall.
    const std::vector<Decal> decals = {
        decal(0, {0.0f, 0.0f, 0.01f}, {0, 0, 1}, {1, 0, 0}, {1.0f, 1.0f}, 0.3f)};
    const Camera behind = camera({0.3, 0.2, -2.0}, {0.0, 0.0, 0.0});
    const Camera before = camera({0.3, 0.2, 2.0}, {0.0, 0.0, 0.0});

    r->setDecalTypes({type(DecalTexture::Paint)});
    const Image cleanBack = renderView(r.value(), behind, View::Final);
    r->setDecals(decals);
    EXPECT_EQ(test::countSet(test::whiteMask(renderView(r.value(), behind, View::Coverage))), 0u);
    EXPECT_EQ(renderView(r.value(), behind, View::Final).rgba, cleanBack.rgba);
    EXPECT_GT(test::countSet(test::whiteMask(renderView(r.value(), before, View::Coverage))), 500u);

    // The box does reach the back face: only the angle test keeps it clean.
    r->setDecalTypes({type(DecalTexture::Paint, false, 180.0f)});
    EXPECT_GT(test::countSet(test::whiteMask(renderView(r.value(), behind, View::Coverage))), 500u);
}

TEST(DecalPass, AngleRejectOffLetsADecalMarkTheBackOfAThinWall) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene scene;
    scene.objects.push_back(object("thin wall", {1.0f, 1.0f, 0.01f}, {0.0, 0.0, 0.0}));
    ASSERT_TRUE(r->setScene(scene).ok());
    const Camera behind = camera({0.3, 0.2, -2.0}, {0.0, 0.0, 0.0});
    r->setDecalTypes({type(DecalTexture::Paint)});
    const Image cleanBack = renderView(r.value(), behind, View::Final);
    r->setDecals({decal(0, {0.0f, 0.0f, 0.01f}, {0, 0, 1}, {1, 0, 0}, {1.0f, 1.0f}, 0.3f)});

    for (bool reject : {true, false}) {
        SCOPED_TRACE(reject ? "angle rejection on" : "angle rejection off");
        RenderOptions options;
        options.decals.angleReject = reject;
        options.view = View::Coverage;
        Result<FrameStats> st = r->render(behind, options);
        ASSERT_TRUE(st.ok()) << st.error();
        const size_t covered = test::countSet(test::whiteMask(r->readback().value()));
        options.view = View::Final;
        ASSERT_TRUE(r->render(behind, options).ok());
        const Image final = r->readback().value();
        EXPECT_EQ(st->decalVariant.find("NO_ANGLE") == std::string::npos, reject) << st->decalVariant;
        if (reject) {
            EXPECT_EQ(covered, 0u);
            EXPECT_EQ(final.rgba, cleanBack.rgba);
        } else {
            EXPECT_GT(covered, 500u);
            EXPECT_NE(final.rgba, cleanBack.rgba);
        }
    }
}

TEST(DecalPass, ObjectsThatTakeNoDecalsAreDrawnOverThem) {
    SPATTER_REQUIRE_GL(gl);
    RendererSettings settings;
    settings.waitForTimers = true;
    Result<Renderer> r = test::makeRenderer(kW, kH, settings);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene scene = wallAndTarget(false);
    scene.objects[1].receivesDecals = false; // the plate in front of the wall
    ASSERT_TRUE(r->setScene(scene).ok());
    test::CoverageInputs in;
    in.types = {type(DecalTexture::Scorch)};
    // On the wall, with a box deep enough to take in the plate 0.35 to 0.45 in front of it.
    in.decals = {decal(0, {0.0f, 0.0f, 0.1f}, {0, 0, 1}, {1, 0, 0}, {1.2f, 1.2f}, 0.6f)};
    r->setDecalTypes(in.types);
    const Camera cam = camera({0.3, 1.7, 3.0}, {0.0, 1.5, 0.0});
    const Image clean = renderView(r.value(), cam, View::Final);
    r->setDecals(in.decals);
    FrameStats st;
    const Image final = renderView(r.value(), cam, View::Final, &st);
    EXPECT_GT(st.gpu.lateMs, 0.0);
    const std::vector<uint8_t> gpu = test::whiteMask(renderView(r.value(), cam, View::Coverage));
    const std::vector<uint8_t> cpu = test::referenceCoverage(scene, in, cam, kW, kH);
    EXPECT_GE(test::iou(gpu, cpu), 0.99);

    // The plate's pixels: where the plate alone would be drawn.
    Scene plateOnly = scene;
    plateOnly.objects[0].transform =
        glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 1.5, 50.0)); // behind the eye
    ASSERT_TRUE(r->setScene(plateOnly).ok());
    const Image ids = renderView(r.value(), cam, View::Ids);
    size_t platePixels = 0, plateCovered = 0, plateChanged = 0, wallCovered = 0;
    for (size_t i = 0; i < gpu.size(); ++i) {
        const bool plate = px(ids, i)[0] != 0; // everything else is background here
        platePixels += plate ? 1 : 0;
        plateCovered += (plate && gpu[i]) ? 1 : 0;
        wallCovered += (!plate && gpu[i]) ? 1 : 0;
        plateChanged += (plate && std::memcmp(px(final, i), px(clean, i), 4) != 0) ? 1 : 0;
    }
    ASSERT_GT(platePixels, 300u);
    EXPECT_EQ(plateCovered, 0u);
    EXPECT_EQ(plateChanged, 0u);
    EXPECT_GT(wallCovered, 500u);
}

TEST(DecalPass, CullsDecalsOutsideTheViewAndSkipsThePassWithoutVisibleDecals) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene scene;
    scene.objects.push_back(object("floor", {20.0f, 0.1f, 20.0f}, {0.0, -0.1, 0.0}));
    ASSERT_TRUE(r->setScene(scene).ok());
    r->setDecalTypes({type()});
    const Camera cam = camera({0.0, 2.0, 5.0}, {0.0, 0.0, 0.0});
    FrameStats st;
    renderView(r.value(), cam, View::Final, &st);
    EXPECT_TRUE(st.decalPassSkipped);
    EXPECT_EQ(st.decalsDrawn, 0u);
    EXPECT_TRUE(st.decalVariant.empty());
    const size_t drawsWithout = st.drawCalls;

    // One in view, one behind the camera, one far to the side.
    r->setDecals({decal(0, {0.0f, 0.1f, 0.0f}, {0, 1, 0}, {1, 0, 0}, {1, 1}, 0.2f),
                  decal(0, {0.0f, 0.1f, 15.0f}, {0, 1, 0}, {1, 0, 0}, {1, 1}, 0.2f),
                  decal(0, {19.0f, 0.1f, -1.0f}, {0, 1, 0}, {1, 0, 0}, {1, 1}, 0.2f)});
    renderView(r.value(), cam, View::Final, &st);
    EXPECT_FALSE(st.decalPassSkipped);
    EXPECT_EQ(st.decals, 3u);
    EXPECT_EQ(st.decalsDrawn, 1u);
    EXPECT_EQ(st.decalsCulled, 2u);
    EXPECT_EQ(st.drawCalls, drawsWithout + 1); // one instanced draw for all visible decals

    // Every decal out of view: no pass at all.
    const Camera away = camera({0.0, 2.0, 5.0}, {-20.0, 2.0, 5.0});
    renderView(r.value(), away, View::Final, &st);
    EXPECT_TRUE(st.decalPassSkipped);
    EXPECT_EQ(st.decalsCulled, 3u);
}

TEST(DecalPass, UploadsOnlyChangedInstances) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene scene;
    scene.objects.push_back(object("floor", {20.0f, 0.1f, 20.0f}, {0.0, -0.1, 0.0}));
    ASSERT_TRUE(r->setScene(scene).ok());
    r->setDecalTypes({type()});
    std::vector<Decal> decals;
    for (int i = 0; i < 50; ++i)
        decals.push_back(decal(0, {float(i % 10) - 5.0f, 0.1f, float(i / 10) - 2.0f}, {0, 1, 0}, {1, 0, 0},
                               {0.5f, 0.5f}, 0.2f));
    const Camera cam = camera({0.0, 6.0, 8.0}, {0.0, 0.0, 0.0});
    r->setDecals(decals);
    FrameStats st;
    renderView(r.value(), cam, View::Final, &st);
    const size_t instance = 192, visible = st.decalsDrawn * sizeof(uint32_t);
    ASSERT_EQ(st.decalsDrawn, 50u);
    EXPECT_EQ(st.decalBytesUploaded, 50 * instance + visible);

    r->setDecals(decals); // nothing changed
    renderView(r.value(), cam, View::Final, &st);
    EXPECT_EQ(st.decalBytesUploaded, visible);

    decals[17].opacity = 0.5f; // one decal fading
    r->setDecals(decals);
    renderView(r.value(), cam, View::Final, &st);
    EXPECT_EQ(st.decalBytesUploaded, instance + visible);

    // The camera moving changes no instance either: they are stored in object space.
    renderView(r.value(), camera({1.0, 5.0, 9.0}, {0.0, 0.0, 0.0}), View::Final, &st);
    EXPECT_EQ(st.decalBytesUploaded, st.decalsDrawn * sizeof(uint32_t));
}

TEST(DecalPass, ShaderVariantFollowsTheFeaturesInUse) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene scene;
    scene.objects.push_back(object("floor", {20.0f, 0.1f, 20.0f}, {0.0, -0.1, 0.0}));
    ASSERT_TRUE(r->setScene(scene).ok());
    DecalType plain = type();
    plain.normalMap = false;
    plain.depthFade = DepthFade::None;
    DecalType wrap = type(DecalTexture::Blood, true);
    r->setDecalTypes({plain, wrap});
    const Camera cam = camera({0.0, 2.0, 5.0}, {0.0, 0.0, 0.0});
    Decal a = decal(0, {0.0f, 0.1f, 0.0f}, {0, 1, 0}, {1, 0, 0}, {1, 1}, 0.2f, 0);
    Decal b = decal(0, {0.0f, 0.1f, 30.0f}, {0, 1, 0}, {1, 0, 0}, {1, 1}, 0.2f, 1); // behind the camera
    r->setDecals({a, b});
    FrameStats st;
    renderView(r.value(), cam, View::Final, &st);
    EXPECT_EQ(st.decalVariant, ""); // no feature beyond the basic projection
    EXPECT_FALSE(st.decalPassSkipped);

    b.center.z = 1.0f; // the wrap-around decal comes into view
    r->setDecals({a, b});
    renderView(r.value(), cam, View::Final, &st);
    EXPECT_EQ(st.decalVariant, "WRAP NORMAL_MAP FADE");
    renderView(r.value(), cam, View::Coverage, &st);
    EXPECT_EQ(st.decalVariant, "WRAP COVERAGE");
}

TEST(DecalPass, SkipsInvalidDecalsWithoutCrashing) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene scene;
    scene.objects.push_back(object("floor", {20.0f, 0.1f, 20.0f}, {0.0, -0.1, 0.0}));
    ASSERT_TRUE(r->setScene(scene).ok());
    DecalType badTexture = type();
    badTexture.texture = 99;
    r->setDecalTypes({type(), badTexture});
    const Decal good = decal(0, {0.0f, 0.1f, 0.0f}, {0, 1, 0}, {1, 0, 0}, {1, 1}, 0.2f);
    std::vector<Decal> decals(9, good);
    decals[1].object = 7;                // no such object
    decals[2].type = 5;                  // no such type
    decals[3].type = 1;                  // its texture layer does not exist
    decals[4].center.x = NAN;            // not finite
    decals[5].size = {0.0f, 1.0f};       // empty
    decals[6].halfDepth = -1.0f;         // negative depth
    decals[7].frame.tangent = {0, 1, 0}; // degenerate frame (tangent along the normal)
    decals[8].opacity = INFINITY;        // not finite
    r->setDecals(decals);
    FrameStats st;
    const Image im = renderView(r.value(), camera({0.0, 2.0, 3.0}, {0.0, 0.0, 0.0}), View::Coverage, &st);
    EXPECT_EQ(st.decalsInvalid, 8u);
    EXPECT_EQ(st.decalsDrawn, 1u);
    EXPECT_GT(test::countSet(test::whiteMask(im)), 100u);
    EXPECT_EQ(gl.debugErrorCount(), 0u);
}

TEST(DecalPass, DecalFollowsItsMovingObject) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene scene = wallAndTarget(true);
    ASSERT_TRUE(r->setScene(scene).ok());
    ASSERT_TRUE(r->setObjectIds({0, 3}).ok());
    test::CoverageInputs in;
    in.types = {type()};
    in.decals = {decal(1, {0.1f, 0.1f, 0.05f}, {0, 0, 1}, {1, 0, 0}, {0.3f, 0.3f}, 0.1f, 0, 3)};
    in.objectIds = {0, 3};
    r->setDecalTypes(in.types);
    r->setDecals(in.decals);
    const Camera cam = camera({0.0, 1.5, 3.0}, {0.0, 1.5, 0.0});
    for (double x : {0.0, -0.8, 0.9}) {
        scene.objects[1].transform = glm::translate(glm::dmat4(1.0), glm::dvec3(x, 1.4, 0.5));
        ASSERT_TRUE(r->setObjectTransform(1, scene.objects[1].transform).ok());
        const std::vector<uint8_t> gpu = test::whiteMask(renderView(r.value(), cam, View::Coverage));
        const std::vector<uint8_t> cpu = test::referenceCoverage(scene, in, cam, kW, kH);
        ASSERT_GT(test::countSet(cpu), 60u);
        EXPECT_GE(test::iou(gpu, cpu), 0.97) << x;
    }
    EXPECT_FALSE(r->setObjectTransform(2, glm::dmat4(1.0)).ok());
    EXPECT_FALSE(r->setObjectTransform(1, glm::dmat4(0.0)).ok());
}

TEST(DecalPass, DecalsChangeAlbedoNormalsAndRoughnessBeforeLighting) {
    SPATTER_REQUIRE_GL(gl);
    for (DecalNormalFrame frame : {DecalNormalFrame::DecalAxes, DecalNormalFrame::DepthDerivatives}) {
        RendererSettings settings;
        settings.normalFrame = frame;
        Result<Renderer> r = test::makeRenderer(kW, kH, settings);
        ASSERT_TRUE(r.ok()) << r.error();
        Scene scene;
        scene.objects.push_back(object("wall", {3.0f, 3.0f, 0.1f}, {0.0, 1.5, -0.1}));
        ASSERT_TRUE(r->setScene(scene).ok());
        const Camera cam = camera({0.3, 1.6, 2.0}, {0.0, 1.5, 0.0});
        DecalType paint = type(DecalTexture::Paint);
        paint.tint = {0.9f, 0.05f, 0.05f, 1.0f};
        paint.roughness = 0.1f;
        DecalType flat = paint;
        flat.normalMap = false;
        r->setDecalTypes({paint, flat});
        const Image albedo0 = renderView(r.value(), cam, View::Albedo);
        const Image normal0 = renderView(r.value(), cam, View::Normal);
        const Image final0 = renderView(r.value(), cam, View::Final);

        for (uint16_t t : {uint16_t(0), uint16_t(1)}) {
            r->setDecals({decal(0, {0.0f, 0.0f, 0.1f}, {0, 0, 1}, {1, 0, 0}, {1.2f, 1.2f}, 0.2f, t)});
            const std::vector<uint8_t> cov = test::whiteMask(renderView(r.value(), cam, View::Coverage));
            const Image albedo = renderView(r.value(), cam, View::Albedo);
            const Image normal = renderView(r.value(), cam, View::Normal);
            const Image final = renderView(r.value(), cam, View::Final);
            size_t red = 0, normalChanged = 0, finalChanged = 0, outsideChanged = 0;
            for (size_t i = 0; i < cov.size(); ++i) {
                const bool changedA = std::memcmp(px(albedo, i), px(albedo0, i), 3) != 0;
                const bool changedN = std::memcmp(px(normal, i), px(normal0, i), 3) != 0;
                const bool changedF = std::memcmp(px(final, i), px(final0, i), 3) != 0;
                if (!cov[i]) {
                    outsideChanged += (changedA || changedN || changedF) ? 1 : 0;
                    continue;
                }
                red += (px(albedo, i)[0] > 2 * px(albedo, i)[1] + 40) ? 1 : 0;
                normalChanged += changedN ? 1 : 0;
                finalChanged += changedF ? 1 : 0;
            }
            EXPECT_EQ(outsideChanged, 0u);
            EXPECT_GT(red, 150u);
            EXPECT_GT(finalChanged, 300u);
            if (t == 0) {
                EXPECT_GT(normalChanged, 200u);
            } else {
                EXPECT_EQ(normalChanged, 0u);
            }
        }
    }
}

TEST(DecalPass, DepthFadeWeakensTheDecalAwayFromItsPlane) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene scene;
    scene.objects.push_back(object("wall", {3.0f, 3.0f, 0.1f}, {0.0, 1.5, -0.1}));
    ASSERT_TRUE(r->setScene(scene).ok());
    const Camera cam = camera({0.0, 1.5, 2.0}, {0.0, 1.5, 0.0});
    DecalType solid = type(DecalTexture::Scorch);
    solid.normalMap = false;
    // Decal plane 0.8 half-depths in front of the wall: the wall is at |z| = 0.8 of the box.
    r->setDecals({decal(0, {0.0f, 0.0f, 0.1f + 0.16f}, {0, 0, 1}, {1, 0, 0}, {1.5f, 1.5f}, 0.2f)});
    auto darkness = [&](DepthFade fade) {
        solid.depthFade = fade;
        r->setDecalTypes({solid});
        const Image albedo = renderView(r.value(), cam, View::Albedo);
        const uint8_t* centre = px(albedo, size_t(kH / 2) * kW + kW / 2);
        return 255 - int(centre[0]);
    };
    const int none = darkness(DepthFade::None);
    const int linear = darkness(DepthFade::Linear);
    const int smooth = darkness(DepthFade::Smooth);
    EXPECT_GT(none, linear + 20);
    EXPECT_GT(linear, smooth); // 0.4 on the linear ramp, 0.352 smoothed
}

TEST(DecalPass, GpuTimersReportEveryPass) {
    SPATTER_REQUIRE_GL(gl);
    RendererSettings settings;
    settings.waitForTimers = true;
    Result<Renderer> r = test::makeRenderer(kW, kH, settings);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r->setScene(wallAndTarget(false)).ok());
    r->setDecalTypes({type()});
    r->setDecals({decal(0, {0.0f, 0.0f, 0.1f}, {0, 0, 1}, {1, 0, 0}, {1.0f, 1.0f}, 0.2f)});
    FrameStats st;
    renderView(r.value(), camera({0.0, 1.5, 3.0}, {0.0, 1.5, 0.0}), View::Final, &st);
    EXPECT_EQ(st.gpu.frame, int64_t(st.frame));
    EXPECT_GT(st.gpu.geometryMs, 0.0);
    EXPECT_GT(st.gpu.decalsMs, 0.0);
    EXPECT_GT(st.gpu.lightingMs, 0.0);
    EXPECT_EQ(st.gpu.lateMs, 0.0);
    EXPECT_FALSE(st.glRenderer.empty());
    // Without waiting, results arrive a frame or more later and never stall the frame.
    RendererSettings async;
    Result<Renderer> r2 = test::makeRenderer(kW, kH, async);
    ASSERT_TRUE(r2.ok()) << r2.error();
    ASSERT_TRUE(r2->setScene(wallAndTarget(false)).ok());
    FrameStats later;
    for (int f = 0; f < 8; ++f) {
        later = r2->render(camera({0.0, 1.5, 3.0}, {0.0, 1.5, 0.0}), View::Final).value();
        EXPECT_LE(later.gpu.frame, int64_t(later.frame));
    }
    EXPECT_GE(later.gpu.frame, 0);
    EXPECT_GT(later.gpu.geometryMs, 0.0);

    const std::string json = toJson(st);
    EXPECT_NE(json.find("\"gpu_ms\":{\"geometry\":"), std::string::npos) << json;
    EXPECT_NE(json.find("\"decals_drawn\":1"), std::string::npos) << json;
}

TEST(DecalPass, PngImagesBecomeDecalTextureLayers) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Image green;
    green.width = green.height = 40;
    green.name = "green";
    for (int i = 0; i < 40 * 40; ++i)
        green.rgba.insert(green.rgba.end(), {20, 220, 40, 255});
    const std::string path = test::scratchDir("decal-png") + "/green.png";
    ASSERT_TRUE(writePng(path, green).ok());
    const int layers = r->decalTextureLayers();
    Result<int> layer = r->addDecalTextureFile(path);
    ASSERT_TRUE(layer.ok()) << layer.error();
    EXPECT_EQ(layer.value(), layers);
    EXPECT_FALSE(r->addDecalTextureFile(path + ".missing").ok());

    Scene scene;
    scene.objects.push_back(object("wall", {3.0f, 3.0f, 0.1f}, {0.0, 1.5, -0.1}));
    ASSERT_TRUE(r->setScene(scene).ok());
    DecalType t = type();
    t.texture = layer.value();
    t.depthFade = DepthFade::None;
    r->setDecalTypes({t});
    r->setDecals({decal(0, {0.0f, 0.0f, 0.1f}, {0, 0, 1}, {1, 0, 0}, {1.0f, 1.0f}, 0.2f)});
    const Image albedo = renderView(r.value(), camera({0.0, 1.5, 2.0}, {0.0, 1.5, 0.0}), View::Albedo);
    const uint8_t* centre = px(albedo, size_t(kH / 2) * kW + kW / 2);
    EXPECT_NEAR(centre[0], 20, 3);
    EXPECT_NEAR(centre[1], 220, 3);
    EXPECT_NEAR(centre[2], 40, 3);
}
