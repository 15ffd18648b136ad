#pragma once
// GltfBuilder: writes small glTF files (.gltf with an embedded or external buffer, or .glb) for the
// tests that load scenes: a document built as JSON plus one binary buffer.

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace spatter::test {

// glTF component types.
constexpr int kByte = 5120, kUnsignedByte = 5121, kUnsignedShort = 5123, kUnsignedInt = 5125, kFloat = 5126;

// Unit quad in the XY plane, counter-clockwise seen from +Z.
inline const std::vector<glm::vec3> kQuad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
inline const std::vector<uint32_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

inline std::string base64(const std::vector<uint8_t>& bytes) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t b0 = bytes[i], b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0,
                       b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
        const uint32_t v = (b0 << 16) | (b1 << 8) | b2;
        out += table[(v >> 18) & 63];
        out += table[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? table[v & 63] : '=';
    }
    return out;
}

inline void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// Builds a glTF document with one binary buffer, then writes it as .gltf or .glb.
struct GltfBuilder {
    nlohmann::json doc = {{"asset", {{"version", "2.0"}}}};
    std::vector<uint8_t> bin;
    size_t declaredBufferLength = 0; // 0: the real length

    // Appends bytes (4-byte aligned) as a new buffer view; returns the view index.
    int addView(const void* data, size_t size, size_t stride = 0) {
        while (bin.size() % 4)
            bin.push_back(0);
        nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}};
        if (stride) view["byteStride"] = stride;
        const auto* bytes = static_cast<const uint8_t*>(data);
        bin.insert(bin.end(), bytes, bytes + size);
        return push("bufferViews", view);
    }
    template <class T> int addView(const std::vector<T>& values, size_t stride = 0) {
        return addView(values.data(), values.size() * sizeof(T), stride);
    }
    int addAccessor(int view, int componentType, size_t count, const char* type, size_t byteOffset = 0) {
        return push("accessors", {{"bufferView", view},
                                  {"componentType", componentType},
                                  {"count", count},
                                  {"type", type},
                                  {"byteOffset", byteOffset}});
    }
    // Adds a mesh of one indexed triangle primitive (float positions, 32-bit indices); returns its index.
    int addMesh(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices) {
        const int p = addAccessor(addView(positions), kFloat, positions.size(), "VEC3");
        const int i = addAccessor(addView(indices), kUnsignedInt, indices.size(), "SCALAR");
        return push("meshes", {{"primitives", {{{"attributes", {{"POSITION", p}}}, {"indices", i}}}}});
    }
    int push(const char* array, const nlohmann::json& value) {
        doc[array].push_back(value);
        return int(doc[array].size()) - 1;
    }

    nlohmann::json buffer(const std::string& uri) const {
        nlohmann::json b = {{"byteLength", declaredBufferLength ? declaredBufferLength : bin.size()}};
        if (!uri.empty()) b["uri"] = uri;
        return b;
    }
    // Writes name.gltf with the buffer embedded as a data URI, or beside it as name.bin.
    std::string writeGltf(const std::string& dir, const std::string& name, bool embedded = true) {
        nlohmann::json d = doc;
        if (!bin.empty()) {
            if (embedded) {
                d["buffers"] = {buffer("data:application/octet-stream;base64," + base64(bin))};
            } else {
                d["buffers"] = {buffer(name + ".bin")};
                writeBytes(dir + "/" + name + ".bin", bin);
            }
        }
        const std::string path = dir + "/" + name + ".gltf";
        std::ofstream(path) << d.dump();
        return path;
    }
    std::vector<uint8_t> glbBytes() const {
        nlohmann::json d = doc;
        d["buffers"] = {buffer("")};
        std::string text = d.dump();
        while (text.size() % 4)
            text += ' ';
        std::vector<uint8_t> chunk = bin;
        while (chunk.size() % 4)
            chunk.push_back(0);
        std::vector<uint8_t> out;
        auto u32 = [&](uint32_t v) {
            for (int i = 0; i < 4; ++i)
                out.push_back(uint8_t(v >> (8 * i)));
        };
        out.insert(out.end(), {'g', 'l', 'T', 'F'});
        u32(2);
        u32(uint32_t(12 + 8 + text.size() + 8 + chunk.size()));
        u32(uint32_t(text.size()));
        u32(0x4E4F534A);
        out.insert(out.end(), text.begin(), text.end());
        u32(uint32_t(chunk.size()));
        u32(0x004E4942);
        out.insert(out.end(), chunk.begin(), chunk.end());
        return out;
    }
};

// A floor (the unit box scaled to 20 x 0.2 x 20, top at y = 0) and a node "crate" (the same box,
// half-extent 0.5) placed by the column-major `crateMatrix`, dynamic or static. `box`: the box's
// positions and indices (MeshBuilder's makeBox(0.5)).
inline GltfBuilder floorAndCrate(const std::vector<glm::vec3>& positions,
                                 const std::vector<uint32_t>& indices, const std::vector<double>& crateMatrix,
                                 bool dynamic) {
    GltfBuilder g;
    g.addMesh(positions, indices);
    g.push("nodes",
           {{"name", "floor"}, {"mesh", 0}, {"scale", {20, 0.2, 20}}, {"translation", {0, -0.1, 0}}});
    g.push("nodes",
           {{"name", "crate"}, {"mesh", 0}, {"matrix", crateMatrix}, {"extras", {{"dynamic", dynamic}}}});
    g.doc["scenes"] = {{{"nodes", {0, 1}}}};
    g.doc["scene"] = 0;
    return g;
}

// Columns [1, 1, 0] and [1, 1 + 1e-9, 0]: invertible in double, singular once rounded to float; the
// crate at (0, 2, 0).
inline const std::vector<double> kColumnsEqualInFloat = {1, 1, 0, 0, 1, 1.000000001, 0, 0,
                                                         0, 0, 1, 0, 0, 2,           0, 1};

} // namespace spatter::test
