#include "GltfMeshopt.hpp"

#include "GltfAccessor.hpp"
#include "GltfExtension.hpp"

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

namespace spatter::gltf {

namespace {

constexpr const char* kMeshopt = "EXT_meshopt_compression";

// What one view's extension says, checked.
struct MeshoptView {
    size_t buffer = 0, byteOffset = 0, byteLength = 0, byteStride = 0, count = 0;
    std::string mode, filter;
};

Result<MeshoptView> readMeshoptView(const tinygltf::Model& model, const tinygltf::Value& ext) {
    MeshoptView v;
    const double kMax = 4294967295.0;
    struct Field {
        const char* key;
        size_t* out;
        long long fallback;
    };
    for (const Field& f : {Field{"buffer", &v.buffer, -1}, Field{"byteOffset", &v.byteOffset, 0},
                           Field{"byteLength", &v.byteLength, -1}, Field{"byteStride", &v.byteStride, -1},
                           Field{"count", &v.count, -1}}) {
        Result<size_t> value = unsignedField(ext, f.key, kMax, f.fallback);
        if (!value) return fail("its " + std::string(kMeshopt) + " " + value.error());
        *f.out = value.value();
    }
    v.mode = stringField(ext, "mode", "");
    v.filter = stringField(ext, "filter", "NONE");
    if (v.buffer >= model.buffers.size())
        return fail("its compressed data refers to buffer " + num(v.buffer) + ", which does not exist");
    const size_t size = model.buffers[v.buffer].data.size();
    if (!rangeInside(v.byteOffset, v.byteLength, size))
        return fail("its compressed data reads past the end of buffer " + num(v.buffer) + " (bytes " +
                    num(v.byteOffset) + " + " + num(v.byteLength) + ", the buffer has " + num(size) + ")");
    return v;
}

// The stride and count rules of each mode and filter.
Status checkLayout(const MeshoptView& v) {
    const size_t s = v.byteStride;
    if (v.mode == "ATTRIBUTES") {
        if (s == 0 || s > 256 || s % 4 != 0)
            return fail("its byte stride " + num(s) +
                        " does not suit ATTRIBUTES (a multiple of 4 up to 256)");
    } else if (v.mode == "TRIANGLES" || v.mode == "INDICES") {
        if (s != 2 && s != 4)
            return fail("its byte stride " + num(s) + " does not suit " + v.mode + " (2 or 4)");
        if (v.mode == "TRIANGLES" && v.count % 3 != 0)
            return fail("its " + num(v.count) + " TRIANGLES indices are not a multiple of 3");
    } else {
        return fail("its mode \"" + v.mode + "\" is not ATTRIBUTES, TRIANGLES or INDICES");
    }
    if (v.filter == "NONE") return {};
    if (v.mode != "ATTRIBUTES") return fail("its filter " + v.filter + " does not suit " + v.mode);
    if (v.filter == "OCTAHEDRAL" && s != 4 && s != 8)
        return fail("its byte stride " + num(s) + " does not suit OCTAHEDRAL (4 or 8)");
    if (v.filter == "QUATERNION" && s != 8)
        return fail("its byte stride " + num(s) + " does not suit QUATERNION (8)");
    if (v.filter != "OCTAHEDRAL" && v.filter != "QUATERNION" && v.filter != "EXPONENTIAL")
        return fail("its filter \"" + v.filter + "\" is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
    return {};
}

Result<std::vector<unsigned char>> decode(const tinygltf::Model& model, const MeshoptView& v) {
    size_t size = 0;
    if (!mulAdd(v.count, v.byteStride, 0, size) || size / kMaxMeshoptRatio > v.byteLength + 1024)
        return fail("its compressed data claims " + num(v.count) + " elements of " + num(v.byteStride) +
                    " bytes from " + num(v.byteLength) + " compressed bytes, more than the codecs can hold");
    std::vector<unsigned char> out(size);
    const unsigned char* src = model.buffers[v.buffer].data.data() + v.byteOffset;
    int rc = 0;
    if (v.mode == "ATTRIBUTES")
        rc = meshopt_decodeVertexBuffer(out.data(), v.count, v.byteStride, src, v.byteLength);
    else if (v.mode == "TRIANGLES")
        rc = meshopt_decodeIndexBuffer(out.data(), v.count, v.byteStride, src, v.byteLength);
    else
        rc = meshopt_decodeIndexSequence(out.data(), v.count, v.byteStride, src, v.byteLength);
    if (rc != 0)
        return fail("its " + v.mode + " data does not decode (meshoptimizer error " + std::to_string(rc) +
                    ")");
    if (v.filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out.data(), v.count, v.byteStride);
    if (v.filter == "QUATERNION") meshopt_decodeFilterQuat(out.data(), v.count, v.byteStride);
    if (v.filter == "EXPONENTIAL") meshopt_decodeFilterExp(out.data(), v.count, v.byteStride);
    return out;
}

Status decodeView(tinygltf::Model& model, size_t index, const tinygltf::Value& ext) {
    Result<MeshoptView> v = readMeshoptView(model, ext);
    if (!v) return fail(v.error());
    if (Status s = checkLayout(v.value()); !s) return s;
    Result<std::vector<unsigned char>> bytes = decode(model, v.value());
    if (!bytes) return fail(bytes.error());
    tinygltf::BufferView& view = model.bufferViews[index];
    if (view.byteLength > bytes->size())
        return fail("it declares " + num(view.byteLength) + " bytes, and its compressed data decodes to " +
                    num(bytes->size()));
    view.buffer = int(model.buffers.size());
    view.byteOffset = 0;
    model.buffers.emplace_back();
    model.buffers.back().data = std::move(bytes.value());
    return {};
}

} // namespace

bool addMeshoptPlaceholders(nlohmann::json& doc) {
    if (!doc.is_object() || !doc.contains("buffers") || !doc["buffers"].is_array()) return false;
    bool changed = false;
    for (nlohmann::json& buffer : doc["buffers"]) {
        if (!buffer.is_object()) continue;
        const auto exts = buffer.find("extensions");
        if (exts == buffer.end() || !exts->is_object()) continue;
        const auto ext = exts->find(kMeshopt);
        if (ext == exts->end() || !ext->is_object()) continue;
        const auto fallback = ext->find("fallback");
        if (fallback == ext->end() || *fallback != true) continue;
        buffer["uri"] = "data:application/octet-stream;base64,AA==";
        buffer["byteLength"] = 1;
        changed = true;
    }
    return changed;
}

Status decodeMeshoptViews(tinygltf::Model& model) {
    const size_t views = model.bufferViews.size();
    for (size_t i = 0; i < views; ++i) {
        const tinygltf::Value* ext = findExtension(model.bufferViews[i].extensions, kMeshopt);
        if (!ext) continue;
        const tinygltf::Value copy = *ext;
        model.bufferViews[i].extensions.erase(kMeshopt);
        if (Status s = decodeView(model, i, copy); !s)
            return fail("buffer view " + num(i) + ": " + s.error());
    }
    return {};
}

} // namespace spatter::gltf
