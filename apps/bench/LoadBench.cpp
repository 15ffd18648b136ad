#include "LoadBench.hpp"

#include "BenchSupport.hpp"

#include "spatter/core/SceneLoader.hpp"

// libdraco's encoder comes with spatter::core's link (libdraco is linked last there, see
// core/CMakeLists.txt); only its headers are named here.
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <meshoptimizer.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace spatter::bench {

namespace {

const char* kLoadCommand = "load";

const char* kLoadUsage =
    R"(usage: spatter-bench load [--grid N] [--repeat R] [--quick] [--json FILE]

The cost of loading Draco-compressed glTF against its uncompressed twin, in the same run: every
file holds one mesh of N x N vertices (a wavy grid: float positions, normals and UVs, 32-bit
triangles); the compressed ones are encoded by libdraco with the quantisation exporters use by
default (positions 14 bits, normals 10, UVs 12) at the speeds of three exporters' defaults:
  level 7   encoder and decoder speed 3 (gltf-pipeline's default compression level)
  level 6   speed 4 (Blender's default compression level)
  speed 5   speed 5 (glTF-Transform's default)
Each row is the median wall time of R loads (loadGltf: read, parse, decode, convert, validate), the
files loaded in turns; the ratio is to the uncompressed file's time. The last row is libdraco's
decoder alone on the level-6 data (DecodeMeshFromBuffer), the part of that load spatter cannot cut.
The meshopt row is the same mesh compressed by meshoptimizer's vertex and index codecs
(EXT_meshopt_compression; float attributes, no filters).

Target: a Draco file at Blender's default (level 6) loads in at most 3x the time of its twin.

--grid N    vertices a side (default 512: 262,144 vertices, 522,242 triangles)
--repeat R  loads of each file (default 9)
--quick     a grid of 128, 3 loads (smoke test)
--json FILE {"grid", "vertices", "triangles", "ratio_level6", "rows": [{"file", "encoder_speed",
            "bytes", "ms", "ratio"}]} (encoder_speed -1: uncompressed, -2: meshopt, -3: the level 6
            file's decoding by libdraco alone)
)";

struct Grid {
    std::vector<float> positions, normals, uvs; // 3, 3, 2 floats a vertex
    std::vector<uint32_t> indices;
};

Grid wavyGrid(size_t n) {
    Grid g;
    const float size = 10.0f;
    for (size_t j = 0; j < n; ++j)
        for (size_t i = 0; i < n; ++i) {
            const float u = float(i) / float(n - 1), v = float(j) / float(n - 1);
            const float x = size * u, y = size * v;
            g.positions.insert(g.positions.end(), {x, y, 0.3f * std::sin(x) * std::cos(y)});
            const float nx = -0.3f * std::cos(x) * std::cos(y), ny = 0.3f * std::sin(x) * std::sin(y);
            const float len = std::sqrt(nx * nx + ny * ny + 1.0f);
            g.normals.insert(g.normals.end(), {nx / len, ny / len, 1.0f / len});
            g.uvs.insert(g.uvs.end(), {u, v});
        }
    for (size_t j = 0; j + 1 < n; ++j)
        for (size_t i = 0; i + 1 < n; ++i) {
            const uint32_t a = uint32_t(j * n + i), b = a + 1, c = a + uint32_t(n), d = c + 1;
            g.indices.insert(g.indices.end(), {a, b, d, a, d, c});
        }
    return g;
}

// Writes a GLB of `doc` with `bin` as its binary chunk (buffer 0), then the buffers `extra`.
Status writeGlb(Json doc, std::vector<uint8_t> bin, const std::string& path,
                const Json& extra = Json::array()) {
    while (bin.size() % 4)
        bin.push_back(0);
    doc["buffers"] = Json::array({{{"byteLength", bin.size()}}});
    for (const Json& b : extra)
        doc["buffers"].push_back(b);
    std::string text = doc.dump();
    while (text.size() % 4)
        text += ' ';
    std::vector<uint8_t> out;
    auto u32 = [&](uint32_t v) {
        for (int i = 0; i < 4; ++i)
            out.push_back(uint8_t(v >> (8 * i)));
    };
    out.insert(out.end(), {'g', 'l', 'T', 'F'});
    u32(2);
    u32(uint32_t(28 + text.size() + bin.size()));
    u32(uint32_t(text.size()));
    u32(0x4E4F534A);
    out.insert(out.end(), text.begin(), text.end());
    u32(uint32_t(bin.size()));
    u32(0x004E4942);
    out.insert(out.end(), bin.begin(), bin.end());
    std::ofstream file(path, std::ios::binary);
    file.write(reinterpret_cast<const char*>(out.data()), std::streamsize(out.size()));
    if (!file) return fail("cannot write " + path);
    return {};
}

Json sceneOf(const Json& primitive) {
    Json doc = {{"asset", {{"version", "2.0"}}}};
    doc["meshes"] = Json::array({{{"primitives", Json::array({primitive})}}});
    doc["nodes"] = Json::array({{{"name", "grid"}, {"mesh", 0}}});
    doc["scenes"] = Json::array({{{"nodes", {0}}}});
    doc["scene"] = 0;
    return doc;
}

Json accessor(int view, int componentType, size_t count, const char* type) {
    Json a = {{"componentType", componentType}, {"count", count}, {"type", type}};
    if (view >= 0) a["bufferView"] = view;
    return a;
}

Status writePlain(const Grid& g, const std::string& path) {
    std::vector<uint8_t> bin;
    Json views = Json::array();
    auto add = [&](const void* data, size_t size) {
        views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}});
        bin.insert(bin.end(), static_cast<const uint8_t*>(data), static_cast<const uint8_t*>(data) + size);
        return int(views.size()) - 1;
    };
    const size_t n = g.positions.size() / 3;
    Json doc = sceneOf({{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}});
    doc["accessors"] = Json::array(
        {accessor(add(g.positions.data(), n * 12), 5126, n, "VEC3"),
         accessor(add(g.normals.data(), n * 12), 5126, n, "VEC3"),
         accessor(add(g.uvs.data(), n * 8), 5126, n, "VEC2"),
         accessor(add(g.indices.data(), g.indices.size() * 4), 5125, g.indices.size(), "SCALAR")});
    doc["accessors"][0]["min"] = {0, 0, -0.3};
    doc["accessors"][0]["max"] = {10, 10, 0.3};
    doc["bufferViews"] = views;
    return writeGlb(doc, bin, path);
}

Status writeDraco(const Grid& g, int speed, const std::string& path, std::vector<uint8_t>& bitstream) {
    draco::TriangleSoupMeshBuilder builder;
    const int faces = int(g.indices.size() / 3);
    builder.Start(faces);
    const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int nor = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
    const int tex = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    for (int f = 0; f < faces; ++f) {
        const uint32_t* c = &g.indices[size_t(f) * 3];
        builder.SetAttributeValuesForFace(pos, draco::FaceIndex(f), &g.positions[c[0] * 3],
                                          &g.positions[c[1] * 3], &g.positions[c[2] * 3]);
        builder.SetAttributeValuesForFace(nor, draco::FaceIndex(f), &g.normals[c[0] * 3],
                                          &g.normals[c[1] * 3], &g.normals[c[2] * 3]);
        builder.SetAttributeValuesForFace(tex, draco::FaceIndex(f), &g.uvs[c[0] * 2], &g.uvs[c[1] * 2],
                                          &g.uvs[c[2] * 2]);
    }
    std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    if (!mesh) return fail("libdraco could not build the mesh");
    draco::Encoder encoder;
    encoder.SetSpeedOptions(speed, speed);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
    draco::EncoderBuffer buffer;
    if (const draco::Status s = encoder.EncodeMeshToBuffer(*mesh, &buffer); !s.ok())
        return fail("libdraco could not encode the mesh: " + s.error_msg_string());
    bitstream.assign(buffer.data(), buffer.data() + buffer.size());
    const size_t points = mesh->num_points();
    Json primitive = {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
                      {"indices", 3},
                      {"extensions",
                       {{"KHR_draco_mesh_compression",
                         {{"bufferView", 0},
                          {"attributes",
                           {{"POSITION", mesh->attribute(pos)->unique_id()},
                            {"NORMAL", mesh->attribute(nor)->unique_id()},
                            {"TEXCOORD_0", mesh->attribute(tex)->unique_id()}}}}}}}};
    Json doc = sceneOf(primitive);
    doc["accessors"] =
        Json::array({accessor(-1, 5126, points, "VEC3"), accessor(-1, 5126, points, "VEC3"),
                     accessor(-1, 5126, points, "VEC2"), accessor(-1, 5125, g.indices.size(), "SCALAR")});
    doc["accessors"][0]["min"] = {0, 0, -0.3};
    doc["accessors"][0]["max"] = {10, 10, 0.3};
    doc["bufferViews"] = Json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", buffer.size()}}});
    doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    return writeGlb(doc, std::vector<uint8_t>(buffer.data(), buffer.data() + buffer.size()), path);
}

// The grid compressed by meshoptimizer without quantisation or filters: the vertex codec
// for each attribute, the index codec for the triangles, over a fallback buffer without data.
Status writeMeshopt(const Grid& g, const std::string& path) {
    std::vector<uint8_t> bin;
    Json views = Json::array();
    size_t fallback = 0;
    auto add = [&](const std::vector<uint8_t>& encoded, size_t count, size_t stride, const char* mode) {
        while (bin.size() % 4)
            bin.push_back(0);
        Json view = {{"buffer", 1},
                     {"byteOffset", fallback},
                     {"byteLength", count * stride},
                     {"extensions",
                      {{"EXT_meshopt_compression",
                        {{"buffer", 0},
                         {"byteOffset", bin.size()},
                         {"byteLength", encoded.size()},
                         {"byteStride", stride},
                         {"count", count},
                         {"mode", mode}}}}}};
        if (std::string(mode) == "ATTRIBUTES") view["byteStride"] = stride;
        views.push_back(view);
        bin.insert(bin.end(), encoded.begin(), encoded.end());
        fallback += (count * stride + 3) / 4 * 4;
        return int(views.size()) - 1;
    };
    auto vertices = [](const float* data, size_t count, size_t stride) {
        std::vector<uint8_t> out(meshopt_encodeVertexBufferBound(count, stride));
        out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), data, count, stride));
        return out;
    };
    const size_t n = g.positions.size() / 3;
    std::vector<uint8_t> triangles(meshopt_encodeIndexBufferBound(g.indices.size(), n));
    triangles.resize(
        meshopt_encodeIndexBuffer(triangles.data(), triangles.size(), g.indices.data(), g.indices.size()));
    Json doc = sceneOf({{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}});
    doc["accessors"] = Json::array(
        {accessor(add(vertices(g.positions.data(), n, 12), n, 12, "ATTRIBUTES"), 5126, n, "VEC3"),
         accessor(add(vertices(g.normals.data(), n, 12), n, 12, "ATTRIBUTES"), 5126, n, "VEC3"),
         accessor(add(vertices(g.uvs.data(), n, 8), n, 8, "ATTRIBUTES"), 5126, n, "VEC2"),
         accessor(add(triangles, g.indices.size(), 4, "TRIANGLES"), 5125, g.indices.size(), "SCALAR")});
    doc["accessors"][0]["min"] = {0, 0, -0.3};
    doc["accessors"][0]["max"] = {10, 10, 0.3};
    doc["bufferViews"] = views;
    doc["extensionsUsed"] = {"EXT_meshopt_compression"};
    doc["extensionsRequired"] = {"EXT_meshopt_compression"};
    const Json fallbackBuffer = {{"byteLength", fallback},
                                 {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}};
    return writeGlb(doc, bin, path, Json::array({fallbackBuffer}));
}

size_t fileSize(const std::string& path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    return in ? size_t(in.tellg()) : 0;
}

} // namespace

int runLoadCommand(int argc, char** argv) {
    int exitCode = 0;
    const std::optional<Args> parsed = commandArgs(argc, argv, kLoadCommand, kLoadUsage,
                                                   {"--grid", "--repeat", "--json"}, {"--quick"}, exitCode);
    if (!parsed) return exitCode;
    const Args& args = *parsed;
    if (!args.positional.empty()) return usageError(kLoadCommand, "no positional arguments");
    const bool quick = args.has("--quick");
    Result<uint64_t> gridArg = parseCount(args.value("--grid", quick ? "128" : "512"), "--grid");
    if (!gridArg) return usageError(kLoadCommand, gridArg.error());
    Result<uint64_t> repeat = parseCount(args.value("--repeat", quick ? "3" : "9"), "--repeat");
    if (!repeat) return usageError(kLoadCommand, repeat.error());
    const size_t n = gridArg.value(), runs = repeat.value();
    if (n < 2 || n > 4096 || runs == 0)
        return usageError(kLoadCommand, "--grid must be from 2 to 4096 and --repeat positive");

    const Grid grid = wavyGrid(n);
    const ScratchDirectory scratch("load");
    const std::string& dir = scratch.path();
    struct File {
        std::string name, path;
        int speed; // Draco's encoder speed; -1: uncompressed, -2: meshopt
        std::vector<double> times;
    };
    std::vector<File> files = {{"uncompressed", dir + "/plain.glb", -1, {}},
                               {"Draco level 7", dir + "/draco-speed3.glb", 3, {}},
                               {"Draco level 6", dir + "/draco-speed4.glb", 4, {}},
                               {"Draco speed 5", dir + "/draco-speed5.glb", 5, {}},
                               {"meshopt", dir + "/meshopt.glb", -2, {}}};
    std::vector<uint8_t> bitstream, level6; // the Draco data at level 6, decoded alone below
    for (const File& f : files)
        if (Status s = f.speed == -1   ? writePlain(grid, f.path)
                       : f.speed == -2 ? writeMeshopt(grid, f.path)
                                       : writeDraco(grid, f.speed, f.path, bitstream);
            !s) {
            std::fprintf(stderr, "spatter-bench load: %s\n", s.error().c_str());
            return 1;
        } else if (f.speed == 4) {
            level6 = bitstream;
        }
    const size_t triangles = grid.indices.size() / 3;
    const MachineInfo machine = machineInfo();
    std::printf("spatter-bench load: a grid of %zu x %zu vertices, %zu triangles; %zu loads of each file\n"
                "machine: %s\n\n",
                n, n, triangles, runs, describe(machine).c_str());

    for (size_t r = 0; r < runs; ++r)
        for (File& f : files) {
            const double t0 = now();
            Result<Scene> scene = loadGltf(f.path);
            f.times.push_back(now() - t0);
            if (!scene || scene->triangleCount() != triangles) {
                std::fprintf(stderr, "spatter-bench load: %s\n",
                             scene ? (f.path + ": wrong triangle count").c_str() : scene.error().c_str());
                return 1;
            }
        }
    // What libdraco's decoder alone costs on the level-6 data: the floor under that file's row.
    std::vector<double> decodeTimes;
    for (size_t r = 0; r < runs; ++r) {
        const double t0 = now();
        draco::DecoderBuffer buffer;
        buffer.Init(reinterpret_cast<const char*>(level6.data()), level6.size());
        draco::Decoder decoder;
        const bool ok = decoder.DecodeMeshFromBuffer(&buffer).ok();
        decodeTimes.push_back(now() - t0);
        if (!ok) {
            std::fprintf(stderr, "spatter-bench load: libdraco cannot decode its own data\n");
            return 1;
        }
    }
    const double plainMs = median(files[0].times) * 1e3;
    std::vector<std::vector<std::string>> table;
    Json rows = Json::array();
    double targetRatio = std::numeric_limits<double>::quiet_NaN(); // until the level 6 file loads
    for (const File& f : files) {
        const double ms = median(f.times) * 1e3, ratio = ms / plainMs;
        if (f.speed == 4) targetRatio = ratio;
        table.push_back({f.name, std::to_string(fileSize(f.path)), fixed(ms, 2), fixed(ratio, 2)});
        rows.push_back({{"file", f.name},
                        {"encoder_speed", f.speed},
                        {"bytes", fileSize(f.path)},
                        {"ms", number(ms)},
                        {"ratio", number(ratio)}});
    }
    const double decodeMs = median(decodeTimes) * 1e3;
    table.push_back({"(libdraco decode alone, level 6)", std::to_string(level6.size()), fixed(decodeMs, 2),
                     fixed(decodeMs / plainMs, 2)});
    rows.push_back({{"file", "libdraco decode alone, level 6"},
                    {"encoder_speed", -3},
                    {"bytes", level6.size()},
                    {"ms", number(decodeMs)},
                    {"ratio", number(decodeMs / plainMs)}});
    printTable({"file", "bytes", "ms", "ratio"}, table);
    std::printf("\nDraco at level 6 within 3x: %s\n", targetRatio <= 3.0 ? "yes" : "no");

    Json j;
    j["command"] = kLoadCommand;
    j["machine"] = toJson(machine);
    j["grid"] = n;
    j["vertices"] = n * n;
    j["triangles"] = triangles;
    j["runs"] = runs;
    j["clock"] = "wall time";
    j["rows"] = rows;
    j["ratio_level6"] = number(targetRatio);
    j["target_ratio"] = 3;
    if (args.has("--json"))
        if (Status s = writeJson(j, args.value("--json")); !s) {
            std::fprintf(stderr, "spatter-bench load: %s\n", s.error().c_str());
            return 1;
        }
    return 0;
}

} // namespace spatter::bench
