// The proxy-versus-render mismatch tests: every shared mesh and builtin:gallery at 0.1%, 0.5% and 2%
// of each object's bounding diagonal (docs/ACCURACY.md holds the figures and how they were made).

#include "Mismatch.hpp"
#include "AccuracyReport.hpp"
#include "TestData.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/SceneLoader.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <string>
#include <tuple>

using namespace spatter;
using namespace spatter::test;

namespace {

using Clock = std::chrono::steady_clock;

struct MeshCase {
    const char* label;
    const char* source; // builtin:... or a path under the shared data
};

const MeshCase kMeshes[] = {
    {"fandisk", "meshes/fandisk.obj"},
    {"rocker-arm", "meshes/rocker-arm.obj"},
    {"stanford-bunny", "meshes/stanford-bunny.obj"},
    {"Box", "gltf/Box/Box.gltf"},
    {"Duck", "gltf/Duck/Duck.gltf"},
    {"DamagedHelmet", "gltf/DamagedHelmet/DamagedHelmet.glb"},
    {"kenney-platform-large-grass", "gltf/KenneyFPS/models/platform-large-grass.glb"},
    {"kenney-wall-high", "gltf/KenneyFPS/models/wall-high.glb"},
    {"gallery", "builtin:gallery"},
};
const float kTolerances[] = {0.001f, 0.005f, 0.02f};

// Rays per case: split over the receivers, at least kMinRaysPerObject each.
constexpr uint32_t kRaysPerCase = 4000;
constexpr uint32_t kMinRaysPerObject = 500;

// One cache directory per process: objects with the same mesh and settings (the gallery's targets)
// build their proxy once. Removed at exit.
struct ProxyCacheDir {
    std::string path = scratchDir("accuracy-proxies");
    ~ProxyCacheDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
};
const std::string& proxyCacheDir() {
    static const ProxyCacheDir dir;
    return dir.path;
}

// The settings the proxies of a case are built with: the builder's defaults with a relative
// tolerance, the proxies spatter-place --proxy TOL builds.
ProxySettings caseSettings(float tolerance) {
    ProxySettings s;
    s.tolerance = tolerance;
    s.toleranceRelative = true;
    s.cacheDirectory = proxyCacheDir();
    return s;
}

const char* kindOf(const Proxy& p) {
    return p.source == ProxySource::Simplified ? proxyBackendName(p.backend)
           : p.source == ProxySource::OwnMesh  ? "own mesh"
                                               : "collider";
}

struct Built {
    std::vector<std::shared_ptr<const Proxy>> proxies;
    std::vector<ProxyFacts> facts;
};

// The proxy of every receiver of `scene`, as spatter-place --proxy TOL builds them.
Result<Built> buildProxies(const Scene& scene, const ProxySettings& settings) {
    Built b;
    b.proxies.resize(scene.objects.size());
    b.facts.resize(scene.objects.size());
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& o = scene.objects[i];
        if (!o.receivesDecals) continue;
        Result<Proxy> p = buildProxy(*o.mesh, settings, o.collider ? &*o.collider : nullptr);
        if (!p) return fail("proxy of '" + o.name + "': " + p.error());
        b.facts[i] = ProxyFacts{kindOf(p.value()), p->toleranceMet};
        b.proxies[i] = shareProxy(std::move(p).value());
    }
    return b;
}

size_t receiverCount(const Scene& scene) {
    size_t receivers = 0;
    for (const SceneObject& o : scene.objects)
        receivers += o.receivesDecals ? 1 : 0;
    return receivers;
}

// Checks the guarantees on every object of a measured case.
void expectGuarantees(const std::vector<ObjectMismatch>& objects) {
    size_t rays = 0, hits = 0;
    for (const ObjectMismatch& o : objects) {
        SCOPED_TRACE("object '" + o.name + "', h = " + std::to_string(o.errorBound));
        rays += o.rays;
        hits += o.proxyHits;
        EXPECT_GT(o.proxyHits, 50u) << "too few rays reach the object to measure it";
        EXPECT_EQ(o.hitsBeyondBound, 0u)
            << "largest proxy-hit distance to the render surface " << o.maxHitDistance;
        EXPECT_EQ(o.decals, o.proxyHits) << "every proxy hit places a decal (no limits, max angle 90)";
        EXPECT_EQ(o.tightDecals, o.proxyHits);
        EXPECT_EQ(o.decalsHolding, o.decals);
        EXPECT_EQ(o.tightHolding, o.tightDecals)
            << "largest |z| / half_depth " << o.tightDepthUse << ", largest lateral use " << o.lateralUse;
        // Decals at least 4h wide (see MismatchSettings) with the default depth margin (0.25 of the
        // size): half_depth >= 2h, so the nearest render point lies in the inner half of the box, where
        // the renderer's default depth fade has not started.
        EXPECT_LE(o.defaultDepthUse, 0.5 + 1e-4);
        // Projected along the shot: the render hit of the same shot, wherever it lies within the
        // half-depth of the decal's plane, is on the box's axis (the footprint centred on it) but for
        // the slope's half-float rounding; it lies farther only where the proxy is not the decal's
        // plane across the shot (edges, silhouettes), for at most 3% of the decals.
        EXPECT_LE(o.shotLateralUse, 0.005);
        EXPECT_GE(double(o.shotInSlab), 0.97 * double(o.shotDecals))
            << o.shotInSlab << " of " << o.shotDecals << " render hits within the half-depth";
    }
    EXPECT_GT(hits, rays / 2) << "most rays must hit for the distributions to mean something";
}

// With the render mesh as its own proxy both worlds hold the same triangles: the same hits.
void expectIdenticalHits(const std::vector<ObjectMismatch>& objects) {
    for (const ObjectMismatch& o : objects) {
        SCOPED_TRACE("object '" + o.name + "'");
        EXPECT_EQ(o.errorBound, 0.0);
        EXPECT_EQ(o.disagreements(), 0u);
        const Distribution offsets = summarize(o.offsets), angles = summarize(o.angles);
        EXPECT_LE(offsets.max, 1e-9);
        EXPECT_LE(angles.max, 1e-6);
    }
}

using CaseParam = std::tuple<size_t, size_t>; // mesh, tolerance

class ProxyVersusRender : public ::testing::TestWithParam<CaseParam> {};

TEST_P(ProxyVersusRender, ProxyHitsStayWithinHAndDecalBoxesHoldTheRenderSurface) {
    const MeshCase& mesh = kMeshes[std::get<0>(GetParam())];
    const float tolerance = kTolerances[std::get<1>(GetParam())];
    std::string source = mesh.source;
    if (source.rfind("builtin:", 0) != 0) {
        SPATTER_REQUIRE_SHARED(path, mesh.source);
        source = path;
    }
    Result<Scene> scene = loadScene(source);
    ASSERT_TRUE(scene) << scene.error();

    const Clock::time_point start = Clock::now();
    const size_t receivers = receiverCount(scene.value());
    Result<Built> built = buildProxies(scene.value(), caseSettings(tolerance));
    ASSERT_TRUE(built) << built.error();
    const Clock::time_point builtAt = Clock::now();

    MismatchSettings ms;
    ms.raysPerObject =
        std::max<uint32_t>(kMinRaysPerObject, kRaysPerCase / uint32_t(std::max<size_t>(receivers, 1)));
    Result<std::vector<ObjectMismatch>> m = measureMismatch(scene.value(), built->proxies, ms);
    ASSERT_TRUE(m) << m.error();
    const Clock::time_point done = Clock::now();

    expectGuarantees(m.value());
    bool allOwn = true;
    for (const std::shared_ptr<const Proxy>& p : built->proxies)
        allOwn = allOwn && (!p || p->source == ProxySource::OwnMesh);
    if (allOwn) expectIdenticalHits(m.value());

    CaseReport report;
    report.mesh = mesh.label;
    report.tolerance = tolerance;
    report.objects = std::move(m).value();
    report.proxies = std::move(built->facts);
    report.buildSeconds = std::chrono::duration<double>(builtAt - start).count();
    report.measureSeconds = std::chrono::duration<double>(done - builtAt).count();
    report.perObject = report.objects.size() > 1;
    std::printf("%s", accuracyTables({report}).c_str());
    recordCase(std::move(report));
}

std::string caseName(const ::testing::TestParamInfo<CaseParam>& info) {
    std::string name = kMeshes[std::get<0>(info.param)].label;
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    const char* tol[] = {"0_1pct", "0_5pct", "2pct"};
    return name + "_" + tol[std::get<1>(info.param)];
}

INSTANTIATE_TEST_SUITE_P(SharedMeshes, ProxyVersusRender,
                         ::testing::Combine(::testing::Range<size_t>(0, std::size(kMeshes)),
                                            ::testing::Range<size_t>(0, std::size(kTolerances))),
                         caseName);

// A bumpy sphere (no shared data needed), as one static object.
Scene bumpySphereScene() {
    Mesh m = makeSphere(1.0f, 48, 96);
    displace(m, [](const glm::vec3& p, const glm::vec3&) {
        return 0.03f * std::sin(9.0f * p.x) * std::cos(7.0f * p.y);
    });
    Scene s;
    s.source = "test:bumpy-sphere";
    SceneObject o;
    o.name = "sphere";
    o.mesh = shareMesh(std::move(m));
    s.objects.push_back(std::move(o));
    return s;
}

TEST(Mismatch, FlagsProxyHitsAndDecalsWhenTheBoundIsUnderstated) {
    const Scene scene = bumpySphereScene();
    ProxySettings s = caseSettings(0.02f);
    s.cacheDirectory.clear();
    Result<Built> built = buildProxies(scene, s);
    ASSERT_TRUE(built) << built.error();
    Proxy proxy = *built->proxies[0];
    ASSERT_EQ(proxy.source, ProxySource::Simplified);
    ASSERT_GT(proxy.errorBound, 0.0);

    MismatchSettings ms;
    ms.raysPerObject = 2000;
    Result<std::vector<ObjectMismatch>> honest = measureMismatch(scene, built->proxies, ms);
    ASSERT_TRUE(honest) << honest.error();
    EXPECT_EQ(honest->at(0).hitsBeyondBound, 0u);
    EXPECT_EQ(honest->at(0).tightHolding, honest->at(0).tightDecals);

    // Claiming a tenth of the real bound: the measurement must catch the proxy hits beyond it, and
    // tight decal boxes that miss the render surface.
    proxy.errorBound *= 0.1;
    built->proxies[0] = shareProxy(proxy);
    Result<std::vector<ObjectMismatch>> understated = measureMismatch(scene, built->proxies, ms);
    ASSERT_TRUE(understated) << understated.error();
    EXPECT_GT(understated->at(0).hitsBeyondBound, 0u);
    EXPECT_LT(understated->at(0).tightHolding, understated->at(0).tightDecals);
    EXPECT_GT(understated->at(0).tightDepthUse, 1.0);
}

TEST(Mismatch, DisagreementsAndOffsetsAreZeroWhenTheRenderMeshIsItsOwnProxy) {
    Scene scene = bumpySphereScene();
    scene.objects[0].mesh = shareMesh(makeSphere(1.0f, 12, 20)); // 440 triangles: below the 512 threshold
    ProxySettings s = caseSettings(0.02f);
    s.cacheDirectory.clear();
    Result<Built> built = buildProxies(scene, s);
    ASSERT_TRUE(built) << built.error();
    ASSERT_EQ(built->proxies[0]->source, ProxySource::OwnMesh);
    Result<std::vector<ObjectMismatch>> m = measureMismatch(scene, built->proxies);
    ASSERT_TRUE(m) << m.error();
    expectGuarantees(m.value());
    expectIdenticalHits(m.value());
}

TEST(Mismatch, SummarizeTakesNearestRankPercentiles) {
    std::vector<double> v;
    for (int i = 200; i >= 1; --i)
        v.push_back(double(i));
    const Distribution d = summarize(v);
    EXPECT_EQ(d.count, 200u);
    EXPECT_EQ(d.p50, 100.0);
    EXPECT_EQ(d.p99, 198.0);
    EXPECT_EQ(d.max, 200.0);
    EXPECT_EQ(summarize({}).count, 0u);
}

} // namespace
