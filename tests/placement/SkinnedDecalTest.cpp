#include "PlacementTestUtil.hpp"
#include "TestData.hpp"

#include "spatter/core/DeformingProxy.hpp"
#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SkinnedArm.hpp"
#include "spatter/core/SkinnedDummy.hpp"
#include "spatter/placement/DecalPersistence.hpp"
#include "spatter/placement/DecalRecords.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

using namespace spatter;
using namespace spatter::test;

namespace {

constexpr float kDecalSize = 0.05f;

// The arm's render mesh at time t, in its object space.
Mesh drawnMesh(const Scene& arm, double t) {
    SceneEvaluator evaluator(arm);
    evaluator.evaluate(0, t);
    return withPositions(*arm.objects[0].mesh, posedPositions(arm, 0, evaluator));
}

Status poseAt(DecalSystem& system, const Scene& arm, double t) {
    SceneEvaluator evaluator(arm);
    evaluator.evaluate(0, t);
    Result<TransformUpdate> r = system.setPose(0, evaluator.objectTransform(0), evaluator.jointMatrices(0),
                                               evaluator.morphWeights(0));
    if (!r) return fail(r.error());
    return {};
}

// A point of the render surface, by triangle and barycentric coordinates.
struct SurfacePoint {
    uint32_t triangle = 0;
    glm::dvec3 bary{0.0};

    // The normal of its triangle in `m`.
    glm::dvec3 normal(const Mesh& m) const {
        const uint32_t* c = &m.indices[3 * size_t(triangle)];
        const glm::dvec3 a(m.positions[c[0]]), b(m.positions[c[1]]), d(m.positions[c[2]]);
        return glm::normalize(glm::cross(b - a, d - a));
    }

    glm::dvec3 on(const Mesh& m) const {
        const uint32_t* c = &m.indices[3 * size_t(triangle)];
        return bary.x * glm::dvec3(m.positions[c[0]]) + bary.y * glm::dvec3(m.positions[c[1]]) +
               bary.z * glm::dvec3(m.positions[c[2]]);
    }
};

SurfacePoint nearestOn(const Mesh& m, const glm::dvec3& p) {
    const ClosestPoint c = ClosestPointQuery::create(m).value().closest(p).value();
    const uint32_t* k = &m.indices[3 * size_t(c.triangle)];
    return {c.triangle, barycentric(c.point, glm::dvec3(m.positions[k[0]]), glm::dvec3(m.positions[k[1]]),
                                    glm::dvec3(m.positions[k[2]]))};
}

// Shots from the front at the forearm and the elbow as they stand at time t (the arm's transform is
// the identity, so object space is world space).
std::vector<Ray> shotsAtForearm(const Mesh& drawn) {
    std::vector<Ray> rays;
    for (size_t i = 0; i < drawn.triangleCount(); i += 7) {
        glm::dvec3 c(0.0);
        for (int k = 0; k < 3; ++k)
            c += glm::dvec3(drawn.positions[drawn.indices[3 * i + size_t(k)]]) / 3.0;
        const glm::dvec3 from = c + glm::dvec3(0.1, 0.2, 2.0);
        rays.push_back(ray(from, c - from));
    }
    return rays;
}

// Room for every shot of the tests in one cell.
DecalSettings roomy() {
    DecalSettings s;
    s.maxPerCell = 1024;
    return s;
}

DecalType bulletHole() {
    DecalType t;
    t.name = "hole";
    t.size = glm::vec2(kDecalSize);
    t.maxAngleDeg = 80.0f;
    return t;
}

struct Drift {
    double along = 0.0; // the largest, over the decals, along the surface: what an image shows
    double whole = 0.0; // the largest distance
};

// Spawns the decals of the arm drawn at t0: what `spawnAll` places.
using Spawner = std::function<std::vector<SpawnResult>(DecalSystem&, const Mesh& drawn, uint16_t type)>;

std::vector<SpawnResult> shootAtForearm(DecalSystem& system, const Mesh& drawn, uint16_t type) {
    std::vector<SpawnResult> out;
    for (const Ray& r : shotsAtForearm(drawn))
        out.push_back(system.spawn(r, type));
    return out;
}

// Spawns at time t0, poses at t1 and measures, over the decals, how far a decal's centre is from the
// render surface point it was placed on (the nearest to its centre at t0), both at t1.
Drift largestDrift(DecalSystem& system, const Scene& arm, double t0, double t1, size_t& decals,
                   const Spawner& spawnAll = shootAtForearm) {
    const uint16_t type = addType(system, bulletHole());
    EXPECT_TRUE(poseAt(system, arm, t0).ok());
    const Mesh at0 = drawnMesh(arm, t0), at1 = drawnMesh(arm, t1);
    std::vector<std::pair<DecalHandle, SurfacePoint>> placed;
    for (const SpawnResult& s : spawnAll(system, at0, type))
        if (s.placed())
            placed.emplace_back(s.handle, nearestOn(at0, glm::dvec3(system.get(s.handle)->center)));
    EXPECT_TRUE(poseAt(system, arm, t1).ok());
    Drift drift;
    for (const auto& [handle, point] : placed) {
        const Decal* d = system.get(handle);
        EXPECT_NE(d, nullptr);
        if (!d) continue;
        const glm::dvec3 off = glm::dvec3(d->center) - point.on(at1), n = point.normal(at1);
        drift.whole = std::max(drift.whole, glm::length(off));
        drift.along = std::max(drift.along, glm::length(off - n * glm::dot(n, off)));
    }
    decals = placed.size();
    return drift;
}

} // namespace

TEST(SkinnedDecals, StayOnTheSkinPointTheyWerePlacedOn) {
    const Scene arm = makeSkinnedArm();
    DecalSystem system = makeSystem(arm, roomy());
    size_t decals = 0;
    const Drift drift = largestDrift(system, arm, 0.3, 1.0, decals);
    EXPECT_GT(decals, 20u);
    EXPECT_LT(drift.whole, 1e-5) << "the render mesh is its own collision mesh";
}

TEST(SkinnedDecals, StayOnTheSkinOverADeformingProxy) {
    const Scene arm = makeSkinnedArm();
    Result<DeformingProxy> proxy = deformingProxy(arm, 0.005f, 16);
    ASSERT_TRUE(proxy.ok()) << proxy.error();
    Result<CollisionWorld> world = CollisionWorld::build(arm, {shareProxy(proxy->proxy)});
    ASSERT_TRUE(world.ok()) << world.error();
    Result<DecalSystem> system = DecalSystem::create(std::move(world).value(), roomy());
    ASSERT_TRUE(system.ok()) << system.error();
    size_t decals = 0;
    const Drift drift = largestDrift(system.value(), arm, 0.3, 1.0, decals);
    EXPECT_GT(decals, 20u);
    // The decal moved from the proxy's hit onto the render surface under it, and rides it.
    EXPECT_LT(drift.whole, 1e-5);
    EXPECT_LT(drift.along, 0.02 * kDecalSize);
    // With no proxy error left to hold, its box is as deep as on a render mesh, not h deeper.
    const float margin = system->settings().depthMargin;
    for (const Decal& d : system->decals())
        EXPECT_NEAR(d.halfDepth, margin * kDecalSize, 1e-6) << "h " << proxy->proxy.errorBound;
}

TEST(SkinnedDecals, DecalsOfSpawnAtAndSpawnAttachedStayOnTheSkinToo) {
    // At the centroids of the forearm's triangles as drawn at t0, facing their normals (the arm's
    // transform is the identity: object space is world space), through a deforming proxy.
    const Scene arm = makeSkinnedArm();
    Result<DeformingProxy> proxy = deformingProxy(arm, 0.005f, 16);
    ASSERT_TRUE(proxy.ok()) << proxy.error();
    const auto centroids = [](const Mesh& drawn) {
        std::vector<std::pair<glm::dvec3, glm::dvec3>> points; // position, normal
        for (size_t i = 0; i < drawn.triangleCount(); i += 7) {
            const SurfacePoint c{uint32_t(i), glm::dvec3(1.0 / 3.0)};
            points.emplace_back(c.on(drawn), c.normal(drawn));
        }
        return points;
    };
    const Spawner at = [&](DecalSystem& system, const Mesh& drawn, uint16_t type) {
        std::vector<SpawnResult> out;
        for (const auto& [p, n] : centroids(drawn))
            out.push_back(system.spawnAt(p, n, type));
        return out;
    };
    const Spawner attached = [&](DecalSystem& system, const Mesh& drawn, uint16_t type) {
        std::vector<SpawnResult> out;
        for (const auto& [p, n] : centroids(drawn)) {
            out.push_back(system.spawnAttached(0, glm::vec3(p), glm::vec3(n), type));
            if (out.back().placed()) { // a point on the drawn surface stays where it was given
                EXPECT_LT(glm::length(glm::dvec3(system.get(out.back().handle)->center) - p), 1e-5);
            }
        }
        return out;
    };
    for (const Spawner& spawnAll : {at, attached}) {
        Result<CollisionWorld> world = CollisionWorld::build(arm, {shareProxy(proxy->proxy)});
        ASSERT_TRUE(world.ok()) << world.error();
        Result<DecalSystem> system = DecalSystem::create(std::move(world).value(), roomy());
        ASSERT_TRUE(system.ok()) << system.error();
        size_t decals = 0;
        const Drift drift = largestDrift(system.value(), arm, 0.3, 1.0, decals, spawnAll);
        EXPECT_GT(decals, 100u);
        EXPECT_LT(drift.whole, 1e-5);
    }
}

TEST(SkinnedDecals, SpawnAttachedInsideABentElbowStaysOnTheGivenPoint) {
    // At the elbow bent 90 degrees, points of the upper arm whose normal meets the forearm within the
    // decal's size: a probe as long as spawnAt's lands on the forearm, 3 to 40 cm away. The render
    // mesh is its own collision mesh (no error bound), so the probe reaches a hundredth of the size
    // either side of the point: most decals stay on it, and those where the skin of the inner elbow
    // folds over itself land on the fold within that reach.
    const Scene arm = makeSkinnedArm();
    DecalSystem system = makeSystem(arm, roomy());
    DecalType wide = bulletHole();
    wide.size = glm::vec2(0.4f);
    const uint16_t type = addType(system, wide);
    ASSERT_TRUE(poseAt(system, arm, 1.0).ok());
    const Mesh drawn = drawnMesh(arm, 1.0);
    size_t facingTheForearm = 0, onThePoint = 0;
    for (uint32_t i = 0; i < drawn.triangleCount(); ++i) {
        const SurfacePoint c{i, glm::dvec3(1.0 / 3.0)};
        const glm::dvec3 p = c.on(drawn), n = c.normal(drawn);
        Ray ahead = ray(p + n * 1e-4, n);
        ahead.tfar = 0.4;
        const std::optional<Hit> forearm = system.world().intersect(ahead);
        if (!forearm || forearm->object != 0) continue;
        ++facingTheForearm;
        const SpawnResult placed = system.spawnAttached(0, glm::vec3(p), glm::vec3(n), type);
        ASSERT_TRUE(placed.placed()) << placed.reason;
        const double off = glm::length(glm::dvec3(system.get(placed.handle)->center) - p);
        EXPECT_LE(off, 0.01 * 0.4 + 1e-6) << "triangle " << i;
        onThePoint += off < 1e-5;
    }
    EXPECT_GT(facingTheForearm, 20u);
    EXPECT_GE(4 * onThePoint, 3 * facingTheForearm);
}

TEST(SkinnedDecals, PosingLogsEveryMovedDecalAsChanged) {
    const Scene arm = makeSkinnedArm();
    DecalSystem system = makeSystem(arm, roomy());
    const uint16_t type = addType(system, bulletHole());
    for (const Ray& r : shotsAtForearm(*arm.objects[0].mesh))
        system.spawn(r, type);
    ASSERT_GT(system.decals().size(), 10u);
    const std::vector<Decal> before = system.decals();
    const uint64_t version = system.version();
    ASSERT_TRUE(poseAt(system, arm, 0.8).ok());
    const DecalChanges changes = system.changesSince(version);
    ASSERT_TRUE(changes.complete);
    EXPECT_EQ(changes.changes.size(), before.size());
    for (const DecalChange& c : changes.changes) {
        EXPECT_EQ(c.kind, DecalChangeKind::Changed);
        EXPECT_EQ(c.index, c.from);
    }
    size_t moved = 0;
    for (size_t i = 0; i < before.size(); ++i)
        moved += before[i].center != system.decals()[i].center;
    EXPECT_GT(moved, before.size() / 2);
}

TEST(SkinnedDecals, RemovedDecalsNoLongerMoveAndBadPosesChangeNothing) {
    const Scene arm = makeSkinnedArm();
    DecalSystem system = makeSystem(arm, roomy());
    const uint16_t type = addType(system, bulletHole());
    std::vector<DecalHandle> handles;
    for (const Ray& r : shotsAtForearm(*arm.objects[0].mesh))
        if (const SpawnResult s = system.spawn(r, type); s.placed()) handles.push_back(s.handle);
    ASSERT_GT(handles.size(), 10u);
    for (size_t i = 0; i < handles.size(); i += 2)
        ASSERT_TRUE(system.remove(handles[i]));
    ASSERT_TRUE(poseAt(system, arm, 1.0).ok());
    const uint64_t version = system.version();
    EXPECT_EQ(system.changesSince(version - system.decals().size()).changes.size(), system.decals().size());

    const std::vector<Decal> before = system.decals();
    EXPECT_FALSE(system.setPose(0, glm::dmat4(1.0), {glm::dmat4(1.0)}, {}).ok());
    EXPECT_EQ(system.version(), version);
    for (size_t i = 0; i < before.size(); ++i)
        EXPECT_TRUE(sameDecal(before[i], system.decals()[i]));
}

TEST(SkinnedDecals, ADecalOnAnArmNeverReachesTheBodyBehindItAtAnyProjectionDepth) {
    Scene scene;
    scene.source = "test:dummy";
    const uint32_t dummy = addSkinnedDummy(scene, glm::dmat4(1.0));
    DecalSystem system = makeSystem(scene, roomy());
    for (const float size : {0.05f, 0.2f}) {
        DecalType deep = bulletHole();
        deep.name = "deep_" + std::to_string(size);
        deep.size = glm::vec2(size);
        deep.halfDepth = 1.8f; // the dummy's height: a box this deep would paint the torso
        const uint16_t type = addType(system, deep);
        for (const double t : {0.0, 0.75, 2.25}) {
            SceneEvaluator evaluator(scene);
            evaluator.evaluate(0, t);
            ASSERT_TRUE(
                system.setPose(dummy, evaluator.objectTransform(dummy), evaluator.jointMatrices(0), {}).ok());
            // From the dummy's left (+X) at its left arm, halfway down, the torso right behind it.
            const SceneObject& o = scene.objects[dummy];
            const std::vector<glm::dvec3> posed = posedPositions(scene, dummy, evaluator);
            glm::dvec3 elbow(0.0); // the outermost point of the left arm about the elbow's height
            for (size_t v = 0; v < posed.size(); ++v)
                if (o.skinWeights.joints[2 * v] != 0 && std::abs(posed[v].y - 1.12) < 0.05 &&
                    posed[v].x > elbow.x)
                    elbow = posed[v];
            const SpawnResult shot =
                system.spawn(ray(elbow + glm::dvec3(3.0, 0.0, 0.0), {-1.0, 0.0, 0.0}), type);
            ASSERT_TRUE(shot.placed()) << shot.reason;
            const glm::mat4 toBox = glm::inverse(system.get(shot.handle)->boxToObject());
            size_t bodyPoints = 0;
            for (size_t v = 0; v < posed.size(); ++v) {
                if (o.skinWeights.joints[2 * v] != 0 || o.skinWeights.weights[2 * v] < 1.0) continue; // arms
                const glm::vec3 u(toBox * glm::vec4(glm::vec3(posed[v]), 1.0f));
                bodyPoints += std::abs(u.x) <= 1.0f && std::abs(u.y) <= 1.0f && std::abs(u.z) <= 1.0f;
            }
            EXPECT_EQ(bodyPoints, 0u) << "size " << size << ", t " << t;
        }
    }
}

TEST(SkinnedDecals, RecordsPlacedAtOneTimeAreLoadedOnTheSurfaceAtAnother) {
    const Scene arm = makeSkinnedArm();
    DecalSystem system = makeSystem(arm, roomy());
    const uint16_t type = addType(system, bulletHole());
    const double placedAt = 0.3, drawnAt = 1.0;
    ASSERT_TRUE(poseAt(system, arm, placedAt).ok());
    const Mesh at0 = drawnMesh(arm, placedAt), at1 = drawnMesh(arm, drawnAt);
    // Records as spatter-place --time writes them: the world box, the time and the anchor.
    const std::string path = test::scratchDir("skinned-records") + "/placed.jsonl";
    std::ofstream file(path);
    std::vector<SurfacePoint> placedOn;
    for (const Ray& r : shotsAtForearm(at0)) {
        const SpawnResult s = system.spawn(r, type);
        if (!s.placed()) continue;
        const Decal& d = *system.get(s.handle);
        const WorldDecal w = system.worldBox(d);
        const SurfacePoint p = nearestOn(at0, glm::dvec3(d.center));
        placedOn.push_back(p);
        const auto v = [](const glm::vec3& a) { return nlohmann::json{a.x, a.y, a.z}; };
        file << nlohmann::json{{"status", "placed"},
                               {"object", "arm"},
                               {"position", {w.center.x, w.center.y, w.center.z}},
                               {"normal", v(w.frame.normal)},
                               {"tangent", v(w.frame.tangent)},
                               {"bitangent", v(w.frame.bitangent)},
                               {"size", {w.size.x, w.size.y}},
                               {"half_depth", w.halfDepth},
                               {"time", placedAt},
                               {"anchor",
                                {{"triangle", p.triangle}, {"bary", {p.bary.x, p.bary.y, p.bary.z}}}}}
                    .dump()
             << "\n";
    }
    file.close();
    ASSERT_GT(placedOn.size(), 20u);
    const auto largestDrift = [&](const LoadedDecals& loaded) {
        double drift = 0.0;
        for (size_t i = 0; i < loaded.decals.size(); ++i)
            drift = std::max(drift, glm::length(glm::dvec3(loaded.decals[i].center) - placedOn[i].on(at1)));
        return drift;
    };
    Result<LoadedDecals> moved =
        loadPlacedRecords(path, arm, bulletHole(), 0, DrawPose{drawnAt, glm::dvec3(0.0)});
    ASSERT_TRUE(moved.ok()) << moved.error();
    ASSERT_EQ(moved->decals.size(), placedOn.size());
    EXPECT_LT(largestDrift(moved.value()), 1e-5);
    Result<LoadedDecals> asPlaced = loadPlacedRecords(path, arm, bulletHole(), 0);
    ASSERT_TRUE(asPlaced.ok()) << asPlaced.error();
    EXPECT_GT(largestDrift(asPlaced.value()), 0.1)
        << "without the pose the records stay where they were placed";

    std::ofstream bad(path);
    bad << R"({"status":"placed","object":"arm","position":[0,0.5,0.1],"normal":[0,0,1],"tangent":[1,0,0],)"
        << R"("bitangent":[0,1,0],"size":[0.05,0.05],"half_depth":0.01,"time":0.3,)"
        << R"("anchor":{"triangle":999999,"bary":[1,0,0]}})"
        << "\n";
    bad.close();
    Result<LoadedDecals> refused =
        loadPlacedRecords(path, arm, bulletHole(), 0, DrawPose{drawnAt, glm::dvec3(0.0)});
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().find("triangle 999999"), std::string::npos) << refused.error();
}

TEST(SkinnedDecals, SavedAndLoadedDecalsKeepFollowingTheSkin) {
    const Scene arm = makeSkinnedArm();
    DecalSystem source = makeSystem(arm, roomy());
    const uint16_t type = addType(source, bulletHole());
    ASSERT_TRUE(poseAt(source, arm, 0.3).ok());
    for (const Ray& r : shotsAtForearm(drawnMesh(arm, 0.3)))
        source.spawn(r, type);
    ASSERT_GT(source.decals().size(), 20u);
    const std::vector<uint8_t> bytes = saveDecals(source);

    DecalSystem loaded = makeSystem(arm, roomy());
    addType(loaded, bulletHole());
    Result<DecalLoadReport> report = loadDecals(loaded, bytes.data(), bytes.size());
    ASSERT_TRUE(report.ok()) << report.error();
    for (double t : {0.3, 1.0, 1.7}) { // both posed alike: the same decals, bit for bit
        ASSERT_TRUE(poseAt(source, arm, t).ok());
        ASSERT_TRUE(poseAt(loaded, arm, t).ok());
        EXPECT_TRUE(sameDecals(source.decals(), loaded.decals())) << "t " << t;
    }
    EXPECT_EQ(saveDecals(loaded), saveDecals(source));
}

TEST(SkinnedDecals, EvictedDecalsStopFollowingAndTheRestKeepTheirPoint) {
    const Scene arm = makeSkinnedArm();
    DecalSettings few = roomy();
    few.maxPerObject = 8; // every shot past the eighth evicts the oldest
    DecalSystem system = makeSystem(arm, few);
    const uint16_t type = addType(system, bulletHole());
    ASSERT_TRUE(poseAt(system, arm, 0.3).ok());
    const Mesh at0 = drawnMesh(arm, 0.3);
    std::vector<std::pair<DecalHandle, SurfacePoint>> shot;
    for (const Ray& r : shotsAtForearm(at0))
        if (const SpawnResult s = system.spawn(r, type); s.placed())
            shot.emplace_back(s.handle, nearestOn(at0, glm::dvec3(system.get(s.handle)->center)));
    ASSERT_GT(system.stats().evicted, 10u);
    ASSERT_EQ(system.decals().size(), 8u);
    const uint64_t version = system.version();
    ASSERT_TRUE(poseAt(system, arm, 1.0).ok());
    EXPECT_EQ(system.changesSince(version).changes.size(), 8u) << "only the live decals move";
    const Mesh at1 = drawnMesh(arm, 1.0);
    size_t live = 0;
    for (const auto& [handle, point] : shot) {
        const Decal* d = system.get(handle);
        if (!d) continue;
        ++live;
        EXPECT_LT(glm::length(glm::dvec3(d->center) - point.on(at1)), 1e-5);
    }
    EXPECT_EQ(live, 8u);
}
