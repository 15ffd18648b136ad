// Transforms single precision cannot trace (TraceTransform.hpp): singular or nearly singular in float,
// strongly sheared, scaled by 0, 1e-20 or 1e20. Through the glTF loader (static and dynamic nodes)
// and through setTransform, in the single-ray and batch paths, such an object is left out of the
// trace with a warning and the rest of the scene traces as before; usable ones trace correctly.

#include "spatter/placement/TraceTransform.hpp"
#include "GltfBuilder.hpp"
#include "PlacementTestUtil.hpp"
#include "TestData.hpp"
#include "spatter/core/SceneLoader.hpp"

#include <gmock/gmock.h>

using namespace spatter;
using namespace spatter::test;
using ::testing::HasSubstr;

namespace {

const glm::dvec3 kCratePlace(0.0, 2.0, 0.0);

struct Linear {
    std::string name;
    glm::dmat3 m;
};

// Linear parts whose float form the trace cannot use.
std::vector<Linear> untraceable() {
    return {{"columns equal in float",
             glm::dmat3(glm::dvec3(1, 1, 0), glm::dvec3(1, 1 + 1e-9, 0), glm::dvec3(0, 0, 1))},
            {"nearly singular", glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(1, 1e-5, 0), glm::dvec3(0, 0, 1))},
            {"mirrored and nearly singular",
             glm::dmat3(glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1e-6))},
            {"strong shear", glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(1e6, 1, 0), glm::dvec3(0, 0, 1))},
            {"scale 0", glm::dmat3(0.0)},
            {"scale 1e-20", glm::dmat3(1e-20)},
            {"scale 1e20", glm::dmat3(1e20)}};
}

// Linear parts it traces, strongly scaled or sheared within the rule.
std::vector<Linear> traceable() {
    return {{"rotation", glm::dmat3(glm::rotate(glm::dmat4(1.0), 0.7, glm::dvec3(1.0, 2.0, 3.0)))},
            {"shear", glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(3, 1, 0), glm::dvec3(0, 0.5, 1))},
            {"squashed", glm::dmat3(glm::dvec3(100, 0, 0), glm::dvec3(0, 0.01, 0), glm::dvec3(0, 0, 100))},
            {"mirrored", glm::dmat3(glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1))},
            {"scale 1e-5", glm::dmat3(1e-5)},
            {"scale 1e6", glm::dmat3(1e6)}};
}

glm::dmat4 placed(const glm::dmat3& m) {
    glm::dmat4 t(m);
    t[3] = glm::dvec4(kCratePlace, 1.0);
    return t;
}

// A static floor (top at y = 0) and, at x = 3, a dynamic ball; the crate (object 1, the box
// [-0.5, 0.5]^3) with `crate` as its transform.
Scene crateScene(const glm::dmat4& crate, bool dynamic) {
    Scene s;
    s.source = "test:crate";
    s.objects.push_back(makeSceneObject("floor", makeBox(glm::vec3(10.0f, 0.1f, 10.0f), 2),
                                        glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, -0.1, 0.0))));
    s.objects.push_back(makeSceneObject("crate", makeBox(glm::vec3(0.5f), 1), crate, dynamic));
    s.objects.push_back(makeSceneObject("ball", makeSphere(0.5f, 8, 12),
                                        glm::translate(glm::dmat4(1.0), glm::dvec3(3.0, 1.0, 0.0)), true));
    return s;
}

// Straight down through the crate's place; down onto the ball; and a narrow burst of 16 rays from
// above the crate (an Embree packet in intersectBatch).
std::vector<Ray> probeRays() {
    std::vector<Ray> rays = {Ray{{0.0, 10.0, 0.0}, {0.0, -1.0, 0.0}},
                             Ray{{3.0, 10.0, 0.0}, {0.0, -1.0, 0.0}}};
    for (int i = 0; i < 16; ++i) {
        const double a = 0.4 * i;
        rays.push_back(Ray{{0.05, 10.0, 0.05}, {0.01 * std::cos(a), -1.0, 0.01 * std::sin(a)}});
    }
    return rays;
}

// The closest hit on the crate box in double (its far side from inside), or -1.
double crateDistance(const glm::dmat4& crate, const Ray& ray) {
    const glm::dmat4 inv = glm::inverse(crate);
    const glm::dvec3 o = glm::dvec3(inv * glm::dvec4(ray.origin, 1.0)), d = glm::dmat3(inv) * ray.direction;
    double lo = 0.0, hi = 1e300;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            if (std::fabs(o[a]) > 0.5) return -1.0;
            continue;
        }
        const double t0 = (-0.5 - o[a]) / d[a], t1 = (0.5 - o[a]) / d[a];
        lo = std::max(lo, std::min(t0, t1));
        hi = std::min(hi, std::max(t0, t1));
    }
    return lo > hi ? -1.0 : lo > 0.0 ? lo : hi; // from inside, the way out
}

// Every probe: the batch equals the single rays, and each ray hits the crate where the double-precision
// box is, when the crate is traced and nearer than what lies behind it (the floor, top at y = 0, or
// the ball, top at 1.5), and passes through to that otherwise.
void expectTrace(const CollisionWorld& w, const glm::dmat4& crate, bool crateTraced,
                 const std::string& what) {
    const std::vector<Ray> rays = probeRays();
    const std::vector<std::optional<Hit>> batch = w.intersectBatch(rays);
    for (size_t i = 0; i < rays.size(); ++i) {
        const std::optional<Hit> single = w.intersect(rays[i]);
        EXPECT_TRUE(sameHit(single, batch[i])) << what << ", ray " << i;
        ASSERT_TRUE(single.has_value()) << what << ", ray " << i;
        const double behind = (rays[i].origin.y - (i == 1 ? 1.5 : 0.0)) / -rays[i].direction.y;
        const double t = crateTraced ? crateDistance(crate, rays[i]) : -1.0;
        if (t >= 0.0 && t < behind - 1e-3) {
            EXPECT_EQ(single->object, 1u) << what << ", ray " << i;
            EXPECT_NEAR(single->t, t, 1e-6 * std::max(1.0, t)) << what << ", ray " << i;
        } else {
            EXPECT_EQ(single->object, i == 1 ? 2u : 0u) << what << ", ray " << i;
            EXPECT_NEAR(single->t, behind, 1e-3) << what << ", ray " << i;
        }
    }
}

// The scene as a glTF file: the floor static, the crate static or dynamic, by node matrices.
std::string writeCrateGltf(const std::string& dir, const std::string& name, const glm::dmat4& crate,
                           bool dynamic) {
    const Mesh box = makeBox(glm::vec3(0.5f), 1);
    const std::vector<double> matrix(&crate[0][0], &crate[0][0] + 16);
    GltfBuilder g = floorAndCrate(box.positions, box.indices, matrix, dynamic);
    return g.writeGltf(dir, name);
}

} // namespace

TEST(TraceTransform, RuleAcceptsRotationsShearsAndStrongScales) {
    for (const Linear& l : traceable())
        EXPECT_EQ(
            traceTransformProblem(placed(l.m), Bounds{glm::vec3(-0.5f), glm::vec3(0.5f)}, glm::dvec3(0.0)),
            "")
            << l.name;
    EXPECT_NEAR(floatConditionNumber(glm::dmat4(1.0)), 3.0, 1e-12);
}

TEST(TraceTransform, RuleRejectsWhatFloatCannotInvertWithTheReason) {
    for (const Linear& l : untraceable())
        EXPECT_NE(traceTransformProblem(placed(l.m), Bounds{}, glm::dvec3(0.0)), "") << l.name;
    const std::string singular = traceTransformProblem(placed(untraceable()[0].m), Bounds{}, glm::dvec3(0.0));
    EXPECT_THAT(singular, HasSubstr("singular in single precision"));
    const std::string near = traceTransformProblem(placed(untraceable()[1].m), Bounds{}, glm::dvec3(0.0));
    EXPECT_THAT(near, HasSubstr("nearly singular in single precision (condition number"));
    EXPECT_THAT(near, HasSubstr("limit 65536)"));
}

TEST(TraceTransform, RuleRejectsObjectsFarBeyondTheFloatFrame) {
    const Bounds unit{glm::vec3(-0.5f), glm::vec3(0.5f)};
    const glm::dmat4 far = glm::translate(glm::dmat4(1.0), glm::dvec3(1e10, 0.0, 0.0));
    EXPECT_THAT(traceTransformProblem(far, unit, glm::dvec3(0.0)),
                HasSubstr("from the collision world's origin"));
    EXPECT_EQ(traceTransformProblem(far, unit, glm::dvec3(1e10, 0.0, 0.0)), "");
}

TEST(TraceTransform, SetTransformTakesAnUntraceableObjectOutOfTheTraceAndBack) {
    const glm::dmat4 home = placed(glm::dmat3(1.0));
    CollisionWorld w = CollisionWorld::build(crateScene(home, true)).value();
    for (const Linear& l : untraceable()) {
        const Result<TransformUpdate> u = w.setTransform(1, placed(l.m));
        ASSERT_TRUE(u.ok()) << l.name << ": " << u.error();
        EXPECT_FALSE(u->traced) << l.name;
        EXPECT_THAT(u->warning, HasSubstr("object 1 (crate): ")) << l.name;
        EXPECT_THAT(u->warning, HasSubstr("; not traced")) << l.name;
        EXPECT_FALSE(w.object(1)->traced);
        EXPECT_EQ(w.object(1)->transform, placed(l.m)) << l.name;
        ASSERT_EQ(w.warnings().size(), 1u);
        EXPECT_EQ(w.warnings()[0], u->warning);
        expectTrace(w, placed(l.m), false, l.name);
        const Result<TransformUpdate> back = w.setTransform(1, home);
        ASSERT_TRUE(back.ok() && back->traced) << l.name;
        EXPECT_TRUE(w.warnings().empty());
        expectTrace(w, home, true, l.name + ", then back");
    }
}

TEST(TraceTransform, SetTransformTracesUsableStrongTransformsCorrectly) {
    CollisionWorld w = CollisionWorld::build(crateScene(placed(glm::dmat3(1.0)), true)).value();
    for (const Linear& l : traceable()) {
        const Result<TransformUpdate> u = w.setTransform(1, placed(l.m));
        ASSERT_TRUE(u.ok() && u->traced) << l.name;
        expectTrace(w, placed(l.m), true, l.name);
    }
}

TEST(TraceTransform, WorldBuildLeavesUntraceableObjectsOutWithAWarning) {
    for (bool dynamic : {false, true})
        for (const Linear& l : untraceable()) {
            const std::string what = l.name + (dynamic ? ", dynamic" : ", static");
            Result<CollisionWorld> w = CollisionWorld::build(crateScene(placed(l.m), dynamic));
            ASSERT_TRUE(w.ok()) << what << ": " << w.error();
            ASSERT_EQ(w->warnings().size(), 1u) << what;
            EXPECT_THAT(w->warnings()[0], HasSubstr("object 1 (crate): ")) << what;
            EXPECT_TRUE(w->object(1)->inWorld && !w->object(1)->traced) << what;
            expectTrace(w.value(), placed(l.m), false, what);
            if (dynamic) { // a usable transform brings it in
                ASSERT_TRUE(w->setTransform(1, placed(glm::dmat3(1.0)))->traced) << what;
                expectTrace(w.value(), placed(glm::dmat3(1.0)), true, what + ", then usable");
            }
        }
}

TEST(TraceTransform, GltfNodesWithUntraceableMatricesLoadAndTraceTheRest) {
    const std::string dir = scratchDir("trace-transform-gltf");
    for (bool dynamic : {false, true}) {
        for (const Linear& l : untraceable()) {
            const std::string what = l.name + (dynamic ? ", dynamic" : ", static");
            Result<Scene> scene = loadScene(writeCrateGltf(dir, "crate", placed(l.m), dynamic));
            ASSERT_TRUE(scene.ok()) << what << ": " << scene.error();
            Result<CollisionWorld> w = CollisionWorld::build(scene.value());
            ASSERT_TRUE(w.ok()) << what << ": " << w.error();
            ASSERT_EQ(w->warnings().size(), 1u) << what;
            EXPECT_THAT(w->warnings()[0], HasSubstr("(crate)")) << what;
            const std::optional<Hit> down = w->intersect(probeRays()[0]);
            ASSERT_TRUE(down.has_value()) << what;
            EXPECT_EQ(down->object, 0u) << what;
            const std::vector<std::optional<Hit>> burst = w->intersectBatch(probeRays());
            for (size_t i = 2; i < burst.size(); ++i)
                EXPECT_TRUE(burst[i] && burst[i]->object == 0u) << what << ", ray " << i;
        }
        for (const Linear& l : traceable()) {
            Result<Scene> scene = loadScene(writeCrateGltf(dir, "crate", placed(l.m), dynamic));
            ASSERT_TRUE(scene.ok()) << l.name << ": " << scene.error();
            Result<CollisionWorld> w = CollisionWorld::build(scene.value());
            ASSERT_TRUE(w.ok() && w->warnings().empty()) << l.name;
            EXPECT_TRUE(w->object(1)->traced) << l.name;
        }
    }
}

TEST(TraceTransform, DecalsStayOnAnObjectTakenOutOfTheTrace) {
    Result<DecalSystem> sys = DecalSystem::create(crateScene(placed(glm::dmat3(1.0)), true));
    ASSERT_TRUE(sys.ok());
    DecalType t;
    t.name = "hole";
    const uint16_t type = sys->registerType(t).value();
    ASSERT_TRUE(sys->spawn(probeRays()[0], type).placed());
    const Decal before = sys->decals()[0];
    const Result<TransformUpdate> u = sys->setTransform(1, placed(glm::dmat3(0.0)));
    ASSERT_TRUE(u.ok() && !u->traced);
    ASSERT_EQ(sys->decals().size(), 1u);
    EXPECT_EQ(std::memcmp(&sys->decals()[0], &before, sizeof(Decal)), 0);
    const WorldDecal box = sys->worldBox(sys->decals()[0]);
    EXPECT_EQ(box.size, glm::vec2(0.0f));
    EXPECT_EQ(box.center, kCratePlace);
    const SpawnResult attached = sys->spawnAttached(1, glm::vec3(0.0f, 0.5f, 0.0f), glm::vec3(0, 1, 0), type);
    EXPECT_EQ(attached.status, SpawnStatus::NotReceiver);
    EXPECT_THAT(attached.reason, HasSubstr("singular in single precision"));
    const SpawnResult shot = sys->spawn(probeRays()[0], type);
    ASSERT_TRUE(shot.placed());
    EXPECT_EQ(sys->get(shot.handle)->object, 0u);
}
