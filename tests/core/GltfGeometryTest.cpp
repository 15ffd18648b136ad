// loadGltf on the core glTF 2.0 geometry that exporters write besides plain float arrays: sparse
// accessors, accessors without a buffer view, normalized integer components, EXT_mesh_gpu_instancing,
// KHR_texture_transform, KHR_materials_unlit and images that only an extension uses. Each file is
// written by the test and compared with the plain file's geometry.

#include "spatter/core/Image.hpp"
#include "spatter/core/ProxyInstances.hpp"
#include "spatter/core/SceneLoader.hpp"

#include "GltfBuilder.hpp"
#include "GltfLoading.hpp"
#include "TestData.hpp"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

using namespace spatter;
using namespace spatter::test;
using ::testing::HasSubstr;

namespace {

const std::vector<glm::vec2> kQuadUvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};

// One node "quad": float positions (accessor 0), 16-bit indices (accessor 1), float UVs (accessor 2).
GltfBuilder uvQuadScene() {
    GltfBuilder g;
    g.addAccessor(g.addView(kQuad), kFloat, kQuad.size(), "VEC3");
    const std::vector<uint16_t> indices(kQuadIndices.begin(), kQuadIndices.end());
    g.addAccessor(g.addView(indices), kUnsignedShort, indices.size(), "SCALAR");
    g.addAccessor(g.addView(kQuadUvs), kFloat, kQuadUvs.size(), "VEC2");
    g.push("meshes",
           {{"name", "quadMesh"},
            {"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 2}}}, {"indices", 1}}}}});
    g.push("nodes", {{"name", "quad"}, {"mesh", 0}});
    g.doc["scenes"] = {{{"nodes", {0}}}};
    g.doc["scene"] = 0;
    return g;
}

// A sparse part for accessor `accessor`: `indices` (16-bit) and their `values` (raw bytes).
void makeSparse(GltfBuilder& g, int accessor, const std::vector<uint16_t>& indices,
                const std::vector<uint8_t>& values) {
    g.doc["accessors"][accessor]["sparse"] = {
        {"count", indices.size()},
        {"indices", {{"bufferView", g.addView(indices)}, {"componentType", kUnsignedShort}}},
        {"values", {{"bufferView", g.addView(values)}}}};
}

template <class T> std::vector<uint8_t> bytesOf(const std::vector<T>& values) {
    const auto* p = reinterpret_cast<const uint8_t*>(values.data());
    return std::vector<uint8_t>(p, p + values.size() * sizeof(T));
}

void expectNear(const glm::vec3& a, const glm::vec3& b, float tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

} // namespace

// --- sparse accessors and accessors without a buffer view ----------------------------------------

TEST(GltfGeometry, SparsePositionsAndIndicesReplaceTheElementsTheyName) {
    GltfBuilder g = uvQuadScene();
    // The dense positions put vertex 2 at (5, 5, 5); the sparse part moves it back to (1, 1, 0).
    std::vector<glm::vec3> wrong = kQuad;
    wrong[2] = glm::vec3(5.0f);
    g.doc["accessors"][0]["bufferView"] = g.addView(wrong);
    makeSparse(g, 0, {2}, bytesOf(std::vector<glm::vec3>{kQuad[2]}));
    // The dense indices read 0 1 3 0 2 3; the sparse part sets element 2 to 2.
    const std::vector<uint16_t> indices = {0, 1, 3, 0, 2, 3};
    g.doc["accessors"][1]["bufferView"] = g.addView(indices);
    makeSparse(g, 1, {2}, bytesOf(std::vector<uint16_t>{2}));
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-geometry-"), "sparse"));
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].mesh->positions, kQuad);
    EXPECT_EQ(scene.objects[0].mesh->indices, kQuadIndices);
}

TEST(GltfGeometry, AccessorWithoutBufferViewIsZerosUnderItsSparseValues) {
    GltfBuilder g = uvQuadScene();
    g.doc["accessors"][0].erase("bufferView");
    g.doc["accessors"][0].erase("byteOffset");
    makeSparse(g, 0, {1, 2, 3}, bytesOf(std::vector<glm::vec3>{kQuad[1], kQuad[2], kQuad[3]}));
    // UVs without a buffer view and without a sparse part: all zero.
    g.doc["accessors"][2].erase("bufferView");
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-geometry-"), "bufferless"));
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].mesh->positions, kQuad);
    EXPECT_EQ(scene.objects[0].mesh->uvs, std::vector<glm::vec2>(4, glm::vec2(0.0f)));
}

TEST(GltfGeometry, IndicesWithoutBufferViewComeFromTheirSparseValues) {
    GltfBuilder g = uvQuadScene();
    g.doc["accessors"][1].erase("bufferView");
    g.doc["accessors"][1].erase("byteOffset");
    // Index 0 of each triangle stays 0; the other five come from the sparse part.
    makeSparse(g, 1, {1, 2, 4, 5}, bytesOf(std::vector<uint16_t>{1, 2, 2, 3}));
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-geometry-"), "sparse-indices"));
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].mesh->indices, kQuadIndices);
}

TEST(GltfGeometry, SparseValuesInNormalizedShortsUnderMeshQuantization) {
    GltfBuilder g = uvQuadScene();
    const std::vector<int16_t> zeros(16, 0);
    g.doc["accessors"][0] = {{"bufferView", g.addView(zeros.data(), 32, 8)},
                             {"componentType", 5122},
                             {"count", 4},
                             {"type", "VEC3"},
                             {"normalized", true}};
    // Tightly packed sparse values (no padding): vertices 1, 2, 3 of the unit quad.
    makeSparse(g, 0, {1, 2, 3}, bytesOf(std::vector<int16_t>{32767, 0, 0, 32767, 32767, 0, 0, 32767, 0}));
    g.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
    g.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-geometry-"), "sparse-short"));
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].mesh->positions, kQuad);
}

TEST(GltfGeometry, RejectsSparseIndicesOutOfRangeOrNotIncreasing) {
    const std::string dir = scratchForTest("gltf-geometry-");
    {
        GltfBuilder g = uvQuadScene();
        makeSparse(g, 0, {9}, bytesOf(std::vector<glm::vec3>{glm::vec3(1.0f)}));
        EXPECT_THAT(
            rejection(g.writeGltf(dir, "past")),
            HasSubstr("accessor 0 (POSITION) has sparse index 9 (entry 0) that is past the elements"));
    }
    {
        GltfBuilder g = uvQuadScene();
        makeSparse(g, 1, {3, 3}, bytesOf(std::vector<uint16_t>{1, 2}));
        EXPECT_THAT(rejection(g.writeGltf(dir, "repeat")),
                    HasSubstr("accessor 1 (indices) has sparse index 3 (entry 1)"));
    }
    {
        GltfBuilder g = uvQuadScene();
        makeSparse(g, 0, {1}, std::vector<uint8_t>(4, 0)); // 4 bytes for a 12-byte value
        EXPECT_THAT(rejection(g.writeGltf(dir, "short")), HasSubstr("its sparse values read past the end"));
    }
    {
        GltfBuilder g = uvQuadScene();
        makeSparse(g, 0, {1}, bytesOf(std::vector<glm::vec3>{glm::vec3(1.0f)}));
        g.doc["accessors"][0]["sparse"]["count"] = 5;
        EXPECT_THAT(rejection(g.writeGltf(dir, "count")),
                    HasSubstr("has a sparse count of 5 for 4 elements"));
    }
}

TEST(GltfGeometry, RejectsAccessorWithoutBufferViewBeyondTheLimit) {
    GltfBuilder g = uvQuadScene();
    g.doc["accessors"][0] = {{"componentType", kFloat}, {"count", (1 << 22) + 1}, {"type", "VEC3"}};
    const std::string error = rejection(g.writeGltf(scratchForTest("gltf-geometry-"), "huge"));
    EXPECT_THAT(error, HasSubstr("accessor 0 (POSITION) has 4194305 elements without a buffer view"));
    EXPECT_THAT(error, HasSubstr("limit"));
}

// --- every component type, normalized and not ----------------------------------------------------

TEST(GltfGeometry, EveryVertexComponentTypeMatchesTheFloatQuadWithinItsStep) {
    struct Case {
        int type;
        bool normalized;
        double scale; // integer value of 1.0
    };
    const Case cases[] = {
        {kByte, true, 127}, {kUnsignedByte, true, 255}, {5122, true, 32767}, {kUnsignedShort, true, 65535},
        {kByte, false, 1},  {kUnsignedByte, false, 1},  {5122, false, 1},    {kUnsignedShort, false, 1}};
    const std::string dir = scratchForTest("gltf-geometry-");
    for (const Case& c : cases) {
        SCOPED_TRACE(std::to_string(c.type) + (c.normalized ? " normalized" : ""));
        GltfBuilder g = uvQuadScene();
        const size_t size = c.type == kByte || c.type == kUnsignedByte ? 1 : 2;
        const size_t stride = size == 1 ? 4 : 8; // vertex attributes are 4-byte aligned
        std::vector<uint8_t> packed(4 * stride, 0);
        for (size_t v = 0; v < 4; ++v)
            for (int k = 0; k < 3; ++k) {
                const long value = std::lround(kQuad[v][k] * c.scale);
                for (size_t b = 0; b < size; ++b)
                    packed[v * stride + size_t(k) * size + b] = uint8_t(value >> (8 * b));
            }
        g.doc["accessors"][0] = {{"bufferView", g.addView(packed.data(), packed.size(), stride)},
                                 {"componentType", c.type},
                                 {"count", 4},
                                 {"type", "VEC3"},
                                 {"normalized", c.normalized}};
        g.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
        g.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
        Scene scene = loaded(g.writeGltf(dir, "q" + std::to_string(c.type) + (c.normalized ? "n" : "")));
        ASSERT_EQ(scene.objects.size(), 1u);
        for (size_t v = 0; v < 4; ++v)
            expectNear(scene.objects[0].mesh->positions[v], kQuad[v], float(0.5 / c.scale));
    }
}

// --- EXT_mesh_gpu_instancing ---------------------------------------------------------------------

namespace {

// The quad's node drawn three times: translated, rotated about z and scaled; the node itself at x = 10.
GltfBuilder instancedQuad() {
    GltfBuilder g = uvQuadScene();
    const std::vector<glm::vec3> t = {{0, 0, 0}, {2, 0, 0}, {0, 3, 1}};
    const float h = std::sqrt(0.5f);
    const std::vector<glm::vec4> r = {{0, 0, 0, 1}, {0, 0, h, h}, {0, 0, 0, 1}}; // xyzw
    const std::vector<glm::vec3> s = {{1, 1, 1}, {1, 1, 1}, {2, 2, 2}};
    const int ta = g.addAccessor(g.addView(t), kFloat, 3, "VEC3");
    const int ra = g.addAccessor(g.addView(r), kFloat, 3, "VEC4");
    const int sa = g.addAccessor(g.addView(s), kFloat, 3, "VEC3");
    g.doc["nodes"][0]["translation"] = {10, 0, 0};
    g.doc["nodes"][0]["extensions"] = {
        {"EXT_mesh_gpu_instancing",
         {{"attributes", {{"TRANSLATION", ta}, {"ROTATION", ra}, {"SCALE", sa}}}}}};
    g.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
    g.doc["extensionsRequired"] = {"EXT_mesh_gpu_instancing"};
    return g;
}

} // namespace

TEST(GltfGeometry, EachInstanceBecomesAnObjectNamedAfterItsIndexSharingTheNodesMesh) {
    Scene scene = loaded(instancedQuad().writeGltf(scratchForTest("gltf-geometry-"), "instanced"));
    ASSERT_EQ(scene.objects.size(), 3u);
    const glm::dmat4 node = glm::translate(glm::dmat4(1.0), glm::dvec3(10, 0, 0));
    const glm::dmat4 expected[3] = {
        node,
        glm::rotate(glm::translate(node, glm::dvec3(2, 0, 0)), glm::half_pi<double>(), glm::dvec3(0, 0, 1)),
        glm::scale(glm::translate(node, glm::dvec3(0, 3, 1)), glm::dvec3(2.0))};
    for (size_t i = 0; i < 3; ++i) {
        SCOPED_TRACE(i);
        const SceneObject& o = scene.objects[i];
        EXPECT_EQ(o.name, "quad#" + std::to_string(i));
        EXPECT_EQ(o.mesh->positions, kQuad);
        EXPECT_EQ(o.mesh, scene.objects[0].mesh); // the scene keeps the mesh once
        EXPECT_EQ(o.node, -1);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                EXPECT_NEAR(o.transform[c][r], expected[i][c][r], 1e-6);
    }
    EXPECT_EQ(proxySources(scene), (std::vector<size_t>{0, 0, 0})); // one proxy for the three
}

TEST(GltfGeometry, NodesOfOneMeshShareItAndInstancesOfTwoNodesShareTheirs) {
    GltfBuilder g = instancedQuad();
    g.push("nodes", {{"name", "plain"}, {"mesh", 0}, {"translation", {0, 0, 5}}});
    g.doc["scenes"][0]["nodes"] = {0, 1};
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-geometry-"), "shared"));
    ASSERT_EQ(scene.objects.size(), 4u);
    for (const SceneObject& o : scene.objects)
        EXPECT_EQ(o.mesh, scene.objects[0].mesh) << o.name;
    EXPECT_EQ(scene.objects[3].name, "plain");
    EXPECT_EQ(scene.objects[3].transform[3], glm::dvec4(0, 0, 5, 1));
}

TEST(GltfGeometry, InstanceRotationsInNormalizedShorts) {
    GltfBuilder g = instancedQuad();
    const std::vector<int16_t> r = {0, 0, 0, 32767, 0, 0, 23170, 23170, 0, 0, 0, 32767};
    const int ra = g.addAccessor(g.addView(r), 5122, 3, "VEC4");
    g.doc["accessors"][ra]["normalized"] = true;
    g.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["ROTATION"] = ra;
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-geometry-"), "rotation16"));
    ASSERT_EQ(scene.objects.size(), 3u);
    const glm::dvec4 corner = scene.objects[1].transform * glm::dvec4(1, 0, 0, 1);
    EXPECT_NEAR(corner.x, 12.0, 1e-4); // (1, 0, 0) turned a quarter about z, then moved to x = 12
    EXPECT_NEAR(corner.y, 1.0, 1e-4);
}

TEST(GltfGeometry, RejectsBadInstanceAccessors) {
    const std::string dir = scratchForTest("gltf-geometry-");
    {
        GltfBuilder g = instancedQuad();
        g.doc["accessors"][5]["count"] = 2; // SCALE: 2 of 3
        EXPECT_THAT(rejection(g.writeGltf(dir, "counts")),
                    HasSubstr("node 0 (quad) has instance attributes of 3 and 2 elements"));
    }
    {
        GltfBuilder g = instancedQuad();
        g.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["ROTATION"] = 0; // VEC3
        EXPECT_THAT(rejection(g.writeGltf(dir, "type")),
                    HasSubstr("accessor 0 (instance ROTATION) is VEC3, expected VEC4"));
    }
    {
        GltfBuilder g = instancedQuad();
        g.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"]["TRANSLATION"] = 99;
        EXPECT_THAT(rejection(g.writeGltf(dir, "missing")),
                    HasSubstr("instance TRANSLATION refers to an accessor that does not exist"));
    }
    {
        GltfBuilder g = instancedQuad();
        const std::vector<glm::vec4> zero(3, glm::vec4(0.0f));
        g.doc["accessors"][4]["bufferView"] = g.addView(zero);
        EXPECT_THAT(rejection(g.writeGltf(dir, "zero")),
                    HasSubstr("instance 0 has a rotation that is zero or not finite"));
    }
    {
        GltfBuilder g = instancedQuad();
        g.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = {
            {"TRANSLATION",
             g.push("accessors", {{"componentType", kFloat}, {"count", 70000}, {"type", "VEC3"}})}};
        EXPECT_THAT(rejection(g.writeGltf(dir, "many")),
                    HasSubstr("has 70000 instances, more than the limit of 65536"));
    }
}

namespace {

// `nodes` nodes, each placing a grid of 33 x 33 vertices `copies` times by instancing, a row apart.
GltfBuilder instancedGrids(size_t nodes, size_t copies) {
    constexpr uint32_t kSide = 33;
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
    for (uint32_t y = 0; y < kSide; ++y)
        for (uint32_t x = 0; x < kSide; ++x) {
            positions.emplace_back(float(x) / kSide, float(y) / kSide, 0.0f);
            if (x + 1 == kSide || y + 1 == kSide) continue;
            const uint32_t i = y * kSide + x;
            indices.insert(indices.end(), {i, i + 1, i + kSide, i + 1, i + kSide + 1, i + kSide});
        }
    std::vector<glm::vec3> offsets(copies);
    for (size_t i = 0; i < copies; ++i)
        offsets[i] = glm::vec3(float(i % 256), float(i / 256), 0.0f) * 1.5f;
    GltfBuilder g;
    g.addAccessor(g.addView(positions), kFloat, positions.size(), "VEC3");
    g.addAccessor(g.addView(indices), kUnsignedInt, indices.size(), "SCALAR");
    const int translation = g.addAccessor(g.addView(offsets), kFloat, copies, "VEC3");
    g.push("meshes",
           {{"name", "grid"}, {"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}});
    g.doc["scenes"] = {{{"nodes", nlohmann::json::array()}}};
    for (size_t n = 0; n < nodes; ++n) {
        g.push("nodes", {{"name", "grids" + std::to_string(n)},
                         {"mesh", 0},
                         {"translation", {0, 0, n}},
                         {"extensions",
                          {{"EXT_mesh_gpu_instancing", {{"attributes", {{"TRANSLATION", translation}}}}}}}});
        g.doc["scenes"][0]["nodes"].push_back(n);
    }
    g.doc["scene"] = 0;
    g.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
    g.doc["extensionsRequired"] = {"EXT_mesh_gpu_instancing"};
    return g;
}

} // namespace

// The scene's bound counts a mesh once however many objects share it: 65,536 grids of 1,089 vertices
// place more than 2^26 vertices, and load as one mesh.
TEST(GltfGeometry, InstancesPlacingMoreVerticesThanTheSceneHoldsShareTheirMesh) {
    Scene scene =
        loaded(instancedGrids(1, 65536).writeGltf(scratchForTest("gltf-geometry-"), "grids", false));
    ASSERT_EQ(scene.objects.size(), 65536u);
    size_t placed = 0;
    for (const SceneObject& o : scene.objects) {
        ASSERT_EQ(o.mesh, scene.objects[0].mesh) << o.name;
        placed += o.mesh->vertexCount();
    }
    EXPECT_GT(placed, size_t(1) << 26);
}

TEST(GltfGeometry, RejectsAFileThatPlacesMoreThanAMillionObjects) {
    EXPECT_THAT(
        rejection(instancedGrids(17, 65536).writeGltf(scratchForTest("gltf-geometry-"), "too-many", false)),
        HasSubstr("places more than 1048576 objects"));
}

TEST(GltfGeometry, InstancesOfAnAnimatedNodeStayInTheRestPose) {
    GltfBuilder g = instancedQuad();
    const std::vector<float> times = {0, 1};
    const std::vector<glm::vec3> moves = {{0, 0, 0}, {0, 5, 0}};
    const int input = g.addAccessor(g.addView(times), kFloat, 2, "SCALAR");
    g.doc["accessors"][input]["min"] = {0};
    g.doc["accessors"][input]["max"] = {1};
    const int output = g.addAccessor(g.addView(moves), kFloat, 2, "VEC3");
    nlohmann::json sampler = {{"input", input}, {"output", output}};
    nlohmann::json channel = {{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}};
    g.push("animations",
           {{"samplers", nlohmann::json::array({sampler})}, {"channels", nlohmann::json::array({channel})}});
    Scene scene = loaded(g.writeGltf(scratchForTest("gltf-geometry-"), "animated-instances"));
    ASSERT_EQ(scene.objects.size(), 3u);
    for (const SceneObject& o : scene.objects) {
        EXPECT_EQ(o.node, -1);
        EXPECT_FALSE(o.dynamic);
    }
    EXPECT_NEAR(scene.objects[1].transform[3][0], 12.0, 1e-12);
}

// --- materials: KHR_texture_transform, KHR_materials_unlit, images only an extension uses ---------

namespace {

std::vector<uint8_t> tinyPng(const std::string& dir) {
    Image pixels;
    pixels.width = 1;
    pixels.height = 1;
    pixels.rgba = {10, 20, 30, 255};
    EXPECT_TRUE(writePng(dir + "/tiny.png", pixels).ok());
    std::ifstream in(dir + "/tiny.png", std::ios::binary);
    return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

GltfBuilder texturedQuad(const std::string& dir, const nlohmann::json& baseColorTexture) {
    GltfBuilder g = uvQuadScene();
    g.doc["images"] = {{{"uri", "data:image/png;base64," + base64(tinyPng(dir))}}};
    g.doc["textures"] = {{{"source", 0}}};
    g.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", baseColorTexture}}}}};
    g.doc["meshes"][0]["primitives"][0]["material"] = 0;
    return g;
}

} // namespace

TEST(GltfGeometry, TextureTransformIsAppliedToTheUvs) {
    const std::string dir = scratchForTest("gltf-geometry-");
    const double rotation = 0.392699;
    GltfBuilder g =
        texturedQuad(dir, {{"index", 0},
                           {"extensions",
                            {{"KHR_texture_transform",
                              {{"offset", {0.5, -0.25}}, {"rotation", rotation}, {"scale", {2, 3}}}}}}});
    g.doc["extensionsUsed"] = {"KHR_texture_transform"};
    g.doc["extensionsRequired"] = {"KHR_texture_transform"};
    Scene scene = loaded(g.writeGltf(dir, "transform"));
    ASSERT_EQ(scene.objects.size(), 1u);
    const std::vector<glm::vec2>& uvs = scene.objects[0].mesh->uvs;
    ASSERT_EQ(uvs.size(), 4u);
    const double c = std::cos(rotation), s = std::sin(rotation);
    for (size_t i = 0; i < 4; ++i) {
        // The extension's matrix, translation * rotation * scale, written out.
        const double u = 2 * kQuadUvs[i].x, v = 3 * kQuadUvs[i].y;
        EXPECT_NEAR(uvs[i].x, c * u - s * v + 0.5, 1e-6);
        EXPECT_NEAR(uvs[i].y, s * u + c * v - 0.25, 1e-6);
    }
    EXPECT_TRUE(scene.warnings.empty());
}

TEST(GltfGeometry, TextureTransformTurnsTheTangentsWithTheUvs) {
    const std::string dir = scratchForTest("gltf-geometry-");
    // A quarter turn: u' = -v, v' = u, so the new u runs along -y; a mirror in u flips the handedness.
    struct Case {
        const char* name;
        nlohmann::json transform;
        glm::vec4 tangent;
    };
    const Case cases[] = {{"turn", {{"rotation", glm::half_pi<double>()}}, {0, -1, 0, 1}},
                          {"mirror", {{"scale", {-1, 1}}}, {-1, 0, 0, -1}}};
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        GltfBuilder g =
            texturedQuad(dir, {{"index", 0}, {"extensions", {{"KHR_texture_transform", c.transform}}}});
        const std::vector<glm::vec3> normals(4, glm::vec3(0, 0, 1));
        const std::vector<glm::vec4> tangents(4, glm::vec4(1, 0, 0, 1));
        auto& attributes = g.doc["meshes"][0]["primitives"][0]["attributes"];
        attributes["NORMAL"] = g.addAccessor(g.addView(normals), kFloat, 4, "VEC3");
        attributes["TANGENT"] = g.addAccessor(g.addView(tangents), kFloat, 4, "VEC4");
        Scene scene = loaded(g.writeGltf(dir, c.name));
        ASSERT_EQ(scene.objects.size(), 1u);
        ASSERT_EQ(scene.objects[0].mesh->tangents.size(), 4u);
        for (const glm::vec4& t : scene.objects[0].mesh->tangents) {
            EXPECT_NEAR(t.x, c.tangent.x, 1e-6);
            EXPECT_NEAR(t.y, c.tangent.y, 1e-6);
            EXPECT_NEAR(t.z, c.tangent.z, 1e-6);
            EXPECT_EQ(t.w, c.tangent.w);
        }
    }
}

TEST(GltfGeometry, RejectsTextureTransformThatIsNotNumbers) {
    const std::string dir = scratchForTest("gltf-geometry-");
    GltfBuilder g =
        texturedQuad(dir, {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"offset", {1}}}}}}});
    EXPECT_THAT(
        rejection(g.writeGltf(dir, "bad")),
        HasSubstr("material 0: base colour texture KHR_texture_transform \"offset\" is not two numbers"));
}

TEST(GltfGeometry, UnlitMaterialsAreFlagged) {
    const std::string dir = scratchForTest("gltf-geometry-");
    GltfBuilder g = texturedQuad(dir, {{"index", 0}});
    g.doc["materials"][0]["extensions"] = {{"KHR_materials_unlit", nlohmann::json::object()}};
    g.doc["extensionsUsed"] = {"KHR_materials_unlit"};
    g.doc["extensionsRequired"] = {"KHR_materials_unlit"};
    Scene scene = loaded(g.writeGltf(dir, "unlit"));
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_TRUE(scene.materials[0].unlit);
}

TEST(GltfGeometry, ImageOnlyAnExtensionUsesFallsBackWithAWarning) {
    const std::string dir = scratchForTest("gltf-geometry-");
    GltfBuilder g = texturedQuad(dir, {{"index", 0}});
    // Image 1 stands for a KTX2 file: bytes no decoder here reads.
    g.doc["images"].push_back(
        {{"uri", "data:image/png;base64," + base64({0xAB, 'K', 'T', 'X', ' ', '2', '0'})}});
    g.doc["textures"][0]["extensions"] = {{"KHR_texture_basisu", {{"source", 1}}}};
    g.doc["extensionsUsed"] = {"KHR_texture_basisu"};
    Scene scene = loaded(g.writeGltf(dir, "basisu"));
    ASSERT_EQ(scene.images.size(), 2u);
    EXPECT_EQ(scene.materials[0].baseColorTexture, 0); // the core image
    EXPECT_EQ(scene.images[1].width, 1);
    ASSERT_EQ(scene.warnings.size(), 1u);
    EXPECT_THAT(scene.warnings[0], HasSubstr("image 1"));
    EXPECT_THAT(scene.warnings[0], HasSubstr("only an image extension uses it"));

    // The same bytes as the texture's core image are an error.
    g.doc["textures"][0]["source"] = 1;
    EXPECT_THAT(rejection(g.writeGltf(dir, "core")), HasSubstr("image 1"));
}

TEST(GltfGeometry, BufferWithoutUriNamesItsProblem) {
    GltfBuilder g = uvQuadScene();
    const std::string dir = scratchForTest("gltf-geometry-");
    const std::string path = g.writeGltf(dir, "nouri");
    nlohmann::json doc;
    std::ifstream(path) >> doc;
    doc["buffers"][0].erase("uri");
    std::ofstream(path) << doc.dump();
    EXPECT_THAT(rejection(path), HasSubstr("buffer 0 has no uri and the file is not a .glb"));
}
