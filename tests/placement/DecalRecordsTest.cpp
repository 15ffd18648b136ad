// Decals read from files for a scene (DecalRecords.hpp) and the built-in looks (DecalLooks.hpp).

#include "PlacementTestUtil.hpp"

#include "TestData.hpp"

#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SkinnedArm.hpp"
#include "spatter/placement/DecalLooks.hpp"
#include "spatter/placement/DecalRecords.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

using namespace spatter;
using ::testing::HasSubstr;

namespace {

// The triangle of `indices` over `positions` that the ray from `origin` along `dir` meets first, by
// brute force (Moller-Trumbore in double); ~0 for none.
size_t firstHit(const std::vector<glm::dvec3>& positions, const std::vector<uint32_t>& indices,
                const glm::dvec3& origin, const glm::dvec3& dir) {
    size_t best = ~size_t(0);
    double nearest = std::numeric_limits<double>::infinity();
    for (size_t t = 0; 3 * t + 2 < indices.size(); ++t) {
        const glm::dvec3 a = positions[indices[3 * t]], e1 = positions[indices[3 * t + 1]] - a,
                         e2 = positions[indices[3 * t + 2]] - a;
        const glm::dvec3 p = glm::cross(dir, e2);
        const double det = glm::dot(e1, p);
        if (std::abs(det) < 1e-15) continue;
        const glm::dvec3 s = origin - a;
        const double u = glm::dot(s, p) / det;
        const glm::dvec3 q = glm::cross(s, e1);
        const double v = glm::dot(dir, q) / det, dist = glm::dot(e2, q) / det;
        if (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && dist > 0.0 && dist < nearest) nearest = dist, best = t;
    }
    return best;
}

std::string json3(const glm::dvec3& v) {
    std::ostringstream s;
    s.precision(17);
    s << "[" << v.x << "," << v.y << "," << v.z << "]";
    return s.str();
}

// The record spatter-place writes for `d`.
std::string placedRecord(const DecalSystem& sys, const Decal& d, double maxAngle) {
    const WorldDecal w = sys.worldBox(d);
    std::ostringstream r;
    r.precision(17);
    r << R"({"ray":0,"status":"placed","reason":"","object":")" << sys.world().object(d.object)->name
      << R"(","object_id":)" << int(d.objectId) << R"(,"decal_id":)" << d.id << R"(,"position":)"
      << json3(w.center) << R"(,"normal":)" << json3(glm::dvec3(w.frame.normal)) << R"(,"tangent":)"
      << json3(glm::dvec3(w.frame.tangent)) << R"(,"bitangent":)" << json3(glm::dvec3(w.frame.bitangent))
      << R"(,"size":[)" << w.size.x << "," << w.size.y << R"(],"half_depth":)" << w.halfDepth
      << R"(,"projection":)" << json3(glm::dvec3(w.projection)) << R"(,"max_angle_deg":)" << maxAngle << "}";
    return r.str();
}

std::string writeFile(const std::string& name, const std::string& text) {
    static const std::string dir = test::scratchDir("decal-records");
    const std::string path = dir + "/" + name;
    std::ofstream(path) << text;
    return path;
}

void expectNear(const glm::vec3& a, const glm::vec3& b, float tolerance) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

} // namespace

// A decal on a turned and scaled moving target, written as spatter-place writes it and read back,
// is the same object-space decal; the target's ID comes from the record, and the other targets get
// one that no decal has.
TEST(DecalRecords, PlacedRecordsGiveBackTheObjectSpaceDecals) {
    const Scene scene = test::rangeScene(3);
    Result<DecalSystem> sys = DecalSystem::create(scene);
    ASSERT_TRUE(sys.ok()) << sys.error();
    DecalType type;
    type.name = "t";
    type.size = {0.3f, 0.2f};
    const uint16_t index = sys->registerType(type).value();
    ASSERT_TRUE(sys->spawn(Ray{{2.0, 1.1, 5.0}, {0.0, 0.0, -1.0}}, index).placed());
    ASSERT_TRUE(sys->spawn(Ray{{-2.0, 1.0, 5.0}, {0.0, 0.0, -1.0}}, index).placed());
    const std::vector<Decal>& placed = sys->decals();
    const std::string path =
        writeFile("placed.jsonl", placedRecord(sys.value(), placed[0], 60.0) + "\n\n" +
                                      R"({"ray":1,"status":"missed","reason":"no hit"})" + "\n" +
                                      placedRecord(sys.value(), placed[1], 80.0) + "\n");

    Result<LoadedDecals> loaded = loadPlacedRecords(path, scene, type, kMixedLooks);
    ASSERT_TRUE(loaded.ok()) << loaded.error();
    EXPECT_EQ(loaded->records, 3u);
    EXPECT_EQ(loaded->placed, 2u);
    ASSERT_EQ(loaded->decals.size(), 2u);
    for (size_t k = 0; k < 2; ++k) {
        const Decal &a = loaded->decals[k], &b = placed[k];
        EXPECT_EQ(a.object, b.object);
        EXPECT_EQ(a.id, b.id);
        EXPECT_EQ(a.objectId, b.objectId);
        expectNear(a.center, b.center, 1e-5f);
        expectNear(a.frame().tangent, b.frame().tangent, 1e-5f);
        expectNear(a.frame().normal, b.frame().normal, 1e-5f);
        EXPECT_NEAR(a.size.x, b.size.x, 1e-5f);
        EXPECT_NEAR(a.halfDepth, b.halfDepth, 1e-5f);
        EXPECT_EQ(b.slant != 0u, k == 0) << "the turned target is hit at an angle, the wall head on";
        expectNear(a.projectionAxis(), b.projectionAxis(), 1e-3f);
        // Mixed looks: the k-th decal has the k-th built-in texture and its record's angle.
        const DecalType& t = loaded->types[a.type];
        EXPECT_EQ(t.texture, int(k));
        EXPECT_FLOAT_EQ(t.maxAngleDeg, k == 0 ? 60.0f : 80.0f);
        EXPECT_EQ(t.size, type.size);
    }
    ASSERT_EQ(loaded->objectIds.size(), scene.objects.size());
    const uint8_t hitId = placed[0].objectId;
    EXPECT_NE(hitId, 0);
    EXPECT_EQ(loaded->objectIds[placed[0].object], hitId);
    for (size_t o = 0; o < scene.objects.size(); ++o) {
        if (o == placed[0].object || !scene.objects[o].dynamic) continue;
        EXPECT_EQ(loaded->objectIds[o], hitId == 1 ? 2 : 1) << o;
    }
}

TEST(DecalRecords, ErrorsNameTheFileLineAndField) {
    const Scene scene = test::boxScene();
    const std::string good =
        R"({"status":"placed","object":"box","position":[0,0,0.5],"normal":[0,0,1],"tangent":[1,0,0],)"
        R"("bitangent":[0,1,0],"size":[0.2,0.2],"half_depth":0.1})";
    struct Case {
        std::string line, expected;
    };
    const Case cases[] = {
        {"[1, 2]", "not a JSON object"},
        {"{\"status\":\"placed\"", "not a JSON object"},
        {R"({"status":"placed","position":[0,0,0]})", "\"object\""},
        {R"({"status":"placed","object":"box","position":[0,0]})", "\"position\""},
        {R"({"status":"placed","object":"box","position":[0,0,0],"normal":[0,0,"1"]})", "\"tangent\""},
        {good.substr(0, good.size() - 1) + ",\"size\":[0.2,-1]}", "\"size\""},
        {good.substr(0, good.size() - 1) + ",\"half_depth\":0}", "\"half_depth\""},
        {good.substr(0, good.size() - 1) + ",\"object_id\":256}", "\"object_id\""},
        {good.substr(0, good.size() - 1) + ",\"max_angle_deg\":95}", "\"max_angle_deg\""},
        {good.substr(0, good.size() - 1) + ",\"max_angle_deg\":\"80\"}", "\"max_angle_deg\""},
        {good.substr(0, good.size() - 1) + ",\"decal_id\":-3}", "\"decal_id\""},
        {good.substr(0, good.size() - 1) + ",\"decal_id\":4294967296}", "\"decal_id\""},
        {good.substr(0, good.size() - 1) + ",\"object\":\"crate\"}", "no object named 'crate'"},
        {good.substr(0, good.size() - 1) + ",\"projection\":[0,1]}", "\"projection\""},
        {good.substr(0, good.size() - 1) + ",\"projection\":[0,0.3,-1]}", "side of its \"normal\""},
        {good.substr(0, good.size() - 1) + ",\"tangent\":[0,0,0]}", "\"tangent\", \"bitangent\""},
        {good.substr(0, good.size() - 1) + ",\"bitangent\":[0,0,-2]}", "parallel to the normal"},
        {good.substr(0, good.size() - 1) + ",\"object_id\":3.7}", "\"object_id\""},
        {good.substr(0, good.size() - 1) + ",\"size\":[1e-300,0.2]}", "float does not hold"},
        {good.substr(0, good.size() - 1) + ",\"size\":[1e300,0.2]}", "float does not hold"},
        {good.substr(0, good.size() - 1) + ",\"anchor\":{\"triangle\":0,\"bary\":[50,-49,0]}}", "\"bary\""},
    };
    for (const Case& c : cases) {
        const std::string path = writeFile("bad.jsonl", good + "\n" + c.line + "\n");
        Result<LoadedDecals> loaded = loadPlacedRecords(path, scene, DecalType{}, 0);
        ASSERT_FALSE(loaded.ok()) << c.line;
        EXPECT_THAT(loaded.error(), HasSubstr(path + ":2: ")) << c.line;
        EXPECT_THAT(loaded.error(), HasSubstr(c.expected)) << c.line;
    }
    Result<LoadedDecals> missing = loadPlacedRecords(writeFile("x", "") + ".missing", scene, DecalType{}, 0);
    ASSERT_FALSE(missing.ok());
    EXPECT_THAT(missing.error(), HasSubstr("cannot read"));
    const std::string path = writeFile("good.jsonl", good + "\n");
    for (const int look : {int(DecalTexture::Count), -2}) {
        Result<LoadedDecals> noLook = loadPlacedRecords(path, scene, DecalType{}, look);
        ASSERT_FALSE(noLook.ok());
        EXPECT_THAT(noLook.error(), HasSubstr("look " + std::to_string(look)));
        Result<LoadedDecals> rays =
            placeRays(writeFile("rays.txt", "0 0 3 0 0 -1\n"), scene, DecalType{}, look, 1);
        ASSERT_FALSE(rays.ok());
        EXPECT_THAT(rays.error(), HasSubstr("look " + std::to_string(look)));
    }
}

// Each distinct "max_angle_deg" takes a type, and a decal's type is 16 bits: the 65,536th is refused
// (it would have wrapped around to the first type).
TEST(DecalRecords, RecordsNeedingMoreTypesThanADecalIndexesAreRefused) {
    const Scene scene = test::boxScene();
    std::string lines;
    for (int i = 0; i <= 65535; ++i)
        lines +=
            R"({"status":"placed","object":"box","position":[0,0,0.5],"normal":[0,0,1],"tangent":[1,0,0],)"
            R"("bitangent":[0,1,0],"size":[0.2,0.2],"half_depth":0.1,"max_angle_deg":)" +
            std::to_string(1.0 + i * 1e-3) + "}\n";
    Result<LoadedDecals> loaded = loadPlacedRecords(writeFile("types.jsonl", lines), scene, DecalType{}, 0);
    ASSERT_FALSE(loaded.ok());
    EXPECT_THAT(loaded.error(), HasSubstr(":65536: more than 65535 decal types"));
}

// Rays are placed in order; a line that does not parse counts as a ray and places nothing.
TEST(DecalRecords, RayFilesArePlacedThroughTheDecalSystem) {
    const Scene scene = test::boxScene();
    const std::string path =
        writeFile("rays.txt", "# two shots at the box\n0 0 3 0 0 -1\n\nnot a ray\n0.1 0.1 3 0 0 -1\n");
    DecalType type;
    type.name = "t";
    type.size = {0.2f, 0.2f};
    Result<LoadedDecals> loaded = placeRays(path, scene, type, int(DecalTexture::Scorch), 7);
    ASSERT_TRUE(loaded.ok()) << loaded.error();
    EXPECT_EQ(loaded->records, 3u);
    EXPECT_EQ(loaded->placed, 2u);
    ASSERT_EQ(loaded->decals.size(), 2u);
    ASSERT_EQ(loaded->types.size(), size_t(DecalTexture::Count));
    for (const Decal& d : loaded->decals) {
        EXPECT_EQ(loaded->types[d.type].texture, int(DecalTexture::Scorch));
        EXPECT_FLOAT_EQ(d.size.x, 0.2f);
    }
    EXPECT_EQ(loaded->objectIds, std::vector<uint8_t>{0});
    // The same seed places the same decals.
    Result<LoadedDecals> again = placeRays(path, scene, type, int(DecalTexture::Scorch), 7);
    ASSERT_TRUE(again.ok());
    EXPECT_EQ(again->decals[1].id, loaded->decals[1].id);
    type.size = {-1.0f, 0.2f};
    EXPECT_FALSE(placeRays(path, scene, type, 0, 7).ok());
}

// With a pose, rays meet a skinned object as it is drawn then: a shot at the bent forearm of
// builtin:skinned-arm places its decal on the posed skin, where at rest there is no forearm.
TEST(DecalRecords, RayFilesMeetASkinnedObjectAsItIsDrawnAtThePose) {
    Scene scene = makeSkinnedArm();
    const double t = 1.0; // the elbow bent most
    SceneEvaluator evaluator(scene);
    evaluator.evaluate(0, t);
    scene.objects[0].transform = evaluator.objectTransform(0); // as spatter-render draws it
    const Mesh& rest = *scene.objects[0].mesh;
    std::vector<glm::dvec3> posed = posedPositions(scene, 0, evaluator);
    for (glm::dvec3& p : posed)
        p = glm::dvec3(scene.objects[0].transform * glm::dvec4(p, 1.0));
    // The forearm triangle a shot along its normal meets first, near the hand.
    std::optional<std::pair<glm::dvec3, glm::dvec3>> aim; // the point and the shot's origin
    for (size_t k = 0; k + 2 < rest.indices.size() && !aim; k += 3) {
        const uint32_t* c = &rest.indices[k];
        if (rest.positions[c[0]].y < 0.85f) continue;
        const glm::dvec3 centre = (posed[c[0]] + posed[c[1]] + posed[c[2]]) / 3.0;
        const glm::dvec3 n = glm::normalize(glm::cross(posed[c[1]] - posed[c[0]], posed[c[2]] - posed[c[0]]));
        const glm::dvec3 origin = centre + 0.3 * n;
        if (firstHit(posed, rest.indices, origin, -n) == k / 3) aim.emplace(centre, origin);
    }
    ASSERT_TRUE(aim);
    const glm::dvec3 d = aim->first - aim->second;
    std::ostringstream ray;
    ray.precision(17);
    ray << aim->second.x << " " << aim->second.y << " " << aim->second.z << " " << d.x << " " << d.y << " "
        << d.z << "\n";
    const std::string path = writeFile("forearm.txt", ray.str());
    DecalType type;
    type.name = "t";
    type.size = {0.05f, 0.05f};

    Result<LoadedDecals> drawn = placeRays(path, scene, type, 0, 7, DrawPose{t, glm::dvec3(0.0)});
    ASSERT_TRUE(drawn.ok()) << drawn.error();
    ASSERT_EQ(drawn->placed, 1u);
    const glm::dvec3 centre =
        glm::dvec3(scene.objects[0].transform * glm::dvec4(glm::dvec3(drawn->decals[0].center), 1.0));
    EXPECT_LT(glm::length(centre - aim->first), 1e-4);

    Result<LoadedDecals> atRest = placeRays(path, scene, type, 0, 7);
    ASSERT_TRUE(atRest.ok()) << atRest.error();
    for (const Decal& decal : atRest->decals) {
        const glm::dvec3 c =
            glm::dvec3(scene.objects[0].transform * glm::dvec4(glm::dvec3(decal.center), 1.0));
        EXPECT_GT(glm::length(c - aim->first), 0.05) << "the rest mesh has no forearm there";
    }
}

// Volumetric rays give each crater the clip planes the decal system found for it: a crater at the
// box's edge is cut at its side face, one in the middle of a face is not.
TEST(DecalRecords, VolumetricRayFilesKeepTheCratersClipPlanes) {
    const Scene scene = test::boxScene();
    const std::string path = writeFile("craters.txt", "0.45 0 3 0 0 -1\n0 0 3 0 0 -1\n");
    DecalType type;
    type.name = "hole";
    type.size = {0.2f, 0.2f};
    type.volumetric = true;
    Result<LoadedDecals> loaded = placeRays(path, scene, type, int(DecalTexture::BulletHole), 7);
    ASSERT_TRUE(loaded.ok()) << loaded.error();
    ASSERT_EQ(loaded->decals.size(), 2u);
    ASSERT_EQ(loaded->clips.size(), 2u);
    EXPECT_TRUE(loaded->clips[0].any());
    EXPECT_FALSE(loaded->clips[1].any());
}

TEST(DecalLooks, NamesGiveTheBuiltInTexturesAndMixedTakesThemInTurn) {
    EXPECT_EQ(parseDecalLook("bullet_hole").value(), int(DecalTexture::BulletHole));
    EXPECT_EQ(parseDecalLook("scorch").value(), int(DecalTexture::Scorch));
    EXPECT_EQ(parseDecalLook("mixed").value(), kMixedLooks);
    Result<int> unknown = parseDecalLook("glitter");
    ASSERT_FALSE(unknown.ok());
    EXPECT_THAT(unknown.error(), HasSubstr("'glitter'"));
    EXPECT_EQ(lookOf(kMixedLooks, 5), 1);
    EXPECT_EQ(lookOf(int(DecalTexture::Paint), 5), int(DecalTexture::Paint));
    DecalType base;
    base.size = {2.0f, 1.0f};
    const DecalType blood = withLook(base, int(DecalTexture::Blood));
    EXPECT_EQ(blood.texture, int(DecalTexture::Blood));
    EXPECT_FLOAT_EQ(blood.roughness, 0.25f);
    EXPECT_EQ(blood.size, base.size);
}
