#include "spatter/core/Mesh.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

using namespace spatter;
using ::testing::HasSubstr;

static Mesh quad() {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    m.indices = {0, 1, 2, 0, 2, 3};
    computeNormals(m);
    return m;
}

TEST(Mesh, ValidQuadPassesValidation) {
    EXPECT_TRUE(validateMesh(quad()).ok());
}

TEST(Mesh, RejectsIndexPastVertexCount) {
    Mesh m = quad();
    m.indices[4] = 9;
    EXPECT_THAT(validateMesh(m).error(), HasSubstr("past the vertex count"));
}

TEST(Mesh, RejectsNonFinitePosition) {
    Mesh m = quad();
    m.positions[2].y = INFINITY;
    EXPECT_THAT(validateMesh(m).error(), HasSubstr("not finite"));
}

TEST(Mesh, RejectsIndexCountNotMultipleOfThree) {
    Mesh m = quad();
    m.indices.push_back(0);
    EXPECT_THAT(validateMesh(m).error(), HasSubstr("multiple of 3"));
}

TEST(Mesh, RejectsMismatchedAttributeArrays) {
    Mesh m = quad();
    m.uvs.pop_back();
    EXPECT_THAT(validateMesh(m).error(), HasSubstr("UVs"));
}

TEST(Mesh, RejectsSubmeshOutsideIndices) {
    Mesh m = quad();
    m.submeshes.push_back({3, 6, -1});
    EXPECT_THAT(validateMesh(m).error(), HasSubstr("submesh 0"));
}

TEST(Mesh, ComputedNormalsAreUnitAndFaceTheWinding) {
    const Mesh m = quad();
    for (const glm::vec3& n : m.normals)
        EXPECT_NEAR(n.z, 1.0f, 1e-6f);
}

TEST(Mesh, DegenerateAndUnreferencedVerticesGetValidNormals) {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {5, 5, 5}}; // collinear triangle, unused vertex
    m.indices = {0, 1, 2};
    computeNormals(m);
    for (const glm::vec3& n : m.normals)
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
}

TEST(Mesh, RepairReplacesOnlyBadNormals) {
    Mesh m = quad();
    m.normals[0] = glm::vec3(NAN);
    m.normals[1] = glm::vec3(0.0f);
    m.normals[2] = glm::vec3(0, 0, 3);
    EXPECT_EQ(repairNormals(m), 2u);
    for (const glm::vec3& n : m.normals)
        EXPECT_NEAR(n.z, 1.0f, 1e-6f);
}

TEST(Mesh, TangentsFollowUvDirection) {
    Mesh m = quad();
    computeTangents(m);
    ASSERT_EQ(m.tangents.size(), 4u);
    for (const glm::vec4& t : m.tangents) {
        EXPECT_NEAR(t.x, 1.0f, 1e-6f);
        EXPECT_EQ(t.w, 1.0f);
    }
}

TEST(Mesh, TangentsWithoutUvsArePerpendicularToNormals) {
    Mesh m = quad();
    m.uvs.clear();
    computeTangents(m);
    for (size_t i = 0; i < m.tangents.size(); ++i) {
        EXPECT_NEAR(glm::length(glm::vec3(m.tangents[i])), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(glm::vec3(m.tangents[i]), m.normals[i]), 0.0f, 1e-6f);
    }
}
