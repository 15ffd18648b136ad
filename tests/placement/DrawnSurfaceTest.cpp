// Decals laid again on the surface that is drawn: the line along a decal's projection axis through its
// box (axisLine), and the decal laid where that line meets the drawn surface (layOnDrawnSurface), as a
// renderer does once it has found the point in its depth.

#include "PlacementTestUtil.hpp"

#include "spatter/core/SkinnedArm.hpp"
#include "spatter/placement/DecalPersistence.hpp"

#include <cmath>

using namespace spatter;
using namespace spatter::test;

namespace {

// What the collision world traces for the drawn floor y = 0 of an object turned and scaled unevenly:
// a proxy tilted 6 degrees against it (bound 0.5), a collider tilted the same way with no drawn
// normals to face (the tilted plane is the world's own mesh), or the floor itself.
enum class FloorTrace { TiltedProxy, TiltedCollider, Floor };

const char* traceName(FloorTrace trace) {
    return trace == FloorTrace::TiltedProxy      ? "tilted proxy"
           : trace == FloorTrace::TiltedCollider ? "tilted collider"
                                                 : "floor";
}

DecalSystem floorSystemTracedBy(FloorTrace trace) {
    Scene scene;
    scene.source = "test:drawn floor";
    scene.objects.push_back(makeSceneObject(
        "floor", tiltedPlane(trace == FloorTrace::TiltedCollider ? 6.0 : 0.0), turnedTransform()));
    std::vector<std::shared_ptr<const Proxy>> proxies;
    if (trace == FloorTrace::TiltedProxy) proxies.push_back(shareProxy(makeProxy(tiltedPlane(6.0), 0.5)));
    Result<DecalSystem> s = DecalSystem::create(buildWorld(scene, proxies));
    EXPECT_TRUE(s.ok()) << s.error();
    return std::move(s).value();
}

// The shot at the floor's object-space point `target` from `degrees` off its normal, turned about it by
// `azimuth`, in the world of turnedTransform().
Ray shotAtDrawnFloor(const glm::dvec3& target, double degrees, double azimuth) {
    const glm::dmat4 toWorld = turnedTransform();
    const glm::dvec3 back =
        glm::normalize(glm::transpose(glm::inverse(glm::dmat3(toWorld))) * shotFrom(degrees, azimuth));
    return ray(glm::dvec3(toWorld * glm::dvec4(target, 1.0)) + 3.0 * back, -back);
}

// Where `line` (world space) meets the floor y = 0 of turnedTransform(), world space.
glm::dvec3 whereAxisMeetsFloor(const DecalAxisLine& line) {
    const glm::dmat4 toWorld = turnedTransform(), toObject = glm::inverse(toWorld);
    const glm::dvec3 a(toObject * glm::dvec4(line.from, 1.0)), b(toObject * glm::dvec4(line.to, 1.0));
    return glm::dvec3(toWorld * glm::dvec4(a + (b - a) * (a.y / (a.y - b.y)), 1.0));
}

// The floor's world normal, not unit (the call takes any length).
glm::dvec3 drawnFloorNormal() {
    return 2.5 * glm::transpose(glm::inverse(glm::dmat3(turnedTransform()))) * glm::dvec3(0.0, 1.0, 0.0);
}

// The shot at the floor's object-space point `target` from `degrees` off the floor's normal in the world
// of turnedTransform(), turned about that normal by `azimuth`.
Ray worldShotAtDrawnFloor(const glm::dvec3& target, double degrees, double azimuth) {
    const glm::dvec3 n = glm::normalize(drawnFloorNormal());
    const glm::dvec3 u = glm::normalize(glm::cross(n, glm::dvec3(1.0, 0.0, 0.0))), v = glm::cross(n, u);
    const glm::dvec3 s = shotFrom(degrees, azimuth);
    const glm::dvec3 back = s.x * u + s.y * n + s.z * v;
    return ray(glm::dvec3(turnedTransform() * glm::dvec4(target, 1.0)) + 3.0 * back, -back);
}

// `point` (world space) in the unit box of `d`, a decal on an object of turnedTransform().
glm::dvec3 worldPointInBox(const Decal& d, const glm::dvec3& point) {
    return inBox(d, glm::dvec3(glm::inverse(turnedTransform()) * glm::dvec4(point, 1.0)));
}

} // namespace

// A decal shot through a proxy (or a collider) tilted 6 degrees against the drawn floor, laid where its
// axis meets the floor with the floor's normal, is the decal the same shot places when the floor is
// the collision mesh (same seed, a type with random rotation): centre, frame, slant, size and
// half-depth; its ID and spawn time are kept.
TEST(DrawnSurface, ADecalLaidOnTheDrawnSurfaceIsTheOneTheShotPlacesOnTheRenderMesh) {
    for (FloorTrace trace : {FloorTrace::TiltedProxy, FloorTrace::TiltedCollider})
        for (double degrees : {10.0, 35.0, 60.0})
            for (double azimuth : {0.3, 2.0, 4.1}) {
                const std::string where = std::string(traceName(trace)) + ", " + std::to_string(degrees) +
                                          " degrees, azimuth " + std::to_string(azimuth);
                DecalSystem tilted = floorSystemTracedBy(trace),
                            onFloor = floorSystemTracedBy(FloorTrace::Floor);
                ASSERT_TRUE(tilted.update(0.5).ok() && onFloor.update(0.5).ok());
                const Ray shot = shotAtDrawnFloor({0.2, 0.0, 0.1}, degrees, azimuth);
                const SpawnResult a = tilted.spawn(shot, addType(tilted, plainType()));
                const SpawnResult b = onFloor.spawn(shot, addType(onFloor, plainType()));
                ASSERT_TRUE(a.placed() && b.placed()) << a.reason << b.reason << where;
                const Decal before = *tilted.get(a.handle), drawn = *onFloor.get(b.handle);
                const std::optional<DecalAxisLine> line = tilted.axisLine(a.handle);
                ASSERT_TRUE(line.has_value()) << where;
                const Result<DrawnSurfaceLaying> laid =
                    tilted.layOnDrawnSurface(a.handle, whereAxisMeetsFloor(*line), drawnFloorNormal());
                ASSERT_TRUE(laid.ok()) << laid.error() << where;
                EXPECT_EQ(laid.value(), DrawnSurfaceLaying::Laid) << where;
                const Decal d = *tilted.get(a.handle);
                EXPECT_LT(glm::length(d.center - drawn.center), 1e-5f) << where;
                const Frame f = d.frame(), g = drawn.frame();
                EXPECT_LT(glm::length(f.normal - g.normal), 1e-5f) << where;
                // The decal's rotation is read back against the shot as its packed projection axis keeps
                // it: through the proxy the decal faces the floor already and only that is undone; turned
                // from the collider's plane, the tangent is as precise as the axis, whose error grows as
                // the shot nears the normal (1.6e-4 at 10 degrees).
                const float tangentError = trace == FloorTrace::TiltedProxy ? 1e-5f : 5e-4f;
                EXPECT_LT(glm::length(f.tangent - g.tangent), tangentError) << where;
                EXPECT_LT(glm::length(f.bitangent - g.bitangent), tangentError) << where;
                EXPECT_EQ(d.mirrored(), drawn.mirrored()) << where;
                EXPECT_LT(glm::length(unpackSlant(d.slant) - unpackSlant(drawn.slant)), 2e-3f) << where;
                EXPECT_LT(glm::length(d.size - drawn.size), 1e-4f * glm::length(drawn.size)) << where;
                EXPECT_NEAR(d.halfDepth, drawn.halfDepth, 1e-6f * drawn.halfDepth) << where;
                EXPECT_EQ(d.id, before.id) << where;
                EXPECT_EQ(d.id, drawn.id) << where << ": the same seed draws the same ID";
                EXPECT_EQ(d.spawnTime, before.spawnTime) << where;
                EXPECT_EQ(d.spawnTime, 0.5) << where;
                EXPECT_EQ(d.type, before.type) << where;
                EXPECT_EQ(d.object, before.object) << where;
                EXPECT_EQ(d.objectId, before.objectId) << where;
                EXPECT_EQ(d.opacity.bits(), before.opacity.bits()) << where;
                // Before it was laid, the decal stood on the tilted surface: through the proxy facing the
                // floor, its box deeper by the proxy's bound; on the collider in the collider's plane.
                EXPECT_GT(glm::length(before.center - drawn.center), 1e-3f) << where;
                if (trace == FloorTrace::TiltedProxy) {
                    EXPECT_GT(before.halfDepth, 2.0f * drawn.halfDepth) << where;
                } else {
                    EXPECT_GT(glm::length(before.frame().normal - g.normal), 0.05f) << where;
                }
            }
}

// The axis line runs through the box from the centre of the face the shot came through (z = +1) to the
// centre of the opposite face (z = -1), along the projection axis, which is the shot's for a decal
// projected along it; a stale handle has none.
TEST(DrawnSurface, TheAxisLineRunsThroughTheBoxFromTheSideTheShotCameFrom) {
    DecalSystem s = floorSystemTracedBy(FloorTrace::TiltedProxy);
    const uint16_t t = addType(s, plainType());
    DecalType alongNormal = plainType("along normal");
    alongNormal.projection = Projection::Normal;
    const SpawnResult n = s.spawn(shotAtDrawnFloor({0.3, 0.0, 0.4}, 30.0, 1.0), addType(s, alongNormal));
    ASSERT_TRUE(n.placed()) << n.reason;
    EXPECT_FALSE(s.axisLine(n.handle)->alongShot);
    for (double degrees : {0.0, 30.0, 70.0}) {
        const std::string where = std::to_string(degrees) + " degrees";
        const Ray shot = shotAtDrawnFloor({-0.3, 0.0, 0.4}, degrees, 1.0);
        const SpawnResult r = s.spawn(shot, t);
        ASSERT_TRUE(r.placed()) << r.reason << where;
        const Decal& d = *s.get(r.handle);
        const std::optional<DecalAxisLine> line = s.axisLine(r.handle);
        ASSERT_TRUE(line.has_value()) << where;
        EXPECT_LT(glm::length(worldPointInBox(d, line->from) - glm::dvec3(0.0, 0.0, 1.0)), 1e-5) << where;
        EXPECT_LT(glm::length(worldPointInBox(d, line->to) - glm::dvec3(0.0, 0.0, -1.0)), 1e-5) << where;
        EXPECT_LT(glm::dot(line->from - line->to, shot.direction), 0.0) << where;
        EXPECT_EQ(line->alongShot, d.slant != 0) << where;
        if (degrees > 0.0) {
            EXPECT_TRUE(line->alongShot) << where;
        }
        const WorldDecal w = s.worldBox(d);
        EXPECT_LT(glm::length(glm::normalize(line->from - line->to) - glm::dvec3(w.projection)), 1e-5)
            << where;
        EXPECT_LT(glm::length(0.5 * (line->from + line->to) - w.center), 1e-6) << where;
    }

    const SpawnResult gone = s.spawn(shotAtDrawnFloor({0.5, 0.0, -0.5}, 20.0, 0.0), t);
    ASSERT_TRUE(gone.placed()) << gone.reason;
    ASSERT_TRUE(s.remove(gone.handle));
    EXPECT_FALSE(s.axisLine(gone.handle).has_value());
}

// An object scaled to nothing (a singular transform) draws nothing: its decals have no axis line and
// are not laid again.
TEST(DrawnSurface, ADecalOnAnObjectScaledToNothingHasNoAxisLineAndIsNotLaid) {
    Scene scene;
    scene.source = "test:dynamic floor";
    scene.objects.push_back(makeSceneObject("floor", tiltedPlane(0.0), turnedTransform(), true));
    DecalSystem s = makeSystem(scene);
    const SpawnResult r = s.spawn(shotAtDrawnFloor({0.0, 0.0, 0.0}, 20.0, 0.5), addType(s, plainType()));
    ASSERT_TRUE(r.placed()) << r.reason;
    const std::optional<DecalAxisLine> line = s.axisLine(r.handle);
    ASSERT_TRUE(line.has_value());
    ASSERT_TRUE(s.setTransform(0, glm::scale(turnedTransform(), glm::dvec3(0.0))).ok());
    EXPECT_FALSE(s.axisLine(r.handle).has_value());
    const std::vector<Decal> decals = s.decals();
    const uint64_t version = s.version();
    const Result<DrawnSurfaceLaying> st =
        s.layOnDrawnSurface(r.handle, glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0));
    ASSERT_FALSE(st.ok());
    EXPECT_NE(st.error().find("singular"), std::string::npos) << st.error();
    EXPECT_TRUE(sameDecals(s.decals(), decals));
    EXPECT_EQ(s.version(), version);
}

// Laying a decal again is one change in place: one Changed entry at its index, the version up by one,
// the other decals as they were.
TEST(DrawnSurface, LayingADecalLogsOneChangeInPlace) {
    DecalSystem s = floorSystemTracedBy(FloorTrace::TiltedProxy);
    const uint16_t t = addType(s, plainType());
    std::vector<DecalHandle> handles;
    for (double x : {-0.6, 0.0, 0.6}) {
        const SpawnResult r = s.spawn(shotAtDrawnFloor({x, 0.0, 0.2}, 25.0, 1.5), t);
        ASSERT_TRUE(r.placed()) << r.reason;
        handles.push_back(r.handle);
    }
    const std::vector<Decal> before = s.decals();
    const uint64_t version = s.version();
    const DecalStats stats = s.stats();
    const uint32_t index = uint32_t(s.get(handles[1]) - s.decals().data());
    const Result<DrawnSurfaceLaying> st =
        s.layOnDrawnSurface(handles[1], whereAxisMeetsFloor(*s.axisLine(handles[1])), drawnFloorNormal());
    ASSERT_TRUE(st.ok()) << st.error();
    EXPECT_EQ(st.value(), DrawnSurfaceLaying::Laid);
    EXPECT_EQ(s.version(), version + 1);
    const DecalChanges changes = s.changesSince(version);
    ASSERT_TRUE(changes.complete);
    EXPECT_EQ(changes.version, version + 1);
    ASSERT_EQ(changes.changes.size(), 1u);
    EXPECT_EQ(changes.changes[0].kind, DecalChangeKind::Changed);
    EXPECT_EQ(changes.changes[0].index, index);
    EXPECT_EQ(changes.changes[0].from, index);
    ASSERT_EQ(s.decals().size(), before.size());
    for (uint32_t i = 0; i < before.size(); ++i) {
        if (i == index)
            EXPECT_FALSE(sameDecal(s.decals()[i], before[i]));
        else
            EXPECT_TRUE(sameDecal(s.decals()[i], before[i])) << "decal " << i;
    }
    EXPECT_TRUE(s.stats() == stats);
}

// Every refusal names its problem and changes nothing: no decal, no version, no stats, no random number
// (the next spawn is the one a system that saw none of them places).
TEST(DrawnSurface, ARefusedLayingChangesNothingAndNamesTheProblem) {
    DecalSystem s = floorSystemTracedBy(FloorTrace::TiltedProxy),
                twin = floorSystemTracedBy(FloorTrace::TiltedProxy);
    DecalType crater = plainType("crater");
    crater.volumetric = true;
    const Ray shot = shotAtDrawnFloor({0.1, 0.0, -0.2}, 30.0, 2.5),
              other = shotAtDrawnFloor({-0.8, 0.0, 0.7}, 15.0, 0.7);
    DecalHandle hole, volumetric, stale;
    for (DecalSystem* sys : {&s, &twin}) {
        const uint16_t t = addType(*sys, plainType()), v = addType(*sys, crater);
        const SpawnResult a = sys->spawn(shot, t), b = sys->spawn(other, v), c = sys->spawn(other, t);
        ASSERT_TRUE(a.placed() && b.placed() && c.placed()) << a.reason << b.reason << c.reason;
        ASSERT_TRUE(sys->remove(c.handle));
        hole = a.handle;
        volumetric = b.handle;
        stale = c.handle;
    }
    const DecalAxisLine line = *s.axisLine(hole);
    const glm::dvec3 meet = whereAxisMeetsFloor(line), up = drawnFloorNormal();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const glm::dvec3 across(s.worldBox(hole)->frame.tangent);
    const DecalAxisLine craterLine = *s.axisLine(volumetric);

    struct Refusal {
        const char* what;
        DecalHandle handle;
        glm::dvec3 point, normal;
        const char* named;
    };
    const Refusal refusals[] = {
        {"stale handle", stale, meet, up, "stale or invalid handle"},
        {"invalid handle", DecalHandle{1000, 1}, meet, up, "stale or invalid handle"},
        {"NaN point", hole, glm::dvec3(nan, 0.0, 0.0), up, "point is not finite"},
        {"infinite normal", hole, meet, glm::dvec3(0.0, std::numeric_limits<double>::infinity(), 0.0),
         "normal is not finite"},
        {"zero normal", hole, meet, glm::dvec3(0.0), "normal is zero"},
        {"point beyond the box's face", hole, line.from + 0.01 * (line.from - line.to), up,
         "outside the decal's box"},
        {"normal at 90 degrees", hole, meet, across, "89 degrees or more"},
        {"volumetric decal", volumetric, 0.5 * (craterLine.from + craterLine.to), up, "volumetric"},
    };
    const std::vector<Decal> decals = s.decals();
    const uint64_t version = s.version();
    const DecalStats stats = s.stats();
    for (const Refusal& r : refusals) {
        const Result<DrawnSurfaceLaying> st = s.layOnDrawnSurface(r.handle, r.point, r.normal);
        ASSERT_FALSE(st.ok()) << r.what;
        EXPECT_NE(st.error().find(r.named), std::string::npos) << r.what << ": " << st.error();
        EXPECT_TRUE(sameDecals(s.decals(), decals)) << r.what;
        EXPECT_EQ(s.version(), version) << r.what;
        EXPECT_TRUE(s.stats() == stats) << r.what;
    }
    // Just inside the box's face the same call is taken.
    EXPECT_TRUE(s.layOnDrawnSurface(hole, line.from + 1e-4 * (line.from - line.to), up).ok());

    const SpawnResult next = s.spawn(other, 0), twinNext = twin.spawn(other, 0);
    ASSERT_TRUE(next.placed() && twinNext.placed());
    EXPECT_EQ(s.get(next.handle)->id, twin.get(twinNext.handle)->id) << "no random number was drawn";
}

// A shot that meets the drawn floor more steeply than its type allows would have placed nothing there
// (spawn on the floor refuses it as grazing): laid on the floor, the decal it placed on a collider
// tilted against the floor is removed, as remove() removes it. The same shot's decal of a type projected
// along its normal keeps no shot and is laid.
TEST(DrawnSurface, ADecalWhoseShotMeetsTheDrawnSurfaceTooSteeplyIsRemoved) {
    int removed = 0;
    for (double azimuth = 0.0; azimuth < 6.28; azimuth += 0.4) {
        const std::string where = "azimuth " + std::to_string(azimuth);
        DecalSystem s = floorSystemTracedBy(FloorTrace::TiltedCollider),
                    onFloor = floorSystemTracedBy(FloorTrace::Floor);
        DecalType steep = plainType(), alongNormal = plainType("along normal");
        steep.maxAngleDeg = alongNormal.maxAngleDeg = 50.0f;
        alongNormal.projection = Projection::Normal;
        const uint16_t t = addType(s, steep), n = addType(s, alongNormal);
        const Ray shot = worldShotAtDrawnFloor({0.2, 0.0, 0.1}, 52.0, azimuth);
        const SpawnResult a = s.spawn(shot, t), b = s.spawn(shot, n);
        const SpawnResult drawn = onFloor.spawn(shot, addType(onFloor, steep));
        if (!a.placed() || drawn.status != SpawnStatus::GrazingAngle) continue;
        ASSERT_TRUE(b.placed()) << b.reason << where;
        const uint64_t version = s.version();
        const DecalStats stats = s.stats();
        const Result<DrawnSurfaceLaying> gone =
            s.layOnDrawnSurface(a.handle, whereAxisMeetsFloor(*s.axisLine(a.handle)), drawnFloorNormal());
        ASSERT_TRUE(gone.ok()) << gone.error() << where;
        EXPECT_EQ(gone.value(), DrawnSurfaceLaying::Removed) << where;
        EXPECT_EQ(s.get(a.handle), nullptr) << where;
        EXPECT_EQ(s.stats().removed, stats.removed + 1) << where;
        EXPECT_EQ(s.stats().alive, stats.alive - 1) << where;
        const DecalChanges changes = s.changesSince(version);
        ASSERT_EQ(changes.changes.size(), 1u) << where;
        EXPECT_EQ(changes.changes[0].kind, DecalChangeKind::Removed) << where;
        const Result<DrawnSurfaceLaying> kept =
            s.layOnDrawnSurface(b.handle, whereAxisMeetsFloor(*s.axisLine(b.handle)), drawnFloorNormal());
        ASSERT_TRUE(kept.ok()) << kept.error() << where;
        EXPECT_EQ(kept.value(), DrawnSurfaceLaying::Laid) << where;
        ++removed;
    }
    EXPECT_GT(removed, 0) << "no shot was placed on the collider and refused by the floor";
}

// The drawn floor y = 0 over [-2, 2]^2 of turnedTransform() traced through a proxy that covers only
// [-1.5, 1.5]^2 of it (bound 0.5): shots at the floor's rim miss the proxy and meet what is drawn.
DecalSystem floorSystemWithSmallProxy() {
    Scene scene;
    scene.source = "test:drawn floor, small proxy";
    scene.objects.push_back(makeSceneObject("floor", tiltedPlane(0.0), turnedTransform()));
    std::vector<std::shared_ptr<const Proxy>> proxies;
    proxies.push_back(shareProxy(makeProxy(makeGrid({-1.5f, 1.5f}, {-1.5f, 1.5f}), 0.5)));
    Result<DecalSystem> s = DecalSystem::create(buildWorld(scene, proxies));
    EXPECT_TRUE(s.ok()) << s.error();
    return std::move(s).value();
}

// The floor's world point of object-space `local`.
glm::dvec3 floorPoint(const glm::dvec3& local) {
    return glm::dvec3(turnedTransform() * glm::dvec4(local, 1.0));
}

// A shot that misses the proxy but meets the drawn floor, spawned where the floor was found, is the
// decal the same shot places when the floor is the collision mesh: centre, frame, slant, size,
// half-depth and ID.
TEST(DrawnSurface, AShotThatMissesTheProxyIsPlacedWhereItMeetsTheDrawnSurface) {
    for (double degrees : {0.0, 30.0, 60.0})
        for (double azimuth : {0.4, 2.5}) {
            const std::string where =
                std::to_string(degrees) + " degrees, azimuth " + std::to_string(azimuth);
            DecalSystem proxied = floorSystemWithSmallProxy(),
                        onFloor = floorSystemTracedBy(FloorTrace::Floor);
            const uint16_t t = addType(proxied, plainType()), u = addType(onFloor, plainType());
            const glm::dvec3 target(1.8, 0.0, -1.7);
            const Ray shot = worldShotAtDrawnFloor(target, degrees, azimuth);
            ASSERT_EQ(proxied.spawn(shot, t).status, SpawnStatus::Missed) << where;
            const SpawnResult drawn = onFloor.spawn(shot, u);
            ASSERT_TRUE(drawn.placed()) << drawn.reason << where;
            const SpawnResult r =
                proxied.spawnOnDrawnSurface(shot, floorPoint(target), drawnFloorNormal(), t);
            ASSERT_TRUE(r.placed()) << r.reason << where;
            const Decal d = *proxied.get(r.handle), e = *onFloor.get(drawn.handle);
            EXPECT_LT(glm::length(d.center - e.center), 1e-5f) << where;
            const Frame f = d.frame(), g = e.frame();
            EXPECT_LT(glm::length(f.normal - g.normal), 1e-5f) << where;
            EXPECT_LT(glm::length(f.tangent - g.tangent), 1e-5f) << where;
            EXPECT_EQ(d.slant, e.slant) << where;
            EXPECT_LT(glm::length(d.size - e.size), 1e-5f * glm::length(e.size)) << where;
            EXPECT_NEAR(d.halfDepth, e.halfDepth, 1e-6f * e.halfDepth) << where;
            EXPECT_EQ(d.id, e.id) << where;
            EXPECT_EQ(d.object, 0u) << where;
        }
}

// A shot that a proxy tilted 6 degrees against the drawn floor refuses as grazing, but that meets the
// floor within its type's angle, spawned where it meets the floor, is the decal the same shot places
// when the floor is the collision mesh.
TEST(DrawnSurface, AShotThatGrazesTheProxyButNotTheDrawnSurfaceIsPlacedWhereItMeetsIt) {
    int placed = 0;
    for (double azimuth = 0.0; azimuth < 6.28; azimuth += 0.4) {
        const std::string where = "azimuth " + std::to_string(azimuth);
        DecalSystem proxied = floorSystemTracedBy(FloorTrace::TiltedProxy),
                    onFloor = floorSystemTracedBy(FloorTrace::Floor);
        DecalType steep = plainType();
        steep.maxAngleDeg = 50.0f;
        const uint16_t t = addType(proxied, steep), u = addType(onFloor, steep);
        const glm::dvec3 target(0.2, 0.0, 0.1);
        const Ray shot = worldShotAtDrawnFloor(target, 48.0, azimuth);
        const SpawnResult refused = proxied.spawn(shot, t), drawn = onFloor.spawn(shot, u);
        ASSERT_TRUE(drawn.placed()) << drawn.reason << where;
        if (refused.status != SpawnStatus::GrazingAngle) continue;
        EXPECT_TRUE(refused.refusedByCollisionSurface()) << where;
        const SpawnResult r = proxied.spawnOnDrawnSurface(shot, floorPoint(target), drawnFloorNormal(), t);
        ASSERT_TRUE(r.placed()) << r.reason << where;
        const Decal d = *proxied.get(r.handle), e = *onFloor.get(drawn.handle);
        EXPECT_LT(glm::length(d.center - e.center), 1e-5f) << where;
        EXPECT_LT(glm::length(d.frame().normal - e.frame().normal), 1e-5f) << where;
        EXPECT_LT(glm::length(d.frame().tangent - e.frame().tangent), 1e-5f) << where;
        EXPECT_EQ(d.slant, e.slant) << where;
        ++placed;
    }
    EXPECT_GT(placed, 0) << "no shot was refused as grazing by the proxy and taken by the floor";
}

// A decal whose shot met the drawn surface before its box (a drawn feature that the proxy let the shot
// pass) gives way to the decal the shot places there: the one the same shot places when the drawn
// surface is the collision mesh, logged as one placement and one removal.
TEST(DrawnSurface, ADecalWhoseShotMetTheDrawnSurfaceBeforeItsBoxGivesWayToTheShotsDecalThere) {
    DecalSystem proxied = floorSystemTracedBy(FloorTrace::TiltedProxy),
                onFloor = floorSystemTracedBy(FloorTrace::Floor);
    const uint16_t t = addType(proxied, plainType()), u = addType(onFloor, plainType());
    const glm::dvec3 target(0.2, 0.0, 0.1);
    const Ray shot = worldShotAtDrawnFloor(target, 30.0, 0.7);
    const SpawnResult old = proxied.spawn(shot, t), drawn = onFloor.spawn(shot, u);
    ASSERT_TRUE(old.placed() && drawn.placed()) << old.reason << drawn.reason;
    const uint64_t version = proxied.version();
    const DecalStats stats = proxied.stats();
    // Nudged along the shot, as a search from its origin finds it.
    const glm::dvec3 met = floorPoint(target);
    const SpawnResult r = proxied.replaceOnDrawnSurface(old.handle, shot, met, drawnFloorNormal());
    ASSERT_TRUE(r.placed()) << r.reason;
    EXPECT_EQ(proxied.get(old.handle), nullptr);
    const Decal d = *proxied.get(r.handle), e = *onFloor.get(drawn.handle);
    EXPECT_LT(glm::length(d.center - e.center), 1e-5f);
    EXPECT_LT(glm::length(d.frame().normal - e.frame().normal), 1e-5f);
    // Its own random turn: the axis, packed relative to the frame, agrees to the packing's precision.
    EXPECT_LT(glm::length(d.projectionAxis() - e.projectionAxis()), 1e-3f);
    EXPECT_EQ(proxied.stats().placed, stats.placed + 1);
    EXPECT_EQ(proxied.stats().removed, stats.removed + 1);
    EXPECT_EQ(proxied.stats().alive, stats.alive);
    const DecalChanges changes = proxied.changesSince(version);
    ASSERT_EQ(changes.changes.size(), 2u);
    EXPECT_EQ(changes.changes[0].kind, DecalChangeKind::Added);
    EXPECT_EQ(changes.changes[1].kind, DecalChangeKind::Removed);
}

// Where the shot met the drawn surface before the box more steeply than the type allows, the render
// mesh would have placed nothing: the decal is removed and the call says GrazingAngle. A stale handle
// and a refusal of the spawn (a point no collision surface lies near) change nothing, stats included.
TEST(DrawnSurface, ADecalWhoseShotMetTheDrawnSurfaceBeforeItsBoxTooSteeplyIsRemoved) {
    DecalSystem s = floorSystemWithSmallProxy();
    const uint16_t t = addType(s, plainType());
    const glm::dvec3 target(0.2, 0.0, 0.1), up = drawnFloorNormal();
    const Ray shot = worldShotAtDrawnFloor(target, 30.0, 0.7);
    const SpawnResult a = s.spawn(shot, t),
                      b = s.spawn(worldShotAtDrawnFloor({-0.4, 0.0, 0.3}, 20.0, 2.0), t);
    ASSERT_TRUE(a.placed() && b.placed()) << a.reason << b.reason;
    const std::vector<Decal> decals = s.decals();
    const uint64_t version = s.version();
    const DecalStats stats = s.stats();
    const SpawnResult stale = s.replaceOnDrawnSurface(DecalHandle{1000, 1}, shot, floorPoint(target), up);
    EXPECT_EQ(stale.status, SpawnStatus::InvalidArgument);
    EXPECT_NE(stale.reason.find("stale or invalid handle"), std::string::npos) << stale.reason;
    const SpawnResult far = s.replaceOnDrawnSurface(a.handle, shot, floorPoint(target) + 3.0 * up, up);
    EXPECT_EQ(far.status, SpawnStatus::Missed) << far.reason;
    EXPECT_TRUE(sameDecals(s.decals(), decals));
    EXPECT_EQ(s.version(), version);
    EXPECT_TRUE(s.stats() == stats) << "a refused replacement counts nothing";
    // Met at a wall standing across the shot's path, edge-on to it.
    const glm::dvec3 edgeOn = glm::normalize(glm::cross(up, shot.direction));
    const SpawnResult gone = s.replaceOnDrawnSurface(a.handle, shot, floorPoint(target), edgeOn);
    EXPECT_EQ(gone.status, SpawnStatus::GrazingAngle) << gone.reason;
    EXPECT_EQ(s.get(a.handle), nullptr);
    EXPECT_NE(s.get(b.handle), nullptr);
    EXPECT_EQ(s.stats().removed, stats.removed + 1);
    EXPECT_EQ(s.stats().alive, stats.alive - 1);
    EXPECT_EQ(s.stats().rejectedTotal(), stats.rejectedTotal());
}

// Every refusal names its problem and leaves the decals, the change log and the random numbers as
// they were.
TEST(DrawnSurface, ASpawnOnTheDrawnSurfaceThatIsRefusedChangesNoDecal) {
    DecalSystem s = floorSystemWithSmallProxy(), twin = floorSystemWithSmallProxy();
    DecalType crater = plainType("crater");
    crater.volumetric = true;
    const uint16_t t = addType(s, plainType()), v = addType(s, crater);
    addType(twin, plainType());
    const glm::dvec3 target(1.8, 0.0, -1.7), point = floorPoint(target), up = drawnFloorNormal();
    const Ray shot = worldShotAtDrawnFloor(target, 20.0, 1.0);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const glm::dvec3 across(glm::normalize(glm::cross(up, shot.direction)));
    Ray zero = shot;
    zero.direction = glm::dvec3(0.0);
    struct Refusal {
        const char* what;
        Ray shot;
        glm::dvec3 point, normal;
        uint16_t type;
        SpawnStatus status;
        const char* named;
    };
    const Refusal refusals[] = {
        {"unknown type", shot, point, up, 7, SpawnStatus::InvalidType, "no decal type"},
        {"zero shot", zero, point, up, t, SpawnStatus::InvalidRay, ""},
        {"volumetric type", shot, point, up, v, SpawnStatus::InvalidArgument, "volumetric"},
        {"NaN point", shot, glm::dvec3(nan, 0.0, 0.0), up, t, SpawnStatus::InvalidArgument,
         "point is not finite"},
        {"zero normal", shot, point, glm::dvec3(0.0), t, SpawnStatus::InvalidArgument, "normal"},
        {"normal across the shot", shot, point, across, t, SpawnStatus::GrazingAngle,
         "degrees from its normal"},
        {"point far from every surface", shot, point + 3.0 * glm::normalize(up), up, t, SpawnStatus::Missed,
         "no one collision surface"},
    };
    const uint64_t version = s.version();
    for (const Refusal& r : refusals) {
        const SpawnResult res = s.spawnOnDrawnSurface(r.shot, r.point, r.normal, r.type);
        EXPECT_EQ(res.status, r.status) << r.what << ": " << res.reason;
        EXPECT_NE(res.reason.find(r.named), std::string::npos) << r.what << ": " << res.reason;
        EXPECT_TRUE(s.decals().empty()) << r.what;
        EXPECT_EQ(s.version(), version) << r.what;
    }
    const SpawnResult a = s.spawnOnDrawnSurface(shot, point, up, t),
                      b = twin.spawnOnDrawnSurface(shot, point, up, 0);
    ASSERT_TRUE(a.placed() && b.placed()) << a.reason << b.reason;
    EXPECT_EQ(s.get(a.handle)->id, twin.get(b.handle)->id) << "no random number was drawn";
}

// A decal on a skinned object lies on the drawn surface from its spawn and follows it (setPose): it is
// not laid again, and nothing changes.
TEST(DrawnSurface, ADecalOnASkinnedObjectIsNotLaidAgain) {
    DecalSystem s = makeSystem(makeSkinnedArm());
    const SpawnResult r = s.spawn(ray({0.0, 0.3, 2.0}, {0.0, 0.0, -1.0}), addType(s, plainType()));
    ASSERT_TRUE(r.placed()) << r.reason;
    ASSERT_TRUE(s.world().deforms(0));
    const DecalAxisLine line = *s.axisLine(r.handle);
    const std::vector<Decal> decals = s.decals();
    const uint64_t version = s.version();
    const Result<DrawnSurfaceLaying> st =
        s.layOnDrawnSurface(r.handle, 0.5 * (line.from + line.to), glm::dvec3(0.0, 0.0, 1.0));
    ASSERT_FALSE(st.ok());
    EXPECT_NE(st.error().find("skinned or morphed"), std::string::npos) << st.error();
    EXPECT_TRUE(sameDecals(s.decals(), decals));
    EXPECT_EQ(s.version(), version);
}

// A decal laid again keeps its area cell, also where its centre moves into another one, and a save
// keeps both: the loaded system holds the same decals and saves the same bytes.
TEST(DrawnSurface, ALaidDecalSurvivesASaveWithItsAreaCell) {
    int crossed = 0;
    for (double x : {-0.6, -0.2, 0.2, 0.6}) {
        DecalSystem s = floorSystemTracedBy(FloorTrace::TiltedProxy);
        const SpawnResult r = s.spawn(shotAtDrawnFloor({x, 0.0, -1.5}, 50.0, 0.9), addType(s, plainType()));
        ASSERT_TRUE(r.placed()) << r.reason;
        const glm::dvec3 before = s.worldBox(r.handle)->center;
        ASSERT_TRUE(
            s.layOnDrawnSurface(r.handle, whereAxisMeetsFloor(*s.axisLine(r.handle)), drawnFloorNormal())
                .ok());
        const glm::dvec3 after = s.worldBox(r.handle)->center;
        const double cell = double(s.settings().cellSize);
        if (glm::floor(before / cell) != glm::floor(after / cell)) ++crossed;
        const std::vector<uint8_t> saved = saveDecals(s);
        DecalSystem loaded = floorSystemTracedBy(FloorTrace::TiltedProxy);
        addType(loaded, plainType());
        const Result<DecalLoadReport> report = loadDecals(loaded, saved.data(), saved.size());
        ASSERT_TRUE(report.ok()) << report.error();
        EXPECT_TRUE(sameDecals(loaded.decals(), s.decals())) << x;
        EXPECT_EQ(saveDecals(loaded), saved) << x;
    }
    EXPECT_GT(crossed, 0) << "no decal moved into another cell";
}
