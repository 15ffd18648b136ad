#include "GltfDraco.hpp"

#include "GltfAccessor.hpp"
#include "GltfExtension.hpp"

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>

#include <type_traits>

namespace spatter::gltf {

namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";

// The Draco mesh in the extension's buffer view.
Result<std::unique_ptr<draco::Mesh>> decodeMesh(const tinygltf::Model& model, const tinygltf::Value& ext) {
    Result<size_t> view = unsignedField(ext, "bufferView", 2147483647.0);
    if (!view) return fail("its " + std::string(kDraco) + " " + view.error());
    if (view.value() >= model.bufferViews.size())
        return fail("its Draco data refers to buffer view " + num(view.value()) + ", which does not exist");
    const tinygltf::BufferView& v = model.bufferViews[view.value()];
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(model.buffers[size_t(v.buffer)].data.data() + v.byteOffset),
                v.byteLength);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok())
        return fail("its Draco data (buffer view " + num(view.value()) +
                    ") cannot be decoded: " + decoded.status().error_msg_string());
    return std::move(decoded).value();
}

// The draco::DataType that holds a T.
template <class T> constexpr draco::DataType dracoType() {
    if constexpr (std::is_same_v<T, float>) return draco::DT_FLOAT32;
    if constexpr (std::is_same_v<T, int8_t>) return draco::DT_INT8;
    if constexpr (std::is_same_v<T, uint8_t>) return draco::DT_UINT8;
    if constexpr (std::is_same_v<T, int16_t>) return draco::DT_INT16;
    if constexpr (std::is_same_v<T, uint16_t>) return draco::DT_UINT16;
    return draco::DT_UINT32;
}

template <class T>
bool writeValues(const draco::PointAttribute& att, const draco::Mesh& mesh, int components,
                 unsigned char* out) {
    const size_t bytes = sizeof(T) * size_t(components);
    // Values already of this type and width are copied as they are; others converted one by one.
    const bool copy = att.data_type() == dracoType<T>() && att.num_components() == components;
    T value[16];
    for (draco::PointIndex p(0); p < mesh.num_points(); ++p, out += bytes) {
        const draco::AttributeValueIndex i = att.mapped_index(p);
        if (i.value() >= att.size()) return false;
        if (copy) {
            std::memcpy(out, att.GetAddress(i), bytes);
        } else {
            if (!att.ConvertValue<T>(i, int8_t(components), value)) return false;
            std::memcpy(out, value, bytes);
        }
    }
    return true;
}

// The values of `att` for every point of `mesh`, `components` of `componentType` each.
Result<std::vector<unsigned char>> attributeBytes(const draco::PointAttribute& att, const draco::Mesh& mesh,
                                                  int componentType, int components) {
    std::vector<unsigned char> bytes(size_t(mesh.num_points()) * componentSize(componentType) *
                                     size_t(components));
    bool ok = false;
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
        ok = writeValues<int8_t>(att, mesh, components, bytes.data());
        break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        ok = writeValues<uint8_t>(att, mesh, components, bytes.data());
        break;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
        ok = writeValues<int16_t>(att, mesh, components, bytes.data());
        break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        ok = writeValues<uint16_t>(att, mesh, components, bytes.data());
        break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        ok = writeValues<uint32_t>(att, mesh, components, bytes.data());
        break;
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
        ok = writeValues<float>(att, mesh, components, bytes.data());
        break;
    default:
        return fail("has component type " + std::to_string(componentType));
    }
    if (!ok) return fail("has Draco values that its component type cannot hold");
    return bytes;
}

// A copy of accessor `source` over the whole of view `view`, `count` elements, not sparse.
int addAccessor(tinygltf::Model& model, const tinygltf::Accessor& source, int view, size_t count) {
    tinygltf::Accessor a = source;
    a.bufferView = view;
    a.byteOffset = 0;
    a.count = count;
    a.sparse.isSparse = false;
    model.accessors.push_back(a);
    return int(model.accessors.size()) - 1;
}

// Points attribute `name` of `prim` at the decoded values of Draco attribute `id`.
Status replaceAttribute(tinygltf::Model& model, tinygltf::Primitive& prim, const std::string& name,
                        const tinygltf::Value& id, const draco::Mesh& mesh) {
    const auto it = prim.attributes.find(name);
    if (it == prim.attributes.end()) return fail("Draco attribute " + name + " is not an attribute of it");
    if (!validIndex(it->second, model.accessors.size()))
        return fail(name + " refers to accessor " + std::to_string(it->second) + ", which does not exist");
    const tinygltf::Accessor source = model.accessors[size_t(it->second)];
    const int components = componentCount(source.type);
    if (components == 0 || componentSize(source.componentType) == 0)
        return fail("accessor " + std::to_string(it->second) + " (" + name +
                    ") has a type Draco cannot fill");
    const draco::PointAttribute* att =
        id.IsNumber() && id.GetNumberAsDouble() >= 0 && id.GetNumberAsDouble() <= 4294967295.0
            ? mesh.GetAttributeByUniqueId(uint32_t(id.GetNumberAsDouble()))
            : nullptr;
    if (!att) return fail("Draco attribute " + name + " is not in its Draco data");
    // Floats decoded for an integer accessor stay floats: Draco dequantized them already.
    tinygltf::Accessor target = source;
    if (att->data_type() == draco::DT_FLOAT32 || att->data_type() == draco::DT_FLOAT64) {
        target.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
        target.normalized = false;
    }
    Result<std::vector<unsigned char>> bytes = attributeBytes(*att, mesh, target.componentType, components);
    if (!bytes) return fail("accessor " + std::to_string(it->second) + " (" + name + ") " + bytes.error());
    const int view = addDecodedView(model, std::move(bytes.value()));
    it->second = addAccessor(model, target, view, size_t(mesh.num_points()));
    return {};
}

// Points `prim`'s indices at the triangles of `mesh` (32-bit).
void replaceIndices(tinygltf::Model& model, tinygltf::Primitive& prim, const draco::Mesh& mesh) {
    std::vector<unsigned char> bytes(size_t(mesh.num_faces()) * 12);
    unsigned char* out = bytes.data();
    for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
        for (int c = 0; c < 3; ++c, out += 4) {
            const uint32_t index = mesh.face(f)[c].value();
            std::memcpy(out, &index, 4);
        }
    tinygltf::Accessor source;
    if (validIndex(prim.indices, model.accessors.size())) source = model.accessors[size_t(prim.indices)];
    source.type = TINYGLTF_TYPE_SCALAR;
    source.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    source.normalized = false;
    const int view = addDecodedView(model, std::move(bytes));
    prim.indices = addAccessor(model, source, view, size_t(mesh.num_faces()) * 3);
    prim.mode = TINYGLTF_MODE_TRIANGLES;
}

Status decodePrimitive(tinygltf::Model& model, tinygltf::Primitive& prim, const tinygltf::Value& ext) {
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP)
        return fail("has Draco data but mode " + std::to_string(prim.mode) + " (triangles or strips only)");
    Result<std::unique_ptr<draco::Mesh>> mesh = decodeMesh(model, ext);
    if (!mesh) return fail(mesh.error());
    if (!ext.Has("attributes") || !ext.Get("attributes").IsObject())
        return fail("its " + std::string(kDraco) + " lacks \"attributes\"");
    const tinygltf::Value& attributes = ext.Get("attributes");
    for (const std::string& name : attributes.Keys())
        if (Status s = replaceAttribute(model, prim, name, attributes.Get(name), *mesh.value()); !s) return s;
    replaceIndices(model, prim, *mesh.value());
    return {};
}

} // namespace

Status decodeDracoPrimitives(tinygltf::Model& model) {
    for (size_t m = 0; m < model.meshes.size(); ++m)
        for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
            tinygltf::Primitive& prim = model.meshes[m].primitives[p];
            const tinygltf::Value* ext = findExtension(prim.extensions, kDraco);
            if (!ext) continue;
            const tinygltf::Value copy = *ext; // the primitive's extensions are erased below
            prim.extensions.erase(kDraco);
            if (Status s = decodePrimitive(model, prim, copy); !s)
                return fail(named("mesh", m, model.meshes[m].name) + " primitive " + num(p) + ": " +
                            s.error());
        }
    return {};
}

} // namespace spatter::gltf
