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
using namespace spatter::test;

namespace {

SceneObject object(const std::string& name, const glm::vec3& halfExtents, const glm::dvec3& position,
                   bool dynamic = false) {
    SceneObject o;
    o.name = name;
    o.mesh = shareMesh(makeBox(halfExtents, 4));
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
    const glm::vec3 n = glm::normalize(normal), t = glm::normalize(tangent);
    d.setFrame({t, glm::cross(n, t), n});
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

// One view of the current decals with `options` (its view aside): the coverage mask, the final
// image, and the stats of the coverage frame.
struct DecalFrame {
    std::vector<uint8_t> coverage;
    Image final;
    FrameStats stats;
};
DecalFrame coverageAndFinal(Renderer& r, const Camera& cam, RenderOptions options = {}) {
    DecalFrame f;
    options.view = View::Coverage;
    f.coverage = test::whiteMask(test::renderView(r, cam, options, &f.stats));
    options.view = View::Final;
    f.final = test::renderView(r, cam, options);
    return f;
}

const uint8_t* px(const Image& im, size_t i) {
    return &im.rgba[i * 4];
}

// Pixels of `region` that a decal covers (`coverage`) and whose final colour it changes (`final`
// against `clean`, the same view without the decal).
struct Marks {
    size_t covered = 0;
    size_t changed = 0;
};
Marks marksIn(const std::vector<uint8_t>& region, const std::vector<uint8_t>& coverage, const Image& final,
              const Image& clean) {
    Marks m;
    for (size_t i = 0; i < coverage.size(); ++i) {
        m.covered += (region[i] && coverage[i]) ? 1 : 0;
        m.changed += (region[i] && std::memcmp(px(final, i), px(clean, i), 4) != 0) ? 1 : 0;
    }
    return m;
}

// A scene of one static box.
Scene oneBox(const std::string& name, const glm::vec3& halfExtents, const glm::dvec3& position) {
    Scene s;
    s.objects.push_back(object(name, halfExtents, position));
    return s;
}

// A static floor whose top is the plane y = 0, 40 x 40 around the origin.
Scene floorScene() {
    return oneBox("floor", {20.0f, 0.1f, 20.0f}, {0.0, -0.1, 0.0});
}

// A static wall whose front face is the plane z = 0, 6 x 6 around (0, 1.5).
Scene wallScene() {
    return oneBox("wall", {3.0f, 3.0f, 0.1f}, {0.0, 1.5, -0.1});
}

// A static wall 2 cm thick, 2 x 2 around the origin: front face z = 0.01, back face z = -0.01.
Scene thinWallScene() {
    return oneBox("thin wall", {1.0f, 1.0f, 0.01f}, {0.0, 0.0, 0.0});
}

// Scene: a static wall whose front face is the plane z = 0 and a dynamic target plate in front.
Scene wallAndTarget(bool targetDynamic) {
    Scene s;
    s.objects.push_back(object("wall", {2.0f, 1.5f, 0.1f}, {0.0, 1.5, -0.1}));
    s.objects.push_back(object("target", {0.3f, 0.3f, 0.05f}, {0.0, 1.5, 0.4}, targetDynamic));
    return s;
}

// Puts wallAndTarget(dynamic) on `r`, the target with object ID 9 when dynamic (0 otherwise).
::testing::AssertionResult showWallAndTarget(Renderer& r, bool dynamic) {
    if (Status st = r.setScene(wallAndTarget(dynamic)); !st)
        return ::testing::AssertionFailure() << st.error();
    if (Status st = r.setObjectIds({0, uint8_t(dynamic ? 9 : 0)}); !st)
        return ::testing::AssertionFailure() << st.error();
    return ::testing::AssertionSuccess();
}

// Pixels of wallAndTarget's ID view that show ID 0 (dark grey): the wall.
std::vector<uint8_t> wallPixels(const Image& ids) {
    std::vector<uint8_t> wall(ids.rgba.size() / 4);
    for (size_t i = 0; i < wall.size(); ++i)
        wall[i] = (px(ids, i)[0] == 64 && px(ids, i)[1] == 64 && px(ids, i)[2] == 64) ? 1 : 0;
    return wall;
}

// A decal on wallAndTarget's target, on its front face (z = 0.45 in the world), whose box reaches
// back through the wall's face at z = 0 and overhangs the target on every side; object ID 9.
Decal decalReachingTheWall() {
    return decal(1, {0.0f, 0.0f, 0.05f}, {0, 0, 1}, {1, 0, 0}, {1.4f, 1.4f}, 0.6f, 0, 9);
}

// The wall behind the target as decalReachingTheWall leaves it: untouched where the decal is kept
// off it, clearly marked where it is not.
void expectWallMarks(const Marks& wall, bool keptOff) {
    if (keptOff) {
        EXPECT_EQ(wall.covered, 0u);
        EXPECT_EQ(wall.changed, 0u);
    } else {
        EXPECT_GT(wall.covered, 200u);
        EXPECT_GT(wall.changed, 100u);
    }
}

} // namespace

TEST(DecalPass, IdClippingKeepsTheWallBehindAMovingTargetClean) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    const Camera cam = test::lookAt({0.4, 1.8, 3.0}, {0.0, 1.5, 0.0});

    // Pixel classes from the ID view of the scene with a dynamic target: ID 0 (the wall) is dark grey.
    ASSERT_TRUE(showWallAndTarget(r.value(), true));
    const Image ids = test::renderView(r.value(), cam, View::Ids);
    const std::vector<uint8_t> wall = wallPixels(ids);
    std::vector<uint8_t> target(size_t(kW * kH));
    for (size_t i = 0; i < target.size(); ++i) {
        const uint8_t* id = px(ids, i);
        target[i] = (id[0] > 70 || id[1] > 70 || id[2] > 70) ? 1 : 0;
    }
    ASSERT_GT(test::countSet(wall), size_t(kW * kH) / 3);
    ASSERT_GT(test::countSet(target), 250u);

    for (bool dynamic : {true, false}) {
        SCOPED_TRACE(dynamic ? "dynamic target" : "static target");
        ASSERT_TRUE(showWallAndTarget(r.value(), dynamic));
        r->setDecalTypes({type()});
        const Image cleanFinal = test::renderView(r.value(), cam, View::Final);
        r->setDecals({decalReachingTheWall()});
        const DecalFrame f = coverageAndFinal(r.value(), cam);
        EXPECT_EQ(f.stats.decalVariant.find("IDS") != std::string::npos, dynamic) << f.stats.decalVariant;
        test::dumpImage(dynamic ? "idclip-dynamic" : "idclip-static", f.final);
        EXPECT_GT(marksIn(target, f.coverage, f.final, cleanFinal).covered, 250u);
        // Without IDs the same box does reach the wall: the clipping with them is the IDs' doing.
        expectWallMarks(marksIn(wall, f.coverage, f.final, cleanFinal), dynamic);
    }
}

TEST(DecalPass, IdClippingOffLetsADecalOnATargetReachTheWallBehind) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    const Camera cam = test::lookAt({0.4, 1.8, 3.0}, {0.0, 1.5, 0.0});
    ASSERT_TRUE(showWallAndTarget(r.value(), true));
    r->setDecalTypes({type()});
    const std::vector<uint8_t> wall = wallPixels(test::renderView(r.value(), cam, View::Ids));
    ASSERT_GT(test::countSet(wall), size_t(kW * kH) / 3);
    const Image cleanFinal = test::renderView(r.value(), cam, View::Final);
    r->setDecals({decalReachingTheWall()});

    for (bool clipping : {true, false}) {
        SCOPED_TRACE(clipping ? "ID clipping on" : "ID clipping off");
        RenderOptions options;
        options.decals.idClipping = clipping;
        const DecalFrame f = coverageAndFinal(r.value(), cam, options);
        EXPECT_EQ(f.stats.decalVariant.find("IDS") != std::string::npos, clipping) << f.stats.decalVariant;
        expectWallMarks(marksIn(wall, f.coverage, f.final, cleanFinal), clipping);
    }
}

TEST(DecalPass, CameraInsideADecalBoxStillDrawsIt) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    const Scene scene = wallScene();
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
        const Camera cam = test::lookAt({0.15, 1.6, z}, {0.0, 1.45, z - 2.0});
        FrameStats st;
        const Image cov = test::renderView(r.value(), cam, View::Coverage, &st);
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
    Scene scene = oneBox("cube", {0.5f, 0.5f, 0.5f}, {0.0, 0.0, 0.0});
    scene.objects[0].mesh = shareMesh(flatBox({0.5f, 0.5f, 0.5f}));
    ASSERT_TRUE(r->setScene(scene).ok());
    const Camera cam = test::lookAt({1.9, 0.5, 1.9}, {0.35, 0.0, 0.35});
    // Face classes from the normals before any decal: +X side face and +Z front face.
    const Image normals = test::renderView(r.value(), cam, View::Normal);
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
        const std::vector<uint8_t> cov =
            test::whiteMask(test::renderView(r.value(), cam, View::Coverage, &st));
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
        test::dumpImage(wrap ? "wrap-final" : "flat-final", test::renderView(r.value(), cam, View::Final));
    }
}

TEST(DecalPass, BackSideOfAThinWallStaysClean) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r->setScene(thinWallScene()).ok());
    // On the front face (+Z); the box goes right through the 2 cm wall.
    const std::vector<Decal> decals = {
        decal(0, {0.0f, 0.0f, 0.01f}, {0, 0, 1}, {1, 0, 0}, {1.0f, 1.0f}, 0.3f)};
    const Camera behind = test::lookAt({0.3, 0.2, -2.0}, {0.0, 0.0, 0.0});
    const Camera before = test::lookAt({0.3, 0.2, 2.0}, {0.0, 0.0, 0.0});

    r->setDecalTypes({type(DecalTexture::Paint)});
    const Image cleanBack = test::renderView(r.value(), behind, View::Final);
    r->setDecals(decals);
    EXPECT_EQ(test::countSet(test::whiteMask(test::renderView(r.value(), behind, View::Coverage))), 0u);
    EXPECT_EQ(test::renderView(r.value(), behind, View::Final).rgba, cleanBack.rgba);
    EXPECT_GT(test::countSet(test::whiteMask(test::renderView(r.value(), before, View::Coverage))), 500u);

    // The box does reach the back face: only the angle test keeps it clean.
    r->setDecalTypes({type(DecalTexture::Paint, false, 180.0f)});
    EXPECT_GT(test::countSet(test::whiteMask(test::renderView(r.value(), behind, View::Coverage))), 500u);
}

TEST(DecalPass, AngleRejectOffLetsADecalMarkTheBackOfAThinWall) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r->setScene(thinWallScene()).ok());
    const Camera behind = test::lookAt({0.3, 0.2, -2.0}, {0.0, 0.0, 0.0});
    r->setDecalTypes({type(DecalTexture::Paint)});
    const Image cleanBack = test::renderView(r.value(), behind, View::Final);
    r->setDecals({decal(0, {0.0f, 0.0f, 0.01f}, {0, 0, 1}, {1, 0, 0}, {1.0f, 1.0f}, 0.3f)});

    for (bool reject : {true, false}) {
        SCOPED_TRACE(reject ? "angle rejection on" : "angle rejection off");
        RenderOptions options;
        options.decals.angleReject = reject;
        const DecalFrame f = coverageAndFinal(r.value(), behind, options);
        const size_t covered = test::countSet(f.coverage);
        EXPECT_EQ(f.stats.decalVariant.find("NO_ANGLE") == std::string::npos, reject) << f.stats.decalVariant;
        if (reject) {
            EXPECT_EQ(covered, 0u);
            EXPECT_EQ(f.final.rgba, cleanBack.rgba);
        } else {
            EXPECT_GT(covered, 500u);
            EXPECT_NE(f.final.rgba, cleanBack.rgba);
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
    const Camera cam = test::lookAt({0.3, 1.7, 3.0}, {0.0, 1.5, 0.0});
    const Image clean = test::renderView(r.value(), cam, View::Final);
    r->setDecals(in.decals);
    FrameStats st;
    const Image final = test::renderView(r.value(), cam, View::Final, &st);
    EXPECT_GT(st.gpu.lateMs, 0.0);
    const std::vector<uint8_t> gpu = test::whiteMask(test::renderView(r.value(), cam, View::Coverage));
    const std::vector<uint8_t> cpu = test::referenceCoverage(scene, in, cam, kW, kH);
    EXPECT_GE(test::iou(gpu, cpu), 0.99);

    // The plate's pixels: where the plate alone would be drawn.
    Scene plateOnly = scene;
    plateOnly.objects[0].transform =
        glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 1.5, 50.0)); // behind the eye
    ASSERT_TRUE(r->setScene(plateOnly).ok());
    const Image ids = test::renderView(r.value(), cam, View::Ids);
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
    ASSERT_TRUE(r->setScene(floorScene()).ok());
    r->setDecalTypes({type()});
    const Camera cam = test::lookAt({0.0, 2.0, 5.0}, {0.0, 0.0, 0.0});
    FrameStats st;
    test::renderView(r.value(), cam, View::Final, &st);
    EXPECT_TRUE(st.decalPassSkipped);
    EXPECT_EQ(st.decalsDrawn, 0u);
    EXPECT_TRUE(st.decalVariant.empty());
    const size_t drawsWithout = st.drawCalls;

    // One in view, one behind the camera, one far to the side.
    r->setDecals({decal(0, {0.0f, 0.1f, 0.0f}, {0, 1, 0}, {1, 0, 0}, {1, 1}, 0.2f),
                  decal(0, {0.0f, 0.1f, 15.0f}, {0, 1, 0}, {1, 0, 0}, {1, 1}, 0.2f),
                  decal(0, {19.0f, 0.1f, -1.0f}, {0, 1, 0}, {1, 0, 0}, {1, 1}, 0.2f)});
    test::renderView(r.value(), cam, View::Final, &st);
    EXPECT_FALSE(st.decalPassSkipped);
    EXPECT_EQ(st.decals, 3u);
    EXPECT_EQ(st.decalsDrawn, 1u);
    EXPECT_EQ(st.decalsCulled, 2u);
    // One box alone: it reads and writes the host's normals in place (no copy), in one instanced draw
    // for all visible decals.
    EXPECT_EQ(st.decalNormalCopy, "in-place");
    EXPECT_EQ(st.drawCalls, drawsWithout + 1);

    // Every decal out of view: no pass at all.
    const Camera away = test::lookAt({0.0, 2.0, 5.0}, {-20.0, 2.0, 5.0});
    test::renderView(r.value(), away, View::Final, &st);
    EXPECT_TRUE(st.decalPassSkipped);
    EXPECT_EQ(st.decalsCulled, 3u);
}

TEST(DecalPass, UploadsOnlyChangedInstances) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r->setScene(floorScene()).ok());
    r->setDecalTypes({type()});
    std::vector<Decal> decals;
    for (int i = 0; i < 50; ++i)
        decals.push_back(decal(0, {float(i % 10) - 5.0f, 0.1f, float(i / 10) - 2.0f}, {0, 1, 0}, {1, 0, 0},
                               {0.5f, 0.5f}, 0.2f));
    const Camera cam = test::lookAt({0.0, 6.0, 8.0}, {0.0, 0.0, 0.0});
    r->setDecals(decals);
    FrameStats st;
    test::renderView(r.value(), cam, View::Final, &st);
    const size_t instance = 44, type = 48, visible = st.decalsDrawn * sizeof(uint32_t);
    ASSERT_EQ(st.decalsDrawn, 50u);
    EXPECT_EQ(st.decalBytesUploaded, 50 * instance + type + visible); // the records, and the type once

    DecalChanges changes; // what a DecalSystem reports: nothing changed
    r->updateDecals(decals, changes);
    test::renderView(r.value(), cam, View::Final, &st);
    EXPECT_EQ(st.decalBytesUploaded, visible);

    decals[17].opacity = 0.5f; // one decal fading
    changes.changes = {DecalChange{17, 17, DecalChangeKind::Changed}};
    r->updateDecals(decals, changes);
    test::renderView(r.value(), cam, View::Final, &st);
    EXPECT_EQ(st.decalBytesUploaded, instance + visible);

    // The camera moving changes no instance either: they are stored in object space.
    test::renderView(r.value(), test::lookAt({1.0, 5.0, 9.0}, {0.0, 0.0, 0.0}), View::Final, &st);
    EXPECT_EQ(st.decalBytesUploaded, st.decalsDrawn * sizeof(uint32_t));
}

TEST(DecalPass, ShaderVariantFollowsTheFeaturesInUse) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r->setScene(floorScene()).ok());
    DecalType plain = type();
    plain.normalMap = false;
    plain.depthFade = DepthFade::None;
    DecalType wrap = type(DecalTexture::Blood, true);
    r->setDecalTypes({plain, wrap});
    const Camera cam = test::lookAt({0.0, 2.0, 5.0}, {0.0, 0.0, 0.0});
    Decal a = decal(0, {0.0f, 0.1f, 0.0f}, {0, 1, 0}, {1, 0, 0}, {1, 1}, 0.2f, 0);
    Decal b = decal(0, {0.0f, 0.1f, 30.0f}, {0, 1, 0}, {1, 0, 0}, {1, 1}, 0.2f, 1); // behind the camera
    r->setDecals({a, b});
    FrameStats st;
    test::renderView(r.value(), cam, View::Final, &st);
    EXPECT_EQ(st.decalVariant, ""); // no feature beyond the basic projection
    EXPECT_FALSE(st.decalPassSkipped);

    b.center.z = 1.0f; // the wrap-around decal comes into view
    r->setDecals({a, b});
    test::renderView(r.value(), cam, View::Final, &st);
    EXPECT_EQ(st.decalVariant, "WRAP NORMAL_MAP FADE");
    test::renderView(r.value(), cam, View::Coverage, &st);
    EXPECT_EQ(st.decalVariant, "WRAP COVERAGE");
}

TEST(DecalPass, SkipsInvalidDecalsWithoutCrashing) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r->setScene(floorScene()).ok());
    DecalType badTexture = type();
    badTexture.texture = 99;
    r->setDecalTypes({type(), badTexture});
    const Decal good = decal(0, {0.0f, 0.1f, 0.0f}, {0, 1, 0}, {1, 0, 0}, {1, 1}, 0.2f);
    std::vector<Decal> decals(9, good);
    decals[1].object = 7;                   // no such object
    decals[2].type = 5;                     // no such type
    decals[3].type = 1;                     // its texture layer does not exist
    decals[4].center.x = NAN;               // not finite
    decals[5].size = {0.0f, 1.0f};          // empty
    decals[6].halfDepth = -1.0f;            // negative depth
    decals[7].packedFrame = kNoOrientation; // what setFrame makes of a degenerate frame
    decals[8].slant = 0x7c00u;              // a projection axis of infinite slope
    r->setDecals(decals);
    FrameStats st;
    const Image im =
        test::renderView(r.value(), test::lookAt({0.0, 2.0, 3.0}, {0.0, 0.0, 0.0}), View::Coverage, &st);
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
    const Camera cam = test::lookAt({0.0, 1.5, 3.0}, {0.0, 1.5, 0.0});
    for (double x : {0.0, -0.8, 0.9}) {
        scene.objects[1].transform = glm::translate(glm::dmat4(1.0), glm::dvec3(x, 1.4, 0.5));
        ASSERT_TRUE(r->setObjectTransform(1, scene.objects[1].transform).ok());
        const std::vector<uint8_t> gpu = test::whiteMask(test::renderView(r.value(), cam, View::Coverage));
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
        ASSERT_TRUE(r->setScene(wallScene()).ok());
        const Camera cam = test::lookAt({0.3, 1.6, 2.0}, {0.0, 1.5, 0.0});
        DecalType paint = type(DecalTexture::Paint);
        paint.tint = {0.9f, 0.05f, 0.05f, 1.0f};
        paint.roughness = 0.1f;
        DecalType flat = paint;
        flat.normalMap = false;
        r->setDecalTypes({paint, flat});
        const Image albedo0 = test::renderView(r.value(), cam, View::Albedo);
        const Image normal0 = test::renderView(r.value(), cam, View::Normal);
        const Image final0 = test::renderView(r.value(), cam, View::Final);

        for (uint16_t t : {uint16_t(0), uint16_t(1)}) {
            r->setDecals({decal(0, {0.0f, 0.0f, 0.1f}, {0, 0, 1}, {1, 0, 0}, {1.2f, 1.2f}, 0.2f, t)});
            const std::vector<uint8_t> cov =
                test::whiteMask(test::renderView(r.value(), cam, View::Coverage));
            const Image albedo = test::renderView(r.value(), cam, View::Albedo);
            const Image normal = test::renderView(r.value(), cam, View::Normal);
            const Image final = test::renderView(r.value(), cam, View::Final);
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
    ASSERT_TRUE(r->setScene(wallScene()).ok());
    const Camera cam = test::lookAt({0.0, 1.5, 2.0}, {0.0, 1.5, 0.0});
    DecalType solid = type(DecalTexture::Scorch);
    solid.normalMap = false;
    // Decal plane 0.8 half-depths in front of the wall: the wall is at |z| = 0.8 of the box.
    r->setDecals({decal(0, {0.0f, 0.0f, 0.1f + 0.16f}, {0, 0, 1}, {1, 0, 0}, {1.5f, 1.5f}, 0.2f)});
    auto darkness = [&](DepthFade fade) {
        solid.depthFade = fade;
        r->setDecalTypes({solid});
        const Image albedo = test::renderView(r.value(), cam, View::Albedo);
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
    test::renderView(r.value(), test::lookAt({0.0, 1.5, 3.0}, {0.0, 1.5, 0.0}), View::Final, &st);
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
        later = r2->render(test::lookAt({0.0, 1.5, 3.0}, {0.0, 1.5, 0.0}), View::Final).value();
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

    ASSERT_TRUE(r->setScene(wallScene()).ok());
    DecalType t = type();
    t.texture = layer.value();
    t.depthFade = DepthFade::None;
    r->setDecalTypes({t});
    r->setDecals({decal(0, {0.0f, 0.0f, 0.1f}, {0, 0, 1}, {1, 0, 0}, {1.0f, 1.0f}, 0.2f)});
    const Image albedo =
        test::renderView(r.value(), test::lookAt({0.0, 1.5, 2.0}, {0.0, 1.5, 0.0}), View::Albedo);
    const uint8_t* centre = px(albedo, size_t(kH / 2) * kW + kW / 2);
    EXPECT_NEAR(centre[0], 20, 3);
    EXPECT_NEAR(centre[1], 220, 3);
    EXPECT_NEAR(centre[2], 40, 3);
}

TEST(DecalPass, MirroredFrameDrawsTheTextureMirrored) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Image halves; // rows 0-19 red, rows 20-39 blue: the texture's v axis runs along the bitangent
    halves.width = halves.height = 40;
    halves.name = "halves";
    for (int i = 0; i < 40 * 40; ++i)
        halves.rgba.insert(halves.rgba.end(), i < 20 * 40 ? std::initializer_list<uint8_t>{230, 20, 20, 255}
                                                          : std::initializer_list<uint8_t>{20, 20, 230, 255});
    Result<int> layer = r->addDecalTexture(halves);
    ASSERT_TRUE(layer.ok()) << layer.error();
    ASSERT_TRUE(r->setScene(wallScene()).ok());
    DecalType t = type();
    t.texture = layer.value();
    t.normalMap = false;
    t.depthFade = DepthFade::None;
    r->setDecalTypes({t});
    const Camera cam = test::lookAt({0.0, 1.5, 2.0}, {0.0, 1.5, 0.0});
    const size_t above = size_t(kH / 2 - kH / 8) * kW + kW / 2, below = size_t(kH / 2 + kH / 8) * kW + kW / 2;
    Decal d = decal(0, {0.0f, 0.0f, 0.1f}, {0, 0, 1}, {1, 0, 0}, {1.0f, 1.0f}, 0.2f);
    r->setDecals({d});
    const Image plain = test::renderView(r.value(), cam, View::Albedo);
    ASSERT_TRUE(d.setFrame({{1, 0, 0}, {0, -1, 0}, {0, 0, 1}})); // left-handed: the bitangent turned round
    ASSERT_TRUE(d.mirrored());
    r->setDecals({d});
    const Image mirrored = test::renderView(r.value(), cam, View::Albedo);
    EXPECT_GT(px(plain, above)[0], 150) << "red above";
    EXPECT_GT(px(plain, below)[2], 150) << "blue below";
    EXPECT_GT(px(mirrored, above)[2], 150) << "blue above";
    EXPECT_GT(px(mirrored, below)[0], 150) << "red below";
}
