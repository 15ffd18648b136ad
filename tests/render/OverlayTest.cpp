// Line overlays (RenderOverlays): per-object wireframes that follow their objects, decal boxes drawn
// where the decals are, depth testing against the scene, and nothing at all when they are off.

#include "RenderTestSupport.hpp"

#include "TestData.hpp"

#include "spatter/core/MeshBuilder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

using namespace spatter;
using namespace spatter::test;

namespace {

// A static wall whose front face is the plane z = 0, and a dynamic plate 0.4 in front of it.
Scene wallAndTarget() {
    Scene s;
    SceneObject wall;
    wall.name = "wall";
    wall.mesh = shareMesh(makeBox({2.0f, 1.5f, 0.1f}, 4));
    wall.transform = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 1.5, -0.1));
    s.objects.push_back(wall);
    SceneObject target;
    target.name = "target";
    target.mesh = shareMesh(makeBox({0.3f, 0.3f, 0.05f}, 2));
    target.transform = glm::translate(glm::dmat4(1.0), glm::dvec3(-0.6, 1.5, 0.4));
    target.dynamic = true;
    s.objects.push_back(target);
    return s;
}

RenderOptions overlays(bool wireframe, bool boxes, bool onTop = false) {
    RenderOptions o;
    o.overlays.proxyWireframe = wireframe;
    o.overlays.decalBoxes = boxes;
    o.overlays.alwaysOnTop = onTop;
    return o;
}

// Pixels whose bytes differ between two images of the same size.
std::vector<uint8_t> changed(const Image& a, const Image& b) {
    std::vector<uint8_t> mask(size_t(a.width) * size_t(a.height), 0);
    for (size_t i = 0; i < mask.size() && i * 4 + 3 < b.rgba.size(); ++i)
        mask[i] = std::memcmp(&a.rgba[i * 4], &b.rgba[i * 4], 4) != 0 ? 1 : 0;
    return mask;
}

// The mask grown by `r` pixels in every direction (a square neighbourhood).
std::vector<uint8_t> dilate(const std::vector<uint8_t>& mask, int r) {
    std::vector<uint8_t> out(mask.size(), 0);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            if (!mask[size_t(y * kW + x)]) continue;
            for (int dy = -r; dy <= r; ++dy)
                for (int dx = -r; dx <= r; ++dx) {
                    const int u = x + dx, v = y + dy;
                    if (u >= 0 && v >= 0 && u < kW && v < kH) out[size_t(v * kW + u)] = 1;
                }
        }
    return out;
}

size_t countOutside(const std::vector<uint8_t>& mask, const std::vector<uint8_t>& region) {
    size_t n = 0;
    for (size_t i = 0; i < mask.size(); ++i)
        n += (mask[i] && !region[i]) ? 1 : 0;
    return n;
}

// Pixels of the target (a bright ID colour in the ids view; the wall's ID 0 is dark grey).
std::vector<uint8_t> targetPixels(Renderer& r, const Camera& cam) {
    RenderOptions o;
    o.view = View::Ids;
    const Image ids = test::renderView(r, cam, o);
    std::vector<uint8_t> mask(size_t(kW * kH), 0);
    for (size_t i = 0; i < mask.size(); ++i)
        mask[i] = (ids.rgba[i * 4] > 70 || ids.rgba[i * 4 + 1] > 70 || ids.rgba[i * 4 + 2] > 70) ? 1 : 0;
    return mask;
}

// The unit cube with every triangle on vertices of its own (36 vertices, 12 triangles).
Mesh unweldedCube() {
    const Mesh cube = makeUnitCube();
    Mesh m;
    for (uint32_t i : cube.indices) {
        m.indices.push_back(uint32_t(m.positions.size()));
        m.positions.push_back(cube.positions[i]);
        m.normals.push_back(cube.normals[i]);
    }
    return m;
}

} // namespace

TEST(Overlays, OffDrawNothingExtra) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> plain = test::makeRenderer(kW, kH);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(plain.ok() && r.ok());
    const Scene scene = wallAndTarget();
    const std::vector<DecalType> types = {DecalType{}};
    const Decal d = [] {
        Decal x;
        x.center = {0.8f, 0.2f, 0.1f};
        x.size = {0.5f, 0.5f};
        x.halfDepth = 0.15f;
        return x;
    }();
    for (Renderer* p : {&plain.value(), &r.value()}) {
        ASSERT_TRUE(p->setScene(scene).ok());
        ASSERT_TRUE(p->setObjectIds({0, 5}).ok());
        p->setDecalTypes(types);
        p->setDecals({d});
    }
    ASSERT_TRUE(r->setOverlayMeshes({*scene.objects[0].mesh, *scene.objects[1].mesh}).ok());
    const Camera cam = test::lookAt({0.5, 1.9, 3.0}, {0.0, 1.4, 0.0});
    for (View view : {View::Final, View::Albedo, View::Coverage}) {
        SCOPED_TRACE(toString(view));
        FrameStats sp, so;
        RenderOptions off;
        off.view = view;
        const Image a = test::renderView(plain.value(), cam, off, &sp);
        const Image b = test::renderView(r.value(), cam, off, &so);
        EXPECT_EQ(a.rgba, b.rgba);
        EXPECT_EQ(so.drawCalls, sp.drawCalls);
        EXPECT_EQ(so.overlayLines, 0u);
        EXPECT_EQ(so.gpu.overlayMs, 0.0);
    }
    EXPECT_EQ(gl.debugErrorCount(), 0u);
}

TEST(Overlays, ProxyWireframeDrawsOverItsObjectAndFollowsItWhenItMoves) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene scene = wallAndTarget();
    ASSERT_TRUE(r->setScene(scene).ok());
    ASSERT_TRUE(r->setObjectIds({0, 9}).ok());
    // Only the target has a wireframe: its render mesh, so every line lies on the drawn surface and
    // shows only through the depth bias.
    ASSERT_TRUE(r->setOverlayMeshes({Mesh{}, *scene.objects[1].mesh}).ok());
    const Camera cam = test::lookAt({0.3, 1.8, 3.0}, {0.0, 1.5, 0.0});

    std::vector<uint8_t> before;
    for (double x : {-0.6, 0.7}) {
        SCOPED_TRACE(x);
        ASSERT_TRUE(r->setObjectTransform(1, glm::translate(glm::dmat4(1.0), glm::dvec3(x, 1.5, 0.4))).ok());
        const std::vector<uint8_t> target = targetPixels(r.value(), cam);
        ASSERT_GT(test::countSet(target), 300u);
        FrameStats off, on;
        const Image clean = test::renderView(r.value(), cam, RenderOptions{}, &off);
        const Image wire = test::renderView(r.value(), cam, overlays(true, false), &on);
        const std::vector<uint8_t> lines = changed(clean, wire);
        test::dumpImage(x < 0 ? "wire-left" : "wire-right", wire);
        // makeBox with 2 x 2 squares per face: 48 triangles, each edge shared by two of them.
        EXPECT_EQ(on.overlayLines, 72u);
        EXPECT_EQ(on.drawCalls, off.drawCalls + 1);
        EXPECT_GT(test::countSet(lines), 120u);
        EXPECT_EQ(countOutside(lines, dilate(target, 1)), 0u);
        if (!before.empty()) {
            // The lines moved with the target: none is left where it was.
            size_t stayed = 0;
            for (size_t i = 0; i < lines.size(); ++i)
                stayed += (lines[i] && before[i]) ? 1 : 0;
            EXPECT_EQ(stayed, 0u);
        }
        before = dilate(target, 1);
    }
    EXPECT_EQ(gl.debugErrorCount(), 0u);
}

TEST(Overlays, WireframeDrawsEachUniqueEdgeOnce) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene scene;
    SceneObject cube;
    cube.name = "cube";
    cube.mesh = shareMesh(makeUnitCube());
    scene.objects.push_back(cube);
    ASSERT_TRUE(r->setScene(scene).ok());
    const Camera cam = test::lookAt({1.5, 1.2, 2.0}, {0.0, 0.0, 0.0});
    // 12 box edges and 6 face diagonals, whether the triangles share vertices or not.
    for (const Mesh& m : {makeUnitCube(), unweldedCube()}) {
        ASSERT_TRUE(r->setOverlayMeshes({m}).ok());
        FrameStats st;
        test::renderView(r.value(), cam, overlays(true, false), &st);
        EXPECT_EQ(st.overlayLines, 18u);
    }
    // A new scene drops them.
    ASSERT_TRUE(r->setScene(scene).ok());
    FrameStats st;
    test::renderView(r.value(), cam, overlays(true, false), &st);
    EXPECT_EQ(st.overlayLines, 0u);
}

TEST(Overlays, DecalBoxesAreDrawnWhereTheDecalIs) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene scene;
    SceneObject wall;
    wall.name = "wall";
    wall.mesh = shareMesh(makeBox({3.0f, 3.0f, 0.1f}, 2));
    wall.transform = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 1.5, -0.1));
    scene.objects.push_back(wall);
    ASSERT_TRUE(r->setScene(scene).ok());
    DecalType type;
    type.texture = int(DecalTexture::Scorch);
    r->setDecalTypes({type});
    // A 0.8 x 0.8 box on the wall, 0.5 to the right of the centre, reaching 0.2 into and out of it.
    Decal d;
    d.object = 0;
    d.center = {0.5f, 0.0f, 0.1f};
    d.size = {0.8f, 0.8f};
    d.halfDepth = 0.2f;
    r->setDecals({d});
    const Camera cam = test::lookAt({-0.5, 2.1, 2.0}, {0.3, 1.4, 0.0});

    // Screen rectangle of the box's corners.
    const glm::dmat4 viewProj = projection(cam, double(kW) / kH) * viewRotation(cam);
    const glm::dmat4 boxToWorld = wall.transform * glm::dmat4(d.boxToObject());
    std::vector<uint8_t> rect(size_t(kW * kH), 0);
    double x0 = kW, x1 = 0, y0 = kH, y1 = 0;
    for (int c = 0; c < 8; ++c) {
        const glm::dvec4 corner((c & 1) ? 1 : -1, (c & 2) ? 1 : -1, (c & 4) ? 1 : -1, 1);
        const glm::dvec4 clip = viewProj * glm::dvec4(glm::dvec3(boxToWorld * corner) - cam.eye, 1.0);
        const double px = (clip.x / clip.w * 0.5 + 0.5) * kW, py = (0.5 - clip.y / clip.w * 0.5) * kH;
        x0 = std::min(x0, px), x1 = std::max(x1, px), y0 = std::min(y0, py), y1 = std::max(y1, py);
    }
    for (int y = std::max(0, int(y0) - 1); y <= std::min(kH - 1, int(y1) + 1); ++y)
        for (int x = std::max(0, int(x0) - 1); x <= std::min(kW - 1, int(x1) + 1); ++x)
            rect[size_t(y * kW + x)] = 1;
    ASSERT_GT(test::countSet(rect), 400u);

    FrameStats st;
    const Image clean = test::renderView(r.value(), cam, RenderOptions{});
    const Image tested = test::renderView(r.value(), cam, overlays(false, true), &st);
    const Image onTop = test::renderView(r.value(), cam, overlays(false, true, true));
    test::dumpImage("boxes-tested", tested);
    test::dumpImage("boxes-on-top", onTop);
    EXPECT_EQ(st.overlayLines, 12u);
    const std::vector<uint8_t> linesTested = changed(clean, tested), linesOnTop = changed(clean, onTop);
    EXPECT_GT(test::countSet(linesTested), 80u);
    EXPECT_EQ(countOutside(linesTested, rect), 0u);
    EXPECT_EQ(countOutside(linesOnTop, rect), 0u);
    // The half of the box behind the wall's face is hidden unless the lines are on top.
    EXPECT_GT(test::countSet(linesOnTop), test::countSet(linesTested) + 30);
    // Static geometry's decal boxes are amber.
    size_t amber = 0;
    for (size_t i = 0; i < linesTested.size(); ++i) {
        const uint8_t* p = &tested.rgba[i * 4];
        // Within a unit of (255, 184, 26): drivers round the line colour's sRGB encoding differently.
        amber +=
            (linesTested[i] && p[0] >= 254 && std::abs(p[1] - 184) <= 1 && std::abs(p[2] - 26) <= 1) ? 1 : 0;
    }
    EXPECT_EQ(amber, test::countSet(linesTested));

    // No decal in view: no boxes and no overlay pass.
    r->setDecals({});
    test::renderView(r.value(), cam, overlays(false, true), &st);
    EXPECT_EQ(st.overlayLines, 0u);
    EXPECT_EQ(gl.debugErrorCount(), 0u);
}

TEST(Overlays, RejectsBadMeshesAndDepthBias) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    const Scene scene = wallAndTarget();
    ASSERT_TRUE(r->setScene(scene).ok());
    ASSERT_TRUE(r->setOverlayMeshes({Mesh{}, *scene.objects[1].mesh}).ok());

    const Status tooFew = r->setOverlayMeshes({*scene.objects[1].mesh});
    ASSERT_FALSE(tooFew.ok());
    EXPECT_NE(tooFew.error().find("1 overlay meshes for 2 objects"), std::string::npos) << tooFew.error();
    Mesh broken = *scene.objects[1].mesh;
    broken.indices.back() = 100000;
    const Status outOfRange = r->setOverlayMeshes({Mesh{}, broken});
    ASSERT_FALSE(outOfRange.ok());
    EXPECT_NE(outOfRange.error().find("object 1"), std::string::npos) << outOfRange.error();
    Mesh nan = *scene.objects[1].mesh;
    nan.positions[3].y = NAN;
    EXPECT_FALSE(r->setOverlayMeshes({nan, Mesh{}}).ok());

    // The meshes set before the failures are still drawn.
    const Camera cam = test::lookAt({0.0, 1.8, 3.0}, {0.0, 1.5, 0.0});
    FrameStats st;
    test::renderView(r.value(), cam, overlays(true, false), &st);
    EXPECT_EQ(st.overlayLines, 72u);

    for (float bias : {-0.1f, 0.8f, float(NAN)}) {
        RenderOptions o = overlays(true, true);
        o.overlays.depthBias = bias;
        EXPECT_FALSE(r->render(cam, o).ok()) << bias;
    }
    EXPECT_EQ(gl.debugErrorCount(), 0u);
}
