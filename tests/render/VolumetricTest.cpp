// Volumetric decals: a crater behind a stencil hole in the wall, on a scene with known geometry.

#include "RenderTestSupport.hpp"

#include "TestData.hpp"

#include "spatter/core/CraterMesh.hpp"
#include "spatter/core/MeshBuilder.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

using namespace spatter;
using spatter::test::renderView;

namespace {

constexpr int kCraterW = 160;
constexpr int kCraterH = 120;
constexpr float kRadius = 0.3f; // crater radius (half the decal size)

// The wall's front face is the plane z = 0, around (0, 1.5).
SceneObject boxObject(const std::string& name, const glm::vec3& halfExtents, const glm::dvec3& position) {
    SceneObject o;
    o.name = name;
    o.mesh = shareMesh(makeBox(halfExtents, 4));
    o.transform = glm::translate(glm::dmat4(1.0), position);
    return o;
}

Scene wallScene(bool redBehind) {
    Scene s;
    s.materials.push_back({});
    s.materials[0].name = "grey";
    s.materials[0].baseColorFactor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
    s.objects.push_back(boxObject("wall", {2.0f, 1.5f, 0.1f}, {0.0, 1.5, -0.1}));
    s.objects[0].editMesh().submeshes = {{0, uint32_t(s.objects[0].mesh->indices.size()), 0}};
    if (redBehind) {
        Material red;
        red.name = "red";
        red.baseColorFactor = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
        s.materials.push_back(red);
        SceneObject back = boxObject("red", {2.5f, 2.0f, 0.05f}, {0.0, 1.5, -0.35});
        back.editMesh().submeshes = {{0, uint32_t(back.mesh->indices.size()), 1}};
        s.objects.push_back(back);
    }
    return s;
}

// A volumetric decal on the wall's front face at world (x, y, 0).
Decal crater(float x, float y, uint32_t id = 1) {
    Decal d;
    d.object = 0;
    d.center = {x, y - 1.5f, 0.1f};
    d.setFrame({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
    d.size = glm::vec2(2.0f * kRadius);
    d.halfDepth = 0.2f;
    d.id = id;
    return d;
}

std::vector<DecalType> types() {
    DecalType t;
    t.name = "hole";
    t.volumetric = true;
    return {t};
}

Camera frontCamera() {
    Camera c;
    c.eye = {0.35, 1.8, 2.0};
    c.target = {0.0, 1.5, 0.0};
    return c;
}

// Where the ray through pixel (i, j) (row 0 at the top) meets the plane z = 0.
glm::dvec3 wallPoint(const Camera& cam, int i, int j) {
    const glm::dvec3 dir = pixelDirection(cam, kCraterW, kCraterH, i, j);
    return cam.eye + dir * (-cam.eye.z / dir.z);
}

// Smallest distance from p to the centres, in the wall plane.
double nearestCentre(const glm::dvec3& p, const std::vector<glm::dvec2>& centres) {
    double best = 1e30;
    for (const glm::dvec2& c : centres)
        best = std::min(best, glm::length(glm::dvec2(p) - c));
    return best;
}

// Depth view value: brighter is nearer.
int depthAt(const Image& im, int i, int j) {
    return im.rgba[(size_t(j) * size_t(kCraterW) + size_t(i)) * 4];
}

} // namespace

TEST(VolumetricDecal, DepthLiesBehindTheWallInsideTheFootprintOnly) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kCraterW, kCraterH);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r->setScene(wallScene(false)).ok());
    r->setDecalTypes(types());
    const Camera cam = frontCamera();
    const Image before = renderView(r.value(), cam, View::Depth);
    r->setDecals({crater(0.0f, 1.5f)});
    FrameStats stats;
    const Image after = renderView(r.value(), cam, View::Depth, &stats);
    EXPECT_EQ(stats.decalsVolumetric, 1u);
    EXPECT_EQ(stats.decalsDrawn, 0u); // not drawn as a flat decal

    size_t inside = 0, deeper = 0, outside = 0;
    const CraterShape shape;
    for (int j = 0; j < kCraterH; ++j)
        for (int i = 0; i < kCraterW; ++i) {
            const double d = nearestCentre(wallPoint(cam, i, j), {{0.0, 1.5}});
            // Well inside the chipped rim: the crater; beyond the unit rim: the untouched wall.
            if (d < kRadius * (1.0 - shape.chip) * 0.8) {
                ++inside;
                if (depthAt(after, i, j) < depthAt(before, i, j)) ++deeper;
            } else if (d > kRadius * 1.05) {
                ++outside;
                ASSERT_EQ(depthAt(after, i, j), depthAt(before, i, j)) << "pixel " << i << ", " << j;
            }
        }
    ASSERT_GT(inside, 200u);
    EXPECT_GT(outside, 5000u);
    // Every pixel well inside is behind the wall (the rim region near the centre line of sight may
    // round to the same 8-bit depth only at the very edge, which is excluded above).
    EXPECT_GE(double(deeper), 0.97 * double(inside));
}

TEST(VolumetricDecal, NothingBehindTheWallShowsThroughTheHole) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kCraterW, kCraterH);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r->setScene(wallScene(true)).ok());
    r->setDecalTypes(types());
    // Overlapping craters, and one seen at a grazing angle.
    r->setDecals({crater(0.0f, 1.5f, 1), crater(0.25f, 1.55f, 2), crater(-0.6f, 1.2f, 3)});
    Camera cam = frontCamera();
    for (const glm::dvec3 eye :
         {glm::dvec3(0.35, 1.8, 2.0), glm::dvec3(-1.8, 1.4, 0.5), glm::dvec3(0.0, 3.0, 0.6)}) {
        cam.eye = eye;
        const Image albedo = renderView(r.value(), cam, View::Albedo);
        const Image normal = renderView(r.value(), cam, View::Normal);
        size_t red = 0, tilted = 0;
        for (size_t p = 0; p < size_t(kCraterW * kCraterH); ++p) {
            // Only around the craters: the red board shows below the wall's lower edge elsewhere.
            const glm::dvec3 onWall = wallPoint(cam, int(p % size_t(kCraterW)), int(p / size_t(kCraterW)));
            if (nearestCentre(onWall, {{0.0, 1.5}, {0.25, 1.55}, {-0.6, 1.2}}) > 1.5 * kRadius) continue;
            const uint8_t* a = &albedo.rgba[p * 4];
            if (a[0] > 150 && a[1] < 60 && a[2] < 60) ++red;
            // The wall's normal is +z (128, 128, 255); the craters' walls are tilted.
            const uint8_t* n = &normal.rgba[p * 4];
            if (std::abs(int(n[0]) - 128) > 20 || std::abs(int(n[1]) - 128) > 20) ++tilted;
        }
        EXPECT_EQ(red, 0u) << "eye " << eye.x << ", " << eye.y << ", " << eye.z;
        EXPECT_GT(tilted, 30u) << "the craters must be drawn (eye " << eye.x << ", " << eye.y << ", " << eye.z
                               << ")";
    }
}

TEST(VolumetricDecal, OverlappingCratersMakeOneHoleWithoutWallInside) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kCraterW, kCraterH);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r->setScene(wallScene(false)).ok());
    r->setDecalTypes(types());
    Camera cam = frontCamera();
    cam.eye = {0.1, 1.5, 1.6};
    const Image before = renderView(r.value(), cam, View::Depth);
    const std::vector<glm::dvec2> centres = {{-0.12, 1.5}, {0.12, 1.5}};
    r->setDecals({crater(float(centres[0].x), 1.5f, 1), crater(float(centres[1].x), 1.5f, 2)});
    const Image after = renderView(r.value(), cam, View::Depth);
    // Between the two centres, where both footprints overlap, the depth stays behind the wall: no
    // cup wall rises back to the surface inside the union of the holes.
    size_t overlap = 0, flush = 0;
    const CraterShape shape;
    for (int j = 0; j < kCraterH; ++j)
        for (int i = 0; i < kCraterW; ++i) {
            const glm::dvec3 p = wallPoint(cam, i, j);
            const double inner = kRadius * (1.0 - shape.chip) * 0.8;
            if (glm::length(glm::dvec2(p) - centres[0]) < inner &&
                glm::length(glm::dvec2(p) - centres[1]) < inner) {
                ++overlap;
                if (depthAt(after, i, j) >= depthAt(before, i, j)) ++flush;
            }
        }
    ASSERT_GT(overlap, 100u);
    EXPECT_EQ(flush, 0u);
}

TEST(VolumetricDecal, IdClippingKeepsTheHoleOffAnotherObject) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kCraterW, kCraterH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene s = wallScene(false);
    // A dynamic plate just in front of the wall (closer than the footprint tolerance) over the
    // crater's right half.
    SceneObject plate = boxObject("plate", {0.3f, 0.5f, 0.01f}, {0.3, 1.5, 0.02});
    plate.dynamic = true;
    plate.editMesh().submeshes = {{0, uint32_t(plate.mesh->indices.size()), 0}};
    s.objects.push_back(plate);
    ASSERT_TRUE(r->setScene(s).ok());
    ASSERT_TRUE(r->setObjectIds({0, 7}).ok());
    r->setDecalTypes(types());
    Camera cam = frontCamera();
    cam.eye = {0.0, 1.5, 2.0};
    const Image before = renderView(r.value(), cam, View::Depth);
    r->setDecals({crater(0.0f, 1.5f)});
    const Image after = renderView(r.value(), cam, View::Depth);
    size_t onPlate = 0, holeLeft = 0;
    for (int j = 0; j < kCraterH; ++j)
        for (int i = 0; i < kCraterW; ++i) {
            const glm::dvec3 p = wallPoint(cam, i, j);
            if (glm::length(glm::dvec2(p) - glm::dvec2(0.0, 1.5)) > kRadius * 0.6) continue;
            if (p.x > 0.05) {
                ++onPlate;
                EXPECT_EQ(depthAt(after, i, j), depthAt(before, i, j)) << "pixel " << i << ", " << j;
            } else if (p.x < -0.05 && depthAt(after, i, j) < depthAt(before, i, j)) {
                ++holeLeft;
            }
        }
    EXPECT_GT(onPlate, 60u);
    EXPECT_GT(holeLeft, 60u);
}

TEST(VolumetricDecal, InvalidDecalsAreCountedNotDrawn) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kCraterW, kCraterH);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r->setScene(wallScene(false)).ok());
    r->setDecalTypes(types());
    Decal nan = crater(0.0f, 1.5f);
    nan.center.x = std::nanf("");
    Decal missing = crater(0.0f, 1.5f);
    missing.object = 5;
    r->setDecals({nan, missing, crater(0.5f, 1.5f)});
    Result<FrameStats> st = r->render(frontCamera(), View::Final);
    ASSERT_TRUE(st.ok()) << st.error();
    EXPECT_EQ(st->decalsVolumetric, 1u);
    EXPECT_EQ(st->decalsInvalid, 2u);
    EXPECT_GE(st->drawCalls, 2u + 2u); // wall, lighting, and the crater's two draws
}

TEST(VolumetricDecal, CraterAtACornerLeavesTheAdjacentFloorAlone) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kCraterW, kCraterH);
    ASSERT_TRUE(r.ok()) << r.error();
    Scene s = wallScene(false);
    // A floor whose top face y = 0 meets the wall's front face along the line y = 0, z = 0.
    SceneObject floor = boxObject("floor", {2.0f, 0.1f, 1.5f}, {0.0, -0.1, 1.5});
    floor.editMesh().submeshes = {{0, uint32_t(floor.mesh->indices.size()), 0}};
    s.objects.push_back(floor);
    ASSERT_TRUE(r->setScene(s).ok());
    r->setDecalTypes(types());
    Camera cam;
    cam.eye = {0.2, 0.9, 1.4};
    cam.target = {0.0, 0.1, 0.0};
    const Image before = renderView(r.value(), cam, View::Depth);
    // The footprint reaches 0.2 below the corner line, behind the floor.
    r->setDecals({crater(0.0f, 0.1f)});
    const Image after = renderView(r.value(), cam, View::Depth);
    size_t floorNear = 0, wallDeeper = 0;
    for (int j = 0; j < kCraterH; ++j)
        for (int i = 0; i < kCraterW; ++i) {
            const glm::dvec3 dir = pixelDirection(cam, kCraterW, kCraterH, i, j);
            if (dir.y >= 0.0) continue;
            const glm::dvec3 onFloor = cam.eye + dir * (-cam.eye.y / dir.y);
            if (onFloor.z > 1e-3 && std::fabs(onFloor.x) < kRadius && onFloor.z < 0.5) {
                ++floorNear;
                EXPECT_EQ(depthAt(after, i, j), depthAt(before, i, j)) << "floor pixel " << i << ", " << j;
            } else if (onFloor.z < -1e-3 && depthAt(after, i, j) < depthAt(before, i, j)) {
                ++wallDeeper;
            }
        }
    EXPECT_GT(floorNear, 200u);
    EXPECT_GT(wallDeeper, 100u);
}

namespace {

// A pillar |x| <= 0.3, |z| <= 0.3, 0 <= y <= 3, with volumetric decals placed by the decal system
// near the edge between its front (z = 0.3) and right (x = 0.3) faces and at its top corner.
struct PillarShots {
    Scene scene;
    std::vector<Decal> decals;
    std::vector<CraterClips> clips; // parallel to decals
};

PillarShots pillarShots() {
    PillarShots out;
    out.scene = wallScene(false);
    out.scene.objects[0] = boxObject("pillar", {0.3f, 1.5f, 0.3f}, {0.0, 1.5, 0.0});
    out.scene.objects[0].editMesh().submeshes = {{0, uint32_t(out.scene.objects[0].mesh->indices.size()), 0}};
    Result<DecalSystem> sys = DecalSystem::create(out.scene);
    EXPECT_TRUE(sys.ok()) << sys.error();
    DecalType t = types()[0];
    t.size = glm::vec2(0.3f);
    EXPECT_TRUE(sys->registerType(t).ok());
    for (const glm::dvec3 target :
         {glm::dvec3(0.24, 1.5, 0.3), glm::dvec3(0.25, 2.0, 0.3), glm::dvec3(0.24, 2.95, 0.3)}) {
        Ray r;
        r.origin = target + glm::dvec3(0.0, 0.0, 2.0);
        r.direction = {0.0, 0.0, -1.0};
        const SpawnResult res = sys->spawn(r, 0);
        EXPECT_TRUE(res.placed()) << res.reason;
    }
    out.decals = sys->decals();
    for (size_t i = 0; i < out.decals.size(); ++i)
        out.clips.push_back(sys->craterClips(i));
    return out;
}

// The largest distance by which a pixel whose depth the craters changed lies outside the pillar, the
// craters cut by `clips` (parallel to `decals`; none when empty).
double pokeOut(Renderer& r, const Camera& cam, const std::vector<Decal>& decals,
               const std::vector<CraterClips>& clips, size_t& changed) {
    r.setDecals({});
    renderView(r, cam, View::Depth);
    const std::vector<float> before = r.readbackDepth().value();
    r.setDecals(decals, craterClipsOf(clips));
    renderView(r, cam, View::Depth);
    const std::vector<float> after = r.readbackDepth().value();
    const glm::dvec3 forward = -cameraBasis(cam).back;
    double worst = 0.0;
    changed = 0;
    for (int j = 0; j < kCraterH; ++j)
        for (int i = 0; i < kCraterW; ++i) {
            const size_t k = size_t(j) * kCraterW + size_t(i);
            if (after[k] == before[k] || after[k] <= 0.0f) continue;
            ++changed;
            const glm::dvec3 dir = pixelDirection(cam, kCraterW, kCraterH, i, j);
            const glm::dvec3 p = cam.eye + dir * (double(after[k]) / glm::dot(dir, forward));
            worst = std::max({worst, p.x - 0.3, p.z - 0.3, p.y - 3.0});
        }
    return worst;
}

} // namespace

TEST(VolumetricDecal, CraterAtAnEdgeOrCornerDoesNotPokeOutOfTheAdjacentFace) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kCraterW, kCraterH);
    ASSERT_TRUE(r.ok()) << r.error();
    PillarShots shots = pillarShots();
    ASSERT_EQ(shots.decals.size(), 3u);
    for (size_t i = 0; i < shots.decals.size(); ++i)
        ASSERT_TRUE(shots.clips[i].planes[0].active())
            << "no clip plane for the decal at " << shots.decals[i].center.x << ", "
            << shots.decals[i].center.y;
    ASSERT_TRUE(r->setScene(shots.scene).ok());
    r->setDecalTypes(types());
    // From the front left and from above, looking into the holes towards the right face and the top.
    for (const glm::dvec3 eye : {glm::dvec3(-1.2, 2.2, 1.6), glm::dvec3(-0.8, 4.2, 1.2)}) {
        Camera cam;
        cam.eye = eye;
        cam.target = {0.25, 2.2, 0.3};
        cam.fovYDeg = 40.0;
        size_t changed = 0;
        EXPECT_LE(pokeOut(r.value(), cam, shots.decals, shots.clips, changed), 2e-3)
            << "eye " << eye.x << ", " << eye.y;
        EXPECT_GT(changed, 100u);
        // The control: without their clip planes the same craters do poke out.
        EXPECT_GT(pokeOut(r.value(), cam, shots.decals, {}, changed), 0.01)
            << "eye " << eye.x << ", " << eye.y;
    }
}

TEST(VolumetricDecal, CoverageViewShowsTheHolesAndNothingElse) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = test::makeRenderer(kCraterW, kCraterH);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r->setScene(wallScene(false)).ok());
    r->setDecalTypes(types());
    r->setDecals({crater(0.0f, 1.5f, 1), crater(-0.6f, 1.2f, 2)});
    const Camera cam = frontCamera();
    const Image coverage = renderView(r.value(), cam, View::Coverage);
    size_t inside = 0, covered = 0;
    for (int j = 0; j < kCraterH; ++j)
        for (int i = 0; i < kCraterW; ++i) {
            const bool white = coverage.rgba[(size_t(j) * kCraterW + size_t(i)) * 4] > 128;
            const double d = nearestCentre(wallPoint(cam, i, j), {{0.0, 1.5}, {-0.6, 1.2}});
            if (white) {
                ++covered;
                EXPECT_LT(d, 1.02 * kRadius) << "pixel " << i << ", " << j;
            }
            if (d < 0.5 * kRadius) inside += white ? 1 : 0;
        }
    EXPECT_GT(covered, 200u);
    EXPECT_GT(inside, 100u);
}
