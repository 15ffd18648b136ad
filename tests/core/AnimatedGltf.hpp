#pragma once
// Small animated glTF documents for the animation tests: a quad moved by node channels, a strip
// skinned to two joints, and a quad with two morph targets. Each is valid as built; tests change one
// thing at a time.

#include "GltfBuilder.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <string>
#include <vector>

namespace spatter::test {

// Unit quad in the XY plane, counter-clockwise seen from +Z.
inline const std::vector<glm::vec3> kAnimQuad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
inline const std::vector<uint32_t> kAnimQuadIndices = {0, 1, 2, 0, 2, 3};

// Adds a float accessor of `values` (count = values.size() / components of `type`).
inline int addFloats(GltfBuilder& g, const std::vector<float>& values, const char* type) {
    const size_t width = std::string(type) == "SCALAR" ? 1
                         : std::string(type) == "VEC3" ? 3
                         : std::string(type) == "VEC4" ? 4
                                                       : 16;
    return g.addAccessor(g.addView(values), kFloat, values.size() / width, type);
}

// Adds animation 0 if needed and a channel on `node`'s `path` with its own sampler; returns the
// channel's index.
inline int addChannel(GltfBuilder& g, int node, const char* path, const std::vector<float>& times,
                      const std::vector<float>& values, const char* type,
                      const char* interpolation = "LINEAR") {
    const int input = addFloats(g, times, "SCALAR");
    const int output = addFloats(g, values, type);
    if (!g.doc.contains("animations"))
        g.push(
            "animations",
            {{"name", "move"}, {"channels", nlohmann::json::array()}, {"samplers", nlohmann::json::array()}});
    nlohmann::json& anim = g.doc["animations"][0];
    anim["samplers"].push_back({{"input", input}, {"output", output}, {"interpolation", interpolation}});
    anim["channels"].push_back(
        {{"sampler", anim["samplers"].size() - 1}, {"target", {{"node", node}, {"path", path}}}});
    return int(anim["channels"].size()) - 1;
}

// Node 0 "quad" (mesh 0) under node 1 "base" (no mesh), plus node 2 "still" (mesh 0) beside them;
// node 0's translation animated LINEAR over keys 0, 1, 2 s.
inline GltfBuilder animatedQuad() {
    GltfBuilder g;
    g.addMesh(kAnimQuad, kAnimQuadIndices);
    g.push("nodes", {{"name", "quad"}, {"mesh", 0}, {"translation", {0, 0, 0}}});
    g.push("nodes", {{"name", "base"}, {"children", {0}}, {"translation", {0, 0, 5}}});
    g.push("nodes", {{"name", "still"}, {"mesh", 0}, {"translation", {3, 0, 0}}});
    g.doc["scenes"] = {{{"nodes", {1, 2}}}};
    g.doc["scene"] = 0;
    addChannel(g, 0, "translation", {0, 1, 2}, {0, 0, 0, 1, 2, 3, 4, 4, 4}, "VEC3");
    return g;
}

// A strip of 3 x 2 vertices along +X skinned to joints "root" (node 1, at the origin) and "tip"
// (node 2, child of root at x = 1). Set 0 holds unsigned-byte joints with normalised unsigned-byte
// weights, set 1 unsigned-short joints with normalised unsigned-short weights, set 2 unsigned-byte
// joints with float weights; the weights of vertices 3 and 4 do not sum to 1 (the loader normalises
// them). "tip" is rotated about +Z by a LINEAR channel and "root" moved up by another.
inline GltfBuilder skinnedStrip() {
    GltfBuilder g;
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0},
                                              {0, 1, 0}, {1, 1, 0}, {2, 1, 0}};
    const std::vector<uint32_t> indices = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
    g.addMesh(positions, indices);
    const std::vector<uint8_t> joints0 = {0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0,
                                          0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0};
    const std::vector<uint8_t> weights0 = {255, 0, 0, 0, 100, 100, 0, 0, 255, 0, 0, 0,
                                           200, 0, 0, 0, 60,  180, 0, 0, 128, 0, 0, 0};
    const std::vector<uint16_t> joints1 = {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                                           1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    const std::vector<uint16_t> weights1 = {0,     0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                                            16384, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    const std::vector<uint8_t> joints2 = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                                          0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0};
    const std::vector<float> weights2 = {0, 0, 0, 0, 0,    0, 0, 0, 0, 0, 0, 0,
                                         0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0, 0, 0};
    const int j0 = g.addAccessor(g.addView(joints0), kUnsignedByte, 6, "VEC4");
    const int w0 = g.addAccessor(g.addView(weights0), kUnsignedByte, 6, "VEC4");
    g.doc["accessors"][w0]["normalized"] = true;
    const int j1 = g.addAccessor(g.addView(joints1), kUnsignedShort, 6, "VEC4");
    const int w1 = g.addAccessor(g.addView(weights1), kUnsignedShort, 6, "VEC4");
    g.doc["accessors"][w1]["normalized"] = true;
    const int j2 = g.addAccessor(g.addView(joints2), kUnsignedByte, 6, "VEC4");
    const int w2 = addFloats(g, weights2, "VEC4");
    g.doc["meshes"][0]["primitives"][0]["attributes"].update({{"JOINTS_0", j0},
                                                              {"WEIGHTS_0", w0},
                                                              {"JOINTS_1", j1},
                                                              {"WEIGHTS_1", w1},
                                                              {"JOINTS_2", j2},
                                                              {"WEIGHTS_2", w2}});
    // Inverse bind matrices: root at the origin, tip at x = 1.
    std::vector<float> ibm(32, 0.0f);
    for (int i = 0; i < 4; ++i)
        ibm[size_t(i * 5)] = ibm[size_t(16 + i * 5)] = 1.0f;
    ibm[16 + 12] = -1.0f;
    const int inverseBind = addFloats(g, ibm, "MAT4");
    g.push("nodes", {{"name", "strip"}, {"mesh", 0}, {"skin", 0}, {"translation", {0, 0, 0}}});
    g.push("nodes", {{"name", "root"}, {"children", {2}}});
    g.push("nodes", {{"name", "tip"}, {"translation", {1, 0, 0}}});
    g.push("skins", {{"joints", {1, 2}}, {"inverseBindMatrices", inverseBind}});
    g.doc["scenes"] = {{{"nodes", {0, 1}}}};
    g.doc["scene"] = 0;
    const float s = float(std::sqrt(0.5));
    addChannel(g, 2, "rotation", {0, 1}, {0, 0, 0, 1, 0, 0, s, s}, "VEC4");
    addChannel(g, 1, "translation", {0, 2}, {0, 0, 0, 0, 2, 0}, "VEC3");
    return g;
}

// The quad with two morph targets (POSITION and NORMAL deltas), mesh weights [0.5, 0], and a
// CUBICSPLINE weights channel over keys 0 and 2 s.
inline GltfBuilder morphQuad() {
    GltfBuilder g;
    g.addMesh(kAnimQuad, kAnimQuadIndices);
    const int up = addFloats(g, {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    const int side = addFloats(g, {0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0}, "VEC3");
    const int tilt = addFloats(g, {0.1f, 0, 0, 0.1f, 0, 0, 0.1f, 0, 0, 0.1f, 0, 0}, "VEC3");
    g.doc["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", up}, {"NORMAL", tilt}},
                                                      {{"POSITION", side}}};
    g.doc["meshes"][0]["weights"] = {0.5, 0};
    g.push("nodes", {{"name", "morph"}, {"mesh", 0}});
    g.doc["scenes"] = {{{"nodes", {0}}}};
    g.doc["scene"] = 0;
    // Per key: in-tangent (2 weights), value (2), out-tangent (2).
    addChannel(g, 0, "weights", {0, 2}, {0, 0, 0, 0, 1, -1, 0.5f, 0.5f, 1, 0.25f, 0, 0}, "SCALAR",
               "CUBICSPLINE");
    return g;
}

// Makes morph target `target`'s `attribute` of morphQuad() a sparse accessor that moves vertices 1
// and 2 by (0, 0, 2) and (0, 3, 0) (unsigned-byte indices), over zeros when `bufferless`, else over
// the dense deltas it had. Returns the accessor's index.
inline int makeSparse(GltfBuilder& g, int target, const char* attribute, bool bufferless) {
    nlohmann::json& targets = g.doc["meshes"][0]["primitives"][0]["targets"];
    const int index = targets[target][attribute];
    nlohmann::json a = g.doc["accessors"][index];
    if (bufferless) a.erase("bufferView");
    const std::vector<uint8_t> indices = {1, 2, 0, 0};
    const std::vector<float> values = {0, 0, 2, 0, 3, 0};
    a["sparse"] = {{"count", 2},
                   {"indices", {{"bufferView", g.addView(indices)}, {"componentType", kUnsignedByte}}},
                   {"values", {{"bufferView", g.addView(values)}}}};
    const int sparse = g.push("accessors", a);
    targets[target][attribute] = sparse;
    return sparse;
}

// Writes `g` as `name`.glb in `dir`; returns the path.
inline std::string writeGlb(const GltfBuilder& g, const std::string& dir, const std::string& name) {
    const std::string path = dir + "/" + name + ".glb";
    writeBytes(path, g.glbBytes());
    return path;
}

} // namespace spatter::test
