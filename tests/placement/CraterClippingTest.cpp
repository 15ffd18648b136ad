// Clip planes of volumetric decals: found in the collision proxy where the solid around the hit ends
// (a side face at an edge, two at a corner, the back of a thin wall), none where the solid goes on.
#include "PlacementTestUtil.hpp"

#include "spatter/core/CraterMesh.hpp"

#include <gtest/gtest.h>

using namespace spatter;
using namespace spatter::test;

namespace {

constexpr float kSize = 0.2f; // crater radius 0.1, depth up to about 0.06

// A box with half extents `half` centred at `centre`, faces cut into 4 x 4.
SceneObject box(std::string name, glm::dvec3 centre, glm::vec3 half, bool dynamic = false) {
    return makeSceneObject(std::move(name), makeBox(half, 4), glm::translate(glm::dmat4(1.0), centre),
                           dynamic);
}

struct Fixture {
    DecalSystem system;
    uint16_t volumetric = 0, flat = 0;
};

Fixture makeFixture(Scene scene) {
    scene.source = "test:crater-clipping";
    Result<DecalSystem> s = DecalSystem::create(scene);
    EXPECT_TRUE(s.ok()) << s.error();
    Fixture f{std::move(s).value()};
    DecalType t;
    t.name = "hole";
    t.size = glm::vec2(kSize);
    t.randomRotation = true;
    t.volumetric = true;
    f.volumetric = f.system.registerType(t).value();
    t.name = "flat";
    t.volumetric = false;
    f.flat = f.system.registerType(t).value();
    return f;
}

// A placed volumetric decal and the clip planes the system keeps for it.
struct Crater {
    Decal decal;
    CraterClips clips;
};

Crater crater(const Fixture& f, DecalHandle handle) {
    const Decal* d = f.system.get(handle);
    return {*d, f.system.craterClips(size_t(d - f.system.decals().data()))};
}

Crater shoot(Fixture& f, glm::dvec3 target, glm::dvec3 dir, uint16_t type) {
    Ray r;
    r.origin = target - 2.0 * dir;
    r.direction = dir;
    const SpawnResult res = f.system.spawn(r, type);
    EXPECT_TRUE(res.placed()) << res.reason;
    return crater(f, res.handle);
}

int activeClips(const Crater& c) {
    return int(c.clips.planes[0].active()) + int(c.clips.planes[1].active());
}

// World positions of the vertices of every crater variant placed by `c`, with or without its clips.
std::vector<glm::dvec3> craterPoints(const Crater& c, const glm::dmat4& objectToWorld, bool clipped) {
    const glm::dmat4 m = objectToWorld * craterToObject(c.decal);
    std::vector<glm::dvec3> out;
    for (uint32_t v = 0; v < 4; ++v) {
        const Result<Mesh> mesh = makeCraterMesh(v);
        for (const glm::vec3& q : mesh.value().positions) {
            bool kept = true;
            for (const CraterClip& plane : c.clips.planes) {
                const glm::vec4 p = unpackCraterClip(plane);
                kept = kept && glm::dot(glm::vec3(p), q) <= p.w;
            }
            if (kept || !clipped) out.push_back(glm::dvec3(m * glm::dvec4(glm::dvec3(q), 1.0)));
        }
    }
    return out;
}

// Largest distance by which `points` stand outside the box |p - centre| <= half.
double outside(const std::vector<glm::dvec3>& points, glm::dvec3 centre, glm::dvec3 half) {
    double worst = 0.0;
    for (const glm::dvec3& p : points) {
        const glm::dvec3 d = glm::abs(p - centre) - half;
        worst = std::max({worst, d.x, d.y, d.z});
    }
    return worst;
}

} // namespace

TEST(CraterClipping, WideThickWallGivesNoClipPlanes) {
    Scene s;
    s.objects.push_back(box("wall", {0, 0, 0}, {2.0f, 2.0f, 0.5f}));
    Fixture f = makeFixture(s);
    const Crater d = shoot(f, {0.3, 0.2, 0.5}, {0.0, 0.0, -1.0}, f.volumetric);
    EXPECT_EQ(activeClips(d), 0);
}

TEST(CraterClipping, CraterNearConvexEdgeIsCutAtTheSideFace) {
    const glm::dvec3 half(0.5, 2.0, 0.5);
    Scene s;
    s.objects.push_back(box("pillar", {0, 0, 0}, glm::vec3(half)));
    Fixture f = makeFixture(s);
    const Crater d = shoot(f, {0.45, 0.0, 0.5}, {0.0, 0.0, -1.0}, f.volumetric);
    ASSERT_EQ(activeClips(d), 1);
    // Unclipped, the cup pokes out of the side face x = 0.5; clipped, nothing does.
    EXPECT_GT(outside(craterPoints(d, glm::dmat4(1.0), false), {0, 0, 0}, half), 0.02);
    EXPECT_LE(outside(craterPoints(d, glm::dmat4(1.0), true), {0, 0, 0}, half), 1e-6);
    // The plane is the side face: its normal along +x in the world, at x = 0.5 within quantisation.
    const glm::vec4 p = unpackCraterClip(d.clips.planes[0]);
    const glm::dmat3 toWorld(craterToObject(d.decal));
    const glm::dvec3 n = glm::normalize(glm::transpose(glm::inverse(toWorld)) * glm::dvec3(p));
    EXPECT_GT(n.x, 0.999);
}

TEST(CraterClipping, CraterAtBoxCornerIsCutByBothSideFaces) {
    const glm::dvec3 half(0.5, 0.5, 0.5);
    Scene s;
    s.objects.push_back(box("crate", {0, 0, 0}, glm::vec3(half)));
    Fixture f = makeFixture(s);
    const Crater d = shoot(f, {0.46, 0.45, 0.5}, {0.0, 0.0, -1.0}, f.volumetric);
    EXPECT_EQ(activeClips(d), 2);
    EXPECT_GT(outside(craterPoints(d, glm::dmat4(1.0), false), {0, 0, 0}, half), 0.02);
    EXPECT_LE(outside(craterPoints(d, glm::dmat4(1.0), true), {0, 0, 0}, half), 1e-6);
}

TEST(CraterClipping, CraterDeeperThanAThinWallIsCutAtItsBack) {
    const glm::dvec3 half(2.0, 2.0, 0.01);
    Scene s;
    s.objects.push_back(box("panel", {0, 0, 0}, glm::vec3(half)));
    Fixture f = makeFixture(s);
    const Crater d = shoot(f, {0.0, 0.3, 0.01}, {0.0, 0.0, -1.0}, f.volumetric);
    ASSERT_EQ(activeClips(d), 1);
    EXPECT_GT(outside(craterPoints(d, glm::dmat4(1.0), false), {0, 0, 0}, half), 0.02);
    EXPECT_LE(outside(craterPoints(d, glm::dmat4(1.0), true), {0, 0, 0}, half), 1e-6);
}

TEST(CraterClipping, WallStandingOnAFloorIsNotCutWhereTheFloorGoesOn) {
    // The wall's bottom face lies on the floor's top: leaving the wall there, the ray enters the
    // floor at once, so the solid goes on and the crater near the seam keeps its whole cup.
    for (const double overlap : {0.0, 0.002}) {
        Scene s;
        s.objects.push_back(box("floor", {0.0, -0.5, 0.0}, {3.0f, 0.5f, 3.0f}));
        s.objects.push_back(box("wall", {0.0, 1.0 - overlap, 0.0}, {2.0f, 1.0f, 0.5f}));
        Fixture f = makeFixture(s);
        const Crater d = shoot(f, {0.2, 0.04, 0.5}, {0.0, 0.0, -1.0}, f.volumetric);
        EXPECT_EQ(activeClips(d), 0) << "overlap " << overlap;
    }
}

TEST(CraterClipping, FlatDecalsGetNoClipPlanes) {
    Scene s;
    s.objects.push_back(box("pillar", {0, 0, 0}, {0.5f, 2.0f, 0.5f}));
    Fixture f = makeFixture(s);
    const Crater d = shoot(f, {0.45, 0.0, 0.5}, {0.0, 0.0, -1.0}, f.flat);
    EXPECT_EQ(activeClips(d), 0);
}

TEST(CraterClipping, SpawnAtAndSpawnAttachedClipLikeSpawn) {
    const glm::dvec3 half(0.5, 2.0, 0.5);
    Scene s;
    s.objects.push_back(box("pillar", {0, 0, 0}, glm::vec3(half)));
    Fixture f = makeFixture(s);
    const SpawnResult at = f.system.spawnAt({0.45, 0.5, 0.5}, {0.0, 0.0, 1.0}, f.volumetric);
    const SpawnResult attached =
        f.system.spawnAttached(0, {0.45f, -0.5f, 0.5f}, {0.0f, 0.0f, 1.0f}, f.volumetric);
    for (const SpawnResult& r : {at, attached}) {
        ASSERT_TRUE(r.placed()) << r.reason;
        const Crater d = crater(f, r.handle);
        EXPECT_EQ(activeClips(d), 1);
        EXPECT_LE(outside(craterPoints(d, glm::dmat4(1.0), true), {0, 0, 0}, half), 1e-6);
    }
}

TEST(CraterClipping, ClipPlanesFollowAMovingObject) {
    const glm::dvec3 half(0.5, 0.5, 0.5), centre(0.0, 1.0, 0.0);
    Scene s;
    s.objects.push_back(box("target", centre, glm::vec3(half), true));
    Fixture f = makeFixture(s);
    const Crater d = shoot(f, {0.45, 1.0, 0.5}, {0.0, 0.0, -1.0}, f.volumetric);
    ASSERT_EQ(activeClips(d), 1);
    glm::dmat4 moved = glm::translate(glm::dmat4(1.0), glm::dvec3(3.0, 2.0, -1.0));
    moved = glm::rotate(moved, 1.1, glm::dvec3(0.3, 1.0, 0.2));
    ASSERT_TRUE(f.system.setTransform(0, moved).ok());
    // In the object's space the cup stays inside the box wherever the object goes.
    std::vector<glm::dvec3> local;
    const glm::dmat4 toLocal = glm::inverse(moved);
    for (const glm::dvec3& p : craterPoints(d, moved, true))
        local.push_back(glm::dvec3(toLocal * glm::dvec4(p, 1.0)));
    EXPECT_LE(outside(local, {0, 0, 0}, half), 1e-5);
}
