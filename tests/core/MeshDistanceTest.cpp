#include "spatter/core/MeshDistance.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/Random.hpp"

#include "ReferenceGeometry.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

using namespace spatter;
using namespace spatter::test;
using ::testing::HasSubstr;

namespace {

Mesh triangleMesh(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices) {
    Mesh m;
    m.positions = positions;
    m.indices = indices;
    computeNormals(m);
    return m;
}

} // namespace

TEST(ClosestPointQuery, MatchesBruteForceOnASphere) {
    const Mesh m = latLongSphere(1.0f, 12, 16);
    Result<ClosestPointQuery> q = ClosestPointQuery::create(m);
    ASSERT_TRUE(q) << q.error();
    Rng rng(7);
    for (int i = 0; i < 500; ++i) {
        const glm::dvec3 p(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
        const std::optional<ClosestPoint> c = q->closest(p);
        ASSERT_TRUE(c);
        EXPECT_NEAR(c->distance, bruteMeshDistance(p, m), 1e-9);
        EXPECT_NEAR(glm::length(c->point - p), c->distance, 1e-12);
        const uint32_t t = c->triangle;
        ASSERT_LT(t, m.triangleCount());
        EXPECT_NEAR(triangleDistance(p, glm::dvec3(m.positions[m.indices[3 * t]]),
                                     glm::dvec3(m.positions[m.indices[3 * t + 1]]),
                                     glm::dvec3(m.positions[m.indices[3 * t + 2]])),
                    c->distance, 1e-9);
    }
}

TEST(ClosestPointQuery, WithinAgreesWithTheClosestPointOnASphere) {
    const Mesh m = latLongSphere(1.0f, 12, 16);
    Result<ClosestPointQuery> q = ClosestPointQuery::create(m);
    ASSERT_TRUE(q) << q.error();
    Rng rng(11);
    for (int i = 0; i < 500; ++i) {
        // Points far from the origin too, where the query point's rounding to float is largest.
        const double scale = i % 2 ? 1.0 : 1e3;
        const glm::dvec3 p = scale * glm::dvec3(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
        const std::optional<ClosestPoint> c = q->closest(p);
        ASSERT_TRUE(c);
        EXPECT_TRUE(q->within(p, c->distance * (1.0 + 1e-12)));
        EXPECT_FALSE(q->within(p, 0.99 * c->distance));
    }
}

// Searched within a reach, the nearest point is the one found everywhere where it lies within the
// reach (at it included), and nothing where it lies beyond or the reach is negative or NaN.
TEST(ClosestPointQuery, WithinAReachFindsTheNearestPointOrNothing) {
    const Mesh m = latLongSphere(1.0f, 12, 16);
    Result<ClosestPointQuery> q = ClosestPointQuery::create(m);
    ASSERT_TRUE(q) << q.error();
    Rng rng(13);
    for (int i = 0; i < 300; ++i) {
        const glm::dvec3 p(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
        const std::optional<ClosestPoint> everywhere = q->closest(p);
        ASSERT_TRUE(everywhere);
        const double d = everywhere->distance;
        for (double reach : {d, 1.5 * d + 1e-9}) {
            const std::optional<ClosestPoint> within = q->closest(p, reach);
            ASSERT_TRUE(within) << "reach " << reach << ", nearest at " << d;
            EXPECT_EQ(within->distance, d);
            EXPECT_EQ(within->triangle, everywhere->triangle);
        }
        if (d > 1e-6) {
            EXPECT_FALSE(q->closest(p, 0.9 * d)) << "nearest at " << d;
        }
    }
    EXPECT_FALSE(q->closest(glm::dvec3(0.0), -1.0));
    EXPECT_FALSE(q->closest(glm::dvec3(0.0), std::nan("")));
}

TEST(ClosestPointQuery, WithinAnswersNoForNonFiniteValuesAndNegativeRadii) {
    const Mesh m = triangleMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
    Result<ClosestPointQuery> q = ClosestPointQuery::create(m);
    ASSERT_TRUE(q);
    const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
    EXPECT_TRUE(q->within({0.2, 0.2, 0.0}, 1e-12)); // on the surface
    EXPECT_TRUE(q->within({0.2, 0.2, 1.0}, 1.0 + 1e-12));
    EXPECT_FALSE(q->within({0.2, 0.2, 1.0}, -1.0));
    EXPECT_FALSE(q->within({0.2, 0.2, 1.0}, nan));
    EXPECT_FALSE(q->within({0.2, 0.2, 1.0}, inf));
    EXPECT_FALSE(q->within({nan, 0.2, 1.0}, 5.0));
}

TEST(ClosestPointQuery, ExactAtFaceEdgeAndCornerOfOneTriangle) {
    const Mesh m = triangleMesh({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}, {0, 1, 2});
    Result<ClosestPointQuery> q = ClosestPointQuery::create(m);
    ASSERT_TRUE(q) << q.error();
    EXPECT_DOUBLE_EQ(q->closest({0.5, 0.5, 3.0})->distance, 3.0);
    EXPECT_DOUBLE_EQ(q->closest({1.0, -4.0, 0.0})->distance, 4.0);
    EXPECT_DOUBLE_EQ(q->closest({-3.0, -4.0, 0.0})->distance, 5.0);
    EXPECT_EQ(q->closest({-3.0, -4.0, 0.0})->point, glm::dvec3(0.0));
}

// Triangles at the same distance: the one first in the mesh, whatever order the BVH visits them in
// (its width follows the processor). Fans of triangles around a vertex, the query above the vertex,
// listed in shuffled orders; and a grid of squares, queried above each shared corner.
TEST(ClosestPointQuery, OfTrianglesAtTheSameDistanceAnswersTheFirstInTheMesh) {
    Rng rng(11);
    for (uint32_t fan : {6u, 24u, 96u}) {
        Mesh m;
        m.positions.push_back({0.0f, 0.0f, 0.0f});
        for (uint32_t k = 0; k < fan; ++k) {
            const float a = 6.2831853f * float(k) / float(fan);
            m.positions.push_back({std::cos(a), std::sin(a), 0.0f});
        }
        std::vector<uint32_t> order(fan);
        for (uint32_t k = 0; k < fan; ++k)
            order[k] = k;
        for (uint32_t k = fan - 1; k > 0; --k)
            std::swap(order[k], order[rng.below(k + 1)]);
        for (uint32_t k : order)
            m.indices.insert(m.indices.end(), {0, 1 + k, 1 + (k + 1) % fan});
        const Result<ClosestPointQuery> q = ClosestPointQuery::create(m);
        ASSERT_TRUE(q) << q.error();
        const std::optional<ClosestPoint> c = q->closest({0.0, 0.0, 0.5});
        ASSERT_TRUE(c);
        EXPECT_EQ(c->triangle, 0u) << fan << " triangles around the vertex";
        EXPECT_EQ(c->distance, 0.5);
    }
    std::vector<float> steps(33);
    for (size_t i = 0; i < steps.size(); ++i)
        steps[i] = float(i);
    const Mesh grid = makeGrid(steps, steps); // in the XZ plane, facing +Y
    const Result<ClosestPointQuery> q = ClosestPointQuery::create(grid);
    ASSERT_TRUE(q) << q.error();
    for (const glm::vec3& corner : grid.positions) {
        const glm::dvec3 above = glm::dvec3(corner) + glm::dvec3(0.0, 0.25, 0.0);
        const std::optional<ClosestPoint> c = q->closest(above);
        ASSERT_TRUE(c);
        uint32_t first = UINT32_MAX;
        for (uint32_t t = 0; t < grid.triangleCount() && first == UINT32_MAX; ++t)
            for (int k = 0; k < 3; ++k)
                if (grid.positions[grid.indices[3 * t + uint32_t(k)]] == corner) first = t;
        EXPECT_EQ(c->triangle, first);
    }
}

TEST(ClosestPointQuery, IgnoresDegenerateTriangles) {
    // A zero-area triangle (collinear corners) and one with a repeated index, far from the real one.
    const Mesh m = triangleMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {10, 0, 0}, {11, 0, 0}, {12, 0, 0}},
                                {0, 1, 2, 3, 4, 5, 3, 3, 4});
    Result<ClosestPointQuery> q = ClosestPointQuery::create(m);
    ASSERT_TRUE(q) << q.error();
    EXPECT_EQ(q->surfaceTriangleCount(), 1u);
    EXPECT_NEAR(q->closest({11, 0, 0})->distance, 10.0, 1e-12);
}

TEST(ClosestPointQuery, MeshWithoutSurfaceAnswersNothing) {
    const Mesh m = triangleMesh({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {0, 1, 2});
    Result<ClosestPointQuery> q = ClosestPointQuery::create(m);
    ASSERT_TRUE(q) << q.error();
    EXPECT_FALSE(q->closest({0, 0, 0}));
}

TEST(ClosestPointQuery, RejectsNonFinitePositionAndBadIndex) {
    Mesh m = triangleMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
    m.positions[1].y = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THAT(ClosestPointQuery::create(m).error(), HasSubstr("position 1 is not finite"));
    m.positions[1].y = 0.0f;
    m.indices[2] = 3;
    EXPECT_THAT(ClosestPointQuery::create(m).error(), HasSubstr("past the vertex count"));
}

TEST(ClosestPointQuery, NonFiniteQueryPointAnswersNothing) {
    const Mesh m = triangleMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
    Result<ClosestPointQuery> q = ClosestPointQuery::create(m);
    ASSERT_TRUE(q);
    EXPECT_FALSE(q->closest({std::numeric_limits<double>::infinity(), 0, 0}));
}

TEST(ClosestPointQuery, RayMeetsTheFirstTriangleWithinReachAndNamesItsMeshIndex) {
    // A degenerate triangle first (left out of the surface), then two parallel triangles at z = 1, 3.
    const Mesh m = triangleMesh({{0, 0, 0},
                                 {1, 0, 0},
                                 {2, 0, 0},
                                 {-1, -1, 1},
                                 {3, -1, 1},
                                 {-1, 3, 1},
                                 {-1, -1, 3},
                                 {3, -1, 3},
                                 {-1, 3, 3}},
                                {0, 1, 2, 3, 4, 5, 6, 7, 8});
    Result<ClosestPointQuery> q = ClosestPointQuery::create(m);
    ASSERT_TRUE(q) << q.error();
    const std::optional<ClosestPointQuery::RayMeet> up = q->firstMeet({0.5, 0.5, 0.0}, {0, 0, 1}, 10.0);
    ASSERT_TRUE(up);
    EXPECT_EQ(up->triangle, 1u);
    EXPECT_NEAR(up->t, 1.0, 1e-6);
    const std::optional<ClosestPointQuery::RayMeet> down = q->firstMeet({0.5, 0.5, 4.0}, {0, 0, -1}, 10.0);
    ASSERT_TRUE(down);
    EXPECT_EQ(down->triangle, 2u);
    EXPECT_FALSE(q->firstMeet({0.5, 0.5, 0.0}, {0, 0, 1}, 0.9));   // out of reach
    EXPECT_FALSE(q->firstMeet({0.5, 0.5, 0.0}, {0, 0, -1}, 10.0)); // away from both
    EXPECT_FALSE(q->firstMeet({std::nan(""), 0.5, 0.0}, {0, 0, 1}, 10.0));
    EXPECT_FALSE(q->firstMeet({0.5, 0.5, 0.0}, {0, 0, 1}, std::numeric_limits<double>::infinity()));
}

TEST(MeshDistance, ParallelSquaresAreTheirOffsetApart) {
    const Mesh a = triangleMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {0, 1, 2, 0, 2, 3});
    const Mesh b =
        triangleMesh({{0, 0, 0.25f}, {1, 0, 0.25f}, {1, 1, 0.25f}, {0, 1, 0.25f}}, {0, 1, 2, 0, 2, 3});
    SurfaceSampling sampling;
    sampling.radius = 0.01;
    Result<MeshDistance> d = measureMeshDistance(a, b, sampling);
    ASSERT_TRUE(d) << d.error();
    EXPECT_NEAR(d->aToB.measuredMax, 0.25, 1e-7);
    EXPECT_NEAR(d->bToA.measuredMax, 0.25, 1e-7);
    EXPECT_GE(d->upperBound(), 0.25);
    EXPECT_LE(d->upperBound(), 0.25 + 0.01 + 1e-6);
}

// The largest distance lies strictly between samples: A is a long sliver along x in [0, 3], B two
// tiny triangles near x = 0 and x = 2.2, so the distance from A peaks near x = 1.1.
TEST(MeshDistance, BoundCoversAMaximumBetweenSamples) {
    const Mesh a = triangleMesh({{0, -0.01f, 0}, {3, 0, 0}, {0, 0.01f, 0}}, {0, 1, 2});
    const Mesh b = triangleMesh(
        {{0, 0, 0}, {0.001f, 0, 0}, {0, 0.001f, 0}, {2.2f, 0, 0}, {2.201f, 0, 0}, {2.2f, 0.001f, 0}},
        {0, 1, 2, 3, 4, 5});
    double truth = 0.0; // dense brute force along the sliver's axis
    for (int i = 0; i <= 300000; ++i)
        truth = std::max(truth, bruteMeshDistance({3.0 * i / 300000.0, 0, 0}, b));
    Result<ClosestPointQuery> qb = ClosestPointQuery::create(b);
    ASSERT_TRUE(qb);
    for (double radius : {0.2, 0.05, 0.001}) {
        SurfaceSampling sampling;
        sampling.radius = radius;
        sampling.randomSamples = 0;
        Result<OneSidedDistance> d = measureOneSidedDistance(a, qb.value(), sampling);
        ASSERT_TRUE(d) << d.error();
        EXPECT_GE(d->bound, truth) << "radius " << radius;
        EXPECT_LE(d->measuredMax, truth + 1e-4); // off-axis points of the sliver are slightly farther
        EXPECT_LE(d->bound, d->measuredMax + radius + 1e-6);
        EXPECT_NEAR(d->margin, d->bound - d->measuredMax, 1e-12);
    }
}

TEST(MeshDistance, BoundHoldsWhenTheSampleBudgetCoarsensTheCutting) {
    const Mesh a = latLongSphere(1.0f, 6, 8);
    const Mesh b = latLongSphere(1.1f, 40, 60);
    Result<ClosestPointQuery> qb = ClosestPointQuery::create(b);
    ASSERT_TRUE(qb);
    SurfaceSampling fine;
    fine.radius = 1e-4;
    fine.maxSamples = 100;
    fine.randomSamples = 0;
    Result<OneSidedDistance> d = measureOneSidedDistance(a, qb.value(), fine);
    ASSERT_TRUE(d) << d.error();
    // Dense independent estimate of the true distance from a to b.
    Rng rng(3);
    double estimate = 0.0;
    for (int i = 0; i < 3000; ++i) {
        const size_t t = rng.below(uint32_t(a.triangleCount()));
        float u = rng.uniform(), v = rng.uniform();
        if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
        const glm::dvec3 p0(a.positions[a.indices[3 * t]]), p1(a.positions[a.indices[3 * t + 1]]),
            p2(a.positions[a.indices[3 * t + 2]]);
        estimate =
            std::max(estimate, bruteMeshDistance(p0 + double(u) * (p1 - p0) + double(v) * (p2 - p0), b));
    }
    EXPECT_GE(d->bound, estimate);
    EXPECT_GT(d->margin, 1e-4); // the budget forced a coarser cutting than asked for
}

TEST(MeshDistance, ReportsProgressAndCancels) {
    const Mesh a = latLongSphere(1.0f, 20, 30);
    const Mesh b = latLongSphere(1.05f, 20, 30);
    SurfaceSampling sampling;
    sampling.radius = 0.01;
    sampling.maxSamples = 20000; // forces a restart of the cutting with a larger radius
    float last = -1.0f;
    bool monotone = true;
    Result<MeshDistance> d = measureMeshDistance(a, b, sampling, [&](float f, const char* stage) {
        monotone = monotone && f >= last && f <= 1.0f && std::string(stage) == "measure";
        last = f;
        return true;
    });
    ASSERT_TRUE(d) << d.error();
    EXPECT_TRUE(monotone);
    EXPECT_GT(last, 0.9f);
    Result<MeshDistance> cancelled =
        measureMeshDistance(a, b, sampling, [](float, const char*) { return false; });
    ASSERT_FALSE(cancelled);
    EXPECT_EQ(cancelled.error(), "cancelled");
}

TEST(MeshDistance, FailsWhenOnlyOneMeshHasASurface) {
    const Mesh a = triangleMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});
    const Mesh empty;
    Result<MeshDistance> d = measureMeshDistance(a, empty, {});
    ASSERT_FALSE(d);
    EXPECT_THAT(d.error(), HasSubstr("no surface"));
    Result<MeshDistance> none = measureMeshDistance(empty, empty, {});
    ASSERT_TRUE(none);
    EXPECT_EQ(none->upperBound(), 0.0);
}
