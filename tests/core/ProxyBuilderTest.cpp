#include "spatter/core/ProxyBuilder.hpp"

#include "spatter/core/ProxyCache.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/core/SceneLoader.hpp"

#include "ReferenceGeometry.hpp"
#include "TestData.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>

using namespace spatter;
using namespace spatter::test;
using ::testing::HasSubstr;

namespace {

// An open height field z = amplitude * sin(3x) cos(2y) over [0, 2]^2, n x n quads.
Mesh displacedGrid(uint32_t n, float amplitude) {
    Mesh m;
    for (uint32_t i = 0; i <= n; ++i)
        for (uint32_t j = 0; j <= n; ++j) {
            const float x = 2.0f * float(i) / float(n), y = 2.0f * float(j) / float(n);
            m.positions.push_back({x, y, amplitude * std::sin(3.0f * x) * std::cos(2.0f * y)});
        }
    auto v = [&](uint32_t i, uint32_t j) { return i * (n + 1) + j; };
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; j < n; ++j)
            m.indices.insert(m.indices.end(),
                             {v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j), v(i + 1, j + 1), v(i, j + 1)});
    computeNormals(m);
    return m;
}

// Lower estimate of the one-sided Hausdorff distance from `from` to `to`, by brute force over every
// triangle of `to` (independent of the library's closest-point code).
double bruteOneSided(const Mesh& from, const Mesh& to, size_t samples, uint64_t seed) {
    double worst = 0.0;
    for (const glm::dvec3& p : surfacePoints(from, samples, seed))
        worst = std::max(worst, bruteMeshDistance(p, to));
    return worst;
}

ProxySettings settingsFor(ProxyBackend backend, float tolerance) {
    ProxySettings s;
    s.backend = backend;
    s.tolerance = tolerance;
    return s;
}

void expectValidProxy(const Proxy& p) {
    EXPECT_TRUE(validateMesh(p.mesh).ok()) << validateMesh(p.mesh).error();
    for (const glm::vec3& n : p.mesh.normals)
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-4f);
    EXPECT_EQ(p.proxyTriangles, p.mesh.triangleCount());
    const double measured = std::max(p.proxyToRenderMax, p.renderToProxyMax);
    EXPECT_GE(p.errorBound, measured);
    EXPECT_NEAR(p.samplingMargin, p.errorBound - measured, 1e-12);
    // The certificate refines until h is within the margin (0.05 of the tolerance by default, four times
    // that for a proxy that missed the tolerance) of what it measured, or under the tolerance.
    const double margin = (p.toleranceMet ? 1.0 : 4.0) * ProxySettings{}.marginFraction * p.tolerance;
    EXPECT_LE(p.errorBound, std::max(measured + margin, p.tolerance) * (1.0 + 1e-9) + 1e-9);
}

class ProxyBackends : public ::testing::TestWithParam<ProxyBackend> {};

} // namespace

TEST(ProxyBuilder, SmallMeshIsItsOwnProxy) {
    const Mesh render = box(1.0f);
    Result<Proxy> p = buildProxy(render, ProxySettings{});
    ASSERT_TRUE(p) << p.error();
    EXPECT_EQ(p->source, ProxySource::OwnMesh);
    EXPECT_EQ(p->backend, ProxyBackend::None);
    EXPECT_EQ(p->errorBound, 0.0);
    EXPECT_TRUE(p->toleranceMet);
    EXPECT_EQ(p->mesh.positions, render.positions);
    EXPECT_EQ(p->mesh.indices, render.indices);
    EXPECT_EQ(p->attempts, 0u);
}

TEST(ProxyBuilder, ZeroToleranceKeepsTheRenderMesh) {
    const Mesh render = latLongSphere(1.0f, 30, 40);
    ProxySettings s;
    s.tolerance = 0.0f;
    Result<Proxy> p = buildProxy(render, s);
    ASSERT_TRUE(p) << p.error();
    EXPECT_EQ(p->source, ProxySource::OwnMesh);
    EXPECT_EQ(p->errorBound, 0.0);
    EXPECT_EQ(p->proxyTriangles, render.triangleCount());
}

// A cube of half-size 1 around the unit sphere: the farthest collider points are its corners, at
// sqrt(3) - 1 from the sphere (a little more from the inscribed polyhedron).
TEST(ProxyBuilder, AuthoredColliderIsUsedAsGivenWithItsBoundMeasured) {
    const Mesh render = latLongSphere(1.0f, 40, 60);
    const Mesh collider = box(1.0f);
    Result<Proxy> p = buildProxy(render, ProxySettings{}, &collider);
    ASSERT_TRUE(p) << p.error();
    EXPECT_EQ(p->source, ProxySource::AuthoredCollider);
    EXPECT_EQ(p->mesh.positions, collider.positions);
    EXPECT_EQ(p->mesh.indices, collider.indices);
    const double analytic = std::sqrt(3.0) - 1.0;
    EXPECT_GE(p->errorBound, analytic);
    EXPECT_NEAR(p->proxyToRenderMax, analytic, 0.005);
    EXPECT_LE(p->errorBound, analytic + 0.02);
    EXPECT_FALSE(p->toleranceMet); // 0.5% of the diagonal is far below 0.73
    EXPECT_GE(p->errorBound, bruteOneSided(collider, render, 2000, 5));
    EXPECT_GE(p->errorBound, bruteOneSided(render, collider, 2000, 6));
    expectValidProxy(p.value());
}

TEST_P(ProxyBackends, SimplifiesASphereWithACertifiedBound) {
    const Mesh render = latLongSphere(1.0f, 40, 60, 0.03f);
    Result<Proxy> p = buildProxy(render, settingsFor(GetParam(), 0.01f));
    ASSERT_TRUE(p) << p.error();
    EXPECT_EQ(p->source, ProxySource::Simplified);
    EXPECT_EQ(p->backend, GetParam());
    EXPECT_LT(p->proxyTriangles, render.triangleCount() / 3);
    expectValidProxy(p.value());
    const double brute =
        std::max(bruteOneSided(p->mesh, render, 1500, 1), bruteOneSided(render, p->mesh, 1500, 2));
    const double dense =
        std::max(denseOneSided(p->mesh, render, 100000, 3), denseOneSided(render, p->mesh, 100000, 4));
    EXPECT_GE(p->errorBound, brute);
    EXPECT_GE(p->errorBound, dense);
    EXPECT_TRUE(p->toleranceMet) << "h " << p->errorBound << " tolerance " << p->tolerance;
    EXPECT_LE(p->errorBound, 2.0 * p->tolerance);
    std::printf(
        "[ sphere   ] %s: %zu -> %zu triangles, h %.5f (dense estimate %.5f), tolerance %.5f, %.3f s\n",
        proxyBackendName(GetParam()), p->inputTriangles, p->proxyTriangles, p->errorBound, dense,
        p->tolerance, p->seconds);
}

TEST_P(ProxyBackends, SimplifiesAnOpenDisplacedGridWithACertifiedBound) {
    const Mesh render = displacedGrid(60, 0.1f);
    Result<Proxy> p = buildProxy(render, settingsFor(GetParam(), 0.005f));
    ASSERT_TRUE(p) << p.error();
    EXPECT_EQ(p->source, ProxySource::Simplified);
    EXPECT_LT(p->proxyTriangles, render.triangleCount() / 2);
    expectValidProxy(p.value());
    const double dense =
        std::max(denseOneSided(p->mesh, render, 100000, 3), denseOneSided(render, p->mesh, 100000, 4));
    EXPECT_GE(p->errorBound, dense);
    EXPECT_GE(p->errorBound, bruteOneSided(render, p->mesh, 2000, 9));
    if (p->toleranceMet) {
        EXPECT_LE(p->errorBound, 2.0 * p->tolerance);
    }
    // Open boundaries are kept by default: every border vertex of the grid lies on the proxy (border
    // vertices on a straight stretch may go, as long as the border itself stays).
    Result<ClosestPointQuery> q = ClosestPointQuery::create(p->mesh);
    ASSERT_TRUE(q);
    for (const glm::vec3& v : render.positions)
        if (v.x == 0.0f || v.y == 0.0f || v.x == 2.0f || v.y == 2.0f) {
            EXPECT_LT(q->closest(glm::dvec3(v))->distance, 1e-6) << v.x << " " << v.y;
        }
}

TEST_P(ProxyBackends, RespectsTheTriangleBudget) {
    const Mesh render = latLongSphere(1.0f, 60, 80, 0.05f);
    ProxySettings s = settingsFor(GetParam(), 0.0005f);
    s.maxTriangles = 150;
    Result<Proxy> p = buildProxy(render, s);
    ASSERT_TRUE(p) << p.error();
    EXPECT_LE(p->proxyTriangles, 150u);
    EXPECT_GT(p->proxyTriangles, 0u);
    EXPECT_FALSE(p->toleranceMet);
    expectValidProxy(p.value());
    EXPECT_GE(p->errorBound, denseOneSided(render, p->mesh, 50000, 8));
}

// A budget no simplification reaches without removing every triangle fails: an empty proxy would let
// every shot through.
TEST_P(ProxyBackends, RefusesABudgetThatLeavesNoTriangle) {
    const Mesh render = latLongSphere(1.0f, 60, 80, 0.05f);
    ProxySettings s = settingsFor(GetParam(), 0.01f);
    s.maxTriangles = 1;
    Result<Proxy> p = buildProxy(render, s);
    ASSERT_FALSE(p.ok()) << p->proxyTriangles << " triangles";
    EXPECT_NE(p.error().find("budget of 1 triangles"), std::string::npos) << p.error();
}

TEST_P(ProxyBackends, SurvivesDegenerateInput) {
    Mesh render = latLongSphere(1.0f, 30, 40);
    const uint32_t n = uint32_t(render.positions.size());
    // Duplicate vertices: a copy of a whole band of triangles on its own vertex copies.
    for (size_t t = 100; t < 140; ++t)
        for (int k = 0; k < 3; ++k) {
            render.positions.push_back(render.positions[render.indices[3 * t + size_t(k)]]);
            render.indices.push_back(uint32_t(render.positions.size() - 1));
        }
    // Zero-area triangles: a repeated index and three collinear points.
    render.indices.insert(render.indices.end(), {5, 5, 6});
    render.positions.insert(render.positions.end(), {{2, 0, 0}, {3, 0, 0}, {4, 0, 0}});
    render.indices.insert(render.indices.end(), {n + 120, n + 121, n + 122});
    // Non-manifold edges: two fins on an existing edge (0, 1), one of them sharing its orientation.
    render.positions.push_back({0.2f, 0.3f, 1.4f});
    render.positions.push_back({-0.2f, 0.1f, 1.5f});
    const uint32_t f = uint32_t(render.positions.size() - 2);
    render.indices.insert(render.indices.end(), {0, 1, f, 0, 1, f + 1});
    computeNormals(render);
    ASSERT_TRUE(validateMesh(render).ok()) << validateMesh(render).error();

    ProxySettings s = settingsFor(GetParam(), 0.02f);
    s.smallMeshTriangles = 0;
    Result<Proxy> p = buildProxy(render, s);
    ASSERT_TRUE(p) << p.error();
    expectValidProxy(p.value());
    EXPECT_LT(p->proxyTriangles, render.triangleCount());
    EXPECT_GE(p->errorBound, denseOneSided(render, p->mesh, 50000, 10));
    EXPECT_GE(p->errorBound, denseOneSided(p->mesh, render, 50000, 11));
}

TEST_P(ProxyBackends, SameInputGivesTheSameProxy) {
    const Mesh render = latLongSphere(1.0f, 30, 40, 0.05f);
    Result<Proxy> a = buildProxy(render, settingsFor(GetParam(), 0.01f));
    Result<Proxy> b = buildProxy(render, settingsFor(GetParam(), 0.01f));
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->mesh.positions, b->mesh.positions);
    EXPECT_EQ(a->mesh.indices, b->mesh.indices);
    EXPECT_EQ(a->errorBound, b->errorBound);
}

INSTANTIATE_TEST_SUITE_P(Backends, ProxyBackends,
                         ::testing::Values(ProxyBackend::OpenMesh, ProxyBackend::MeshOpt),
                         [](const ::testing::TestParamInfo<ProxyBackend>& backend) {
                             return backend.param == ProxyBackend::OpenMesh ? std::string("OpenMesh")
                                                                            : std::string("MeshOpt");
                         });

TEST(ProxyBuilder, RejectsNonFinitePositionsWithAClearError) {
    Mesh render = latLongSphere(1.0f, 30, 40);
    render.positions[17].z = std::numeric_limits<float>::quiet_NaN();
    Result<Proxy> p = buildProxy(render, ProxySettings{});
    ASSERT_FALSE(p);
    EXPECT_THAT(p.error(), HasSubstr("render mesh: position 17 is not finite"));

    Mesh collider = box(1.0f);
    collider.positions[2].x = std::numeric_limits<float>::infinity();
    Result<Proxy> c = buildProxy(latLongSphere(1.0f, 30, 40), ProxySettings{}, &collider);
    ASSERT_FALSE(c);
    EXPECT_THAT(c.error(), HasSubstr("authored collider: position 2 is not finite"));
}

TEST(ProxyBuilder, RejectsIndexPastTheVertexCount) {
    Mesh render = latLongSphere(1.0f, 30, 40);
    render.indices[40] = uint32_t(render.positions.size());
    Result<Proxy> p = buildProxy(render, ProxySettings{});
    ASSERT_FALSE(p);
    EXPECT_THAT(p.error(), HasSubstr("render mesh: index 40"));
}

TEST(ProxyBuilder, RejectsInvalidSettings) {
    const Mesh render = latLongSphere(1.0f, 30, 40);
    ProxySettings s;
    s.tolerance = -1.0f;
    EXPECT_THAT(buildProxy(render, s).error(), HasSubstr("tolerance"));
    s = ProxySettings{};
    s.tolerance = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THAT(buildProxy(render, s).error(), HasSubstr("tolerance"));
    s = ProxySettings{};
    s.marginFraction = 1.5f;
    EXPECT_THAT(buildProxy(render, s).error(), HasSubstr("margin fraction"));
    s = ProxySettings{};
    s.backend = ProxyBackend::None;
    EXPECT_THAT(buildProxy(render, s).error(), HasSubstr("backend"));
    s = ProxySettings{};
    s.threads = 17;
    EXPECT_THAT(buildProxy(render, s).error(), HasSubstr("threads 17"));
}

// The proxy, its bound and its drawn normals are the same whatever the number of threads a build
// uses (one: the calling thread alone), so that every machine builds the same: the gallery's pillar
// and a crate, whose certificates cut their hierarchies, and the crate's search from earlier runs.
TEST(ProxyBuilder, SameProxyOnAnyNumberOfThreads) {
    for (const auto& [name, tolerance] :
         {std::pair<const char*, float>{"pillar_2", 0.01f}, {"crate_0", 0.002f}}) {
        const std::shared_ptr<const Mesh> object = galleryMesh(name);
        ASSERT_TRUE(object) << name;
        std::vector<Proxy> built;
        for (const unsigned threads : {1u, 2u, 5u, 16u}) {
            ProxySettings s = settingsFor(ProxyBackend::MeshOpt, tolerance);
            s.threads = threads;
            Result<Proxy> p = buildProxy(*object, s);
            ASSERT_TRUE(p) << p.error();
            built.push_back(std::move(p).value());
        }
        for (const Proxy& p : built) {
            EXPECT_EQ(p.mesh.positions, built[0].mesh.positions) << name;
            EXPECT_EQ(p.mesh.indices, built[0].mesh.indices) << name;
            EXPECT_EQ(p.errorBound, built[0].errorBound) << name;
            EXPECT_EQ(p.proxyToRenderMax, built[0].proxyToRenderMax) << name;
            EXPECT_EQ(p.renderToProxyMax, built[0].renderToProxyMax) << name;
            EXPECT_EQ(p.drawnNormals.packed(), built[0].drawnNormals.packed()) << name;
        }
    }
}

TEST(ProxyBuilder, ProgressReportsFractionsOfTheBuildAndCanCancel) {
    const Mesh render = latLongSphere(1.0f, 40, 60);
    std::set<std::string> stages;
    float last = 0.0f;
    Result<Proxy> p = buildProxy(render, settingsFor(ProxyBackend::MeshOpt, 0.01f), nullptr,
                                 [&](float f, const char* stage) {
                                     EXPECT_GE(f, last) << stage; // the whole build: never going back
                                     EXPECT_LE(f, 1.0f);
                                     last = f;
                                     stages.insert(stage);
                                     return true;
                                 });
    ASSERT_TRUE(p) << p.error();
    EXPECT_EQ(last, 1.0f);
    EXPECT_GT(p->attempts, 1u);
    EXPECT_EQ(stages, (std::set<std::string>{"simplify", "measure"}));
    for (ProxyBackend backend : {ProxyBackend::MeshOpt, ProxyBackend::OpenMesh}) {
        Result<Proxy> cancelled = buildProxy(render, settingsFor(backend, 0.01f), nullptr,
                                             [](float f, const char*) { return f < 0.5f; });
        ASSERT_FALSE(cancelled);
        EXPECT_EQ(cancelled.error(), "cancelled");
    }
}

TEST(ProxyBuilder, AutoIsTheMeshoptimizerSearch) {
    EXPECT_EQ(resolveProxyBackend(ProxyBackend::Auto, 5000, 0.005, 1.0), ProxyBackend::MeshOpt);
    EXPECT_EQ(resolveProxyBackend(ProxyBackend::Auto, 50000, 0.05, 1.0), ProxyBackend::MeshOpt);
    EXPECT_EQ(resolveProxyBackend(ProxyBackend::OpenMesh, 5000, 0.005, 1.0), ProxyBackend::OpenMesh);
    const Mesh render = latLongSphere(1.0f, 30, 40, 0.03f);
    Result<Proxy> p = buildProxy(render, settingsFor(ProxyBackend::Auto, 0.01f));
    Result<Proxy> meshopt = buildProxy(render, settingsFor(ProxyBackend::MeshOpt, 0.01f));
    ASSERT_TRUE(p && meshopt) << p.error();
    EXPECT_TRUE(p->toleranceMet);
    EXPECT_EQ(p->backend, ProxyBackend::MeshOpt);
    EXPECT_EQ(p->mesh.indices, meshopt->mesh.indices);
}

TEST(ProxyBuilder, SecondBuildComesFromTheCacheWithoutSimplifying) {
    const std::string dir = test::scratchDir("proxy-cache-hit");
    const Mesh render = latLongSphere(1.0f, 40, 60, 0.03f);
    ProxySettings s = settingsFor(ProxyBackend::MeshOpt, 0.01f);
    s.cacheDirectory = dir;
    Result<Proxy> first = buildProxy(render, s);
    ASSERT_TRUE(first) << first.error();
    EXPECT_FALSE(first->cached);
    EXPECT_TRUE(std::filesystem::exists(proxyCachePath(dir, proxyCacheKey(render, s, nullptr))));

    std::set<std::string> stages;
    Result<Proxy> second = buildProxy(render, s, nullptr, [&](float, const char* stage) {
        stages.insert(stage);
        return true;
    });
    ASSERT_TRUE(second) << second.error();
    EXPECT_TRUE(second->cached);
    EXPECT_EQ(stages, (std::set<std::string>{"cache"}));
    EXPECT_EQ(second->attempts, first->attempts);
    EXPECT_EQ(second->mesh.positions, first->mesh.positions);
    EXPECT_EQ(second->mesh.normals, first->mesh.normals);
    EXPECT_EQ(second->mesh.indices, first->mesh.indices);
    EXPECT_EQ(second->errorBound, first->errorBound);
    EXPECT_EQ(second->backend, ProxyBackend::MeshOpt);
    EXPECT_LT(second->seconds, first->seconds);

    // Other settings are another entry.
    ProxySettings other = s;
    other.tolerance = 0.02f;
    Result<Proxy> third = buildProxy(render, other);
    ASSERT_TRUE(third);
    EXPECT_FALSE(third->cached);
}

TEST(ProxyBuilder, CorruptCacheEntryIsDetectedAndRebuilt) {
    const std::string dir = test::scratchDir("proxy-cache-corrupt");
    const Mesh render = latLongSphere(1.0f, 40, 60, 0.03f);
    ProxySettings s = settingsFor(ProxyBackend::MeshOpt, 0.01f);
    s.cacheDirectory = dir;
    Result<Proxy> first = buildProxy(render, s);
    ASSERT_TRUE(first) << first.error();
    const std::string path = proxyCachePath(dir, proxyCacheKey(render, s, nullptr));
    const uintmax_t size = std::filesystem::file_size(path);

    auto damage = [&](const std::function<void()>& how) {
        how();
        std::set<std::string> stages;
        Result<Proxy> rebuilt = buildProxy(render, s, nullptr, [&](float, const char* stage) {
            stages.insert(stage);
            return true;
        });
        ASSERT_TRUE(rebuilt) << rebuilt.error();
        EXPECT_FALSE(rebuilt->cached);
        EXPECT_TRUE(stages.count("simplify"));
        ASSERT_FALSE(rebuilt->notes.empty());
        EXPECT_THAT(rebuilt->notes.front(), HasSubstr("corrupt"));
        EXPECT_EQ(rebuilt->mesh.indices, first->mesh.indices);
        EXPECT_EQ(std::filesystem::file_size(path), size); // overwritten with a good entry
        Result<Proxy> again = buildProxy(render, s);
        ASSERT_TRUE(again);
        EXPECT_TRUE(again->cached);
    };
    damage([&] { // flip a byte in the vertex data
        std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(std::streamoff(size / 2));
        f.put(char(0x5a));
    });
    damage([&] { std::filesystem::resize_file(path, size / 3); });
    damage([&] { std::filesystem::resize_file(path, 0); });
}

TEST(ProxyBuilder, HundredThousandTrianglesToOnePercentOnTheFastPath) {
    const Mesh render = latLongSphere(1.0f, 201, 250, 0.05f);
    ASSERT_EQ(render.triangleCount(), 100000u);
    ProxySettings s = settingsFor(ProxyBackend::MeshOpt, 0.05f);
    s.maxTriangles = 1000;
    Result<Proxy> p = buildProxy(render, s);
    ASSERT_TRUE(p) << p.error();
    EXPECT_LE(p->proxyTriangles, 1000u);
    EXPECT_GE(p->proxyTriangles, 500u);
    expectValidProxy(p.value());
    std::printf("[ perf     ] meshopt: %zu -> %zu triangles in %.3f s (h %.5f, tolerance %.5f, %u runs, %zu "
                "samples)\n",
                p->inputTriangles, p->proxyTriangles, p->seconds, p->errorBound, p->tolerance, p->attempts,
                p->samples);
    RecordProperty("seconds", std::to_string(p->seconds));
}

// Over 100,000 triangles the search's runs start from one simplification far below the tolerance;
// the certificate still measures against the render mesh, so the bound holds as ever.
TEST(ProxyBuilder, LargeMeshIsSearchedFromACoarserCopyAndCertifiedAgainstTheRenderMesh) {
    const Mesh render = latLongSphere(1.0f, 241, 250, 0.05f);
    ASSERT_GT(render.triangleCount(), 100000u);
    Result<Proxy> p = buildProxy(render, settingsFor(ProxyBackend::MeshOpt, 0.01f));
    ASSERT_TRUE(p) << p.error();
    EXPECT_EQ(p->source, ProxySource::Simplified);
    EXPECT_TRUE(p->toleranceMet);
    EXPECT_LT(p->proxyTriangles, render.triangleCount() / 10);
    expectValidProxy(p.value());
    const double dense =
        std::max(denseOneSided(p->mesh, render, 50000, 5), denseOneSided(render, p->mesh, 50000, 6));
    EXPECT_GE(p->errorBound, dense);
    EXPECT_LE(p->errorBound, p->tolerance * (1.0 + 1e-9));
    Result<Proxy> again = buildProxy(render, settingsFor(ProxyBackend::MeshOpt, 0.01f));
    ASSERT_TRUE(again);
    EXPECT_EQ(again->mesh.indices, p->mesh.indices);
    EXPECT_EQ(again->errorBound, p->errorBound);
}

// A run above the coarsest one judged within starts from that run's mesh where it left room under the
// tolerance: the gallery's crate, a bevelled cube with flush boards, comes out a box at 2% of its
// diagonal, where runs from the render mesh alone stop at about 50 triangles.
TEST(ProxyBuilder, SearchContinuesFromARunWithRoomLeftUnderTheTolerance) {
    const std::shared_ptr<const Mesh> crate = galleryMesh("crate_0");
    ASSERT_TRUE(crate);
    const Mesh& render = *crate;
    Result<Proxy> p = buildProxy(render, settingsFor(ProxyBackend::MeshOpt, 0.02f));
    ASSERT_TRUE(p) << p.error();
    expectValidProxy(p.value());
    EXPECT_TRUE(p->toleranceMet) << "h " << p->errorBound << " tolerance " << p->tolerance;
    EXPECT_LE(p->proxyTriangles, 16u);
    EXPECT_GE(p->errorBound,
              std::max(denseOneSided(p->mesh, render, 50000, 41), denseOneSided(render, p->mesh, 50000, 42)));
}

TEST(ProxyBuilder, FandiskAtHalfAPercentWithBothBackends) {
    SPATTER_REQUIRE_SHARED(path, "meshes/fandisk.obj");
    Result<Scene> scene = loadScene(path);
    ASSERT_TRUE(scene) << scene.error();
    const Mesh& render = *scene->objects.at(0).mesh;
    for (ProxyBackend backend : {ProxyBackend::MeshOpt, ProxyBackend::OpenMesh}) {
        ProxySettings s = settingsFor(backend, 0.005f);
        if (backend == ProxyBackend::OpenMesh) {
            s.maxAttempts = 1;          // keeps the suite fast
            s.keepSharpFeatures = true; // a CAD part: OpenMesh's one run needs its feature edges marked
        }
        Result<Proxy> p = buildProxy(render, s);
        ASSERT_TRUE(p) << p.error();
        expectValidProxy(p.value());
        EXPECT_LT(p->proxyTriangles, render.triangleCount() / 10);
        if (backend == ProxyBackend::MeshOpt) { // the search's path does not depend on timing
            Result<Proxy> again = buildProxy(render, s);
            ASSERT_TRUE(again);
            EXPECT_EQ(again->mesh.indices, p->mesh.indices);
            EXPECT_EQ(again->errorBound, p->errorBound);
            EXPECT_EQ(again->attempts, p->attempts);
            EXPECT_EQ(again->samples, p->samples);
        }
        const double dense =
            std::max(denseOneSided(p->mesh, render, 100000, 21), denseOneSided(render, p->mesh, 100000, 22));
        EXPECT_GE(p->errorBound, dense);
        EXPECT_LE(p->errorBound, dense + 2.0 * p->samplingMargin);
        std::printf(
            "[ fandisk  ] %s: %zu -> %zu triangles, h %.5f (%.3f%% of the diagonal; dense estimate %.5f), "
            "tolerance %.5f met %d, %u runs, %.3f s\n",
            proxyBackendName(backend), p->inputTriangles, p->proxyTriangles, p->errorBound,
            100.0 * p->errorBound / (p->tolerance / 0.005), dense, p->tolerance, int(p->toleranceMet),
            p->attempts, p->seconds);
    }
}

// The search keeps the coarsest certified proxy: at a tenth of a percent of the diagonal the shared
// scans shrink to a fraction of their triangles, every one certified, and a looser tolerance never
// gives more triangles.
TEST(ProxyBuilder, TenthOfAPercentIsCertifiedWithAFractionOfTheTriangles) {
    for (const auto& [file, fraction] : {std::pair<const char*, double>{"meshes/fandisk.obj", 0.3},
                                         std::pair<const char*, double>{"meshes/rocker-arm.obj", 0.7}}) {
        SPATTER_REQUIRE_SHARED(path, file);
        Result<Scene> scene = loadScene(path);
        ASSERT_TRUE(scene) << scene.error();
        const Mesh& render = *scene->objects.at(0).mesh;
        Result<Proxy> fine = buildProxy(render, settingsFor(ProxyBackend::Auto, 0.001f));
        Result<Proxy> loose = buildProxy(render, settingsFor(ProxyBackend::Auto, 0.002f));
        ASSERT_TRUE(fine && loose) << file;
        expectValidProxy(fine.value());
        EXPECT_TRUE(fine->toleranceMet)
            << file << ": h " << fine->errorBound << " tolerance " << fine->tolerance;
        EXPECT_LT(double(fine->proxyTriangles), fraction * double(render.triangleCount())) << file;
        EXPECT_LE(loose->proxyTriangles, fine->proxyTriangles) << file;
        EXPECT_GE(fine->errorBound, std::max(denseOneSided(fine->mesh, render, 50000, 31),
                                             denseOneSided(render, fine->mesh, 50000, 32)))
            << file;
        std::printf(
            "[ 0.1%%     ] %s: %zu -> %zu triangles (0.2%%: %zu), h %.6f, tolerance %.6f, %u runs, %.3f s\n",
            file, fine->inputTriangles, fine->proxyTriangles, loose->proxyTriangles, fine->errorBound,
            fine->tolerance, fine->attempts, fine->seconds);
    }
}
