// loadGltf on compressed geometry the test writes itself: KHR_draco_mesh_compression through
// libdraco's encoder and EXT_meshopt_compression through meshoptimizer's, each compared with the
// plain mesh within its quantisation step (Draco also with what libdraco decodes, to the bit);
// truncated and inconsistent compressed data is refused.

#include "spatter/core/SceneLoader.hpp"

#include "GltfBuilder.hpp"
#include "GltfLoading.hpp"
#include "TestData.hpp"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>

using namespace spatter;
using namespace spatter::test;
using ::testing::HasSubstr;
using json = nlohmann::json;

namespace {

// A wavy grid of n x n vertices over [0, 4] x [0, 4]: positions, unit normals, UVs and triangles.
struct Plain {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs;
    std::vector<uint32_t> indices;
};

Plain wavyGrid(int n = 12) {
    Plain p;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const float x = 4.0f * float(i) / float(n - 1), y = 4.0f * float(j) / float(n - 1);
            p.positions.push_back({x, y, 0.3f * std::sin(x) * std::cos(y)});
            p.normals.push_back(glm::normalize(
                glm::vec3(-0.3f * std::cos(x) * std::cos(y), 0.3f * std::sin(x) * std::sin(y), 1.0f)));
            p.uvs.push_back({float(i) / float(n - 1), float(j) / float(n - 1)});
        }
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            const uint32_t a = uint32_t(j * n + i), b = a + 1, c = a + uint32_t(n), d = c + 1;
            p.indices.insert(p.indices.end(), {a, b, d, a, d, c});
        }
    return p;
}

// Triangles as their smallest corner first, winding kept, then sorted.
std::vector<std::array<uint32_t, 3>> triangles(const std::vector<uint32_t>& indices,
                                               const std::vector<uint32_t>* map = nullptr) {
    std::vector<std::array<uint32_t, 3>> out;
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
        std::array<uint32_t, 3> t = {indices[i], indices[i + 1], indices[i + 2]};
        if (map)
            for (uint32_t& c : t)
                c = (*map)[c];
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        out.push_back(t);
    }
    std::sort(out.begin(), out.end());
    return out;
}

// Each loaded vertex lies within `tol` of a vertex of `plain` (its match, by nearest position), and
// the loaded triangles are the plain ones over the matched vertices, with the same winding. Normals
// and UVs of matched vertices agree within `normalTol` and `uvTol`.
void expectSameGeometry(const Mesh& mesh, const Plain& plain, float tol, float normalTol, float uvTol) {
    ASSERT_EQ(mesh.indices.size(), plain.indices.size());
    std::vector<uint32_t> match(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        size_t best = 0;
        for (size_t w = 1; w < plain.positions.size(); ++w)
            if (glm::distance(mesh.positions[v], plain.positions[w]) <
                glm::distance(mesh.positions[v], plain.positions[best]))
                best = w;
        match[v] = uint32_t(best);
        ASSERT_LE(glm::distance(mesh.positions[v], plain.positions[best]), tol) << "vertex " << v;
        EXPECT_LE(glm::distance(mesh.normals[v], plain.normals[best]), normalTol) << "vertex " << v;
        if (!mesh.uvs.empty()) {
            EXPECT_LE(glm::distance(mesh.uvs[v], plain.uvs[best]), uvTol) << "vertex " << v;
        }
    }
    EXPECT_EQ(triangles(mesh.indices, &match), triangles(plain.indices));
}

// Writes `g` as name.gltf with its binary data embedded as buffer 0, then `extra` buffers.
std::string writeWithBuffers(const GltfBuilder& g, const std::string& dir, const std::string& name,
                             const json& extra) {
    json d = g.doc;
    d["buffers"] = {
        {{"byteLength", g.bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(g.bin)}}};
    for (const json& b : extra)
        d["buffers"].push_back(b);
    const std::string path = dir + "/" + name + ".gltf";
    std::ofstream(path) << d.dump();
    return path;
}

// The same as a .glb: buffer 0 is the binary chunk.
std::string writeGlbWithBuffers(const GltfBuilder& g, const std::string& dir, const std::string& name,
                                const json& extra) {
    json d = g.doc;
    d["buffers"] = {{{"byteLength", g.bin.size()}}};
    for (const json& b : extra)
        d["buffers"].push_back(b);
    std::string text = d.dump();
    while (text.size() % 4)
        text += ' ';
    std::vector<uint8_t> chunk = g.bin;
    while (chunk.size() % 4)
        chunk.push_back(0);
    std::vector<uint8_t> out;
    auto u32 = [&](uint32_t v) {
        for (int i = 0; i < 4; ++i)
            out.push_back(uint8_t(v >> (8 * i)));
    };
    out.insert(out.end(), {'g', 'l', 'T', 'F'});
    u32(2);
    u32(uint32_t(28 + text.size() + chunk.size()));
    u32(uint32_t(text.size()));
    u32(0x4E4F534A);
    out.insert(out.end(), text.begin(), text.end());
    u32(uint32_t(chunk.size()));
    u32(0x004E4942);
    out.insert(out.end(), chunk.begin(), chunk.end());
    const std::string path = dir + "/" + name + ".glb";
    writeBytes(path, out);
    return path;
}

// --- Draco ---------------------------------------------------------------------------------------

struct DracoBits {
    int position = 14, normal = 10, uv = 12;
};

// `plain` encoded by libdraco; `ids` receives the unique ids of POSITION, NORMAL and TEXCOORD_0. With
// `shortUvs` the UVs are normalised 16-bit integers, which libdraco does not quantise.
std::vector<uint8_t> dracoEncode(const Plain& plain, const DracoBits& bits, int speed,
                                 std::array<int, 3>& ids, bool shortUvs = false) {
    draco::TriangleSoupMeshBuilder builder;
    const int faces = int(plain.indices.size() / 3);
    builder.Start(faces);
    const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int nor = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
    const int tex = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2,
                                         shortUvs ? draco::DT_UINT16 : draco::DT_FLOAT32);
    std::vector<std::array<uint16_t, 2>> uvShorts;
    for (const glm::vec2& uv : plain.uvs)
        uvShorts.push_back({uint16_t(std::lround(uv.x * 65535.0f)), uint16_t(std::lround(uv.y * 65535.0f))});
    auto uv = [&](uint32_t v) -> const void* { return shortUvs ? (const void*)&uvShorts[v] : &plain.uvs[v]; };
    for (int f = 0; f < faces; ++f) {
        const uint32_t* c = &plain.indices[size_t(f) * 3];
        builder.SetAttributeValuesForFace(pos, draco::FaceIndex(f), &plain.positions[c[0]],
                                          &plain.positions[c[1]], &plain.positions[c[2]]);
        builder.SetAttributeValuesForFace(nor, draco::FaceIndex(f), &plain.normals[c[0]],
                                          &plain.normals[c[1]], &plain.normals[c[2]]);
        builder.SetAttributeValuesForFace(tex, draco::FaceIndex(f), uv(c[0]), uv(c[1]), uv(c[2]));
    }
    std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    mesh->attribute(tex)->set_normalized(shortUvs);
    ids = {int(mesh->attribute(pos)->unique_id()), int(mesh->attribute(nor)->unique_id()),
           int(mesh->attribute(tex)->unique_id())};
    draco::Encoder encoder;
    encoder.SetSpeedOptions(speed, speed);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, bits.position);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, bits.normal);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, bits.uv);
    draco::EncoderBuffer buffer;
    const draco::Status status = encoder.EncodeMeshToBuffer(*mesh, &buffer);
    EXPECT_TRUE(status.ok()) << status.error_msg_string();
    return std::vector<uint8_t>(buffer.data(), buffer.data() + buffer.size());
}

// A glTF of one node whose primitive is the Draco data of `plain`: accessors without buffer views,
// as exporters write them when the extension is required.
GltfBuilder dracoScene(const Plain& plain, const std::vector<uint8_t>& draco, const std::array<int, 3>& ids) {
    GltfBuilder g;
    const size_t points = plain.positions.size();
    g.push("accessors", {{"componentType", kFloat}, {"count", points}, {"type", "VEC3"}});
    g.push("accessors", {{"componentType", kFloat}, {"count", points}, {"type", "VEC3"}});
    g.push("accessors", {{"componentType", kFloat}, {"count", points}, {"type", "VEC2"}});
    g.push("accessors",
           {{"componentType", kUnsignedInt}, {"count", plain.indices.size()}, {"type", "SCALAR"}});
    const int view = g.addView(draco);
    g.push(
        "meshes",
        {{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
            {"indices", 3},
            {"extensions",
             {{"KHR_draco_mesh_compression",
               {{"bufferView", view},
                {"attributes", {{"POSITION", ids[0]}, {"NORMAL", ids[1]}, {"TEXCOORD_0", ids[2]}}}}}}}}}}});
    g.push("nodes", {{"name", "grid"}, {"mesh", 0}});
    g.doc["scenes"] = {{{"nodes", {0}}}};
    g.doc["scene"] = 0;
    g.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    g.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    return g;
}

// The uncompressed twin of the Draco data: what libdraco's decoder gives with all its transforms done,
// every point's POSITION, NORMAL and TEXCOORD_0 as floats (ConvertValue, as the loader converts values
// of another type) and the faces as 32-bit indices.
GltfBuilder decodedTwin(const std::vector<uint8_t>& bytes, const std::array<int, 3>& ids) {
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    draco::Decoder decoder;
    std::unique_ptr<draco::Mesh> mesh = std::move(decoder.DecodeMeshFromBuffer(&buffer)).value();
    GltfBuilder g;
    json attributes;
    const char* names[] = {"POSITION", "NORMAL", "TEXCOORD_0"};
    for (int a = 0; a < 3; ++a) {
        const draco::PointAttribute& att = *mesh->GetAttributeByUniqueId(uint32_t(ids[size_t(a)]));
        const int n = a == 2 ? 2 : 3;
        std::vector<float> values(size_t(mesh->num_points()) * size_t(n));
        for (draco::PointIndex p(0); p < mesh->num_points(); ++p)
            EXPECT_TRUE(
                att.ConvertValue<float>(att.mapped_index(p), int8_t(n), &values[p.value() * size_t(n)]));
        attributes[names[a]] =
            g.addAccessor(g.addView(values), kFloat, mesh->num_points(), n == 3 ? "VEC3" : "VEC2");
    }
    std::vector<uint32_t> indices;
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
        for (const draco::PointIndex& p : mesh->face(f))
            indices.push_back(p.value());
    const int i = g.addAccessor(g.addView(indices), kUnsignedInt, indices.size(), "SCALAR");
    g.push("meshes", {{"primitives", {{{"attributes", attributes}, {"indices", i}}}}});
    g.push("nodes", {{"name", "grid"}, {"mesh", 0}});
    g.doc["scenes"] = {{{"nodes", {0}}}};
    g.doc["scene"] = 0;
    return g;
}

template <class T> bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// The Draco file loads to the same bits as its decoded twin: positions, normals, UVs and triangles.
void expectSameAsDecodedTwin(const std::vector<uint8_t>& bytes, const std::array<int, 3>& ids,
                             const Plain& plain, const std::string& name) {
    const std::string dir = scratchForTest("gltf-compression-");
    Scene draco = loaded(dracoScene(plain, bytes, ids).writeGltf(dir, name));
    Scene twin = loaded(decodedTwin(bytes, ids).writeGltf(dir, name + "-twin"));
    ASSERT_EQ(draco.objects.size(), 1u);
    ASSERT_EQ(twin.objects.size(), 1u);
    const Mesh &a = *draco.objects[0].mesh, &b = *twin.objects[0].mesh;
    EXPECT_TRUE(sameBits(a.positions, b.positions));
    EXPECT_TRUE(sameBits(a.normals, b.normals));
    EXPECT_TRUE(sameBits(a.uvs, b.uvs));
    EXPECT_EQ(a.indices, b.indices);
}

} // namespace

TEST(GltfCompression, DracoGivesThePlainGeometryWithinTheQuantisationStep) {
    const Plain plain = wavyGrid();
    const std::string dir = scratchForTest("gltf-compression-");
    const DracoBits bits;
    for (int speed : {0, 5, 10}) { // edgebreaker at 0 and 5, the sequential coder at 10
        SCOPED_TRACE(speed);
        std::array<int, 3> ids{};
        const std::vector<uint8_t> bytes = dracoEncode(plain, bits, speed, ids);
        Scene scene = loaded(dracoScene(plain, bytes, ids).writeGltf(dir, "draco" + std::to_string(speed)));
        ASSERT_EQ(scene.objects.size(), 1u);
        // The positions span 4 units: a step of 4 / 2^14; normals and UVs likewise.
        expectSameGeometry(*scene.objects[0].mesh, plain, 4.0f / float(1 << bits.position),
                           4.0f / float(1 << bits.normal), 1.0f / float(1 << bits.uv));
    }
}

TEST(GltfCompression, DracoInAGlbWithIndicesOfSixteenBits) {
    const Plain plain = wavyGrid();
    std::array<int, 3> ids{};
    GltfBuilder g = dracoScene(plain, dracoEncode(plain, DracoBits{}, 5, ids), ids);
    g.doc["accessors"][3]["componentType"] = kUnsignedShort; // the declared type; decoded data is 32-bit
    const std::string path = scratchForTest("gltf-compression-") + "/draco.glb";
    writeBytes(path, g.glbBytes());
    Scene scene = loaded(path);
    ASSERT_EQ(scene.objects.size(), 1u);
    expectSameGeometry(*scene.objects[0].mesh, plain, 4.0f / (1 << 14), 4.0f / (1 << 10), 1.0f / (1 << 12));
}

// The loader dequantises positions, normals and UVs itself (libdraco skips that step): the floats
// must be those libdraco's own dequantisation gives, to the bit, whatever the coder and prediction.
TEST(GltfCompression, DracoDequantisedByTheLoaderAsByLibdraco) {
    const Plain plain = wavyGrid(40);
    for (int speed : {0, 4, 5, 10}) {
        SCOPED_TRACE(speed);
        std::array<int, 3> ids{};
        const std::vector<uint8_t> bytes = dracoEncode(plain, DracoBits{}, speed, ids);
        expectSameAsDecodedTwin(bytes, ids, plain, "speed" + std::to_string(speed));
    }
}

// Integer UVs for a float accessor keep their normalisation: libdraco would hand them over as plain
// 32-bit integers when told to skip the transforms of UVs. The floats then come dequantised by
// libdraco, copied point by point (edgebreaker) or as one block (the sequential coder).
TEST(GltfCompression, DracoNormalisedIntegerUvsForAFloatAccessor) {
    const Plain plain = wavyGrid();
    for (int speed : {5, 10}) {
        SCOPED_TRACE(speed);
        std::array<int, 3> ids{};
        const std::vector<uint8_t> bytes = dracoEncode(plain, DracoBits{}, speed, ids, true);
        const std::string name = "short-uvs" + std::to_string(speed);
        expectSameAsDecodedTwin(bytes, ids, plain, name);
        Scene scene = loaded(
            dracoScene(plain, bytes, ids).writeGltf(scratchForTest("gltf-compression-"), name + "-plain"));
        ASSERT_EQ(scene.objects.size(), 1u);
        expectSameGeometry(*scene.objects[0].mesh, plain, 4.0f / (1 << 14), 4.0f / (1 << 10), 1.0f / 65535);
    }
}

TEST(GltfCompression, RejectsTruncatedOrInconsistentDracoData) {
    const Plain plain = wavyGrid();
    const std::string dir = scratchForTest("gltf-compression-");
    std::array<int, 3> ids{};
    const std::vector<uint8_t> bytes = dracoEncode(plain, DracoBits{}, 5, ids);
    for (size_t keep : {size_t(0), size_t(4), size_t(16), bytes.size() / 2, bytes.size() - 1}) {
        SCOPED_TRACE(keep);
        const std::vector<uint8_t> cut(bytes.begin(), bytes.begin() + std::ptrdiff_t(keep));
        GltfBuilder g = dracoScene(plain, cut.empty() ? std::vector<uint8_t>{0} : cut, ids);
        EXPECT_THAT(rejection(g.writeGltf(dir, "cut" + std::to_string(keep))),
                    HasSubstr("mesh 0 primitive 0: its Draco data (buffer view 0) cannot be decoded"));
    }
    {
        GltfBuilder g = dracoScene(plain, bytes, ids);
        g.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]
             ["NORMAL"] = 77;
        EXPECT_THAT(rejection(g.writeGltf(dir, "id")),
                    HasSubstr("Draco attribute NORMAL is not in its Draco data"));
    }
    {
        GltfBuilder g = dracoScene(plain, bytes, ids);
        g.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"] = 9;
        EXPECT_THAT(rejection(g.writeGltf(dir, "view")),
                    HasSubstr("refers to buffer view 9, which does not exist"));
    }
    {
        GltfBuilder g = dracoScene(plain, bytes, ids);
        g.doc["meshes"][0]["primitives"][0]["attributes"].erase("NORMAL");
        EXPECT_THAT(rejection(g.writeGltf(dir, "attr")),
                    HasSubstr("Draco attribute NORMAL is not an attribute of it"));
    }
}

// --- meshopt -------------------------------------------------------------------------------------

namespace {

// Adds the meshopt-compressed `data` (count elements of `stride` bytes) as a view over the fallback
// buffer 1 at `fallbackOffset`; returns the view.
int addMeshoptView(GltfBuilder& g, const std::vector<uint8_t>& compressed, size_t count, size_t stride,
                   const char* mode, const char* filter, size_t& fallbackOffset, bool vertexStride) {
    while (g.bin.size() % 4)
        g.bin.push_back(0);
    const size_t offset = g.bin.size();
    g.bin.insert(g.bin.end(), compressed.begin(), compressed.end());
    json ext = {{"buffer", 0},          {"byteOffset", offset}, {"byteLength", compressed.size()},
                {"byteStride", stride}, {"count", count},       {"mode", mode}};
    if (filter) ext["filter"] = filter;
    json view = {{"buffer", 1},
                 {"byteOffset", fallbackOffset},
                 {"byteLength", count * stride},
                 {"extensions", {{"EXT_meshopt_compression", ext}}}};
    if (vertexStride) view["byteStride"] = stride;
    fallbackOffset += (count * stride + 3) / 4 * 4;
    return g.push("bufferViews", view);
}

std::vector<uint8_t> encodeVertices(const void* data, size_t count, size_t stride) {
    std::vector<uint8_t> out(meshopt_encodeVertexBufferBound(count, stride));
    out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), data, count, stride));
    return out;
}

// The grid with meshopt-compressed views: float positions, octahedral-filtered normals (normalized
// shorts), float UVs, and 32-bit triangles (TRIANGLES) or a 16-bit index sequence (INDICES).
// `fallbackLength` receives the fallback buffer's length.
GltfBuilder meshoptScene(const Plain& plain, bool sequence, size_t& fallbackLength) {
    GltfBuilder g;
    size_t fallback = 0;
    const size_t n = plain.positions.size();
    const int pv = addMeshoptView(g, encodeVertices(plain.positions.data(), n, 12), n, 12, "ATTRIBUTES",
                                  nullptr, fallback, true);
    std::vector<float> normals4;
    for (const glm::vec3& v : plain.normals)
        normals4.insert(normals4.end(), {v.x, v.y, v.z, 0.0f});
    std::vector<int16_t> oct(n * 4);
    meshopt_encodeFilterOct(oct.data(), n, 8, 16, normals4.data());
    const int nv =
        addMeshoptView(g, encodeVertices(oct.data(), n, 8), n, 8, "ATTRIBUTES", "OCTAHEDRAL", fallback, true);
    const int uv = addMeshoptView(g, encodeVertices(plain.uvs.data(), n, 8), n, 8, "ATTRIBUTES", nullptr,
                                  fallback, true);
    int iv;
    if (sequence) {
        std::vector<uint8_t> enc(meshopt_encodeIndexSequenceBound(plain.indices.size(), n));
        enc.resize(
            meshopt_encodeIndexSequence(enc.data(), enc.size(), plain.indices.data(), plain.indices.size()));
        iv = addMeshoptView(g, enc, plain.indices.size(), 2, "INDICES", nullptr, fallback, false);
    } else {
        std::vector<uint8_t> enc(meshopt_encodeIndexBufferBound(plain.indices.size(), n));
        enc.resize(
            meshopt_encodeIndexBuffer(enc.data(), enc.size(), plain.indices.data(), plain.indices.size()));
        iv = addMeshoptView(g, enc, plain.indices.size(), 4, "TRIANGLES", nullptr, fallback, false);
    }
    g.addAccessor(pv, kFloat, n, "VEC3");
    const int na = g.addAccessor(nv, 5122, n, "VEC3");
    g.doc["accessors"][na]["normalized"] = true;
    g.addAccessor(uv, kFloat, n, "VEC2");
    g.addAccessor(iv, sequence ? kUnsignedShort : kUnsignedInt, plain.indices.size(), "SCALAR");
    g.push("meshes",
           {{"primitives",
             {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}}}}});
    g.push("nodes", {{"name", "grid"}, {"mesh", 0}});
    g.doc["scenes"] = {{{"nodes", {0}}}};
    g.doc["scene"] = 0;
    g.doc["extensionsUsed"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
    g.doc["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
    fallbackLength = fallback;
    return g;
}

json fallbackBuffer(size_t length) {
    return json::array(
        {{{"byteLength", length}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}});
}

} // namespace

TEST(GltfCompression, MeshoptGivesThePlainGeometryInGltfAndGlb) {
    const Plain plain = wavyGrid();
    const std::string dir = scratchForTest("gltf-compression-");
    for (bool sequence : {false, true}) {
        SCOPED_TRACE(sequence ? "INDICES" : "TRIANGLES");
        size_t fallback = 0;
        const GltfBuilder g = meshoptScene(plain, sequence, fallback);
        const std::string name = sequence ? "sequence" : "triangles";
        for (const std::string& path : {writeWithBuffers(g, dir, name, fallbackBuffer(fallback)),
                                        writeGlbWithBuffers(g, dir, name, fallbackBuffer(fallback))}) {
            SCOPED_TRACE(path);
            Scene scene = loaded(path);
            ASSERT_EQ(scene.objects.size(), 1u);
            const std::vector<std::string> extensions = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
            EXPECT_EQ(scene.extensionsUsed, extensions);
            EXPECT_EQ(scene.extensionsRequired, extensions);
            const Mesh& mesh = *scene.objects[0].mesh;
            // Positions and UVs are lossless; normals went through 16-bit octahedral encoding.
            EXPECT_EQ(mesh.positions, plain.positions);
            EXPECT_EQ(mesh.uvs, plain.uvs);
            // The index codec may rotate a triangle's corners; the index sequence keeps them.
            if (sequence)
                EXPECT_EQ(mesh.indices, plain.indices);
            else
                EXPECT_EQ(triangles(mesh.indices), triangles(plain.indices));
            for (size_t v = 0; v < plain.normals.size(); ++v)
                EXPECT_LE(glm::distance(mesh.normals[v], plain.normals[v]), 1e-3f) << v;
        }
    }
}

TEST(GltfCompression, MeshoptFallbackFileIsNeverRead) {
    const Plain plain = wavyGrid();
    size_t fallback = 0;
    const GltfBuilder g = meshoptScene(plain, false, fallback);
    json buffers = fallbackBuffer(fallback);
    buffers[0]["uri"] = "absent-fallback.bin";
    Scene scene = loaded(writeWithBuffers(g, scratchForTest("gltf-compression-"), "fallback-file", buffers));
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].mesh->positions, plain.positions);
}

TEST(GltfCompression, RejectsTruncatedOrInconsistentMeshoptData) {
    const Plain plain = wavyGrid();
    const std::string dir = scratchForTest("gltf-compression-");
    size_t fallback = 0;
    auto edited = [&](const std::string& name, auto edit) {
        GltfBuilder g = meshoptScene(plain, false, fallback);
        edit(g.doc["bufferViews"]);
        return rejection(writeWithBuffers(g, dir, name, fallbackBuffer(fallback)));
    };
    auto ext = [](json& views, int v) -> json& { return views[v]["extensions"]["EXT_meshopt_compression"]; };
    EXPECT_THAT(edited("short", [&](json& v) { ext(v, 0)["byteLength"] = 20; }),
                HasSubstr("buffer view 0: its ATTRIBUTES data does not decode"));
    EXPECT_THAT(edited("indices", [&](json& v) { ext(v, 3)["byteLength"] = 10; }),
                HasSubstr("buffer view 3: its TRIANGLES data does not decode"));
    EXPECT_THAT(edited("past", [&](json& v) { ext(v, 0)["byteLength"] = 1 << 20; }),
                HasSubstr("buffer view 0: its compressed data reads past the end of buffer 0"));
    EXPECT_THAT(edited("stride", [&](json& v) { ext(v, 0)["byteStride"] = 6; }),
                HasSubstr("buffer view 0: its byte stride 6 does not suit ATTRIBUTES"));
    EXPECT_THAT(edited("mode", [&](json& v) { ext(v, 0)["mode"] = "POINTS"; }),
                HasSubstr("its mode \"POINTS\" is not ATTRIBUTES"));
    EXPECT_THAT(edited("filter", [&](json& v) { ext(v, 0)["filter"] = "OCTAHEDRAL"; }),
                HasSubstr("its byte stride 12 does not suit OCTAHEDRAL"));
    EXPECT_THAT(edited("unknown", [&](json& v) { ext(v, 1)["filter"] = "WAVELET"; }),
                HasSubstr("its filter \"WAVELET\" is not NONE"));
    EXPECT_THAT(edited("count", [&](json& v) { ext(v, 0).erase("count"); }),
                HasSubstr("buffer view 0: its EXT_meshopt_compression lacks \"count\""));
    EXPECT_THAT(edited("huge", [&](json& v) { ext(v, 0)["count"] = 1e9; }),
                HasSubstr("more than the codecs can hold"));
    EXPECT_THAT(edited("buffer", [&](json& v) { ext(v, 0)["buffer"] = 7; }),
                HasSubstr("refers to buffer 7, which does not exist"));
}

TEST(GltfCompression, MeshoptViewLongerThanItsDecodedDataIsRefused) {
    const Plain plain = wavyGrid();
    size_t fallback = 0;
    GltfBuilder g = meshoptScene(plain, false, fallback);
    g.doc["bufferViews"][0]["byteLength"] = plain.positions.size() * 12 + 4;
    EXPECT_THAT(rejection(writeWithBuffers(g, scratchForTest("gltf-compression-"), "long",
                                           fallbackBuffer(fallback + 4))),
                HasSubstr("buffer view 0: it declares"));
}
