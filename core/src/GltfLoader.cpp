// glTF 2.0 loading. tinygltf parses the JSON, reads the buffers and hands over image bytes; every index,
// byte range and value is checked here before it is used, and any problem rejects the whole file.
//
// Conventions of this loader:
// - Objects come from the default scene (`scene`, else scene 0, else every root node), one per node
//   whose mesh has triangles; transforms are composed in double precision.
// - Node extras {"dynamic": true} and {"decals": false} (booleans, or numbers where 0 is false) set the
//   object's flags. Both are inherited by descendants. A node may override an inherited "decals", but
//   not an inherited "dynamic": a child of a moving node moves with it, so {"dynamic": false} under a
//   dynamic ancestor is an error.
// - Nodes named UCX_* or *-col are colliders: their triangles, mapped into the space of the nearest
//   ancestor that became an object, are appended to that object's collider and are not drawn.
// - Every image is decoded to RGBA8 by decodeImage; an image that cannot be read or decoded is an error,
//   unless only an image extension uses it (GltfImages.hpp).
// - Tangents are kept only when every triangle primitive of a mesh has them.

#include "spatter/core/SceneLoader.hpp"

#include "GltfAccessor.hpp"
#include "GltfAnimation.hpp"
#include "GltfDraco.hpp"
#include "GltfExtension.hpp"
#include "GltfFiles.hpp"
#include "GltfImages.hpp"
#include "GltfInstancing.hpp"
#include "GltfJsonTypes.hpp"
#include "GltfMeshopt.hpp"
#include "GltfPrepare.hpp"
#include "GltfRequired.hpp"
#include "GltfTextureTransform.hpp"
#include "RegularFile.hpp"

#include <tiny_gltf.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <optional>

namespace spatter {

namespace {

using namespace gltf;

// Required extensions whose data is read correctly here. KHR_mesh_quantization only allows integer
// component types for vertex attributes, which the accessor reader handles anyway.
const char* const kSupportedRequiredExtensions[] = {"KHR_mesh_quantization",   "KHR_draco_mesh_compression",
                                                    "EXT_meshopt_compression", "EXT_mesh_gpu_instancing",
                                                    "KHR_texture_transform",   "KHR_materials_unlit"};

constexpr uint32_t kGlbJsonChunk = 0x4E4F534A; // "JSON"

// Upper bounds on one scene: the vertices, and the indices, of its meshes (each counted once however
// many objects share it) and of its colliders (each owner keeps its own); and its objects.
constexpr size_t kMaxSceneElements = size_t(1) << 26;
constexpr size_t kMaxSceneObjects = size_t(1) << 20;

// The input a JSON parse error quotes ("last read: '...'", at the end or before "; expected"), cut to
// kQuotedInputChars.
constexpr size_t kQuotedInputChars = 32;
std::string shortenQuotedInput(std::string text) {
    const std::string marker = "last read: '";
    const size_t start = text.find(marker);
    if (start == std::string::npos) return text;
    const size_t from = start + marker.size();
    size_t end = text.find("'; expected", from); // nlohmann's message may go on after the quote
    if (end == std::string::npos) end = text.rfind('\'');
    if (end < from) return text;
    if (end - from > kQuotedInputChars)
        text.replace(from + kQuotedInputChars, end - from - kQuotedInputChars, "...");
    return text;
}

// tinygltf's messages are newline-terminated and may quote whole data URIs or, for a document that is
// not JSON, its bytes: join them into one printable line (other bytes as \xNN), cut each data URI
// after its header and the quoted input to a short excerpt.
std::string tidyParserMessage(const std::string& message) {
    const std::string text = shortenQuotedInput(message);
    std::string out;
    size_t i = 0;
    while (i < text.size()) {
        if (text.compare(i, 5, "data:") == 0) {
            const size_t comma = text.find(',', i);
            const size_t end = text.find_first_of(" \n\"'", i);
            if (comma != std::string::npos && comma < end) {
                out.append(text, i, comma + 1 - i).append("...");
                i = end == std::string::npos ? text.size() : end;
                continue;
            }
        }
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (c == '\n') {
            if (i + 1 < text.size()) out += "; ";
        } else if (c < 0x20 || c >= 0x7f) {
            static const char kHex[] = "0123456789ABCDEF";
            out += "\\x";
            out += kHex[c >> 4];
            out += kHex[c & 15];
        } else {
            out += char(c);
        }
        ++i;
    }
    return out;
}

Status checkBufferViews(const tinygltf::Model& model) {
    for (size_t i = 0; i < model.bufferViews.size(); ++i) {
        const tinygltf::BufferView& view = model.bufferViews[i];
        if (!validIndex(view.buffer, model.buffers.size()))
            return fail("buffer view " + num(i) + " refers to buffer " + std::to_string(view.buffer) +
                        ", which does not exist");
        const size_t bufferSize = model.buffers[size_t(view.buffer)].data.size();
        if (!rangeInside(view.byteOffset, view.byteLength, bufferSize))
            return fail("buffer view " + num(i) + " reads past the end of buffer " +
                        std::to_string(view.buffer) + " (bytes " + num(view.byteOffset) + " + " +
                        num(view.byteLength) + ", the buffer has " + num(bufferSize) + ")");
    }
    return {};
}

// --- meshes -------------------------------------------------------------------------------------

// How many triangle primitives of one glTF mesh there were, and how many of them had each attribute.
struct AttributeCounts {
    size_t primitives = 0, normals = 0, uvs = 0, tangents = 0;
};

// Turns the primitive's vertex order into triangle corners (3 per triangle) for `mode` 4, 5 or 6.
// Strips and fans drop the triangles that repeat a vertex (the usual strip stitching).
Result<std::vector<uint32_t>> triangleCorners(const std::vector<uint32_t>& order, int mode) {
    std::vector<uint32_t> corners;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (order.size() % 3 != 0)
            return fail("has " + num(order.size()) + " triangle list vertices, not a multiple of 3");
        return order;
    }
    for (size_t i = 0; i + 2 < order.size(); ++i) {
        uint32_t a, b, c;
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            a = order[i];
            b = order[i + 1 + i % 2];
            c = order[i + 2 - i % 2];
        } else {
            a = order[i + 1];
            b = order[i + 2];
            c = order[0];
        }
        if (a == b || b == c || a == c) continue;
        corners.insert(corners.end(), {a, b, c});
    }
    return corners;
}

void addWarning(std::vector<std::string>& warnings, const std::string& warning) {
    if (!warning.empty() && std::find(warnings.begin(), warnings.end(), warning) == warnings.end())
        warnings.push_back(warning);
}

// Appends one primitive's triangles to `mesh` as a submesh. Points and lines add nothing.
// Attributes the primitive lacks are filled with zeros and counted in `counts`. The UVs get the
// material's texture transform (GltfTextureTransform.hpp).
Status appendPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& prim, Mesh& mesh,
                       AttributeCounts& counts, std::vector<std::string>& warnings) {
    if (prim.mode >= TINYGLTF_MODE_POINTS && prim.mode <= TINYGLTF_MODE_LINE_STRIP) return {};
    if (prim.mode < TINYGLTF_MODE_TRIANGLES || prim.mode > TINYGLTF_MODE_TRIANGLE_FAN)
        return fail("mode " + std::to_string(prim.mode) + " is not a glTF primitive mode");
    if (prim.material != -1 && !validIndex(prim.material, model.materials.size()))
        return fail("refers to material " + std::to_string(prim.material) + ", which does not exist");
    std::string uvWarning;
    Result<std::optional<glm::dmat3>> uvTransform = materialUvTransform(model, prim.material, uvWarning);
    if (!uvTransform) return fail(uvTransform.error());
    addWarning(warnings, uvWarning);

    const auto posIt = prim.attributes.find("POSITION");
    if (posIt == prim.attributes.end()) return fail("has no POSITION attribute");
    Result<AccessorView> pos =
        viewAccessor(model, posIt->second, "POSITION", TINYGLTF_TYPE_VEC3, kVertexTypes);
    if (!pos) return fail(pos.error());
    const size_t n = pos->count;

    // An optional attribute with as many elements as POSITION, or no view when absent.
    auto optional = [&](const char* name, int type) -> Result<AccessorView> {
        const auto it = prim.attributes.find(name);
        if (it == prim.attributes.end()) return AccessorView{};
        Result<AccessorView> v = viewAccessor(model, it->second, name, type, kVertexTypes);
        if (v && v->count != n)
            return fail("accessor " + std::to_string(it->second) + " (" + name + ") has " + num(v->count) +
                        " elements, POSITION has " + num(n));
        return v;
    };
    Result<AccessorView> normal = optional("NORMAL", TINYGLTF_TYPE_VEC3);
    if (!normal) return fail(normal.error());
    Result<AccessorView> uv = optional("TEXCOORD_0", TINYGLTF_TYPE_VEC2);
    if (!uv) return fail(uv.error());
    Result<AccessorView> tangent = optional("TANGENT", TINYGLTF_TYPE_VEC4);
    if (!tangent) return fail(tangent.error());

    std::vector<uint32_t> order;
    if (prim.indices == -1) {
        if (n > std::numeric_limits<uint32_t>::max())
            return fail("has more vertices than 32-bit indices address");
        order.resize(n);
        for (size_t i = 0; i < n; ++i)
            order[i] = uint32_t(i);
    } else {
        Result<AccessorView> idx =
            viewAccessor(model, prim.indices, "indices", TINYGLTF_TYPE_SCALAR, kIndexTypes);
        if (!idx) return fail(idx.error());
        order.resize(idx->count);
        for (size_t i = 0; i < idx->count; ++i) {
            order[i] = idx->index(i);
            if (order[i] >= n)
                return fail("index " + num(order[i]) + " (element " + num(i) + " of accessor " +
                            std::to_string(prim.indices) + ") is past the vertex count " + num(n));
        }
    }
    Result<std::vector<uint32_t>> corners = triangleCorners(order, prim.mode);
    if (!corners) return fail(corners.error());
    if (corners->empty()) return {};

    const size_t base = mesh.positions.size();
    if (n > std::numeric_limits<uint32_t>::max() - base)
        return fail("the mesh has more vertices than 32-bit indices address");
    if (corners->size() > std::numeric_limits<uint32_t>::max() - mesh.indices.size())
        return fail("the mesh has more indices than a submesh range addresses");
    // Non-finite positions, UVs and tangents are errors; non-finite normals are repaired later.
    auto notFinite = [&](const char* name, size_t i) {
        return fail("accessor " + std::to_string(prim.attributes.at(name)) + " (" + name + ") element " +
                    num(i) + " is not finite (NaN or Inf)");
    };
    for (size_t i = 0; i < n; ++i) {
        mesh.positions.push_back(pos->vec<3>(i));
        if (!finite(mesh.positions.back())) return notFinite("POSITION", i);
        mesh.normals.push_back(normal->present ? normal->vec<3>(i) : glm::vec3(0.0f));
        mesh.uvs.push_back(uv->present ? uv->vec<2>(i) : glm::vec2(0.0f));
        if (!finite(mesh.uvs.back())) return notFinite("TEXCOORD_0", i);
        if (uv->present && uvTransform.value()) {
            transformUvs(*uvTransform.value(), mesh.uvs, mesh.uvs.size() - 1, mesh.uvs.size());
            if (!finite(mesh.uvs.back()))
                return fail("TEXCOORD_0 element " + num(i) + " is not finite after the material's " +
                            "KHR_texture_transform");
        }
        mesh.tangents.push_back(tangent->present ? tangent->vec<4>(i) : glm::vec4(0.0f));
        if (!finite(mesh.tangents.back())) return notFinite("TANGENT", i);
    }

    if (tangent->present && uv->present && uvTransform.value())
        transformTangents(*uvTransform.value(), mesh.normals, mesh.tangents, mesh.tangents.size() - n,
                          mesh.tangents.size());

    Submesh sub;
    sub.firstIndex = uint32_t(mesh.indices.size());
    sub.indexCount = uint32_t(corners->size());
    sub.material = prim.material;
    for (uint32_t c : corners.value())
        mesh.indices.push_back(uint32_t(base) + c);
    mesh.submeshes.push_back(sub);

    ++counts.primitives;
    counts.normals += normal->present ? 1 : 0;
    counts.uvs += uv->present ? 1 : 0;
    counts.tangents += tangent->present ? 1 : 0;
    return {};
}

// Unit xyz and w = +-1; tangents that cannot be normalised are recomputed from the UVs.
void finishTangents(Mesh& mesh) {
    for (glm::vec4& t : mesh.tangents) {
        const float len = glm::length(glm::vec3(t));
        if (!(len > 1e-12f)) {
            computeTangents(mesh);
            return;
        }
        t = glm::vec4(glm::vec3(t) / len, t.w < 0.0f ? -1.0f : 1.0f);
    }
}

// The render mesh of glTF mesh `index`: its triangle primitives as submeshes, with their joint
// influences and morph targets in `deformation`. Normals are computed where the file has none and
// repaired where they are unusable.
Result<Mesh> convertMesh(const tinygltf::Model& model, size_t index, MeshDeformation& deformation,
                         std::vector<std::string>& warnings) {
    const tinygltf::Mesh& source = model.meshes[index];
    Mesh mesh;
    AttributeCounts counts;
    for (size_t p = 0; p < source.primitives.size(); ++p) {
        const size_t base = mesh.vertexCount();
        Status s = appendPrimitive(model, source.primitives[p], mesh, counts, warnings);
        if (s && mesh.vertexCount() > base)
            s = appendDeformation(model, source.primitives[p], base, mesh.vertexCount() - base, deformation);
        if (!s) return fail(named("mesh", index, source.name) + " primitive " + num(p) + ": " + s.error());
    }
    finishDeformation(mesh.vertexCount(), deformation);
    if (counts.normals == 0)
        computeNormals(mesh);
    else
        repairNormals(mesh);
    if (counts.uvs == 0) mesh.uvs.clear();
    if (counts.tangents < counts.primitives || counts.primitives == 0)
        mesh.tangents.clear();
    else
        finishTangents(mesh);
    return mesh;
}

// --- nodes --------------------------------------------------------------------------------------

Result<glm::dmat4> localTransform(const tinygltf::Node& node) {
    // JSON numbers are finite; a composed transform that overflows is caught by validateScene.
    SceneNode trs;
    if (Status s = gltf::readTrs(node, trs); !s) return fail(s.error());
    if (trs.hasMatrix) return trs.matrix;
    return glm::scale(glm::translate(glm::dmat4(1.0), trs.translation) * glm::mat4_cast(trs.rotation),
                      trs.scale);
}

// The parent of every node (-1 for roots), after checking that the children lists form a forest:
// valid indices, no node with two parents, no cycles.
Result<std::vector<int>> nodeParents(const tinygltf::Model& model) {
    const size_t count = model.nodes.size();
    std::vector<int> parent(count, -1);
    for (size_t p = 0; p < count; ++p)
        for (int c : model.nodes[p].children) {
            if (!validIndex(c, count))
                return fail(named("node", p, model.nodes[p].name) + " has child " + std::to_string(c) +
                            ", which does not exist");
            if (size_t(c) == p)
                return fail("the node hierarchy has a cycle: node " + num(p) + " is its own child");
            if (parent[size_t(c)] != -1)
                return fail(named("node", size_t(c), model.nodes[size_t(c)].name) +
                            " has two parents (nodes " + std::to_string(parent[size_t(c)]) + " and " +
                            num(p) + ")");
            parent[size_t(c)] = int(p);
        }
    // With at most one parent each, a cycle shows up as a parent chain that returns to itself.
    enum : char { Unknown, OnWalk, Acyclic };
    std::vector<char> state(count, Unknown);
    std::vector<size_t> walk;
    for (size_t start = 0; start < count; ++start) {
        walk.clear();
        int n = int(start);
        while (n != -1 && state[size_t(n)] == Unknown) {
            state[size_t(n)] = OnWalk;
            walk.push_back(size_t(n));
            n = parent[size_t(n)];
        }
        if (n != -1 && state[size_t(n)] == OnWalk)
            return fail("the node hierarchy has a cycle through " +
                        named("node", size_t(n), model.nodes[size_t(n)].name));
        for (size_t w : walk)
            state[w] = Acyclic;
    }
    return parent;
}

// Root nodes of the default scene: `scene`, else scene 0, else every node without a parent.
Result<std::vector<int>> sceneRoots(const tinygltf::Model& model, const std::vector<int>& parent) {
    std::vector<int> roots;
    if (model.scenes.empty()) {
        for (size_t n = 0; n < parent.size(); ++n)
            if (parent[n] == -1) roots.push_back(int(n));
        return roots;
    }
    const int s = model.defaultScene == -1 ? 0 : model.defaultScene;
    if (!validIndex(s, model.scenes.size()))
        return fail("default scene " + std::to_string(s) + " does not exist");
    std::vector<bool> listed(model.nodes.size(), false);
    for (int n : model.scenes[size_t(s)].nodes) {
        if (!validIndex(n, model.nodes.size()))
            return fail("scene " + std::to_string(s) + " lists node " + std::to_string(n) +
                        ", which does not exist");
        if (parent[size_t(n)] != -1)
            return fail("scene " + std::to_string(s) + " lists node " + std::to_string(n) +
                        " as a root, but it is a child of node " + std::to_string(parent[size_t(n)]));
        if (listed[size_t(n)])
            return fail("scene " + std::to_string(s) + " lists node " + std::to_string(n) + " twice");
        listed[size_t(n)] = true;
        roots.push_back(n);
    }
    return roots;
}

// extras[key] as a flag: absent gives no value; booleans and numbers (0 is false) are accepted.
Result<std::optional<bool>> extrasFlag(const tinygltf::Value& extras, const char* key) {
    if (!extras.IsObject() || !extras.Has(key)) return std::optional<bool>();
    const tinygltf::Value& v = extras.Get(key);
    if (v.IsBool()) return std::optional<bool>(v.Get<bool>());
    if (v.IsNumber()) return std::optional<bool>(v.GetNumberAsDouble() != 0.0);
    return fail(std::string("extras.") + key + " is not a boolean");
}

bool isColliderName(const std::string& name) {
    const std::string suffix = "-col";
    return name.rfind("UCX_", 0) == 0 ||
           (name.size() >= suffix.size() &&
            name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0);
}

// Appends the triangles of `part` to `collider`, mapping positions by `toObject`.
Status appendCollider(std::optional<Mesh>& collider, const Mesh& part, const glm::dmat4& toObject) {
    if (!collider) collider = Mesh{};
    const size_t base = collider->positions.size();
    if (part.positions.size() > std::numeric_limits<uint32_t>::max() - base)
        return fail("the collider has more vertices than 32-bit indices address");
    for (const glm::vec3& p : part.positions) {
        const glm::vec3 q(toObject * glm::dvec4(glm::dvec3(p), 1.0));
        if (!finite(q)) return fail("is not finite in its object's space (singular transform)");
        collider->positions.push_back(q);
    }
    for (uint32_t i : part.indices)
        collider->indices.push_back(uint32_t(base) + i);
    return {};
}

// --- materials and images -----------------------------------------------------------------------

// Image index behind texture `texture` (-1 stays -1, as does a texture without a source image).
Result<int> textureImage(const tinygltf::Model& model, int texture) {
    if (texture == -1) return -1;
    if (!validIndex(texture, model.textures.size()))
        return fail("refers to texture " + std::to_string(texture) + ", which does not exist");
    const int source = model.textures[size_t(texture)].source;
    if (source != -1 && !validIndex(source, model.images.size()))
        return fail("refers to texture " + std::to_string(texture) + ", whose image " +
                    std::to_string(source) + " does not exist");
    return source;
}

Result<Material> convertMaterial(const tinygltf::Model& model, size_t index) {
    const tinygltf::Material& source = model.materials[index];
    const tinygltf::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
    const std::string what = named("material", index, source.name);
    Material m;
    m.name = source.name;
    if (pbr.baseColorFactor.size() != 4)
        return fail(what + " has a base colour factor that is not 4 numbers");
    m.baseColorFactor = glm::vec4(glm::make_vec4(pbr.baseColorFactor.data()));
    m.roughness = float(pbr.roughnessFactor);
    m.metallic = float(pbr.metallicFactor);
    m.normalScale = float(source.normalTexture.scale);
    Result<int> base = textureImage(model, pbr.baseColorTexture.index);
    if (!base) return fail(what + ": base colour texture " + base.error());
    Result<int> normal = textureImage(model, source.normalTexture.index);
    if (!normal) return fail(what + ": normal texture " + normal.error());
    m.baseColorTexture = base.value();
    m.normalTexture = normal.value();
    m.unlit = findExtension(source.extensions, "KHR_materials_unlit") != nullptr;
    return m;
}

// --- parsing ------------------------------------------------------------------------------------

uint32_t le32(const std::vector<unsigned char>& bytes, size_t offset) {
    uint32_t v;
    std::memcpy(&v, bytes.data() + offset, 4);
    return v;
}

// Checks the GLB container (header and chunk lengths) and returns the length it declares.
Result<size_t> checkGlbLayout(const std::vector<unsigned char>& bytes) {
    if (bytes.size() < 12)
        return fail("truncated GLB: " + num(bytes.size()) + " bytes, less than its header");
    const uint32_t version = le32(bytes, 4), length = le32(bytes, 8);
    if (version != 2) return fail("GLB version " + num(version) + " is not supported (only 2)");
    if (length > bytes.size())
        return fail("truncated GLB: the header declares " + num(length) + " bytes, the file has " +
                    num(bytes.size()));
    if (length < 20) return fail("truncated GLB: no JSON chunk");
    const uint32_t jsonLength = le32(bytes, 12);
    if (le32(bytes, 16) != kGlbJsonChunk) return fail("the first GLB chunk is not JSON");
    if (uint64_t(jsonLength) + 20 > length)
        return fail("truncated GLB: the JSON chunk of " + num(jsonLength) +
                    " bytes ends past the end of the data");
    const size_t next = 20 + size_t(jsonLength);
    if (next < length) {
        if (length - next < 8) return fail("truncated GLB: incomplete chunk header after the JSON chunk");
        const uint32_t binLength = le32(bytes, next);
        if (uint64_t(binLength) + next + 8 > length)
            return fail("truncated GLB: the binary chunk of " + num(binLength) +
                        " bytes ends past the end of the data");
    }
    return size_t(length);
}

// The GLB `bytes` (`length` of them, checked by checkGlbLayout) with its JSON chunk replaced by `json`.
std::vector<unsigned char> replaceGlbJson(const std::vector<unsigned char>& bytes, size_t length,
                                          std::string json) {
    while (json.size() % 4 != 0)
        json += ' ';
    const size_t rest = 20 + size_t(le32(bytes, 12)); // the chunks after the JSON chunk
    std::vector<unsigned char> out(20 + json.size() + (length - rest));
    std::memcpy(out.data(), bytes.data(), 20);
    std::memcpy(out.data() + 20, json.data(), json.size());
    if (length > rest) std::memcpy(out.data() + 20 + json.size(), bytes.data() + rest, length - rest);
    const uint32_t total = uint32_t(out.size()), jsonLength = uint32_t(json.size());
    std::memcpy(out.data() + 8, &total, 4);
    std::memcpy(out.data() + 12, &jsonLength, 4);
    return out;
}

// The bytes of `path` as tinygltf should see them (GltfPrepare.hpp). `length` is the length to parse.
Status prepareDocument(std::vector<unsigned char>& bytes, bool binary, size_t& length) {
    const char* json = reinterpret_cast<const char*>(bytes.data()) + (binary ? 20 : 0);
    const size_t jsonLength = binary ? size_t(le32(bytes, 12)) : length;
    std::optional<std::string> rewritten = prepareJson(json, jsonLength);
    if (!rewritten) return {};
    if (binary) {
        bytes = replaceGlbJson(bytes, length, std::move(rewritten.value()));
    } else {
        bytes.assign(rewritten->begin(), rewritten->end());
    }
    length = bytes.size();
    if (length > std::numeric_limits<uint32_t>::max()) return fail("file is larger than 4 GiB");
    return {};
}

Result<std::vector<unsigned char>> readFile(const std::string& path) {
    if (std::string problem = detail::regularFileProblem(path); !problem.empty()) return fail(problem);
    std::ifstream in(path, std::ios::binary);
    if (!in) return fail("cannot open file");
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) return fail("read error");
    return bytes;
}

// Parses .gltf (JSON, detected by content) or .glb (binary) with tinygltf, images decoded to RGBA8.
Status parseModel(const std::string& path, tinygltf::Model& model, ImageDecoding& images) {
    Result<std::vector<unsigned char>> bytes = readFile(path);
    if (!bytes) return fail(bytes.error());
    if (bytes->empty()) return fail("file is empty");
    if (bytes->size() > std::numeric_limits<uint32_t>::max()) return fail("file is larger than 4 GiB");
    const bool binary = bytes->size() >= 4 && std::memcmp(bytes->data(), "glTF", 4) == 0;
    size_t length = bytes->size();
    if (binary) {
        Result<size_t> declared = checkGlbLayout(bytes.value());
        if (!declared) return fail(declared.error());
        length = declared.value();
    }
    const char* json = reinterpret_cast<const char*>(bytes->data()) + (binary ? 20 : 0);
    if (Status s = checkPropertyTypes(json, binary ? size_t(le32(bytes.value(), 12)) : length); !s) return s;
    if (Status s = prepareDocument(bytes.value(), binary, length); !s) return s;

    tinygltf::TinyGLTF parser;
    images.model = &model;
    parser.SetImageLoader(&decodeGltfImage, &images);
    tinygltf::FsCallbacks files = regularFileCallbacks();
    parser.SetFsCallbacks(files);
    const std::string baseDir = std::filesystem::path(path).parent_path().string();
    std::string err, warn;
    bool parsed = false;
    try {
        parsed = binary ? parser.LoadBinaryFromMemory(&model, &err, &warn, bytes->data(), unsigned(length),
                                                      baseDir)
                        : parser.LoadASCIIFromString(&model, &err, &warn,
                                                     reinterpret_cast<const char*>(bytes->data()),
                                                     unsigned(length), baseDir);
    } catch (const std::exception& e) {
        return fail("not valid glTF: " + tidyParserMessage(e.what()));
    }
    if (!parsed) {
        std::string why = tidyParserMessage(err.empty() ? warn : err);
        if (!binary && err.find("'uri' is missing") != std::string::npos)
            if (std::string m = bufferWithoutUri(reinterpret_cast<const char*>(bytes->data()), length);
                !m.empty())
                why = m;
        if (why.empty()) // tinygltf refuses some documents that lack a required property in silence
            why = binary ? missingRequiredProperty(reinterpret_cast<const char*>(bytes->data()) + 20,
                                                   le32(bytes.value(), 12))
                         : missingRequiredProperty(reinterpret_cast<const char*>(bytes->data()), length);
        return fail("not valid glTF: " + (why.empty() ? std::string("the parser gave no reason") : why));
    }
    restoreMovedIndices(model);
    explainUnreadImageFiles(model, baseDir, images.errors);
    return {};
}

// --- scene --------------------------------------------------------------------------------------

Status checkRequiredExtensions(const tinygltf::Model& model) {
    for (const std::string& ext : model.extensionsRequired)
        if (std::find(std::begin(kSupportedRequiredExtensions), std::end(kSupportedRequiredExtensions),
                      ext) == std::end(kSupportedRequiredExtensions))
            return fail("requires extension " + ext + ", which is not supported");
    return {};
}

// A node with a mesh, found while walking the hierarchy; objects are made only once the whole
// scene's size is known.
struct Placement {
    size_t node;
    size_t mesh;
    glm::dmat4 world;
    bool dynamic;
    bool decals;
    int owner;         // for a collider, the drawn placement it joins; -1 for drawn ones
    int instance = -1; // EXT_mesh_gpu_instancing: which instance of the node; -1 for none
};

// Walks the default scene's hierarchy and makes the objects and colliders.
Status addObjects(const tinygltf::Model& model, Scene& scene) {
    Result<std::vector<int>> parent = nodeParents(model);
    if (!parent) return fail(parent.error());
    Result<std::vector<int>> roots = sceneRoots(model, parent.value());
    if (!roots) return fail(roots.error());

    std::vector<std::shared_ptr<const Mesh>> meshes(model.meshes.size()); // converted on first use
    std::vector<MeshDeformation> deformations(model.meshes.size());
    std::vector<Placement> drawn, colliders;
    struct Visit {
        int node;
        glm::dmat4 parentWorld;
        bool dynamic;
        bool decals;
        int drawnAncestor; // nearest ancestor in `drawn`, -1 for none
    };
    std::vector<Visit> stack;
    for (auto r = roots->rbegin(); r != roots->rend(); ++r)
        stack.push_back({*r, glm::dmat4(1.0), false, true, -1});
    while (!stack.empty()) {
        const Visit visit = stack.back();
        stack.pop_back();
        const size_t index = size_t(visit.node);
        const tinygltf::Node& node = model.nodes[index];
        const std::string what = named("node", index, node.name);

        Result<glm::dmat4> local = localTransform(node);
        if (!local) return fail(what + " " + local.error());
        const glm::dmat4 world = visit.parentWorld * local.value();
        Result<std::optional<bool>> dynamicFlag = extrasFlag(node.extras, "dynamic");
        if (!dynamicFlag) return fail(what + ": " + dynamicFlag.error());
        Result<std::optional<bool>> decalsFlag = extrasFlag(node.extras, "decals");
        if (!decalsFlag) return fail(what + ": " + decalsFlag.error());
        if (visit.dynamic && dynamicFlag.value() == false)
            return fail(what + " has \"dynamic\": false under a dynamic ancestor, which moves it");
        const bool dynamic = visit.dynamic || dynamicFlag.value().value_or(false);
        const bool decals = decalsFlag.value().value_or(visit.decals);

        if (node.skin != -1 && !validIndex(node.skin, model.skins.size()))
            return fail(what + " refers to skin " + std::to_string(node.skin) + ", which does not exist");
        int drawnAncestor = visit.drawnAncestor;
        if (node.mesh != -1) {
            if (!validIndex(node.mesh, model.meshes.size()))
                return fail(what + " refers to mesh " + std::to_string(node.mesh) + ", which does not exist");
            const size_t m = size_t(node.mesh);
            if (!meshes[m]) {
                Result<Mesh> converted = convertMesh(model, m, deformations[m], scene.warnings);
                if (!converted) return fail(converted.error());
                meshes[m] = shareMesh(std::move(converted.value()));
            }
            if (isColliderName(node.name)) {
                if (visit.drawnAncestor == -1)
                    return fail("collider " + what + " has no ancestor node with a drawn mesh to attach to");
                colliders.push_back({index, m, world, dynamic, decals, visit.drawnAncestor});
            } else if (meshes[m]->triangleCount() > 0) {
                Result<std::optional<std::vector<glm::dmat4>>> instances = instanceTransforms(model, node);
                if (!instances) return fail(what + " " + instances.error());
                drawnAncestor = int(drawn.size()); // colliders below an instanced node join instance 0
                if (!instances.value()) drawn.push_back({index, m, world, dynamic, decals, -1});
                for (size_t i = 0; instances.value() && i < instances.value()->size(); ++i)
                    drawn.push_back({index, m, world * (*instances.value())[i], dynamic, decals, -1, int(i)});
                if (drawnAncestor == int(drawn.size())) drawnAncestor = visit.drawnAncestor;
                if (drawn.size() > kMaxSceneObjects)
                    return fail("the default scene places more than " + num(kMaxSceneObjects) +
                                " objects (the limit)");
            }
        }
        for (auto c = node.children.rbegin(); c != node.children.rend(); ++c)
            stack.push_back({*c, world, dynamic, decals, drawnAncestor});
    }
    if (drawn.empty()) return fail("the default scene has no triangle meshes");

    // Instancing lets a small file describe a huge scene: bound what it keeps before making any object.
    size_t vertices = 0, indices = 0;
    auto add = [&](size_t mesh) {
        vertices += meshes[mesh]->vertexCount();
        indices += meshes[mesh]->indices.size();
    };
    std::vector<bool> counted(meshes.size(), false); // a drawn mesh once, however many objects share it
    for (const Placement& p : drawn)
        if (!counted[p.mesh]) {
            counted[p.mesh] = true;
            add(p.mesh);
        }
    for (const Placement& p : colliders)
        add(p.mesh); // each owner keeps its own copy of a collider
    if (vertices > kMaxSceneElements || indices > kMaxSceneElements)
        return fail("the default scene has " + num(vertices) + " vertices and " + num(indices) +
                    " indices in its meshes and colliders, more than the limit of " + num(kMaxSceneElements));

    for (const Placement& p : drawn) {
        SceneObject o;
        const tinygltf::Node& node = model.nodes[p.node];
        const std::string& meshName = model.meshes[p.mesh].name;
        o.name = !node.name.empty() ? node.name : !meshName.empty() ? meshName : "node" + num(p.node);
        if (p.instance >= 0) o.name += "#" + std::to_string(p.instance);
        o.mesh = meshes[p.mesh]; // shared by every node and instance that places it
        o.transform = p.world;
        o.dynamic = p.dynamic;
        o.receivesDecals = p.decals;
        o.node = p.instance >= 0 ? -1 : int(p.node);
        scene.objects.push_back(std::move(o));
    }
    for (const Placement& p : colliders) {
        SceneObject& owner = scene.objects[size_t(p.owner)];
        // An owner scaled by 0 has no object space to put a collider in; it is not traced either.
        const glm::dmat4 toOwner = glm::inverse(owner.transform) * p.world;
        if (!transformProblem(toOwner).empty()) continue;
        if (Status s = appendCollider(owner.collider, *meshes[p.mesh], toOwner); !s)
            return fail("collider " + named("node", p.node, model.nodes[p.node].name) + " " + s.error());
    }
    for (SceneObject& o : scene.objects)
        if (o.collider) computeNormals(*o.collider);
    return addAnimation(model, deformations, scene);
}

Result<Scene> buildScene(tinygltf::Model& model, const std::map<int, std::string>& decodeErrors) {
    if (Status s = checkRequiredExtensions(model); !s) return fail(s.error());
    if (Status s = decodeMeshoptViews(model); !s) return fail(s.error());
    if (Status s = checkBufferViews(model); !s) return fail(s.error());
    if (Status s = decodeDracoPrimitives(model); !s) return fail(s.error());

    Scene scene;
    scene.extensionsUsed = model.extensionsUsed;
    scene.extensionsRequired = model.extensionsRequired;
    for (size_t i = 0; i < model.images.size(); ++i) {
        Result<Image> image = convertImage(model, i, decodeErrors, scene.warnings);
        if (!image) return fail(image.error());
        scene.images.push_back(std::move(image.value()));
    }
    for (size_t i = 0; i < model.materials.size(); ++i) {
        Result<Material> m = convertMaterial(model, i);
        if (!m) return fail(m.error());
        scene.materials.push_back(std::move(m.value()));
    }
    if (Status s = addObjects(model, scene); !s) return fail(s.error());
    if (Status s = validateScene(scene); !s) return fail(s.error());
    return scene;
}

} // namespace

Result<Scene> loadGltf(const std::string& path) {
    tinygltf::Model model;
    ImageDecoding images;
    if (Status s = parseModel(path, model, images); !s) return fail(path + ": " + s.error());
    Result<Scene> scene = buildScene(model, images.errors);
    if (!scene) return fail(path + ": " + scene.error());
    scene->source = path;
    return scene;
}

} // namespace spatter
