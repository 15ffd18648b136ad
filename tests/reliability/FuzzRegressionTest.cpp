// Regressions of what the fuzz targets (tests/fuzz) found; docs/RELIABILITY.md lists each finding.

#include "GltfBuilder.hpp"
#include "TestData.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/SceneLoader.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cfloat>
#include <chrono>
#include <cmath>
#include <csignal>
#include <fstream>
#include <limits>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

using namespace spatter;
using ::testing::HasSubstr;

namespace {

// A static box [-0.5, 0.5]^3 (its render mesh is its collision mesh: h = 0) and a dynamic box at x = 3.
Scene boxes() {
    Scene s;
    s.source = "test:boxes";
    SceneObject still;
    still.name = "still";
    still.mesh = shareMesh(makeBox(glm::vec3(0.5f), 1));
    s.objects.push_back(still);
    SceneObject moving = still;
    moving.name = "moving";
    moving.dynamic = true;
    moving.transform = glm::translate(glm::dmat4(1.0), glm::dvec3(3.0, 0.0, 0.0));
    s.objects.push_back(moving);
    return s;
}

DecalSystem makeSystem(const DecalSettings& settings = {}) {
    Result<DecalSystem> sys = DecalSystem::create(boxes(), settings);
    EXPECT_TRUE(sys) << sys.error();
    return std::move(sys).value();
}

DecalType namedType(const char* name) {
    DecalType t;
    t.name = name;
    return t;
}

const Ray kAtStill{{0.1, 0.2, 5.0}, {0.0, 0.0, -1.0}};

void expectConsistent(const DecalStats& st) {
    EXPECT_EQ(st.placed, st.alive - st.fading + st.evicted + st.expired + st.removed)
        << "placed " << st.placed << " alive " << st.alive << " fading " << st.fading << " evicted "
        << st.evicted << " expired " << st.expired << " removed " << st.removed;
}

// The scene of fuzz_spawn: a floor, a static sphere, a dynamic crate, a dynamic non-receiver and a
// dynamic scaled sphere.
Scene fuzzSpawnScene() {
    Scene s;
    s.source = "fuzz:spawn";
    const glm::dmat4 id(1.0);
    s.objects.push_back(makeSceneObject("floor", makeBox(glm::vec3(10.0f, 0.1f, 10.0f), 2),
                                        glm::translate(id, glm::dvec3(0.0, -0.1, 0.0))));
    s.objects.push_back(
        makeSceneObject("pillar", makeSphere(1.0f, 8, 12), glm::translate(id, glm::dvec3(3, 1, 0))));
    s.objects.push_back(
        makeSceneObject("crate", makeBox(glm::vec3(0.5f), 1), glm::translate(id, glm::dvec3(0, 1, 0)), true));
    s.objects.push_back(makeSceneObject("ghost", makeBox(glm::vec3(0.5f), 1),
                                        glm::translate(id, glm::dvec3(-3, 1, 0)), true));
    s.objects.back().receivesDecals = false;
    s.objects.push_back(
        makeSceneObject("ball", makeSphere(0.5f, 6, 8),
                        glm::scale(glm::translate(id, glm::dvec3(0, 1, 3)), glm::dvec3(1, 2, 0.5)), true));
    return s;
}

} // namespace

// fuzz_spawn: depthMargin 0 on a collision mesh with h = 0 made decals of half-depth 0, boxes the
// renderer cannot invert.
TEST(FuzzRegression, ZeroDepthMarginOnAnExactMeshIsRejectedNotDegenerate) {
    DecalSettings settings;
    settings.depthMargin = 0.0f;
    DecalSystem sys = makeSystem(settings);
    const uint16_t flat = sys.registerType(namedType("flat")).value();
    DecalType thick = namedType("thick");
    thick.halfDepth = 0.05f;
    const uint16_t deep = sys.registerType(thick).value();

    const SpawnResult r = sys.spawn(kAtStill, flat);
    EXPECT_EQ(r.status, SpawnStatus::InvalidArgument);
    EXPECT_THAT(r.reason, HasSubstr("degenerate"));
    EXPECT_TRUE(sys.decals().empty());
    EXPECT_EQ(sys.stats().rejected[size_t(SpawnStatus::InvalidArgument)], 1u);
    EXPECT_EQ(sys.spawnAttached(0, {0.5f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, flat).status,
              SpawnStatus::InvalidArgument);
    EXPECT_EQ(sys.spawnAt({0.0, 0.5, 0.0}, {0.0, 1.0, 0.0}, flat).status, SpawnStatus::InvalidArgument);

    // The rejections drew no random number: the next decal is the first decal of a fresh system.
    ASSERT_TRUE(sys.spawn(kAtStill, deep).placed());
    DecalSystem fresh = makeSystem(settings);
    (void)fresh.registerType(namedType("flat"));
    const uint16_t freshDeep = fresh.registerType(thick).value();
    ASSERT_TRUE(fresh.spawn(kAtStill, freshDeep).placed());
    EXPECT_EQ(sys.decals()[0].id, fresh.decals()[0].id);
    EXPECT_GT(sys.decals()[0].halfDepth, 0.0f);
}

// fuzz_spawn: type sizes at the float limits made decals of size 0 or infinity.
TEST(FuzzRegression, TypeSizesAtTheFloatLimitsAreRejectedNotDegenerate) {
    DecalSystem sys = makeSystem();
    DecalType tiny = namedType("tiny");
    tiny.size = {FLT_MIN, FLT_MIN}; // its half-depth, a quarter of that, would be denormal
    DecalType huge = namedType("huge");
    huge.size = {FLT_MAX, FLT_MAX};
    huge.sizeJitter = 0.5f;
    for (const DecalType& t : {tiny, huge}) {
        const Result<uint16_t> type = sys.registerType(t);
        ASSERT_TRUE(type) << type.error();
        const SpawnResult r = sys.spawn(kAtStill, type.value());
        EXPECT_EQ(r.status, SpawnStatus::InvalidArgument) << t.name;
        EXPECT_THAT(r.reason, HasSubstr("degenerate"));
    }
    EXPECT_TRUE(sys.decals().empty());
    expectConsistent(sys.stats());
}

// fuzz_spawn: a ray from near the double limit towards the world clipped to an infinite distance and
// reached Embree with an infinite origin, where an assertion (enabled in Debian's libembree3) aborted
// the process.
TEST(FuzzRegression, RayFromNearTheDoubleLimitMissesInsteadOfAborting) {
    DecalSystem sys = makeSystem();
    const uint16_t type = sys.registerType(namedType("hole")).value();
    const Ray far{{1.211159206544672e+308, 1.0358636109513978e+308, 1.6356596673513972e+308},
                  {-2.6949186889728738, -2.3048730417068293, -3.6394635672381788}};
    EXPECT_FALSE(sys.world().intersect(far));
    EXPECT_FALSE(sys.world().intersectBatch({far, far})[1]);
    EXPECT_EQ(sys.spawn(far, type).status, SpawnStatus::Missed);
    std::vector<SpawnResult> results;
    sys.spawnBatch({far, kAtStill}, type, results);
    ASSERT_EQ(results.size(), 2u);
    EXPECT_EQ(results[0].status, SpawnStatus::Missed);
    EXPECT_TRUE(results[1].placed());
    // fuzz_spawn, second finding: from 1e154 the distance is representable but cancellation leaves a
    // start point beyond the float range, which Embree's assertion rejected in the same way.
    const Ray cancelled{{1e154, 1e154, 1e154},
                        {-1.1754943508222876e+116, -1.1754943508222876e+116, -1.1754943508222876e+116}};
    EXPECT_FALSE(sys.world().intersect(cancelled));
    EXPECT_EQ(sys.spawn(cancelled, type).status, SpawnStatus::Missed);
    sys.spawnBatch({cancelled, far, cancelled}, type, results);
    ASSERT_EQ(results.size(), 3u);
    for (const SpawnResult& r : results)
        EXPECT_EQ(r.status, SpawnStatus::Missed);
    // fuzz_spawn, third finding: a start point inside the float range but beyond Embree's limit of
    // +-1.844e18 for ray origins hit the same assertion.
    const Ray beyondEmbree{{6.0853498172423995e+307, -14.763746247996906, 3.4028234663852886e+38},
                           {-3.0065622876257777e-16, 7.4109846876186982e-323, -1.6812181736033969e-285}};
    EXPECT_FALSE(sys.world().intersect(beyondEmbree));
    EXPECT_EQ(sys.spawn(beyondEmbree, type).status, SpawnStatus::Missed);
    // Far, but with a representable distance: still traced.
    const Ray distant{{0.1, 0.2, 1e9}, {0.0, 0.0, -1.0}};
    EXPECT_TRUE(sys.spawn(distant, type).placed());
}

// fuzz_spawn (the stats invariant): a decal fading out after an eviction was counted again when it
// was removed, and fading decals were counted as both alive and evicted.
TEST(FuzzRegression, FadingDecalsAreCountedOnce) {
    DecalSettings settings;
    settings.budget = 1;
    settings.policy = LimitPolicy::FadeOldest;
    DecalSystem sys = makeSystem(settings);
    DecalType slow = namedType("slow");
    slow.fadeOutTime = 10.0f;
    const uint16_t type = sys.registerType(slow).value();

    const SpawnResult first = sys.spawn(kAtStill, type);
    ASSERT_TRUE(first.placed());
    ASSERT_TRUE(sys.spawn(kAtStill, type).placed()); // evicts the first: it fades
    EXPECT_EQ(sys.stats().evicted, 1u);
    EXPECT_EQ(sys.stats().fading, 1u);
    EXPECT_EQ(sys.stats().alive, 2u);
    expectConsistent(sys.stats());

    EXPECT_TRUE(sys.remove(first.handle)); // removing the fading one does not count it again
    EXPECT_EQ(sys.stats().removed, 0u);
    EXPECT_EQ(sys.stats().fading, 0u);
    expectConsistent(sys.stats());

    // On the dynamic object: removeObject takes a fading and a live decal.
    const Ray atMoving{{3.0, 0.1, 5.0}, {0.0, 0.0, -1.0}};
    ASSERT_TRUE(sys.spawn(atMoving, type).placed());
    ASSERT_TRUE(sys.spawn(atMoving, type).placed());
    EXPECT_EQ(sys.stats().fading, 2u);
    expectConsistent(sys.stats());
    ASSERT_TRUE(sys.removeObject(1).ok());
    EXPECT_EQ(sys.stats().removed, 1u);
    EXPECT_EQ(sys.stats().fading, 1u);
    expectConsistent(sys.stats());

    ASSERT_TRUE(sys.update(11.0).ok()); // the last fading decal ends
    EXPECT_EQ(sys.stats().fading, 0u);
    EXPECT_EQ(sys.stats().alive, 0u);
    expectConsistent(sys.stats());
}

// --- mesh files (fuzz_mesh_file) ---------------------------------------------------------------------

namespace {

// Loads `bytes` saved as NAME in a scratch directory, in a child process first: the error, or
// "finished" when it loads; "killed: ..." when the child does not end within 20 s or dies.
std::string loadInChild(const std::string& name, const std::string& bytes) {
    const std::string path = test::scratchDir("fuzz-mesh") + "/" + name;
    std::ofstream(path, std::ios::binary) << bytes;
    const pid_t pid = fork();
    if (pid == 0) {
        (void)loadScene(path);
        _exit(0);
    }
    int status = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (waitpid(pid, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > deadline) {
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            return "killed: still loading after 20 s";
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return "killed: the loader crashed";
    Result<Scene> scene = loadScene(path);
    return scene ? "finished" : scene.error();
}

} // namespace

// fuzz_mesh_file: OpenMesh's PLY header parser loops forever on a header without end_header.
TEST(FuzzRegression, PlyHeaderWithoutEndHeaderIsRejectedInsteadOfHanging) {
    EXPECT_THAT(loadInChild("open.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n0 0 0\n"),
                HasSubstr("no end_header"));
}

// fuzz_mesh_file: the same loop once any header read fails (here an element count that is no number).
TEST(FuzzRegression, PlyHeaderWithABadCountIsRejectedInsteadOfHanging) {
    EXPECT_THAT(loadInChild("count.ply", "ply\nformat ascii 1.0\nelement vertex f<\nproperty float x\n"
                                         "end_header\n0\n"),
                HasSubstr("element without a name and a count"));
    EXPECT_THAT(loadInChild("version.ply", "ply\nformat ascii one\nelement vertex 1\nend_header\n"),
                HasSubstr("no format line"));
}

// Found reading the PLY reader after that finding: a property before any element takes the last
// element of an empty list; faces of billions of corners; binary faces past the end of the data.
TEST(FuzzRegression, PlyBodiesTheReaderCannotTakeAreRejected) {
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                               "end_header\n0 0 0\n1 0 0\n0 1 0\n";
    EXPECT_THAT(loadInChild("orphan.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n"),
                HasSubstr("property before any element"));
    EXPECT_THAT(loadInChild("corners.ply", header + "4000000000 0 1 2\n"), HasSubstr("corners"));
    EXPECT_THAT(loadInChild("short.ply", header + "3 0 1\n"), HasSubstr("truncated"));
    EXPECT_EQ(loadInChild("good.ply", header + "3 0 1 2\n"), "finished");
    EXPECT_THAT(loadInChild("huge.ply", "ply\nformat ascii 1.0\nelement vertex 4294967295\nend_header\n"),
                HasSubstr("more than the file has bytes"));

    std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                         "property float y\nproperty float z\nelement face 2\n"
                         "property list uchar int vertex_indices\nend_header\n";
    const float vertices[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    binary.append(reinterpret_cast<const char*>(vertices), sizeof vertices);
    const int32_t face[3] = {0, 1, 2};
    binary += char(3);
    binary.append(reinterpret_cast<const char*>(face), sizeof face);
    EXPECT_THAT(loadInChild("cut.ply", binary), HasSubstr("truncated")); // the second face is missing
    binary += char(3);
    binary.append(reinterpret_cast<const char*>(face), sizeof face);
    EXPECT_EQ(loadInChild("whole.ply", binary), "finished");
}

// fuzz_mesh_file: OpenMesh's OBJ reader stores a corner's texture coordinate and normal at its vertex
// without checking the vertex index: a write out of bounds.
TEST(FuzzRegression, ObjCornerPastTheVerticesIsRejectedNotWrittenOutOfBounds) {
    EXPECT_THAT(loadInChild("none.obj", "vt 0 1\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\n"),
                HasSubstr("refers to vertex 1 of 0"));
    EXPECT_THAT(loadInChild("past.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 1\nf 1/1 2/1 4/1\n"),
                HasSubstr("refers to vertex 4 of 3"));
    EXPECT_THAT(loadInChild("back.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n"),
                HasSubstr("vertex 0 of 3"));
    EXPECT_THAT(loadInChild("word.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf x/1 2/1 3/1\n"),
                HasSubstr("no vertex index"));
    EXPECT_EQ(loadInChild("fine.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 1\nf 1/1 2/1 -1/1 # comment\n"),
              "finished");
}

// fuzz_mesh_file: a face count of -4 (4294967292) in an OFF header made OpenMesh reserve 16 GiB.
TEST(FuzzRegression, OffCountsBeyondTheFileAreRejectedNotReserved) {
    EXPECT_THAT(loadInChild("faces.off", "OFF\n4 -4 0\n0 0 0\n1 0 1\n"),
                HasSubstr("more than the file has bytes"));
    EXPECT_THAT(loadInChild("corners.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n100000 0 1 2\n"),
                HasSubstr("corners"));
    EXPECT_THAT(loadInChild("cut.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), HasSubstr("truncated"));
    EXPECT_EQ(loadInChild("fine.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), "finished");
}

TEST(FuzzRegression, BurstsFromInsideABoxHitItsFarFacesAsSingleRaysDo) {
    // Embree's coherent (frustum) packet traversal skipped the far faces of the floor for these
    // bursts, which start on its top face or inside it; alone, each ray hits the face at z = 10.
    Scene s;
    s.source = "test:floor";
    s.objects.push_back(makeSceneObject("floor", makeBox(glm::vec3(10.0f, 0.1f, 10.0f), 2),
                                        glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, -0.1, 0.0))));
    Result<CollisionWorld> w = CollisionWorld::build(s);
    ASSERT_TRUE(w) << w.error();
    for (const double y : {1e-45, -0.05}) {
        const glm::dvec3 o(1e-45, y, 1e-45);
        const std::vector<Ray> rays = {
            {o, {-6.2232053867062281e-39, -7.3068642468443462e-39, -6.2232053867062281e-39}},
            {o, {-6.2232053867062281e-39, -7.3068642468443462e-39, 1.1438830171484802e-08}},
            {o, {-6.2232053867062281e-39, -1.626851594628444e-10, 1.1438830171484802e-08}},
            {o, {-6.2232053867062163e-39, -1.626851594628444e-10, 1.1438830171484802e-08}},
            {o, {-6.2232053867062046e-39, -1.626851594628444e-10, 1.1438830171484802e-08}},
            {o, {-6.2232053867061928e-39, 3.8976905463837465e-11, 1.1287004760204579e-08}},
            {o, {-0.3, -0.01, 1.0}},
            {o, {-0.31, -0.012, 1.0}},
            {o, {-0.29, -0.009, 1.0}},
            {o, {-0.3, -0.011, 0.99}},
        };
        const std::vector<std::optional<Hit>> batch = w->intersectBatch(rays);
        ASSERT_EQ(batch.size(), rays.size());
        for (size_t i = 0; i < rays.size(); ++i) {
            const std::optional<Hit> single = w->intersect(rays[i]);
            ASSERT_EQ(single.has_value(), batch[i].has_value()) << "ray " << i << ", origin y " << y;
            if (!single) continue;
            EXPECT_EQ(single->t, batch[i]->t) << "ray " << i << ", origin y " << y;
            EXPECT_EQ(single->primitive, batch[i]->primitive) << "ray " << i << ", origin y " << y;
            if (i != 0 && i != 5) {
                EXPECT_NEAR(batch[i]->position.z, 10.0, 1e-9) << "ray " << i << ", origin y " << y;
            }
        }
    }
}

// fuzz_gltf, once it traced what it loads: a node matrix whose bottom row is not (0, 0, 0, 1) passed
// validateScene, and then CollisionWorld::build refused the scene, so a file every loader took could
// not be traced by any tool. validateScene now refuses such a transform, naming the object.
TEST(FuzzRegression, NodeMatrixThatIsNotAffineIsRejectedWhenLoading) {
    test::GltfBuilder g;
    const Mesh box = makeBox(glm::vec3(1.0f), 1);
    g.addMesh(box.positions, box.indices);
    g.push("nodes", {{"children", {1}}, {"matrix", {1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 2}}});
    g.push("nodes", {{"mesh", 0}});
    g.doc["scenes"] = {{{"nodes", {0}}}};
    g.doc["scene"] = 0;
    const Result<Scene> scene = loadScene(g.writeGltf(test::scratchDir("fuzz-affine"), "projective"));
    ASSERT_FALSE(scene.ok());
    EXPECT_THAT(scene.error(), HasSubstr("transform is not affine"));
}

// fuzz_spawn, once its rays aimed at moved objects: a type as wide as float allows (FLT_MAX)
// attached to a scaled sphere gave a decal whose object-space box was sound but whose world box,
// rounded back, overflowed to infinity. Such a spawn is now degenerate (InvalidArgument).
TEST(FuzzRegression, DecalWhoseWorldBoxOverflowsIsRejectedAsDegenerate) {
    const Scene s = fuzzSpawnScene();
    DecalSettings settings;
    settings.seed = 11732013733571554261ull;
    settings.cellSize = 3.56594253f;
    settings.maxPerCell = 5;
    settings.budget = 6;
    settings.maxPerObject = 10;
    settings.depthMargin = 0.25f;
    settings.idSeparation = 5.2772501708131694;
    for (bool rotate : {false, true}) {
        Result<DecalSystem> sys = DecalSystem::create(s, settings);
        ASSERT_TRUE(sys) << sys.error();
        DecalType t = namedType("t0");
        t.size = glm::vec2(1.943503f, FLT_MAX);
        t.maxAngleDeg = 86.689056f;
        t.fadeOutTime = 3.052714f;
        t.randomRotation = rotate;
        const uint16_t type = sys->registerType(t).value();
        const SpawnResult r = sys->spawnAttached(4, glm::vec3(0.34855151f, 0.23637171f, -0.2709063f),
                                                 glm::vec3(-1.0f, 1.0f, -0.1294175f), type);
        if (r.placed()) {
            const WorldDecal w = sys->worldBox(*sys->get(r.handle));
            EXPECT_TRUE(std::isfinite(w.size.x) && std::isfinite(w.size.y) && std::isfinite(w.halfDepth));
        } else {
            EXPECT_EQ(r.status, SpawnStatus::InvalidArgument) << r.reason;
            EXPECT_THAT(r.reason, HasSubstr("degenerate"));
        }
    }
}

// fuzz_gltf, once it traced what it loads: a dynamic node and its dynamic child whose collision meshes
// were single points at one place (indices read from a float buffer, all 0) gave the world a top
// level whose every instance box was that point, and Embree's BVH builder asserted
// (diag[dim] > 0). An object whose collision bounds are a point, or too small for float at their
// place, is now left out of the trace (TraceTransform.hpp, rule 4).
TEST(FuzzRegression, CollisionMeshesThatAreOnePointAreLeftOutInsteadOfAborting) {
    Scene s;
    s.source = "fuzz:points";
    Mesh point;
    point.positions = {glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)};
    point.indices = {0, 0, 0, 0, 0, 0};
    computeNormals(point);
    s.objects.push_back(makeSceneObject("root", point, glm::dmat4(1.0), true));
    s.objects.push_back(makeSceneObject("child", point, glm::dmat4(1.0), true));
    Result<CollisionWorld> w = CollisionWorld::build(s);
    ASSERT_TRUE(w) << w.error();
    ASSERT_EQ(w->warnings().size(), 2u);
    EXPECT_THAT(w->warnings()[0], HasSubstr("collision mesh is a single point"));
    EXPECT_FALSE(w->intersect(Ray{{0.0, 0.0, 5.0}, {0.0, 0.0, -1.0}}));
    EXPECT_FALSE(w->intersectBatch({Ray{{0.0, 0.0, 5.0}, {0.0, 0.0, -1.0}}})[0]);
}

// fuzz_spawn, once it drew transforms singular in single precision: the crate turned so that its
// first and third columns differ by factors 1 + k 2^-40 (equal in float, invertible in double), then
// a shot through its place. Embree got the singular float matrix, inverted it and asserted on the NaN
// rays (ray.valid()). The crate now leaves the trace and the shot goes on.
TEST(FuzzRegression, CrateTurnedSingularInFloatLeavesTheTraceInsteadOfAborting) {
    DecalSettings settings;
    settings.seed = 4425030522700391117ull;
    settings.cellSize = 3.68939376f;
    settings.maxPerCell = 3;
    settings.budget = 14;
    settings.maxPerObject = 14;
    settings.policy = LimitPolicy::Reject;
    settings.idSeparation = 1.0;
    Result<DecalSystem> sys = DecalSystem::create(fuzzSpawnScene(), settings);
    ASSERT_TRUE(sys) << sys.error();
    const glm::dmat4 m(glm::dvec4(0.74245116792759003, 0.14805637757023157, 0.65333419649299707, 0.0),
                       glm::dvec4(-0.6624898728902533, 0.30693617441022286, 0.68329887542441725, 0.0),
                       glm::dvec4(0.74245116792691479, 0.14805637756996226, 0.65333419649121449, 0.0),
                       glm::dvec4(10.566416382088232, -6.6054295593395072, 11.26155006451685, 1.0));
    const Result<TransformUpdate> moved = sys->setTransform(2, m);
    ASSERT_TRUE(moved) << moved.error();
    EXPECT_FALSE(moved->traced);
    EXPECT_THAT(moved->warning, HasSubstr("singular in single precision"));
    const uint16_t type = sys->registerType(namedType("hole")).value();
    const Ray shot{{-13.715689917364514, -13.924088494789226, 1.1754943508222875e-38},
                   {45.11292520850408, 13.905771574806389, 19.806600449248723}};
    const SpawnResult r = sys->spawn(shot, type);
    EXPECT_NE(r.status, SpawnStatus::InvalidRay) << r.reason;
    std::vector<SpawnResult> results;
    sys->spawnBatch({shot, shot, shot, shot, shot}, type, results);
    EXPECT_EQ(results.size(), 5u);
    const std::optional<Hit> aimed = sys->world().intersect(Ray{{10.5, 10.0, 11.2}, {0.0, -1.0, 0.0}});
    EXPECT_TRUE(!aimed || aimed->object != 2u);
}
