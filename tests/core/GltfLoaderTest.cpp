// loadGltf on small glTF files written by each test: a valid quad scene, then one defect at a time.

#include "spatter/core/SceneLoader.hpp"

#include "FifoWriter.hpp"
#include "GltfBuilder.hpp"
#include "GltfLoading.hpp"
#include "TestData.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include <sys/stat.h>

using namespace spatter;
using ::testing::HasSubstr;
using ::testing::Not;
using json = nlohmann::json;
using namespace spatter::test;

namespace {

std::vector<uint8_t> readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::vector<uint8_t> packIndices(const std::vector<uint32_t>& indices, int componentType) {
    std::vector<uint8_t> out;
    const size_t size = componentType == kUnsignedByte ? 1 : componentType == kUnsignedShort ? 2 : 4;
    for (uint32_t i : indices)
        for (size_t b = 0; b < size; ++b)
            out.push_back(uint8_t(i >> (8 * b)));
    return out;
}

// One node "quad" with a one-primitive mesh: positions in accessor 0, indices in accessor 1.
GltfBuilder quadScene(int indexType = kUnsignedShort) {
    GltfBuilder g;
    g.addAccessor(g.addView(kQuad), kFloat, kQuad.size(), "VEC3");
    g.addAccessor(g.addView(packIndices(kQuadIndices, indexType)), indexType, kQuadIndices.size(), "SCALAR");
    g.push("meshes",
           {{"name", "quadMesh"}, {"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}});
    g.push("nodes", {{"name", "quad"}, {"mesh", 0}});
    g.doc["scenes"] = {{{"nodes", {0}}}};
    g.doc["scene"] = 0;
    return g;
}

glm::dvec3 worldPoint(const SceneObject& o, size_t vertex) {
    return glm::dvec3(o.transform * glm::dvec4(glm::dvec3(o.mesh->positions[vertex]), 1.0));
}

void expectNear(const glm::dvec3& a, const glm::dvec3& b, double tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

} // namespace

// --- valid files ---------------------------------------------------------------------------------

TEST(GltfLoader, LoadsIndexedQuad) {
    const std::string path = quadScene().writeGltf(scratchForTest("gltf-"), "quad");
    Scene scene = loaded(path);
    ASSERT_EQ(scene.objects.size(), 1u);
    const SceneObject& o = scene.objects[0];
    EXPECT_EQ(o.name, "quad");
    EXPECT_EQ(scene.source, path);
    EXPECT_EQ(o.mesh->positions, kQuad);
    EXPECT_EQ(o.mesh->indices, kQuadIndices);
    ASSERT_EQ(o.mesh->submeshes.size(), 1u);
    EXPECT_EQ(o.mesh->submeshes[0].indexCount, 6u);
    EXPECT_EQ(o.mesh->submeshes[0].material, -1);
    EXPECT_TRUE(o.mesh->uvs.empty());
    EXPECT_TRUE(o.mesh->tangents.empty());
    EXPECT_FALSE(o.dynamic);
    EXPECT_TRUE(o.receivesDecals);
    EXPECT_FALSE(o.collider.has_value());
}

TEST(GltfLoader, ReadsEightSixteenAndThirtyTwoBitIndices) {
    const std::string dir = scratchForTest("gltf-");
    for (int type : {kUnsignedByte, kUnsignedShort, kUnsignedInt}) {
        SCOPED_TRACE(type);
        Scene scene = loaded(quadScene(type).writeGltf(dir, "quad" + std::to_string(type)));
        ASSERT_EQ(scene.objects.size(), 1u);
        EXPECT_EQ(scene.objects[0].mesh->indices, kQuadIndices);
    }
}

TEST(GltfLoader, RejectsSignedIndices) {
    GltfBuilder g = quadScene();
    g.doc["accessors"][1]["componentType"] = 5122;
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "signed")),
                HasSubstr("accessor 1 (indices) has component type"));
}

TEST(GltfLoader, LoadsNonIndexedTriangles) {
    GltfBuilder g = quadScene();
    const std::vector<glm::vec3> soup = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    g.doc["accessors"][0] = {
        {"bufferView", g.addView(soup)}, {"componentType", kFloat}, {"count", 6}, {"type", "VEC3"}};
    g.doc["meshes"][0]["primitives"][0].erase("indices");
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-"), "soup"));
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].mesh->indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
    EXPECT_EQ(scene.objects[0].mesh->positions, soup);
}

TEST(GltfLoader, ReadsInterleavedAttributesWithOffsets) {
    // Per vertex: position (12 bytes), normal (12), uv (8), tangent (16) = 48 bytes; one leading
    // vertex of garbage skipped through the accessors' byteOffset.
    struct Vertex {
        float p[3], n[3], uv[2], t[4];
    };
    std::vector<Vertex> vertices = {{{9, 9, 9}, {9, 9, 9}, {9, 9}, {9, 9, 9, 9}}};
    for (size_t i = 0; i < kQuad.size(); ++i)
        vertices.push_back({{kQuad[i].x, kQuad[i].y, 0}, {0, 0, 2}, {0.25f * float(i), 0.5f}, {2, 0, 0, -3}});
    GltfBuilder g = quadScene();
    const int view = g.addView(vertices, sizeof(Vertex));
    g.doc["accessors"][0] = {
        {"bufferView", view}, {"componentType", kFloat}, {"count", 4}, {"type", "VEC3"}, {"byteOffset", 48}};
    const int normal = g.addAccessor(view, kFloat, 4, "VEC3", 48 + 12);
    const int uv = g.addAccessor(view, kFloat, 4, "VEC2", 48 + 24);
    const int tangent = g.addAccessor(view, kFloat, 4, "VEC4", 48 + 32);
    g.doc["meshes"][0]["primitives"][0]["attributes"] = {
        {"POSITION", 0}, {"NORMAL", normal}, {"TEXCOORD_0", uv}, {"TANGENT", tangent}};
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-"), "interleaved"));
    ASSERT_EQ(scene.objects.size(), 1u);
    const Mesh& m = *scene.objects[0].mesh;
    EXPECT_EQ(m.positions, kQuad);
    ASSERT_EQ(m.uvs.size(), 4u);
    ASSERT_EQ(m.tangents.size(), 4u);
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(m.normals[i], glm::vec3(0, 0, 1)); // normalised from (0, 0, 2)
        EXPECT_EQ(m.uvs[i], glm::vec2(0.25f * float(i), 0.5f));
        EXPECT_EQ(m.tangents[i], glm::vec4(1, 0, 0, -1)); // unit xyz, w reduced to its sign
    }
}

TEST(GltfLoader, ReadsNormalizedIntegerUvs) {
    GltfBuilder g = quadScene();
    const std::vector<uint16_t> uvs = {0, 0, 65535, 0, 65535, 65535, 0, 32768};
    const int uv = g.addAccessor(g.addView(uvs), kUnsignedShort, 4, "VEC2");
    g.doc["accessors"][uv]["normalized"] = true;
    g.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = uv;
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-"), "uv16"));
    ASSERT_EQ(scene.objects.size(), 1u);
    const std::vector<glm::vec2>& got = scene.objects[0].mesh->uvs;
    ASSERT_EQ(got.size(), 4u);
    EXPECT_EQ(got[0], glm::vec2(0, 0));
    EXPECT_EQ(got[2], glm::vec2(1, 1));
    EXPECT_FLOAT_EQ(got[3].y, 32768.0f / 65535.0f);
}

TEST(GltfLoader, ReadsNormalizedSignedBytePositionsUnderMeshQuantization) {
    GltfBuilder g = quadScene();
    const std::vector<int8_t> packed = {0, 0, 0, 0, 127, 0, 0, 0, -128, 127, 0, 0, 0, 127, 0, 0};
    g.doc["accessors"][0] = {{"bufferView", g.addView(packed.data(), packed.size(), 4)},
                             {"componentType", kByte},
                             {"count", 4},
                             {"type", "VEC3"},
                             {"normalized", true}};
    g.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
    g.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-"), "quantized"));
    ASSERT_EQ(scene.objects.size(), 1u);
    const std::vector<glm::vec3>& p = scene.objects[0].mesh->positions;
    EXPECT_EQ(p[1], glm::vec3(1, 0, 0));
    EXPECT_EQ(p[2], glm::vec3(-1, 1, 0)); // -128 clamps to -1
}

TEST(GltfLoader, MatrixAndTrsGiveTheSameTransform) {
    GltfBuilder g = quadScene();
    const glm::dvec3 t(1.5, -2, 3);
    const glm::dquat q = glm::angleAxis(0.7, glm::normalize(glm::dvec3(1, 2, 3)));
    const glm::dvec3 s(2, 3, 0.5);
    const glm::dmat4 expected =
        glm::translate(glm::dmat4(1.0), t) * glm::mat4_cast(q) * glm::scale(glm::dmat4(1.0), s);
    std::vector<double> matrix(&expected[0][0], &expected[0][0] + 16);
    g.doc["nodes"][0]["translation"] = {t.x, t.y, t.z};
    g.doc["nodes"][0]["rotation"] = {q.x, q.y, q.z, q.w};
    g.doc["nodes"][0]["scale"] = {s.x, s.y, s.z};
    g.push("nodes", {{"name", "byMatrix"}, {"mesh", 0}, {"matrix", matrix}});
    g.doc["scenes"][0]["nodes"] = {0, 1};
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-"), "trs"));
    ASSERT_EQ(scene.objects.size(), 2u);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            EXPECT_NEAR(scene.objects[0].transform[c][r], expected[c][r], 1e-12);
            EXPECT_NEAR(scene.objects[1].transform[c][r], expected[c][r], 1e-12);
        }
}

TEST(GltfLoader, ComposesNodeHierarchyInDoublePrecision) {
    GltfBuilder g = quadScene();
    // root: far from the origin, scaled by 2; middle: no mesh, 90 degrees about +Z; leaf: the quad.
    g.doc["nodes"] = {
        {{"name", "root"}, {"translation", {1e7, 0, 0}}, {"scale", {2, 2, 2}}, {"children", {1}}},
        {{"name", "turn"}, {"rotation", {0, 0, std::sqrt(0.5), std::sqrt(0.5)}}, {"children", {2}}},
        {{"name", "leaf"}, {"translation", {0, 0, 1}}, {"mesh", 0}}};
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-"), "hierarchy"));
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].name, "leaf");
    // Vertex (1, 1, 0): leaf (1, 1, 1), turned (-1, 1, 1), scaled (-2, 2, 2), moved (1e7 - 2, 2, 2).
    expectNear(worldPoint(scene.objects[0], 2), glm::dvec3(1e7 - 2, 2, 2), 1e-6);
    expectNear(worldPoint(scene.objects[0], 1), glm::dvec3(1e7, 2, 2), 1e-6);
}

TEST(GltfLoader, UsesTheDefaultSceneOrElseEveryRootNode) {
    GltfBuilder g = quadScene();
    g.push("nodes", {{"name", "other"}, {"mesh", 0}});
    g.doc["scenes"] = {{{"nodes", {0}}}, {{"nodes", {1}}}};
    g.doc["scene"] = 1;
    const std::string dir = scratchForTest("gltf-");
    Scene chosen = loaded(g.writeGltf(dir, "scene1"));
    ASSERT_EQ(chosen.objects.size(), 1u);
    EXPECT_EQ(chosen.objects[0].name, "other");

    g.doc.erase("scene");
    Scene first = loaded(g.writeGltf(dir, "scene0"));
    ASSERT_EQ(first.objects.size(), 1u);
    EXPECT_EQ(first.objects[0].name, "quad");

    g.doc.erase("scenes");
    Scene all = loaded(g.writeGltf(dir, "noscene"));
    ASSERT_EQ(all.objects.size(), 2u);
}

TEST(GltfLoader, NamesObjectsAfterNodeThenMeshThenIndex) {
    GltfBuilder g = quadScene();
    g.doc["nodes"][0].erase("name");
    g.push("meshes", g.doc["meshes"][0]);
    g.doc["meshes"][1].erase("name");
    g.push("nodes", {{"mesh", 1}});
    g.doc["scenes"][0]["nodes"] = {0, 1};
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-"), "names"));
    ASSERT_EQ(scene.objects.size(), 2u);
    EXPECT_EQ(scene.objects[0].name, "quadMesh");
    EXPECT_EQ(scene.objects[1].name, "node1");
}

TEST(GltfLoader, ExtrasSetDynamicAndDecalFlagsAndDescendantsInheritThem) {
    GltfBuilder g = quadScene();
    g.doc["nodes"] = {{{"name", "crate"}, {"mesh", 0}, {"extras", {{"dynamic", true}}}, {"children", {1}}},
                      {{"name", "lid"}, {"mesh", 0}},
                      {{"name", "glass"}, {"mesh", 0}, {"extras", {{"decals", false}}}, {"children", {3}}},
                      {{"name", "pane"}, {"mesh", 0}, {"children", {4}}},
                      {{"name", "sticker"}, {"mesh", 0}, {"extras", {{"decals", true}}}}};
    g.doc["scenes"][0]["nodes"] = {0, 2};
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-"), "flags"));
    ASSERT_EQ(scene.objects.size(), 5u);
    const std::vector<std::string> names = {"crate", "lid", "glass", "pane", "sticker"};
    const std::vector<bool> dynamic = {true, true, false, false, false};
    const std::vector<bool> decals = {true, true, false, false, true};
    for (size_t i = 0; i < 5; ++i) {
        EXPECT_EQ(scene.objects[i].name, names[i]);
        EXPECT_EQ(scene.objects[i].dynamic, dynamic[i]) << names[i];
        EXPECT_EQ(scene.objects[i].receivesDecals, decals[i]) << names[i];
    }
}

TEST(GltfLoader, RejectsStaticChildOfDynamicNode) {
    GltfBuilder g = quadScene();
    g.doc["nodes"] = {{{"name", "door"}, {"mesh", 0}, {"extras", {{"dynamic", true}}}, {"children", {1}}},
                      {{"name", "handle"}, {"mesh", 0}, {"extras", {{"dynamic", false}}}}};
    const std::string error = rejection(g.writeGltf(scratchForTest("gltf-"), "static-child"));
    EXPECT_THAT(error, HasSubstr("handle"));
    EXPECT_THAT(error, HasSubstr("dynamic"));
}

TEST(GltfLoader, RejectsNonBooleanFlag) {
    GltfBuilder g = quadScene();
    g.doc["nodes"][0]["extras"] = {{"decals", "no"}};
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "flag")),
                HasSubstr("extras.decals is not a boolean"));
}

TEST(GltfLoader, CollidersJoinTheirDrawnAncestorAndAreNotDrawn) {
    GltfBuilder g = quadScene();
    // wall at x = 5; UCX_ child 1 up in z; an empty group below it holding a -col child 2 up in z.
    g.doc["nodes"] = {{{"name", "wall"}, {"mesh", 0}, {"translation", {5, 0, 0}}, {"children", {1, 2}}},
                      {{"name", "UCX_wall"}, {"mesh", 0}, {"translation", {0, 0, 1}}},
                      {{"name", "group"}, {"scale", {2, 2, 2}}, {"children", {3}}},
                      {{"name", "wall-col"}, {"mesh", 0}, {"translation", {0, 0, 1}}}};
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-"), "collider"));
    ASSERT_EQ(scene.objects.size(), 1u);
    const SceneObject& wall = scene.objects[0];
    EXPECT_EQ(wall.name, "wall");
    EXPECT_EQ(wall.mesh->triangleCount(), 2u);
    ASSERT_TRUE(wall.collider.has_value());
    const Mesh& c = *wall.collider;
    ASSERT_EQ(c.positions.size(), 8u);
    EXPECT_EQ(c.triangleCount(), 4u);
    EXPECT_EQ(c.normals.size(), 8u);
    for (size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(c.positions[i], kQuad[i] + glm::vec3(0, 0, 1)); // wall space, not world
        EXPECT_EQ(c.positions[4 + i], 2.0f * kQuad[i] + glm::vec3(0, 0, 2));
    }
    EXPECT_EQ(c.indices[6], 4u); // second collider's indices follow its own vertices
}

TEST(GltfLoader, RejectsColliderWithoutDrawnAncestor) {
    GltfBuilder g = quadScene();
    g.push("nodes", {{"name", "UCX_floor"}, {"mesh", 0}});
    g.doc["scenes"][0]["nodes"] = {0, 1};
    const std::string error = rejection(g.writeGltf(scratchForTest("gltf-"), "orphan"));
    EXPECT_THAT(error, HasSubstr("UCX_floor"));
    EXPECT_THAT(error, HasSubstr("no ancestor"));
}

TEST(GltfLoader, ComputesNormalsWhenAbsent) {
    Scene scene = loaded(quadScene().writeGltf(scratchForTest("gltf-"), "nonormals"));
    ASSERT_EQ(scene.objects.size(), 1u);
    ASSERT_EQ(scene.objects[0].mesh->normals.size(), 4u);
    for (const glm::vec3& n : scene.objects[0].mesh->normals)
        EXPECT_EQ(n, glm::vec3(0, 0, 1));
}

TEST(GltfLoader, RepairsNonFiniteAndZeroNormals) {
    GltfBuilder g = quadScene();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<glm::vec3> normals = {{0, 0, 1}, {nan, 0, 0}, {0, 0, 0}, {0, 0, 3}};
    g.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] =
        g.addAccessor(g.addView(normals), kFloat, 4, "VEC3");
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-"), "badnormals"));
    ASSERT_EQ(scene.objects.size(), 1u);
    for (const glm::vec3& n : scene.objects[0].mesh->normals)
        EXPECT_EQ(n, glm::vec3(0, 0, 1));
}

TEST(GltfLoader, ConvertsTriangleStripsAndFans) {
    const std::string dir = scratchForTest("gltf-");
    // Both orders cover the quad with two counter-clockwise triangles.
    for (auto [mode, order] : {std::pair<int, std::vector<uint32_t>>{5, {0, 1, 3, 2}}, {6, {0, 1, 2, 3}}}) {
        SCOPED_TRACE(mode);
        GltfBuilder g = quadScene(kUnsignedInt);
        g.doc["accessors"][1] = {{"bufferView", g.addView(order)},
                                 {"componentType", kUnsignedInt},
                                 {"count", 4},
                                 {"type", "SCALAR"}};
        g.doc["meshes"][0]["primitives"][0]["mode"] = mode;
        Scene scene = loaded(g.writeGltf(dir, "mode" + std::to_string(mode)));
        ASSERT_EQ(scene.objects.size(), 1u);
        const Mesh& m = *scene.objects[0].mesh;
        ASSERT_EQ(m.triangleCount(), 2u);
        for (const glm::vec3& n : m.normals)
            EXPECT_EQ(n, glm::vec3(0, 0, 1));
    }
}

TEST(GltfLoader, SkipsPointAndLinePrimitives) {
    GltfBuilder g = quadScene();
    json& primitives = g.doc["meshes"][0]["primitives"];
    primitives.push_back({{"attributes", {{"POSITION", 0}}}, {"mode", 0}});
    primitives.push_back({{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"mode", 1}});
    g.push("meshes", {{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"mode", 3}}}}});
    g.push("nodes", {{"name", "wire"}, {"mesh", 1}});
    g.doc["scenes"][0]["nodes"] = {0, 1};
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-"), "lines"));
    ASSERT_EQ(scene.objects.size(), 1u); // the lines-only node draws nothing
    EXPECT_EQ(scene.objects[0].mesh->submeshes.size(), 1u);
    EXPECT_EQ(scene.objects[0].mesh->positions.size(), 4u);
}

TEST(GltfLoader, ReadsMaterialsAndTextures) {
    const std::string dir = scratchForTest("gltf-");
    Image pixels;
    pixels.width = 2;
    pixels.height = 1;
    pixels.rgba = {255, 0, 0, 255, 0, 0, 255, 128};
    ASSERT_TRUE(writePng(dir + "/albedo.png", pixels).ok());
    GltfBuilder g = quadScene();
    const std::vector<uint8_t> png = readBytes(dir + "/albedo.png");
    g.doc["images"] = {{{"uri", "albedo.png"}}, {{"uri", "data:image/png;base64," + base64(png)}}};
    g.doc["textures"] = {{{"source", 1}}, {{"source", 0}}};
    g.doc["materials"] = {{{"name", "paint"},
                           {"pbrMetallicRoughness",
                            {{"baseColorFactor", {0.5, 0.25, 1, 1}},
                             {"baseColorTexture", {{"index", 1}}},
                             {"roughnessFactor", 0.3},
                             {"metallicFactor", 0.9}}},
                           {"normalTexture", {{"index", 0}, {"scale", 0.5}}}}};
    g.doc["meshes"][0]["primitives"][0]["material"] = 0;
    Scene scene = loaded(g.writeGltf(dir, "material"));
    ASSERT_EQ(scene.materials.size(), 1u);
    const Material& m = scene.materials[0];
    EXPECT_EQ(m.name, "paint");
    EXPECT_EQ(m.baseColorFactor, glm::vec4(0.5f, 0.25f, 1, 1));
    EXPECT_EQ(m.baseColorTexture, 0); // texture 1 -> image 0
    EXPECT_EQ(m.normalTexture, 1);    // texture 0 -> image 1
    EXPECT_FLOAT_EQ(m.normalScale, 0.5f);
    EXPECT_FLOAT_EQ(m.roughness, 0.3f);
    EXPECT_FLOAT_EQ(m.metallic, 0.9f);
    ASSERT_EQ(scene.images.size(), 2u);
    for (const Image& image : scene.images) {
        EXPECT_EQ(image.width, 2);
        EXPECT_EQ(image.height, 1);
        EXPECT_EQ(image.rgba, pixels.rgba);
    }
    EXPECT_EQ(scene.objects[0].mesh->submeshes[0].material, 0);
}

TEST(GltfLoader, LoadsGlbAndGltfWithExternalBuffer) {
    const std::string dir = scratchForTest("gltf-");
    GltfBuilder g = quadScene();
    const std::string glb = dir + "/quad.glb";
    writeBytes(glb, g.glbBytes());
    Scene fromGlb = loaded(glb);
    Scene fromBin = loaded(g.writeGltf(dir, "external", false));
    ASSERT_EQ(fromGlb.objects.size(), 1u);
    ASSERT_EQ(fromBin.objects.size(), 1u);
    EXPECT_EQ(fromGlb.objects[0].mesh->positions, kQuad);
    EXPECT_EQ(fromBin.objects[0].mesh->positions, kQuad);
    EXPECT_EQ(fromGlb.objects[0].mesh->indices, kQuadIndices);
}

TEST(GltfLoader, AcceptsOptionalExtensionsItDoesNotKnow) {
    GltfBuilder g = quadScene();
    g.doc["extensionsUsed"] = {"KHR_texture_transform"};
    EXPECT_EQ(loaded(g.writeGltf(scratchForTest("gltf-"), "used")).objects.size(), 1u);
}

// --- malformed files -----------------------------------------------------------------------------

TEST(GltfLoader, RejectsMissingFile) {
    EXPECT_THAT(rejection(scratchForTest("gltf-") + "/absent.gltf"), HasSubstr("not found"));
}

TEST(GltfLoader, RejectsMalformedJson) {
    const std::string path = scratchForTest("gltf-") + "/broken.gltf";
    std::ofstream(path) << R"({"asset": {"version": "2.0"}, "nodes": [)";
    EXPECT_THAT(rejection(path), HasSubstr("parse error"));
}

TEST(GltfLoader, RejectsMissingBufferFile) {
    const std::string dir = scratchForTest("gltf-");
    const std::string path = quadScene().writeGltf(dir, "nobin", false);
    std::filesystem::remove(dir + "/nobin.bin");
    const std::string error = rejection(path);
    EXPECT_THAT(error, HasSubstr("nobin.bin"));
    EXPECT_THAT(error, HasSubstr("not found"));
}

TEST(GltfLoader, RejectsBufferShorterThanDeclared) {
    const std::string dir = scratchForTest("gltf-");
    GltfBuilder g = quadScene();
    g.declaredBufferLength = g.bin.size() + 8;
    const std::string external = rejection(g.writeGltf(dir, "shortbin", false));
    EXPECT_THAT(external, HasSubstr("shortbin.bin"));
    EXPECT_THAT(external, HasSubstr("size mismatch"));
    const std::string embedded = rejection(g.writeGltf(dir, "shortdata"));
    EXPECT_THAT(embedded, HasSubstr("Buffer"));
    EXPECT_THAT(embedded, Not(HasSubstr("AAAA"))); // the data URI itself is not repeated
    const std::string glb = dir + "/short.glb";
    writeBytes(glb, g.glbBytes());
    EXPECT_THAT(rejection(glb), HasSubstr("byteLength"));
}

TEST(GltfLoader, RejectsAccessorPastEndOfBufferView) {
    GltfBuilder g = quadScene();
    g.doc["accessors"][0]["count"] = 5;
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "accessor")),
                HasSubstr("accessor 0 (POSITION) reads past the end of buffer view 0"));
}

TEST(GltfLoader, RejectsAccessorOffsetPastEndOfBufferView) {
    GltfBuilder g = quadScene();
    g.doc["accessors"][1]["byteOffset"] = 4;
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "offset")),
                HasSubstr("accessor 1 (indices) reads past the end of buffer view 1"));
}

TEST(GltfLoader, RejectsAbsurdAccessorCountWithoutOverflow) {
    GltfBuilder g = quadScene();
    g.doc["accessors"][0]["count"] = uint64_t(1) << 62;
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "absurd")),
                HasSubstr("reads past the end of buffer view 0"));
}

namespace {

// A node named `parent` with 1025 children, each placing one 65535-vertex mesh; `childName` names them.
GltfBuilder crowd(const std::string& parent, const std::string& childName) {
    GltfBuilder g;
    const std::vector<glm::vec3> soup(65535, glm::vec3(0.0f));
    g.addAccessor(g.addView(soup), kFloat, soup.size(), "VEC3");
    g.push("meshes", {{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}});
    json children = json::array();
    for (int i = 1; i <= 1025; ++i)
        children.push_back(i);
    g.push("nodes", {{"name", parent}, {"mesh", 0}, {"children", children}});
    for (int i = 1; i <= 1025; ++i)
        g.push("nodes", {{"name", childName + std::to_string(i)}, {"mesh", 0}});
    return g;
}

} // namespace

TEST(GltfLoader, CountsAMeshPlacedByManyNodesOnceTowardsTheSceneBound) {
    // 1026 placements of a 65535-vertex mesh: 67.2 million vertices placed, one mesh kept.
    const Scene scene = loaded(crowd("crowd", "member").writeGltf(scratchForTest("gltf-"), "crowd", false));
    ASSERT_EQ(scene.objects.size(), 1026u);
    for (const SceneObject& o : scene.objects)
        ASSERT_EQ(o.mesh, scene.objects[0].mesh) << o.name;
}

TEST(GltfLoader, RejectsAbsurdColliderTotal) {
    // The same mesh as 1025 colliders of one owner, which keeps a copy of each: 67.2 million vertices,
    // over the 2^26 limit.
    EXPECT_THAT(rejection(crowd("crowd", "UCX_crowd").writeGltf(scratchForTest("gltf-"), "colliders", false)),
                HasSubstr("more than the limit of 67108864"));
}

TEST(GltfLoader, RejectsBufferViewPastEndOfBuffer) {
    GltfBuilder g = quadScene();
    g.doc["bufferViews"][1]["byteLength"] = 64;
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "view")),
                HasSubstr("buffer view 1 reads past the end of buffer 0"));
}

TEST(GltfLoader, RejectsStrideSmallerThanElement) {
    GltfBuilder g = quadScene();
    g.doc["bufferViews"][0]["byteStride"] = 8;
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "stride")),
                HasSubstr("smaller than one element"));
}

TEST(GltfLoader, RejectsIndexPastVertexCount) {
    GltfBuilder g = quadScene();
    g.doc["accessors"][0]["count"] = 3; // index 3 now names a vertex that does not exist
    const std::string error = rejection(g.writeGltf(scratchForTest("gltf-"), "index"));
    EXPECT_THAT(error, HasSubstr("index 3"));
    EXPECT_THAT(error, HasSubstr("vertex count 3"));
    EXPECT_THAT(error, HasSubstr("mesh 0 (quadMesh) primitive 0"));
}

TEST(GltfLoader, RejectsTriangleListNotMultipleOfThree) {
    GltfBuilder g = quadScene();
    g.doc["accessors"][1]["count"] = 5;
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "five")), HasSubstr("not a multiple of 3"));
}

TEST(GltfLoader, RejectsNonFinitePositions) {
    const std::string dir = scratchForTest("gltf-");
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        GltfBuilder g = quadScene();
        std::vector<glm::vec3> positions = kQuad;
        positions[2].y = bad;
        std::memcpy(g.bin.data() + 2 * sizeof(glm::vec3), &positions[2], sizeof(glm::vec3));
        const std::string error = rejection(g.writeGltf(dir, std::isnan(bad) ? "nan" : "inf"));
        EXPECT_THAT(error, HasSubstr("accessor 0 (POSITION) element 2 is not finite"));
    }
}

TEST(GltfLoader, RejectsNonFiniteUvs) {
    GltfBuilder g = quadScene();
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<glm::vec2> uvs = {{0, 0}, {1, 0}, {1, inf}, {0, 1}};
    g.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] =
        g.addAccessor(g.addView(uvs), kFloat, 4, "VEC2");
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "uvinf")),
                HasSubstr("(TEXCOORD_0) element 2 is not finite"));
}

TEST(GltfLoader, RejectsAttributeCountDifferentFromPositions) {
    GltfBuilder g = quadScene();
    const std::vector<glm::vec3> normals(3, glm::vec3(0, 0, 1));
    g.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] =
        g.addAccessor(g.addView(normals), kFloat, 3, "VEC3");
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "normals3")),
                HasSubstr("(NORMAL) has 3 elements, POSITION has 4"));
}

TEST(GltfLoader, RejectsWrongAccessorType) {
    GltfBuilder g = quadScene();
    g.doc["accessors"][0]["type"] = "VEC2";
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "vec2")),
                HasSubstr("accessor 0 (POSITION) is VEC2, expected VEC3"));
}

TEST(GltfLoader, RejectsUnsupportedRequiredExtension) {
    GltfBuilder g = quadScene();
    g.doc["extensionsUsed"] = {"KHR_texture_basisu"};
    g.doc["extensionsRequired"] = {"KHR_texture_basisu"};
    const std::string error = rejection(g.writeGltf(scratchForTest("gltf-"), "basisu"));
    EXPECT_THAT(error, HasSubstr("extension KHR_texture_basisu"));
    EXPECT_THAT(error, HasSubstr("not supported"));
}

TEST(GltfLoader, RejectsTruncatedGlb) {
    const std::string dir = scratchForTest("gltf-");
    const std::vector<uint8_t> full = quadScene().glbBytes();
    // Header cut short, and a header declaring more bytes than the file has.
    writeBytes(dir + "/header.glb", std::vector<uint8_t>(full.begin(), full.begin() + 10));
    EXPECT_THAT(rejection(dir + "/header.glb"), HasSubstr("truncated GLB"));
    writeBytes(dir + "/short.glb", std::vector<uint8_t>(full.begin(), full.end() - 4));
    EXPECT_THAT(rejection(dir + "/short.glb"), HasSubstr("truncated GLB: the header declares"));
    // Cut inside the JSON chunk and inside the binary chunk, with the header's length matching the cut.
    for (auto [keep, chunk] :
         {std::pair<size_t, const char*>{40, "JSON chunk"}, {full.size() - 4, "binary chunk"}}) {
        SCOPED_TRACE(keep);
        std::vector<uint8_t> cut(full.begin(), full.begin() + std::ptrdiff_t(keep));
        for (int i = 0; i < 4; ++i)
            cut[8 + size_t(i)] = uint8_t(keep >> (8 * i));
        const std::string path = dir + "/cut" + std::to_string(keep) + ".glb";
        writeBytes(path, cut);
        const std::string error = rejection(path);
        EXPECT_THAT(error, HasSubstr("truncated GLB"));
        EXPECT_THAT(error, HasSubstr(chunk));
    }
}

TEST(GltfLoader, RejectsMalformedGlbHeader) {
    const std::string dir = scratchForTest("gltf-");
    std::vector<uint8_t> version = quadScene().glbBytes();
    version[4] = 1;
    writeBytes(dir + "/v1.glb", version);
    EXPECT_THAT(rejection(dir + "/v1.glb"), HasSubstr("GLB version 1 is not supported"));
    std::vector<uint8_t> chunk = quadScene().glbBytes();
    chunk[16] = 'X';
    writeBytes(dir + "/chunk.glb", chunk);
    EXPECT_THAT(rejection(dir + "/chunk.glb"), HasSubstr("first GLB chunk is not JSON"));
}

TEST(GltfLoader, RejectsInvalidMeshIndex) {
    GltfBuilder g = quadScene();
    g.doc["nodes"][0]["mesh"] = 7;
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "mesh7")),
                HasSubstr("node 0 (quad) refers to mesh 7"));
}

TEST(GltfLoader, RejectsInvalidAttributeAccessorIndex) {
    GltfBuilder g = quadScene();
    g.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9;
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "accessor9")),
                HasSubstr("POSITION refers to accessor 9"));
}

TEST(GltfLoader, RejectsInvalidIndicesAccessor) {
    GltfBuilder g = quadScene();
    g.doc["meshes"][0]["primitives"][0]["indices"] = 9;
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "indices9")), HasSubstr("accessor"));
}

TEST(GltfLoader, RejectsInvalidChildAndSceneNodeIndices) {
    const std::string dir = scratchForTest("gltf-");
    GltfBuilder child = quadScene();
    child.doc["nodes"][0]["children"] = {4};
    EXPECT_THAT(rejection(child.writeGltf(dir, "child")), HasSubstr("node 0 (quad) has child 4"));
    GltfBuilder root = quadScene();
    root.doc["scenes"][0]["nodes"] = {3};
    EXPECT_THAT(rejection(root.writeGltf(dir, "root")), HasSubstr("scene 0 lists node 3"));
    GltfBuilder scene = quadScene();
    scene.doc["scene"] = 2;
    EXPECT_THAT(rejection(scene.writeGltf(dir, "scene")), HasSubstr("default scene 2 does not exist"));
}

TEST(GltfLoader, RejectsInvalidMaterialAndTextureIndices) {
    const std::string dir = scratchForTest("gltf-");
    GltfBuilder material = quadScene();
    material.doc["meshes"][0]["primitives"][0]["material"] = 2;
    EXPECT_THAT(rejection(material.writeGltf(dir, "material")), HasSubstr("refers to material 2"));
    GltfBuilder texture = quadScene();
    texture.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 3}}}}}}};
    EXPECT_THAT(rejection(texture.writeGltf(dir, "texture")),
                HasSubstr("base colour texture refers to texture 3"));
}

TEST(GltfLoader, RejectsNodeHierarchyCycles) {
    const std::string dir = scratchForTest("gltf-");
    GltfBuilder g = quadScene();
    g.push("nodes", {{"name", "a"}, {"children", {2}}});
    g.push("nodes", {{"name", "b"}, {"children", {1}}});
    EXPECT_THAT(rejection(g.writeGltf(dir, "cycle")), HasSubstr("cycle"));
    GltfBuilder self = quadScene();
    self.doc["nodes"][0]["children"] = {0};
    EXPECT_THAT(rejection(self.writeGltf(dir, "self")), HasSubstr("cycle"));
}

TEST(GltfLoader, RejectsNodeWithTwoParents) {
    GltfBuilder g = quadScene();
    g.push("nodes", {{"name", "left"}, {"children", {0}}});
    g.push("nodes", {{"name", "right"}, {"children", {0}}});
    g.doc["scenes"][0]["nodes"] = {1, 2};
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "twoparents")),
                HasSubstr("node 0 (quad) has two parents"));
}

TEST(GltfLoader, RejectsMalformedTransforms) {
    const std::string dir = scratchForTest("gltf-");
    const std::vector<std::pair<json, std::string>> cases = {
        {{{"matrix", {1, 0, 0, 0, 1}}}, "matrix of 5 numbers"},
        {{{"translation", {1, 2}}}, "translation of 2 numbers"},
        {{{"rotation", {0, 0, 0, 0}}}, "zero rotation quaternion"}};
    for (size_t i = 0; i < cases.size(); ++i) {
        SCOPED_TRACE(cases[i].second);
        GltfBuilder g = quadScene();
        g.doc["nodes"][0].update(cases[i].first);
        EXPECT_THAT(rejection(g.writeGltf(dir, "transform" + std::to_string(i))), HasSubstr(cases[i].second));
    }
}

TEST(GltfLoader, RejectsComposedTransformThatOverflows) {
    GltfBuilder g = quadScene();
    g.doc["nodes"] = {{{"name", "huge"}, {"scale", {1e300, 1e300, 1e300}}, {"children", {1}}},
                      {{"name", "huger"}, {"scale", {1e300, 1e300, 1e300}}, {"mesh", 0}}};
    const std::string error = rejection(g.writeGltf(scratchForTest("gltf-"), "overflow"));
    EXPECT_THAT(error, HasSubstr("huger"));
    EXPECT_THAT(error, HasSubstr("not finite"));
}

TEST(GltfLoader, LoadsANodeScaledByZeroAndDropsItsColliderWhichHasNoSpaceToLiveIn) {
    GltfBuilder g = quadScene();
    g.doc["nodes"] = {{{"name", "flat"}, {"mesh", 0}, {"scale", {1, 1, 0}}, {"children", {1}}},
                      {{"name", "UCX_flat"}, {"mesh", 0}}};
    const Scene scene = loaded(g.writeGltf(scratchForTest("gltf-"), "singular"));
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].name, "flat");
    EXPECT_FALSE(scene.objects[0].collider.has_value());
}

TEST(GltfLoader, RejectsSceneRootThatIsAChildOrListedTwice) {
    const std::string dir = scratchForTest("gltf-");
    GltfBuilder child = quadScene();
    child.push("nodes", {{"name", "group"}, {"children", {0}}});
    child.doc["scenes"][0]["nodes"] = {1, 0};
    EXPECT_THAT(rejection(child.writeGltf(dir, "child")),
                HasSubstr("lists node 0 as a root, but it is a child of node 1"));
    GltfBuilder twice = quadScene();
    twice.doc["scenes"][0]["nodes"] = {0, 0};
    EXPECT_THAT(rejection(twice.writeGltf(dir, "twice")), HasSubstr("lists node 0 twice"));
}

TEST(GltfLoader, RejectsMissingImageFile) {
    GltfBuilder g = quadScene();
    g.doc["images"] = {{{"uri", "Textures/missing.png"}}};
    const std::string error = rejection(g.writeGltf(scratchForTest("gltf-"), "noimage"));
    EXPECT_THAT(error, HasSubstr("image 0 (Textures/missing.png)"));
    EXPECT_THAT(error, HasSubstr("cannot be read"));
}

TEST(GltfLoader, RejectsUndecodableImage) {
    GltfBuilder g = quadScene();
    g.doc["images"] = {{{"uri", "data:image/png;base64," + base64({1, 2, 3, 4, 5, 6, 7, 8})}}};
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "badpng")), HasSubstr("image 0"));
}

TEST(GltfLoader, RejectsImageBufferViewPastEndOfBuffer) {
    GltfBuilder g = quadScene();
    const std::vector<uint8_t> junk(16, 7);
    const int view = g.addView(junk);
    g.doc["bufferViews"][view]["byteLength"] = 4096;
    g.doc["images"] = {{{"bufferView", view}, {"mimeType", "image/png"}}};
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "imageview")),
                HasSubstr("reads past the end of its buffer"));
}

TEST(GltfLoader, RejectsSceneWithoutTriangles) {
    GltfBuilder g = quadScene();
    g.doc["meshes"][0]["primitives"][0]["mode"] = 0;
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "points")), HasSubstr("no triangle meshes"));
}

// tinygltf's own file callbacks open a buffer's or image's uri to see whether it exists, which waits
// forever on a FIFO, and take a directory's length as an allocation ("std::bad_alloc").
TEST(GltfLoader, ReadsBuffersAndImagesFromRegularFilesOnly) {
    const std::string dir = scratchForTest("gltf-");
    GltfBuilder folder = quadScene();
    folder.writeGltf(dir, "folder", false);
    json doc = json::parse(std::ifstream(dir + "/folder.gltf"));
    doc["buffers"][0]["uri"] = ".";
    std::ofstream(dir + "/folder.gltf") << doc.dump();
    EXPECT_THAT(rejection(dir + "/folder.gltf"), HasSubstr("/. : is a directory"));

    ASSERT_EQ(mkfifo((dir + "/pipe.bin").c_str(), 0644), 0);
    doc["buffers"][0]["uri"] = "pipe.bin";
    std::ofstream(dir + "/pipe.gltf") << doc.dump();
    FifoWriter writer(dir + "/pipe.bin");
    EXPECT_THAT(rejection(dir + "/pipe.gltf"),
                HasSubstr("pipe.bin : is a FIFO (named pipe), not a regular file"));
    GltfBuilder textured = quadScene();
    textured.doc["images"] = {{{"uri", "."}}};
    textured.doc["textures"] = {{{"source", 0}}};
    textured.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    textured.doc["meshes"][0]["primitives"][0]["material"] = 0;
    EXPECT_THAT(rejection(textured.writeGltf(dir, "imagefolder")),
                HasSubstr("image 0 (.): '" + dir + "/.' is a directory"));
    ASSERT_EQ(mkfifo((dir + "/pipe.png").c_str(), 0644), 0);
    FifoWriter imageWriter(dir + "/pipe.png");
    textured.doc["images"][0]["uri"] = "pipe.png";
    EXPECT_THAT(rejection(textured.writeGltf(dir, "imagepipe")),
                HasSubstr("image 0 (pipe.png): '" + dir + "/pipe.png' is a FIFO"));
}

// The JSON parser's message quotes the input it stopped at: raw bytes of a binary file, or a whole
// string of thousands of characters.
TEST(GltfLoader, QuotesAtMostAShortPrintableExcerptOfInputThatIsNotJson) {
    const std::string dir = scratchForTest("gltf-");
    auto printable = [](const std::string& text) {
        for (unsigned char c : text)
            if (c < 0x20 || c >= 0x7f) return false;
        return true;
    };
    std::vector<uint8_t> glb = quadScene().glbBytes();
    const uint32_t jsonLength = uint32_t(glb[12]) | uint32_t(glb[13]) << 8 | uint32_t(glb[14]) << 16;
    std::fill(glb.begin() + 20, glb.begin() + 20 + jsonLength, uint8_t(0xff));
    writeBytes(dir + "/garbage.glb", glb);
    const std::string garbage = rejection(dir + "/garbage.glb");
    EXPECT_THAT(garbage, HasSubstr("last read: '\\xFF'"));
    EXPECT_TRUE(printable(garbage)) << garbage;

    std::ofstream(dir + "/long.gltf", std::ios::binary)
        << "{\"asset\": \"" << std::string(5000, 'a') << "\x01\"}";
    const std::string longString = rejection(dir + "/long.gltf");
    EXPECT_THAT(longString, HasSubstr("last read: '\"" + std::string(31, 'a') + "...'"));
    EXPECT_LT(longString.size(), 400u);
    EXPECT_TRUE(printable(longString)) << longString;
}

// A missing mesh index is an error; a missing skin index was ignored when the file had no skins.
TEST(GltfLoader, RejectsInvalidSkinIndex) {
    GltfBuilder g = quadScene();
    g.doc["nodes"][0]["skin"] = 5;
    EXPECT_THAT(rejection(g.writeGltf(scratchForTest("gltf-"), "skin5")),
                HasSubstr("node 0 (quad) refers to skin 5, which does not exist"));
}

// tinygltf takes an optional property of the wrong JSON type as absent: the node would stay at the
// origin, the accessor read from offset 0, the node lose its mesh.
TEST(GltfLoader, RejectsPropertiesOfTheWrongJsonType) {
    const std::string dir = scratchForTest("gltf-");
    auto error = [&](const std::string& name, const char* collection, const char* property,
                     const json& value) {
        GltfBuilder g = quadScene();
        g.doc[collection][0][property] = value;
        return rejection(g.writeGltf(dir, name));
    };
    EXPECT_THAT(error("translation", "nodes", "translation", "abc"),
                HasSubstr("node 0 (quad): \"translation\" is \"abc\", not an array of numbers"));
    EXPECT_THAT(error("rotation", "nodes", "rotation", {0, 0, "1", 0}),
                HasSubstr("\"rotation\" is [0,0,\"1\",0]"));
    EXPECT_THAT(error("mesh", "nodes", "mesh", "0"),
                HasSubstr("node 0 (quad): \"mesh\" is \"0\", not an integer of at least 0"));
    EXPECT_THAT(error("children", "nodes", "children", {-1}), HasSubstr("\"children\" is [-1]"));
    EXPECT_THAT(error("offset", "accessors", "byteOffset", -4),
                HasSubstr("accessor 0: \"byteOffset\" is -4, not an integer of at least 0"));
    EXPECT_THAT(error("offset4", "accessors", "byteOffset", 4.0), HasSubstr("\"byteOffset\" is 4.0"));
    EXPECT_THAT(error("view", "bufferViews", "byteOffset", "0"), HasSubstr("buffer view 0: \"byteOffset\""));
    GltfBuilder attribute = quadScene();
    attribute.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = "0";
    EXPECT_THAT(rejection(attribute.writeGltf(dir, "attribute")),
                HasSubstr("mesh 0 (quadMesh) primitive 0: attribute \"POSITION\" is \"0\""));
    // Strings of any length are read whole around the data URI of the buffer.
    GltfBuilder named = quadScene();
    named.doc["nodes"][0]["name"] = std::string(5000, 'n') + "\"\\";
    named.doc["nodes"][0]["translation"] = {1, 2, 3};
    EXPECT_EQ(loaded(named.writeGltf(dir, "named")).objects.size(), 1u);
}
