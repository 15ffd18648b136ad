// Triangles two surfaces share corner for corner lie on both, so the certificate bounds none of them
// (HausdorffBound.hpp) and HausdorffSurface::sameTriangles finds them whatever the order of the
// vertices and corners: a proxy simplified from a render mesh keeps many of its triangles as they are.

#include "spatter/core/HausdorffBound.hpp"

#include "ReferenceGeometry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

using namespace spatter;
using namespace spatter::test;

namespace {

HausdorffSurface prepared(const Mesh& m) {
    Result<HausdorffSurface> s = HausdorffSurface::create(m);
    EXPECT_TRUE(s) << s.error();
    return std::move(s).value();
}

// A flat n x n grid over the unit square at height 0, two triangles a cell.
Mesh flatGrid(uint32_t n) {
    Mesh m;
    for (uint32_t i = 0; i <= n; ++i)
        for (uint32_t j = 0; j <= n; ++j)
            m.positions.push_back({float(i) / float(n), float(j) / float(n), 0.0f});
    for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = 0; j < n; ++j) {
            const uint32_t v = i * (n + 1) + j;
            m.indices.insert(m.indices.end(), {v, v + n + 1, v + n + 2, v, v + n + 2, v + 1});
        }
    return m;
}

bool touches(const Mesh& m, size_t t, uint32_t v) {
    return m.indices[3 * t] == v || m.indices[3 * t + 1] == v || m.indices[3 * t + 2] == v;
}

} // namespace

TEST(SharedTriangles, AMeshAgainstItselfIsBoundedWithoutAQuery) {
    const Mesh grid = flatGrid(16);
    const HausdorffSurface a = prepared(grid), b = prepared(grid);
    HausdorffSettings s;
    s.margin = 1e-4;
    Result<HausdorffPair> h = boundBothWays(a, b, s);
    ASSERT_TRUE(h) << h.error();
    EXPECT_EQ(h->ab.queries, 0u);
    EXPECT_EQ(h->ba.queries, 0u);
    EXPECT_LE(h->ab.upper, 1e-8);
    EXPECT_LE(h->ba.upper, 1e-8);
}

// Moving one vertex of a grid up leaves the six triangles around it sharing an edge each with their
// old selves, and every other triangle shared: those six are still bounded, and the vertex is
// measured at its height.
TEST(SharedTriangles, AMovedVertexIsMeasuredThoughTheTrianglesAroundItShareEdges) {
    const Mesh flat = flatGrid(32); // more triangles than the walk's subtrees hold leaves
    Mesh raised = flat;
    const uint32_t moved = 16 * 33 + 16;
    raised.positions[moved].z = 0.05f;
    const HausdorffSurface a = prepared(flat), b = prepared(raised);

    const std::vector<uint32_t> same = a.sameTriangles(raised);
    size_t around = 0;
    for (size_t t = 0; t < same.size(); ++t) {
        around += touches(raised, t, moved) ? 1 : 0;
        EXPECT_EQ(same[t], touches(raised, t, moved) ? UINT32_MAX : uint32_t(t)) << "triangle " << t;
    }
    EXPECT_EQ(around, 6u);

    HausdorffSettings s;
    s.margin = 1e-4;
    Result<HausdorffPair> h = boundBothWays(b, a, s);
    ASSERT_TRUE(h) << h.error();
    EXPECT_NEAR(h->ab.lower, 0.05, 1e-7); // the raised vertex, straight above the grid
    EXPECT_GE(h->ab.upper, 0.05);
    EXPECT_GE(h->ba.upper, denseOneSided(flat, raised, 20000, 3));
    EXPECT_GT(h->ba.lower, 0.0);
    EXPECT_LE(h->ab.upper, h->ab.lower + s.margin + 1e-9);
}

// The same triangles through another vertex order, each turned and some wound the other way, with
// -0 for 0: all found; a triangle naming a vertex the mesh lacks is not.
TEST(SharedTriangles, AreFoundWhateverTheOrderOfVerticesAndCornersAndTheSignOfZero) {
    const Mesh grid = flatGrid(8);
    Mesh other;
    const uint32_t n = uint32_t(grid.positions.size());
    for (uint32_t v = 0; v < n; ++v) {
        glm::vec3 p = grid.positions[n - 1 - v];
        if (p.x == 0.0f) p.x = -0.0f;
        p.z = -0.0f;
        other.positions.push_back(p);
    }
    for (size_t t = 0; t < grid.triangleCount(); ++t) {
        uint32_t c[3];
        for (int k = 0; k < 3; ++k)
            c[k] = n - 1 - grid.indices[3 * t + size_t((k + t) % 3)];
        if (t % 2 == 1) std::swap(c[1], c[2]);
        other.indices.insert(other.indices.end(), {c[0], c[1], c[2]});
    }
    other.indices.insert(other.indices.end(), {0, 1, n}); // vertex n is past the end
    const std::vector<uint32_t> same = prepared(grid).sameTriangles(other);
    ASSERT_EQ(same.size(), grid.triangleCount() + 1);
    for (size_t t = 0; t < grid.triangleCount(); ++t)
        EXPECT_EQ(same[t], uint32_t(t)) << "triangle " << t;
    EXPECT_EQ(same.back(), UINT32_MAX);
}

// A surface of more than 4 times the other's triangles looks for none: a proxy that small keeps few.
TEST(SharedTriangles, AreNotLookedForInASurfaceManyTimesLarger) {
    const Mesh grid = flatGrid(8); // 128 triangles
    auto firstTriangles = [&grid](size_t count) {
        Mesh m = grid;
        m.indices.resize(3 * count);
        return m;
    };
    const HausdorffSurface s = prepared(grid);
    const std::vector<uint32_t> quarter = s.sameTriangles(firstTriangles(32));
    EXPECT_TRUE(std::all_of(quarter.begin(), quarter.end(), [](uint32_t t) { return t != UINT32_MAX; }));
    const std::vector<uint32_t> fewer = s.sameTriangles(firstTriangles(31));
    EXPECT_TRUE(std::all_of(fewer.begin(), fewer.end(), [](uint32_t t) { return t == UINT32_MAX; }));
}
