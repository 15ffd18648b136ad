// UV overlap check: layouts that can and cannot carry texture-space decals.

#include "spatter/core/UvOverlap.hpp"
#include "spatter/core/MeshBuilder.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace spatter;

namespace {

// Two triangles forming the unit square, sharing the diagonal.
Mesh uvQuad() {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    m.indices = {0, 1, 2, 0, 2, 3};
    computeNormals(m);
    return m;
}

} // namespace

TEST(UvOverlap, AcceptsTrianglesSharingAnEdge) {
    Result<UvOverlapReport> r = findUvOverlaps(uvQuad());
    ASSERT_TRUE(r) << r.error();
    EXPECT_EQ(r->triangles, 2u);
    EXPECT_EQ(r->overlappingPairs, 0u);
    EXPECT_TRUE(r->usable()) << r->summary();
}

TEST(UvOverlap, ReportsTriangleFoldedOntoItsNeighbour) {
    Mesh m = uvQuad();
    m.uvs[3] = {0.9f, 0.2f}; // the second triangle now lies over the first
    Result<UvOverlapReport> r = findUvOverlaps(m);
    ASSERT_TRUE(r) << r.error();
    EXPECT_EQ(r->overlappingPairs, 1u);
    ASSERT_EQ(r->pairs.size(), 1u);
    EXPECT_EQ(r->pairs[0], std::make_pair(0u, 1u));
    EXPECT_FALSE(r->usable());
}

TEST(UvOverlap, ReportsBoxFacesSharingTheirUvs) {
    Mesh box = makeBox(glm::vec3(0.5f), 2); // box-projected UVs: opposite faces coincide
    fitUvsToUnitSquare(box);
    Result<UvOverlapReport> r = findUvOverlaps(box);
    ASSERT_TRUE(r) << r.error();
    EXPECT_GT(r->overlappingPairs, 0u) << r->summary();
    EXPECT_FALSE(r->usable());
}

TEST(UvOverlap, AcceptsGridFittedIntoTheUnitSquare) {
    Mesh grid = makeGrid(makeSamples(-2.0f, 2.0f, 0.25f), makeSamples(-1.0f, 1.0f, 0.25f));
    Result<UvOverlapReport> before = findUvOverlaps(grid);
    ASSERT_TRUE(before) << before.error();
    EXPECT_GT(before->outOfRange, 0u); // metres: outside [0, 1]
    fitUvsToUnitSquare(grid, 0.05f);
    for (const glm::vec2& uv : grid.uvs) {
        EXPECT_GE(uv.x, 0.05f - 1e-6f);
        EXPECT_LE(uv.x, 0.95f + 1e-6f);
        EXPECT_LE(uv.y, 0.5f + 1e-6f); // aspect kept: half as tall as wide
    }
    Result<UvOverlapReport> after = findUvOverlaps(grid);
    ASSERT_TRUE(after) << after.error();
    EXPECT_TRUE(after->usable()) << after->summary();
}

TEST(UvOverlap, ReportsLatheSeamColumn) {
    Mesh lathe = makeLathe({{0.5f, 0.0f}, {0.5f, 1.0f}}, 12); // the seam column spans every u
    fitUvsToUnitSquare(lathe);
    Result<UvOverlapReport> r = findUvOverlaps(lathe);
    ASSERT_TRUE(r) << r.error();
    EXPECT_GT(r->overlappingPairs, 0u) << r->summary();
}

TEST(UvOverlap, CountsDegenerateAndNonFiniteTriangles) {
    Mesh m = uvQuad();
    m.uvs[2] = {1.0f, 0.0f}; // first triangle: two equal UVs
    Result<UvOverlapReport> r = findUvOverlaps(m);
    ASSERT_TRUE(r) << r.error();
    EXPECT_EQ(r->degenerate, 1u);
    m.uvs[0].x = std::nanf("");
    r = findUvOverlaps(m);
    ASSERT_TRUE(r) << r.error();
    EXPECT_EQ(r->outOfRange, 2u);
}

TEST(UvOverlap, RejectsMeshWithoutUvsOrWithBadIndices) {
    Mesh m = uvQuad();
    m.uvs.clear();
    EXPECT_FALSE(findUvOverlaps(m));
    m = uvQuad();
    m.indices.push_back(99);
    m.indices.push_back(0);
    m.indices.push_back(1);
    EXPECT_FALSE(findUvOverlaps(m));
}
