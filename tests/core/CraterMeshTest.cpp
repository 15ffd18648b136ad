#include "spatter/core/CraterMesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <utility>

using namespace spatter;

namespace {

// Number of triangles using each undirected edge.
std::map<std::pair<uint32_t, uint32_t>, int> edgeUse(const Mesh& m) {
    std::map<std::pair<uint32_t, uint32_t>, int> use;
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            uint32_t a = m.indices[t + size_t(k)], b = m.indices[t + size_t((k + 1) % 3)];
            ++use[{std::min(a, b), std::max(a, b)}];
        }
    return use;
}

} // namespace

TEST(CraterMesh, RimLiesInTheZeroPlaneAndNothingRisesAboveIt) {
    const CraterShape shape;
    for (uint32_t v = 0; v < 4; ++v) {
        Result<Mesh> m = makeCraterMesh(v, shape);
        ASSERT_TRUE(m) << m.error();
        ASSERT_TRUE(validateMesh(m.value()));
        float maxRadius = 0.0f;
        for (size_t i = 0; i < m->positions.size(); ++i) {
            const glm::vec3 p = m->positions[i];
            if (i < size_t(shape.segments))
                EXPECT_EQ(p.z, 0.0f);
            else
                EXPECT_LT(p.z, 0.0f);
            maxRadius = std::max(maxRadius, glm::length(glm::vec2(p)));
        }
        EXPECT_NEAR(maxRadius, 1.0f, 1e-5f);
    }
}

TEST(CraterMesh, OpenBoundaryIsOneLoopOfTheRimAndTheRestIsClosed) {
    const CraterShape shape;
    Result<Mesh> m = makeCraterMesh(7, shape);
    ASSERT_TRUE(m) << m.error();
    std::map<uint32_t, int> boundaryDegree;
    size_t boundaryEdges = 0;
    for (const auto& [e, n] : edgeUse(m.value())) {
        ASSERT_LE(n, 2) << "non-manifold edge " << e.first << "-" << e.second;
        if (n == 1) {
            ++boundaryEdges;
            ++boundaryDegree[e.first];
            ++boundaryDegree[e.second];
            EXPECT_LT(e.first, uint32_t(shape.segments));
            EXPECT_LT(e.second, uint32_t(shape.segments));
        }
    }
    EXPECT_EQ(boundaryEdges, size_t(shape.segments));
    EXPECT_EQ(boundaryDegree.size(), size_t(shape.segments));
    for (const auto& [v, d] : boundaryDegree)
        EXPECT_EQ(d, 2) << "rim vertex " << v;
}

TEST(CraterMesh, TrianglesFaceOutOfTheCavity) {
    Result<Mesh> m = makeCraterMesh(3);
    ASSERT_TRUE(m) << m.error();
    for (size_t t = 0; t < m->indices.size(); t += 3) {
        const glm::vec3 a = m->positions[m->indices[t]], b = m->positions[m->indices[t + 1]],
                        c = m->positions[m->indices[t + 2]];
        EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << "triangle " << t / 3;
    }
}

TEST(CraterMesh, SameVariantSameMeshAndVariantsDiffer) {
    Result<Mesh> a = makeCraterMesh(11), b = makeCraterMesh(11), c = makeCraterMesh(12);
    ASSERT_TRUE(a && b && c);
    EXPECT_EQ(a->positions, b->positions);
    EXPECT_EQ(a->indices, b->indices);
    EXPECT_NE(a->positions, c->positions);
}

TEST(CraterMesh, RejectsShapesOutOfRange) {
    CraterShape s;
    s.depth = std::nanf("");
    EXPECT_FALSE(makeCraterMesh(0, s));
    s = {};
    s.segments = 3;
    EXPECT_FALSE(makeCraterMesh(0, s));
    s = {};
    s.chip = 0.95f;
    Result<Mesh> r = makeCraterMesh(0, s);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().find("chip"), std::string::npos);
}

TEST(CraterMesh, DepthBoundHoldsForEveryVariantAndShape) {
    for (const float depth : {0.2f, 0.45f, 1.5f})
        for (const float roughness : {0.0f, 0.08f, 0.5f}) {
            CraterShape shape;
            shape.depth = depth;
            shape.roughness = roughness;
            for (uint32_t v = 0; v < 32; ++v) {
                const Result<Mesh> m = makeCraterMesh(v, shape);
                ASSERT_TRUE(m.ok()) << m.error();
                for (const glm::vec3& p : m.value().positions)
                    EXPECT_LE(-p.z, craterDepthBound(shape)) << "variant " << v;
            }
        }
}
