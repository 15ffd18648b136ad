#include "spatter/core/SceneLoader.hpp"

#include "TestData.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

using namespace spatter;
using ::testing::HasSubstr;

static std::string writeFile(const std::string& dir, const std::string& name, const std::string& text) {
    const std::string path = dir + "/" + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

static void expectMesh(const std::string& path, size_t vertices, size_t triangles) {
    Result<Scene> scene = loadScene(path);
    ASSERT_TRUE(scene.ok()) << scene.error();
    ASSERT_EQ(scene->objects.size(), 1u);
    const SceneObject& o = scene->objects[0];
    EXPECT_EQ(o.mesh->vertexCount(), vertices);
    EXPECT_EQ(o.mesh->triangleCount(), triangles);
    EXPECT_FALSE(o.dynamic);
    EXPECT_TRUE(o.receivesDecals);
    EXPECT_TRUE(validateMesh(*o.mesh).ok());
}

// Counts from ../shared/data/SOURCES.md.
TEST(MeshFileLoader, LoadsOpenBunnyWithEveryTriangleAndUnreferencedVertex) {
    SPATTER_REQUIRE_SHARED(path, "meshes/stanford-bunny.obj");
    expectMesh(path, 35947, 69451);
}

TEST(MeshFileLoader, LoadsFandisk) {
    SPATTER_REQUIRE_SHARED(path, "meshes/fandisk.obj");
    expectMesh(path, 6475, 12946);
}

TEST(MeshFileLoader, LoadsRockerArm) {
    SPATTER_REQUIRE_SHARED(path, "meshes/rocker-arm.obj");
    expectMesh(path, 10044, 20088);
}

TEST(MeshFileLoader, LoadsEachFormat) {
    const std::string dir = test::scratchDir("meshformats");
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    const std::string off = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
    const std::string ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                            "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const std::string stl = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                            "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
    expectMesh(writeFile(dir, "quad.obj", obj), 4, 2);
    expectMesh(writeFile(dir, "quad.off", off), 4, 2);
    expectMesh(writeFile(dir, "tri.ply", ply), 3, 1);
    expectMesh(writeFile(dir, "tri.stl", stl), 3, 1);
}

TEST(MeshFileLoader, RejectsMissingFile) {
    Result<Scene> scene = loadScene("/nonexistent/dir/mesh.obj");
    EXPECT_THAT(scene.error(), HasSubstr("not found"));
    EXPECT_THAT(scene.error(), HasSubstr("mesh.obj"));
}

TEST(MeshFileLoader, RejectsEmptyFile) {
    const std::string dir = test::scratchDir("meshempty");
    EXPECT_THAT(loadScene(writeFile(dir, "empty.obj", "")).error(), HasSubstr("empty"));
}

TEST(MeshFileLoader, RejectsFileWithoutFaces) {
    const std::string dir = test::scratchDir("meshnofaces");
    EXPECT_THAT(loadScene(writeFile(dir, "points.obj", "v 0 0 0\nv 1 0 0\n")).error(), HasSubstr("no faces"));
}

TEST(MeshFileLoader, RejectsUnparseablePositionInObj) {
    const std::string dir = test::scratchDir("meshnanobj");
    EXPECT_FALSE(loadScene(writeFile(dir, "nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n")).ok());
}

TEST(MeshFileLoader, RejectsNonFinitePositionInBinaryPly) {
    const std::string dir = test::scratchDir("meshnanply");
    std::string bytes = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                        "property float y\nproperty float z\nelement face 1\n"
                        "property list uchar int vertex_indices\nend_header\n";
    const float xyz[9] = {0, 0, 0, NAN, 0, 0, 0, 1, 0};
    const uint8_t corners = 3;
    const int32_t face[3] = {0, 1, 2};
    bytes.append(reinterpret_cast<const char*>(xyz), sizeof(xyz));
    bytes.append(reinterpret_cast<const char*>(&corners), 1);
    bytes.append(reinterpret_cast<const char*>(face), sizeof(face));
    Result<Scene> scene = loadScene(writeFile(dir, "nan.ply", bytes));
    EXPECT_THAT(scene.error(), HasSubstr("not finite"));
}

TEST(MeshFileLoader, RejectsIndexPastVertexCount) {
    const std::string dir = test::scratchDir("meshindex");
    Result<Scene> scene = loadScene(writeFile(dir, "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n"));
    EXPECT_FALSE(scene.ok());
}
