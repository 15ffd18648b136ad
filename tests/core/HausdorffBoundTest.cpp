#include "spatter/core/HausdorffBound.hpp"

#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/core/SceneLoader.hpp"

#include "ReferenceGeometry.hpp"
#include "TestData.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>

using namespace spatter;
using namespace spatter::test;
using ::testing::HasSubstr;

namespace {

HausdorffSurface surface(const Mesh& m) {
    Result<HausdorffSurface> s = HausdorffSurface::create(m);
    EXPECT_TRUE(s) << s.error();
    return std::move(s).value();
}

Mesh square(float z, float size) {
    Mesh m;
    m.positions = {{0, 0, z}, {size, 0, z}, {size, size, z}, {0, size, z}};
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

// An n x n grid over the unit square with a bump 0.1 high at (0.43, 0.57), of squared width `width`.
Mesh bumpOverSquare(uint32_t n, float width) {
    Mesh bumpy;
    for (uint32_t i = 0; i <= n; ++i)
        for (uint32_t j = 0; j <= n; ++j) {
            const float x = float(i) / float(n), y = float(j) / float(n);
            const float r2 = (x - 0.43f) * (x - 0.43f) + (y - 0.57f) * (y - 0.57f);
            bumpy.positions.push_back({x, y, 0.1f * std::exp(-r2 / width)});
        }
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; j < n; ++j) {
            const uint32_t v = i * (n + 1) + j;
            bumpy.indices.insert(bumpy.indices.end(), {v, v + n + 1, v + n + 2, v, v + n + 2, v + 1});
        }
    return bumpy;
}

// A meshoptimizer proxy of `render` at `tolerance` of the diagonal (the builder's own bound is not
// used here, only its mesh).
Mesh proxyOf(const Mesh& render, float tolerance) {
    ProxySettings s;
    s.backend = ProxyBackend::MeshOpt;
    s.tolerance = tolerance;
    Result<Proxy> p = buildProxy(render, s);
    EXPECT_TRUE(p) << p.error();
    return p->mesh;
}

} // namespace

TEST(HausdorffBound, ParallelSquaresAreTheirOffsetApart) {
    const HausdorffSurface a = surface(square(0.0f, 1.0f)), b = surface(square(0.25f, 1.0f));
    HausdorffSettings s;
    s.margin = 1e-3;
    Result<HausdorffResult> h = boundHausdorff(a, b, s);
    ASSERT_TRUE(h) << h.error();
    EXPECT_NEAR(h->lower, 0.25, 1e-6);
    EXPECT_GE(h->upper, 0.25);
    EXPECT_LE(h->upper, 0.25 + 1e-6);
    EXPECT_FALSE(h->exceeded);
}

// A bump in the middle of a fine grid over a square of two triangles: the farthest point of the grid
// from the square is the bump's top; the early answer says no below it and yes above it.
TEST(HausdorffBound, BumpOverASquareIsBoundedAndAnsweredEarly) {
    const Mesh bumpy = bumpOverSquare(64, 0.002f);
    const Mesh flat = square(0.0f, 1.0f);
    const HausdorffSurface a = surface(bumpy), b = surface(flat);
    const double dense = std::max(denseOneSided(bumpy, flat, 20000, 1), denseOneSided(flat, bumpy, 20000, 2));
    HausdorffSettings s;
    s.margin = 1e-3;
    Result<HausdorffResult> h = boundHausdorff(b, a, s);
    ASSERT_TRUE(h) << h.error();
    EXPECT_GE(h->upper, dense);
    EXPECT_LE(h->lower, h->upper);
    EXPECT_LE(h->upper, h->lower + s.margin + 1e-9);
    EXPECT_LE(h->upper, dense + s.margin + 1e-9);
    EXPECT_GT(dense, 0.09);

    s.tolerance = 0.09; // below the bump: no
    Result<HausdorffResult> no = boundHausdorff(b, a, s);
    ASSERT_TRUE(no);
    EXPECT_TRUE(no->exceeded);
    EXPECT_FALSE(no->within(s.tolerance));
    EXPECT_GT(no->lower, 0.09);
    s.tolerance = 0.11; // above it: yes, with fewer queries than the sharp bound
    Result<HausdorffResult> yes = boundHausdorff(b, a, s);
    ASSERT_TRUE(yes);
    EXPECT_TRUE(yes->within(s.tolerance));
    EXPECT_GE(yes->upper, dense);
    EXPECT_LE(yes->queries, h->queries);
}

// The bound says where it measured its largest distance: on the bump's top for the sharp bound, and
// a point beyond the tolerance when it stops there (a point of the bumpy grid is its height above
// the square away from it).
TEST(HausdorffBound, ReportsAPointWhereItsLargestDistanceWasMeasured) {
    const HausdorffSurface a = surface(bumpOverSquare(64, 0.002f)), b = surface(square(0.0f, 1.0f));
    HausdorffSettings s;
    s.margin = 1e-3;
    Result<HausdorffResult> sharp = boundOneSided(a, b, s);
    ASSERT_TRUE(sharp) << sharp.error();
    EXPECT_NEAR(sharp->farthest.z, sharp->lower, 1e-12);
    EXPECT_NEAR(sharp->farthest.x, 0.43, 0.02);
    EXPECT_NEAR(sharp->farthest.y, 0.57, 0.02);
    s.tolerance = 0.05;
    Result<HausdorffResult> no = boundOneSided(a, b, s);
    ASSERT_TRUE(no) << no.error();
    EXPECT_TRUE(no->exceeded);
    EXPECT_NEAR(no->farthest.z, no->lower, 1e-12);
    EXPECT_GT(no->farthest.z, 0.05);
}

// A tolerance a little above the bump: the margin shrinks near it, so that the bound ends under the
// tolerance in one walk rather than up to a margin above it, and stays a true bound.
TEST(HausdorffBound, MarginShrinksNearTheToleranceSoThatACloseCaseIsDecided) {
    const Mesh bumpy = bumpOverSquare(48, 0.004f);
    const Mesh flat = square(0.0f, 1.0f);
    const HausdorffSurface a = surface(bumpy), b = surface(flat);
    HausdorffSettings s;
    s.tolerance = 0.102;          // the bump's top is at most 0.1 above the square
    s.margin = 0.5 * s.tolerance; // a coarse margin, which a bound near the tolerance overshoots
    Result<HausdorffPair> plain = boundBothWays(b, a, s); // the margin as given: undecided
    ASSERT_TRUE(plain) << plain.error();
    EXPECT_FALSE(plain->ab.exceeded || plain->ba.exceeded);
    EXPECT_GT(std::max(plain->ab.upper, plain->ba.upper), s.tolerance);
    s.roomShare = 0.25;
    Result<HausdorffPair> h = boundBothWays(b, a, s);
    ASSERT_TRUE(h) << h.error();
    EXPECT_TRUE(h->ab.within(s.tolerance) && h->ba.within(s.tolerance));
    EXPECT_GE(h->ba.upper, denseOneSided(bumpy, flat, 20000, 1));
    s.tolerance = 0.09; // below the top: still no
    Result<HausdorffPair> no = boundBothWays(b, a, s);
    ASSERT_TRUE(no);
    EXPECT_TRUE(no->ba.exceeded);
}

// Both directions at once: each bound is a true upper bound of its direction, a "no" in either
// direction stops both, and the answer is the same on every run.
TEST(HausdorffBound, BothWaysBoundsEachDirectionAndStopsOnEitherNo) {
    Mesh bumpy = square(0.0f, 1.0f);
    bumpy.positions.push_back({0.5f, 0.5f, 0.2f}); // a tent over the square's diagonal
    bumpy.indices = {0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
    const Mesh flat = square(0.0f, 1.0f);
    const HausdorffSurface a = surface(bumpy), b = surface(flat);
    HausdorffSettings s;
    s.margin = 1e-3;
    Result<HausdorffPair> both = boundBothWays(a, b, s);
    ASSERT_TRUE(both) << both.error();
    EXPECT_FALSE(both->ab.exceeded || both->ba.exceeded);
    EXPECT_GE(both->ab.upper, denseOneSided(bumpy, flat, 20000, 1));
    EXPECT_GE(both->ba.upper, denseOneSided(flat, bumpy, 20000, 2));
    EXPECT_NEAR(both->ab.lower, 0.2, 1e-6); // the tent's top
    EXPECT_LE(both->ab.upper, 0.2 + s.margin + 1e-6);
    EXPECT_LE(both->ba.upper, 0.2 + s.margin + 1e-6);

    s.tolerance = 0.15; // the tent's top strays in one direction only: both stop
    Result<HausdorffPair> no = boundBothWays(a, b, s);
    ASSERT_TRUE(no);
    EXPECT_TRUE(no->ab.exceeded && no->ba.exceeded);
    EXPECT_FALSE(no->ab.within(s.tolerance) || no->ba.within(s.tolerance));
    s.tolerance = 0.25;
    Result<HausdorffPair> yes = boundBothWays(a, b, s), again = boundBothWays(a, b, s);
    ASSERT_TRUE(yes && again);
    EXPECT_TRUE(yes->ab.within(s.tolerance) && yes->ba.within(s.tolerance));
    EXPECT_EQ(yes->ab.upper, again->ab.upper);
    EXPECT_EQ(yes->ba.queries, again->ba.queries);
    Mesh degenerate;
    degenerate.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    degenerate.indices = {0, 1, 2};
    EXPECT_FALSE(boundBothWays(a, surface(degenerate), s));
}

// A proxy's bound is the same on any machine: the walk's subtrees do not follow the thread count.
// The gallery's pillar at 1% against its proxy, certified at the tolerance and sharp.
TEST(HausdorffBound, SameBoundOnAnyNumberOfThreads) {
    const std::shared_ptr<const Mesh> pillar = galleryMesh("pillar_2");
    ASSERT_TRUE(pillar);
    ProxySettings ps;
    ps.tolerance = 0.01f;
    const Result<Proxy> proxy = buildProxy(*pillar, ps);
    ASSERT_TRUE(proxy);
    const HausdorffSurface render = surface(*pillar), coarse = surface(proxy->mesh);
    for (const double tolerance : {proxy->tolerance, std::numeric_limits<double>::infinity()}) {
        HausdorffSettings s;
        s.margin = 0.05 * proxy->tolerance;
        s.tolerance = tolerance;
        s.roomShare = 0.25;
        std::vector<HausdorffPair> bounds;
        for (const unsigned threads : {1u, 2u, 3u, 8u, 16u}) {
            s.threads = threads;
            const Result<HausdorffPair> both = boundBothWays(render, coarse, s);
            ASSERT_TRUE(both) << both.error();
            ASSERT_FALSE(both->ab.exceeded || both->ba.exceeded);
            bounds.push_back(both.value());
        }
        for (const HausdorffPair& b : bounds) {
            EXPECT_EQ(b.ab.upper, bounds[0].ab.upper) << "tolerance " << tolerance;
            EXPECT_EQ(b.ba.upper, bounds[0].ba.upper) << "tolerance " << tolerance;
            EXPECT_EQ(b.ab.lower, bounds[0].ab.lower);
            EXPECT_EQ(b.ba.lower, bounds[0].ba.lower);
        }
    }
}

TEST(HausdorffBound, RejectsBadSettingsAndAOneSidedSurface) {
    const HausdorffSurface a = surface(square(0.0f, 1.0f));
    Mesh degenerate;
    degenerate.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    degenerate.indices = {0, 1, 2};
    const HausdorffSurface empty = surface(degenerate);
    HausdorffSettings s;
    EXPECT_THAT(boundHausdorff(a, a, s).error(), HasSubstr("margin"));
    s.margin = 0.01;
    s.tolerance = -1.0;
    EXPECT_THAT(boundHausdorff(a, a, s).error(), HasSubstr("tolerance"));
    s.tolerance = 1.0;
    s.roomShare = 1.0;
    EXPECT_THAT(boundBothWays(a, a, s).error(), HasSubstr("roomShare"));
    s.roomShare = 0.25;
    s.minRoom = 0.0;
    EXPECT_THAT(boundOneSided(a, a, s).error(), HasSubstr("minRoom"));
    s.minRoom = 0.01;
    s.threads = 17;
    EXPECT_THAT(boundBothWays(a, a, s).error(), HasSubstr("threads 17"));
    s.threads = 0;
    s.tolerance = std::numeric_limits<double>::infinity();
    EXPECT_THAT(boundHausdorff(a, empty, s).error(), HasSubstr("no surface"));
    Result<HausdorffResult> none = boundHausdorff(empty, empty, s);
    ASSERT_TRUE(none);
    EXPECT_EQ(none->upper, 0.0);
    Mesh bad = square(0.0f, 1.0f);
    bad.indices[2] = 9;
    EXPECT_THAT(HausdorffSurface::create(bad).error(), HasSubstr("past the vertex count"));
}

TEST(HausdorffBound, ProgressCanCancel) {
    const Mesh render = latLongSphere(1.0f, 60, 80, 0.05f);
    const HausdorffSurface a = surface(render), b = surface(latLongSphere(1.0f, 12, 16));
    HausdorffSettings s;
    s.margin = 0.001;
    float last = -1.0f;
    Result<HausdorffResult> h = boundHausdorff(a, b, s, [&](float f, const char* stage) {
        EXPECT_STREQ(stage, "measure");
        EXPECT_GE(f, last);
        last = f;
        return true;
    });
    ASSERT_TRUE(h) << h.error();
    EXPECT_EQ(last, 1.0f);
    Result<HausdorffResult> cancelled =
        boundHausdorff(a, b, s, [](float f, const char*) { return f < 0.3f; });
    ASSERT_FALSE(cancelled);
    EXPECT_EQ(cancelled.error(), "cancelled");
}

// On the shared scans, against meshoptimizer proxies: the bound is never below a dense estimate, it
// is within its margin of what it measured, it agrees with the sampling measurement, and it is the
// same on every run.
TEST(HausdorffBound, NeverBelowTheDenseEstimateOnSharedMeshes) {
    for (const char* file : {"meshes/fandisk.obj", "meshes/rocker-arm.obj", "meshes/stanford-bunny.obj"}) {
        SPATTER_REQUIRE_SHARED(path, file);
        Result<Scene> scene = loadScene(path);
        ASSERT_TRUE(scene) << scene.error();
        const Mesh& render = *scene->objects.at(0).mesh;
        const double diagonal = double(render.bounds().diagonal());
        const Mesh proxy = proxyOf(render, 0.004f);
        const HausdorffSurface r = surface(render), p = surface(proxy);
        HausdorffSettings s;
        s.margin = 0.0005 * diagonal;
        const auto start = std::chrono::steady_clock::now();
        Result<HausdorffResult> h = boundHausdorff(p, r, s);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        ASSERT_TRUE(h) << h.error();
        const double dense =
            std::max(denseOneSided(proxy, render, 100000, 3), denseOneSided(render, proxy, 100000, 4));
        EXPECT_GE(h->upper, dense) << file;
        EXPECT_LE(h->lower, h->upper);
        EXPECT_LE(h->upper, h->lower + s.margin * (1.0 + 1e-6)) << file;
        SurfaceSampling sampling;
        sampling.radius = s.margin;
        Result<MeshDistance> sampled = measureMeshDistance(proxy, render, sampling);
        ASSERT_TRUE(sampled) << sampled.error();
        EXPECT_GE(h->upper, sampled->lowerBound()) << file;
        EXPECT_GE(sampled->upperBound(), h->lower) << file;
        Result<HausdorffResult> again = boundHausdorff(p, r, s);
        ASSERT_TRUE(again);
        EXPECT_EQ(again->upper, h->upper);
        EXPECT_EQ(again->lower, h->lower);
        std::printf("[ hausdorff ] %s: %zu vs %zu triangles: h in [%.6f, %.6f] (dense %.6f, sampled [%.6f, "
                    "%.6f]), %zu queries, %.3f s\n",
                    file, proxy.triangleCount(), render.triangleCount(), h->lower, h->upper, dense,
                    sampled->lowerBound(), sampled->upperBound(), h->queries, seconds);
    }
}

// The sampled lower bound steers the builder's search: it is a lower bound (never above the certified
// bound), and it stops once a distance is above the level it is given.
TEST(HausdorffBound, SampledLowerBoundStaysUnderTheCertifiedBound) {
    SPATTER_REQUIRE_SHARED(path, "meshes/fandisk.obj");
    Result<Scene> scene = loadScene(path);
    ASSERT_TRUE(scene) << scene.error();
    const Mesh& render = *scene->objects.at(0).mesh;
    const Mesh proxy = proxyOf(render, 0.01f);
    const HausdorffSurface r = surface(render), p = surface(proxy);
    HausdorffSettings s;
    s.margin = 0.0005 * double(render.bounds().diagonal());
    Result<HausdorffResult> h = boundHausdorff(p, r, s);
    ASSERT_TRUE(h) << h.error();
    const double inf = std::numeric_limits<double>::infinity();
    Result<double> p2r = sampledLowerBound(p, r, 100000, inf), r2p = sampledLowerBound(r, p, 100000, inf);
    ASSERT_TRUE(p2r && r2p);
    EXPECT_GT(std::max(p2r.value(), r2p.value()), 0.5 * h->lower);
    EXPECT_LE(std::max(p2r.value(), r2p.value()), h->upper);
    Result<double> early = sampledLowerBound(p, r, 100000, 0.25 * p2r.value());
    ASSERT_TRUE(early);
    EXPECT_GT(early.value(), 0.25 * p2r.value());
    EXPECT_THAT(sampledLowerBound(p, surface(Mesh{}), 10, inf).error(), HasSubstr("no surface"));
}

// A mesh not yet prepared for the certifier is sampled at the same points as its prepared surface
// wherever every triangle is sampled (the builder judges a run before it prepares it), and a bad one
// is refused.
TEST(HausdorffBound, SampledLowerBoundFromAMeshEqualsTheOneFromItsSurface) {
    SPATTER_REQUIRE_SHARED(path, "meshes/fandisk.obj");
    Result<Scene> scene = loadScene(path);
    ASSERT_TRUE(scene) << scene.error();
    const Mesh& render = *scene->objects.at(0).mesh;
    Mesh proxy = proxyOf(render, 0.01f);
    // The farthest point: the last triangle's last corner, lifted off the surface.
    proxy.positions[proxy.indices.back()] += glm::vec3(0.0f, 0.0f, 0.05f * render.bounds().diagonal());
    const HausdorffSurface r = surface(render), p = surface(proxy);
    const double inf = std::numeric_limits<double>::infinity();
    Result<double> fromSurface = sampledLowerBound(p, r, 100000, inf);
    Result<double> fromMesh = sampledLowerBound(proxy, r, 100000, inf);
    ASSERT_TRUE(fromSurface && fromMesh) << fromMesh.error();
    EXPECT_GT(fromMesh.value(), 0.01 * double(render.bounds().diagonal()));
    EXPECT_EQ(fromMesh.value(), fromSurface.value());
    Mesh broken = proxy;
    broken.indices.back() = uint32_t(broken.positions.size());
    EXPECT_THAT(sampledLowerBound(broken, r, 100000, inf).error(), HasSubstr("past the vertex count"));
    EXPECT_EQ(sampledLowerBound(Mesh{}, r, 10, inf).value(), 0.0);
}

// A coarse square over a fine grid in its plane: the distance is 0 everywhere, and pieces across the
// grid's edges are bounded (by the two triangles on either side, or laid over the grid) instead of
// being cut down to the tolerance along every edge.
TEST(HausdorffBound, PiecesAcrossCoplanarEdgesAreBoundedWithoutCutting) {
    Mesh grid; // 61 x 61 cells over [-0.01, 1.01]^2, not aligned with the square's halvings
    const uint32_t n = 61;
    for (uint32_t i = 0; i <= n; ++i)
        for (uint32_t j = 0; j <= n; ++j)
            grid.positions.push_back(
                {-0.01f + 1.02f * float(i) / float(n), -0.01f + 1.02f * float(j) / float(n), 0.0f});
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; j < n; ++j) {
            const uint32_t v = i * (n + 1) + j;
            grid.indices.insert(grid.indices.end(), {v, v + n + 1, v + n + 2, v, v + n + 2, v + 1});
        }
    const HausdorffSurface square = surface(::square(0.0f, 1.0f)), fine = surface(grid);
    HausdorffSettings s;
    s.margin = 1e-4;
    s.tolerance = 1e-3;
    Result<HausdorffResult> h = boundOneSided(square, fine, s);
    ASSERT_TRUE(h) << h.error();
    EXPECT_TRUE(h->within(1e-3));
    EXPECT_LT(h->lower, 1e-12);
    std::printf("[ coplanar  ] %zu queries\n", h->queries);
    EXPECT_LT(h->queries, 100000u);
}

namespace {

// A grid of n x n cells over [x0, x0 + size]^2 at height z(x, y), two triangles a cell.
template <class Height> Mesh grid(uint32_t n, float x0, float size, Height z) {
    Mesh m;
    for (uint32_t i = 0; i <= n; ++i)
        for (uint32_t j = 0; j <= n; ++j) {
            const float x = x0 + size * float(i) / float(n), y = x0 + size * float(j) / float(n);
            m.positions.push_back({x, y, z(x, y)});
        }
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; j < n; ++j) {
            const uint32_t v = i * (n + 1) + j;
            m.indices.insert(m.indices.end(), {v, v + n + 1, v + n + 2, v, v + n + 2, v + 1});
        }
    return m;
}

// `m` with every triangle wound the other way.
Mesh reversed(Mesh m) {
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3)
        std::swap(m.indices[t + 1], m.indices[t + 2]);
    return m;
}

// A one-sided bound and a dense estimate of the same distance.
struct BoundAndEstimate {
    double lower = 0.0, dense = 0.0;
};

// Bounds `coarse` against `under` with a small margin and checks the bound against a dense estimate:
// never below it, at most the margin above the largest distance measured.
BoundAndEstimate expectBoundAboveDense(const Mesh& coarse, const Mesh& under, uint64_t seed) {
    const HausdorffSurface a = surface(coarse), b = surface(under);
    HausdorffSettings s;
    s.margin = 1e-4;
    Result<HausdorffResult> h = boundOneSided(a, b, s);
    EXPECT_TRUE(h) << h.error();
    const double dense = denseOneSided(coarse, under, 50000, seed);
    if (!h) return {0.0, dense};
    EXPECT_GE(h->upper, dense);
    EXPECT_LE(h->upper, h->lower + s.margin + 1e-9);
    return {h->lower, dense};
}

} // namespace

// A coarse square a little above a fine grid: each of its two triangles lies over thousands of the
// grid's, and is bounded by laying it over them (a part per grid triangle, each bounded at its
// corners) instead of being cut into pieces the tolerance across, several thousand queries; with the
// grid's vertices split along every edge too.
TEST(HausdorffBound, PiecesOverAFineGridAreLaidOverItsTrianglesInsteadOfCut) {
    const Mesh fine = grid(61, -0.01f, 1.02f, [](float, float) { return 0.0f; });
    for (const Mesh& under : {fine, unshared(fine)}) {
        const HausdorffSurface square = surface(::square(0.01f, 1.0f)), b = surface(under);
        HausdorffSettings s;
        s.margin = 1e-4;
        s.tolerance = 0.02;
        Result<HausdorffResult> h = boundOneSided(square, b, s);
        ASSERT_TRUE(h) << h.error();
        EXPECT_TRUE(h->within(0.02));
        EXPECT_NEAR(h->lower, 0.01, 1e-6);
        EXPECT_GE(h->upper, 0.01);
        EXPECT_LE(h->upper, 0.01 + 1e-6);
        std::printf("[ overlay   ] %zu queries\n", h->queries);
        EXPECT_LT(h->queries, 100u);
    }
}

// Where the grid under a coarse surface has a hole, folds back under itself or is split along every
// edge, the bound is still never below the dense estimate, whether the overlay covers a piece or the
// piece is cut instead.
TEST(HausdorffBound, PiecesOverHolesFoldsAndSeamsStayAboveTheDenseEstimate) {
    Rng rng(5);
    Mesh bumpy = grid(40, 0.0f, 1.0f, [&](float x, float y) {
        return 0.02f * std::sin(9.0f * x) * std::cos(7.0f * y) + 0.002f * float(rng.uniform());
    });
    Mesh holed; // a hole of four cells, and a fold: a strip of triangles turned over
    holed.positions = bumpy.positions;
    for (size_t t = 0; t < bumpy.triangleCount(); ++t) {
        const size_t cell = t / 2, i = cell / 40, j = cell % 40;
        if ((i == 20 || i == 21) && (j == 20 || j == 21)) continue;
        const uint32_t* c = &bumpy.indices[3 * t];
        if (i == 10)
            holed.indices.insert(holed.indices.end(), {c[0], c[2], c[1]});
        else
            holed.indices.insert(holed.indices.end(), {c[0], c[1], c[2]});
    }
    Mesh coarse = grid(3, 0.05f, 0.9f, [](float x, float y) { return 0.015f * (x - y); });
    for (const Mesh& under : {bumpy, holed, unshared(holed)}) {
        const BoundAndEstimate h = expectBoundAboveDense(coarse, under, 9);
        EXPECT_LE(h.dense, h.lower + 1e-9);
    }
}

namespace {

// Flattened tubes along y, each wound to face up on both its sheets (so that the winding does not
// show the folds along its two sides), open at y = 0 and y = 1: tube k over x in [x0[k], x0[k] + 0.4],
// its sheets at z = 0 and z = 0.01.
Mesh flatTubesFacingUp(const std::vector<float>& x0) {
    Mesh m;
    const uint32_t rows = 10, half = 8, loop = 2 * half; // columns around a tube, the last closing it
    for (float start : x0) {
        const uint32_t first = uint32_t(m.positions.size());
        for (uint32_t i = 0; i < loop; ++i) {
            const bool top = i < half;
            const float u = float(top ? i : loop - i) / float(half);
            for (uint32_t j = 0; j <= rows; ++j)
                m.positions.push_back({start + 0.4f * u, float(j) / float(rows), top ? 0.01f : 0.0f});
        }
        auto faceUp = [&](uint32_t a, uint32_t b, uint32_t c) {
            const glm::vec3 n = glm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
            m.indices.insert(m.indices.end(), {a, n.z > 0.0f ? b : c, n.z > 0.0f ? c : b});
        };
        for (uint32_t i = 0; i < loop; ++i)
            for (uint32_t j = 0; j < rows; ++j) {
                const uint32_t v = first + i * (rows + 1) + j, w = first + ((i + 1) % loop) * (rows + 1) + j;
                faceUp(v, w, w + 1);
                faceUp(v, w + 1, v + 1);
            }
    }
    return m;
}

} // namespace

// A coarse square over two flattened tubes with a gap between them: the square is farthest from
// them over the gap, away from its corners. The tubes' sheets all face up, so only their geometry
// shows that the edges along their sides are folds: the overlay must not lay a piece across a fold
// onto the sheet on its own side of the edge, which would leave the gap uncovered and the bound below
// the distance.
TEST(HausdorffBound, PiecesOverFoldsWoundToFaceUpStayAboveTheDenseEstimate) {
    const Mesh tubes = flatTubesFacingUp({0.0f, 0.6f});
    const Mesh coarse = grid(1, 0.05f, 0.9f, [](float, float) { return 0.03f; });
    EXPECT_GT(expectBoundAboveDense(coarse, tubes, 3).dense, 0.09); // over the gap, 0.1 from either tube
    // The square wound to face down (laid along the tubes' facing, opposite its own).
    EXPECT_GT(expectBoundAboveDense(reversed(coarse), tubes, 4).dense, 0.09);
}

namespace {

// A fine grid folded down at x = 1 like the edge of a box: a top z = 0 over [0, 1] x [0, 1] facing
// up, and a side x = 1 down to z = -0.3 facing +x, 50 and 15 cells across, welded along the edge.
Mesh boxEdge() {
    Mesh m = grid(65, 0.0f, 1.3f, [](float, float) { return 0.0f; });
    for (glm::vec3& p : m.positions)
        if (p.x > 1.0f)
            p = {1.0f, p.y * 1.0f / 1.3f, -(p.x - 1.0f)};
        else
            p.y *= 1.0f / 1.3f;
    return m;
}

// Bounds `coarse` against `under` at a tolerance of 0.02: within, never below a dense estimate; the
// queries it took.
size_t expectWithinAndAboveDense(const Mesh& coarse, const Mesh& under, uint64_t seed) {
    HausdorffSettings s;
    s.margin = 1e-4;
    s.tolerance = 0.02;
    Result<HausdorffResult> h = boundOneSided(surface(coarse), surface(under), s);
    EXPECT_TRUE(h) << h.error();
    if (!h) return 0;
    EXPECT_TRUE(h->within(s.tolerance));
    EXPECT_GE(h->upper, denseOneSided(coarse, under, 50000, seed));
    return h->queries;
}

} // namespace

// A coarse square over the top of a box edge, reaching a little past the edge and below the top:
// the corners past the edge find the side closest, which does not face along the square's normal.
// The square is laid over both faces along the mean of their normals instead of being cut down to
// the tolerance along the edge.
TEST(HausdorffBound, PiecesByACreaseAreLaidOverBothFacesInsteadOfCut) {
    Mesh coarse = square(0.0f, 1.0f);
    coarse.positions = {
        {0.1f, 0.1f, 0.01f}, {1.004f, 0.1f, -0.001f}, {1.004f, 0.9f, -0.001f}, {0.1f, 0.9f, 0.01f}};
    const Mesh edge = boxEdge();
    for (const Mesh& under : {edge, unshared(edge)}) {
        const size_t queries = expectWithinAndAboveDense(coarse, under, 11);
        std::printf("[ crease    ] %zu queries\n", queries);
        EXPECT_LT(queries, 100u);
    }
}

// A coarse square just under a thin slab, whose bottom sheet faces down, away from the square's
// normal: the square is laid over that sheet along its facing instead of being cut.
TEST(HausdorffBound, PiecesUnderASheetFacingAwayAreLaidOverIt) {
    const Mesh top = grid(61, -0.01f, 1.02f, [](float, float) { return 0.004f; });
    Mesh slab = top;
    const Mesh bottom = reversed(grid(61, -0.01f, 1.02f, [](float, float) { return 0.0f; }));
    for (uint32_t i : bottom.indices)
        slab.indices.push_back(i + uint32_t(top.positions.size()));
    slab.positions.insert(slab.positions.end(), bottom.positions.begin(), bottom.positions.end());
    const Mesh coarse = grid(1, 0.1f, 0.8f, [](float, float) { return -0.01f; });
    const size_t queries = expectWithinAndAboveDense(coarse, slab, 12);
    std::printf("[ facing away ] %zu queries\n", queries);
    EXPECT_LT(queries, 100u);
}
