#include "spatter/core/MeshBuilder.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <map>
#include <utility>

using namespace spatter;

namespace {

// Closed and consistently oriented: every directed edge appears exactly once and its reverse too,
// so every undirected edge is shared by exactly two triangles.
::testing::AssertionResult isClosed(const Mesh& mesh) {
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k)
            ++directed[{mesh.indices[t + k], mesh.indices[t + (k + 1) % 3]}];
    for (const auto& [edge, count] : directed) {
        if (count != 1)
            return ::testing::AssertionFailure()
                   << "edge " << edge.first << "-" << edge.second << " used " << count << " times one way";
        auto reverse = directed.find({edge.second, edge.first});
        if (reverse == directed.end())
            return ::testing::AssertionFailure()
                   << "edge " << edge.first << "-" << edge.second << " is a border";
    }
    return ::testing::AssertionSuccess();
}

// Divergence theorem: positive for outward-facing closed meshes.
double signedVolume(const Mesh& mesh) {
    double v = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::dvec3 a(mesh.positions[mesh.indices[t]]), b(mesh.positions[mesh.indices[t + 1]]),
            c(mesh.positions[mesh.indices[t + 2]]);
        v += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    return v;
}

size_t zeroAreaTriangles(const Mesh& mesh) {
    size_t n = 0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                        c = mesh.positions[mesh.indices[t + 2]];
        if (glm::length(glm::cross(b - a, c - a)) < 1e-12f) ++n;
    }
    return n;
}

// Complete attributes, unit normals and tangents, valid indices.
void expectWellFormed(const Mesh& mesh) {
    ASSERT_TRUE(validateMesh(mesh).ok()) << validateMesh(mesh).error();
    ASSERT_EQ(mesh.uvs.size(), mesh.vertexCount());
    ASSERT_EQ(mesh.tangents.size(), mesh.vertexCount());
    for (size_t i = 0; i < mesh.vertexCount(); ++i) {
        EXPECT_NEAR(glm::length(mesh.normals[i]), 1.0f, 1e-5f) << "normal " << i;
        EXPECT_NEAR(glm::length(glm::vec3(mesh.tangents[i])), 1.0f, 1e-5f) << "tangent " << i;
        EXPECT_TRUE(std::isfinite(mesh.uvs[i].x) && std::isfinite(mesh.uvs[i].y)) << "uv " << i;
    }
    EXPECT_EQ(zeroAreaTriangles(mesh), 0u);
}

// Every triangle's geometric normal points away from `center` (for convex shapes).
void expectFacesPointAwayFrom(const Mesh& mesh, const glm::vec3& center) {
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                        c = mesh.positions[mesh.indices[t + 2]];
        EXPECT_GT(glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f - center), 0.0f)
            << "triangle " << t / 3;
    }
}

} // namespace

TEST(MeshBuilder, UnitCubeHasEightSharedVerticesAndTwelveTriangles) {
    const Mesh cube = makeUnitCube();
    ASSERT_EQ(cube.vertexCount(), 8u);
    ASSERT_EQ(cube.triangleCount(), 12u);
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 expected((i & 1) ? 0.5f : -0.5f, (i & 2) ? 0.5f : -0.5f, (i & 4) ? 0.5f : -0.5f);
        EXPECT_EQ(cube.positions[size_t(i)], expected);
        EXPECT_NEAR(glm::dot(cube.normals[size_t(i)], glm::normalize(expected)), 1.0f, 1e-6f);
    }
    expectWellFormed(cube);
}

TEST(MeshBuilder, UnitCubeIsClosedWithOutwardFaces) {
    const Mesh cube = makeUnitCube();
    EXPECT_TRUE(isClosed(cube));
    EXPECT_NEAR(signedVolume(cube), 1.0, 1e-6);
    expectFacesPointAwayFrom(cube, glm::vec3(0.0f));
}

TEST(MeshBuilder, SubdividedBoxCountsAndClosure) {
    const Mesh box = makeBox({1.0f, 0.5f, 2.0f}, 3);
    EXPECT_EQ(box.vertexCount(), 6u * 9u + 2u);
    EXPECT_EQ(box.triangleCount(), 12u * 9u);
    EXPECT_TRUE(isClosed(box));
    EXPECT_NEAR(signedVolume(box), 8.0, 1e-5);
    const Bounds b = box.bounds();
    EXPECT_EQ(b.min, glm::vec3(-1.0f, -0.5f, -2.0f));
    EXPECT_EQ(b.max, glm::vec3(1.0f, 0.5f, 2.0f));
    expectFacesPointAwayFrom(box, glm::vec3(0.0f));
    expectWellFormed(box);
}

TEST(MeshBuilder, BeveledBoxIsClosedRoundedAndKeepsItsFlatFaces) {
    BoxSettings s;
    s.halfExtents = {1.0f, 0.5f, 0.25f};
    s.bevel = 0.05f;
    s.bevelSteps = 3;
    s.maxEdge = 0.2f;
    const Mesh box = makeBeveledBox(s);
    EXPECT_TRUE(isClosed(box));
    expectFacesPointAwayFrom(box, glm::vec3(0.0f));
    expectWellFormed(box);
    const Bounds b = box.bounds();
    EXPECT_EQ(b.min, -s.halfExtents);
    EXPECT_EQ(b.max, s.halfExtents);
    // Volume of a box with rounded edges and corners of radius r.
    const double r = s.bevel, x = 2.0 - 2 * r, y = 1.0 - 2 * r, z = 0.5 - 2 * r;
    const double exact = x * y * z + 2 * r * (x * y + y * z + z * x) + M_PI * r * r * (x + y + z) +
                         4.0 / 3.0 * M_PI * r * r * r;
    EXPECT_NEAR(signedVolume(box), exact, 2e-3 * exact);
    EXPECT_LT(signedVolume(box), 1.0);
    // Every vertex on a rounded part lies at distance `bevel` from the inner box.
    for (const glm::vec3& p : box.positions) {
        const glm::vec3 inner = s.halfExtents - glm::vec3(s.bevel);
        const glm::vec3 d = p - glm::clamp(p, -inner, inner);
        if (int(d.x != 0) + int(d.y != 0) + int(d.z != 0) >= 2) {
            EXPECT_NEAR(glm::length(d), s.bevel, 1e-5f);
        }
    }
}

TEST(MeshBuilder, BeveledBoxPutsLatticeLinesOnBreaks) {
    BoxSettings s;
    s.halfExtents = glm::vec3(0.5f);
    s.bevel = 0.02f;
    s.maxEdge = 1.0f;
    s.breaks[0] = {0.123f, -0.3f, 0.49f /* inside the bevel: ignored */};
    const Mesh box = makeBeveledBox(s);
    bool found123 = false, found03 = false, found049 = false;
    for (const glm::vec3& p : box.positions) {
        found123 |= p.x == 0.123f;
        found03 |= p.x == -0.3f;
        found049 |= p.x == 0.49f;
    }
    EXPECT_TRUE(found123);
    EXPECT_TRUE(found03);
    EXPECT_FALSE(found049);
    EXPECT_TRUE(isClosed(box));
}

TEST(MeshBuilder, BoxRejectsNonFiniteOrNonPositiveExtents) {
    EXPECT_EQ(makeBox({1.0f, std::numeric_limits<float>::quiet_NaN(), 1.0f}, 2).vertexCount(), 0u);
    EXPECT_EQ(makeBox({1.0f, 0.0f, 1.0f}, 2).vertexCount(), 0u);
    BoxSettings s;
    s.halfExtents = {-1.0f, 1.0f, 1.0f};
    EXPECT_EQ(makeBeveledBox(s).vertexCount(), 0u);
    s.halfExtents = glm::vec3(1.0f);
    s.bevel = std::numeric_limits<float>::infinity();
    s.maxEdge = std::numeric_limits<float>::quiet_NaN();
    const Mesh box = makeBeveledBox(s);
    EXPECT_TRUE(isClosed(box));
    expectWellFormed(box);
}

TEST(MeshBuilder, SamplesIncludeEndsAndBreaksWithBoundedSteps) {
    const std::vector<float> s = makeSamples(-1.0f, 2.0f, 0.4f, {0.05f, 5.0f, -1.0f, 0.05f, 1.99995f});
    ASSERT_GE(s.size(), 2u);
    EXPECT_EQ(s.front(), -1.0f);
    EXPECT_EQ(s.back(), 2.0f);
    bool hasBreak = false;
    for (size_t i = 0; i < s.size(); ++i) {
        hasBreak |= s[i] == 0.05f;
        if (i > 0) {
            EXPECT_GE(s[i] - s[i - 1], 1e-4f);
            EXPECT_LE(s[i] - s[i - 1], 0.4f + 1e-4f);
        }
    }
    EXPECT_TRUE(hasBreak);
    EXPECT_EQ(makeSamples(1.0f, 1.0f, 0.1f), std::vector<float>{1.0f});
    EXPECT_TRUE(makeSamples(std::numeric_limits<float>::quiet_NaN(), 1.0f, 0.1f).empty());
}

TEST(MeshBuilder, SphereVerticesLieOnRadius) {
    const float radius = 1.75f;
    const Mesh sphere = makeSphere(radius, 12, 24);
    EXPECT_EQ(sphere.vertexCount(), 2u + 11u * 24u);
    EXPECT_EQ(sphere.triangleCount(), 2u * 24u * 11u);
    for (size_t i = 0; i < sphere.vertexCount(); ++i) {
        EXPECT_NEAR(glm::length(sphere.positions[i]), radius, 1e-5f * radius);
        EXPECT_NEAR(glm::dot(sphere.normals[i], glm::normalize(sphere.positions[i])), 1.0f, 1e-6f);
    }
    EXPECT_TRUE(isClosed(sphere));
    expectFacesPointAwayFrom(sphere, glm::vec3(0.0f));
    expectWellFormed(sphere);
    const double exact = 4.0 / 3.0 * M_PI * radius * radius * radius;
    EXPECT_GT(signedVolume(sphere), 0.9 * exact);
    EXPECT_LT(signedVolume(sphere), exact);
}

TEST(MeshBuilder, LatheRingsFollowTheDocumentedAngles) {
    const Mesh lathe = makeLathe({{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 2.0f}, {0.0f, 2.0f}}, 4);
    ASSERT_EQ(lathe.vertexCount(), 2u + 2u * 4u);
    EXPECT_EQ(lathe.positions[0], glm::vec3(0.0f));
    EXPECT_NEAR(lathe.positions[1].z, 1.0f, 1e-6f); // k = 0 at (0, y, r)
    EXPECT_NEAR(lathe.positions[2].x, 1.0f, 1e-6f); // k = 1 at (r, y, 0)
    EXPECT_TRUE(isClosed(lathe));
    EXPECT_NEAR(signedVolume(lathe), 4.0, 1e-5); // a square prism of side sqrt(2), height 2
}

TEST(MeshBuilder, LatheRejectsBadProfiles) {
    EXPECT_EQ(makeLathe({{0.0f, 0.0f}}, 8).vertexCount(), 0u);
    EXPECT_EQ(makeLathe({{0.0f, 0.0f}, {0.0f, 1.0f}, {0.0f, 2.0f}}, 8).vertexCount(), 0u);
    EXPECT_EQ(makeLathe({{0.0f, 0.0f}, {std::nanf(""), 1.0f}, {0.0f, 2.0f}}, 8).vertexCount(), 0u);
    EXPECT_EQ(makeLathe({{-1.0f, 0.0f}, {1.0f, 1.0f}}, 8).vertexCount(), 0u);
    // An open lathe (no poles) is valid but has borders.
    const Mesh tube = makeLathe({{1.0f, 0.0f}, {1.0f, 1.0f}}, 8);
    EXPECT_EQ(tube.triangleCount(), 16u);
    EXPECT_FALSE(isClosed(tube));
}

TEST(MeshBuilder, CylinderIsClosedWithExpectedVolume) {
    const Mesh plain = makeCylinder(0.5f, 2.0f, 64);
    EXPECT_TRUE(isClosed(plain));
    EXPECT_NEAR(signedVolume(plain), M_PI * 0.25 * 2.0, 0.01 * M_PI * 0.5);
    const Bounds b = plain.bounds();
    EXPECT_FLOAT_EQ(b.min.y, 0.0f);
    EXPECT_FLOAT_EQ(b.max.y, 2.0f);
    const Mesh bevelled = makeCylinder(0.5f, 2.0f, 64, 0.05f);
    EXPECT_TRUE(isClosed(bevelled));
    expectWellFormed(bevelled);
    EXPECT_LT(signedVolume(bevelled), signedVolume(plain));
    EXPECT_EQ(makeCylinder(0.5f, -1.0f, 16).vertexCount(), 0u);
}

TEST(MeshBuilder, GridFacesUpWithWorldScaleUvs) {
    const Mesh grid = makeGrid({-1.0f, 0.0f, 2.0f}, {0.0f, 0.5f});
    EXPECT_EQ(grid.vertexCount(), 6u);
    EXPECT_EQ(grid.triangleCount(), 4u);
    for (size_t i = 0; i < grid.vertexCount(); ++i) {
        EXPECT_EQ(grid.normals[i], glm::vec3(0.0f, 1.0f, 0.0f));
        EXPECT_EQ(grid.uvs[i], glm::vec2(grid.positions[i].x, grid.positions[i].z));
    }
    expectWellFormed(grid);
    EXPECT_EQ(makeGrid({0.0f, 0.0f}, {0.0f, 1.0f}).vertexCount(), 0u);
}

TEST(MeshBuilder, DisplaceMovesAlongNormalsAndKeepsClosure) {
    Mesh sphere = makeSphere(1.0f, 16, 32);
    displace(sphere, [](const glm::vec3&, const glm::vec3&) { return 0.25f; });
    for (const glm::vec3& p : sphere.positions)
        EXPECT_NEAR(glm::length(p), 1.25f, 1e-5f);
    EXPECT_TRUE(isClosed(sphere));
    expectWellFormed(sphere);

    Mesh box = makeBox(glm::vec3(1.0f), 4);
    const std::vector<glm::vec3> before = box.positions;
    displace(box, [](const glm::vec3& p, const glm::vec3&) { return p.y > 0.99f ? std::nanf("") : -0.1f; });
    for (size_t i = 0; i < before.size(); ++i) {
        if (before[i].y > 0.99f) {
            EXPECT_EQ(box.positions[i], before[i]);
        } else {
            EXPECT_NEAR(glm::distance(box.positions[i], before[i]), 0.1f, 1e-6f);
        }
    }
    expectWellFormed(box);
}

TEST(MeshBuilder, AppendMeshTransformsPositionsNormalsAndIndices) {
    Mesh dst = makeUnitCube();
    const Mesh cube = makeUnitCube();
    const glm::mat4 xf = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(5.0f, 0.0f, 0.0f)),
                                     0.5f * float(M_PI), glm::vec3(0.0f, 0.0f, 1.0f));
    appendMesh(dst, cube, xf);
    ASSERT_EQ(dst.vertexCount(), 16u);
    ASSERT_EQ(dst.triangleCount(), 24u);
    EXPECT_TRUE(dst.submeshes.empty());
    for (size_t i = 0; i < 8; ++i) {
        const glm::vec3 p = cube.positions[i];
        const glm::vec3 expected(5.0f - p.y, p.x, p.z); // rotate 90 degrees about Z, then translate
        EXPECT_NEAR(glm::distance(dst.positions[8 + i], expected), 0.0f, 1e-5f);
        const glm::vec3 n = cube.normals[i];
        EXPECT_NEAR(glm::distance(dst.normals[8 + i], glm::vec3(-n.y, n.x, n.z)), 0.0f, 1e-5f);
        EXPECT_EQ(dst.uvs[8 + i], cube.uvs[i]);
    }
    for (size_t k = 0; k < cube.indices.size(); ++k)
        EXPECT_EQ(dst.indices[36 + k], cube.indices[k] + 8u);
    EXPECT_TRUE(isClosed(dst));
    EXPECT_NEAR(signedVolume(dst), 2.0, 1e-5);
    expectWellFormed(dst);
}

TEST(MeshBuilder, AppendMeshMirrorKeepsTrianglesFacingOutward) {
    Mesh dst;
    appendMesh(dst, makeSphere(1.0f, 8, 16), glm::scale(glm::mat4(1.0f), glm::vec3(-2.0f, 1.0f, 1.0f)));
    EXPECT_TRUE(isClosed(dst));
    EXPECT_GT(signedVolume(dst), 0.0);
    expectFacesPointAwayFrom(dst, glm::vec3(0.0f));
    for (size_t i = 0; i < dst.vertexCount(); ++i) {
        const glm::vec3 p = dst.positions[i];
        EXPECT_GT(glm::dot(dst.normals[i], glm::vec3(p.x / 4.0f, p.y, p.z)), 0.0f); // ellipsoid gradient
    }
}

TEST(MeshBuilder, AppendMeshMergesSubmeshesAndDropsMissingAttributes) {
    Mesh dst = makeUnitCube();
    Mesh src = makeUnitCube();
    src.submeshes = {{0, 18, 3}, {18, 18, 4}};
    src.uvs.clear();
    appendMesh(dst, src, glm::mat4(1.0f));
    ASSERT_EQ(dst.submeshes.size(), 3u);
    EXPECT_EQ(dst.submeshes[0].firstIndex, 0u);
    EXPECT_EQ(dst.submeshes[0].indexCount, 36u);
    EXPECT_EQ(dst.submeshes[0].material, -1);
    EXPECT_EQ(dst.submeshes[1].firstIndex, 36u);
    EXPECT_EQ(dst.submeshes[1].material, 3);
    EXPECT_EQ(dst.submeshes[2].firstIndex, 54u);
    EXPECT_EQ(dst.submeshes[2].material, 4);
    EXPECT_TRUE(dst.uvs.empty());
    EXPECT_EQ(dst.normals.size(), 16u);
    EXPECT_TRUE(validateMesh(dst).ok()) << validateMesh(dst).error();
}
