#include "GltfDraco.hpp"

#include "GltfAccessor.hpp"
#include "GltfExtension.hpp"

#include <draco/attributes/attribute_octahedron_transform.h>
#include <draco/attributes/attribute_quantization_transform.h>
#include <draco/compression/attributes/normal_compression_utils.h>
#include <draco/compression/decode.h>
#include <draco/core/quantization_utils.h>
#include <draco/mesh/mesh.h>

#include <algorithm>
#include <iterator>
#include <type_traits>

namespace spatter::gltf {

namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";

// The attribute types whose quantisation libdraco is told to leave undone: dequantising them while
// gathering them for the accessors (dequantisedBytes) saves libdraco a pass over them and a float
// copy of each.
constexpr draco::GeometryAttribute::Type kKeptQuantised[] = {draco::GeometryAttribute::POSITION,
                                                             draco::GeometryAttribute::NORMAL,
                                                             draco::GeometryAttribute::TEX_COORD};

// Whether `att` holds the quantised values of a float attribute, its transform skipped.
bool keptQuantised(const draco::PointAttribute& att) {
    const draco::AttributeTransformData* t = att.GetAttributeTransformData();
    return t && (t->transform_type() == draco::ATTRIBUTE_QUANTIZATION_TRANSFORM ||
                 t->transform_type() == draco::ATTRIBUTE_OCTAHEDRON_TRANSFORM);
}

// Whether libdraco, skipping the transforms of kKeptQuantised, replaced an integer attribute of those
// types by its int32 copy, which loses the attribute's type and normalisation.
bool lostIntegerType(const draco::Mesh& mesh) {
    for (int32_t a = 0; a < mesh.num_attributes(); ++a) {
        const draco::PointAttribute& att = *mesh.attribute(a);
        const bool skipped = std::find(std::begin(kKeptQuantised), std::end(kKeptQuantised),
                                       att.attribute_type()) != std::end(kKeptQuantised);
        if (skipped && !keptQuantised(att) && att.data_type() != draco::DT_FLOAT32 &&
            att.data_type() != draco::DT_FLOAT64)
            return true;
    }
    return false;
}

// The Draco mesh in buffer view `view`, quantised attributes of kKeptQuantised types left quantised
// when asked.
Result<std::unique_ptr<draco::Mesh>> decodeView(const tinygltf::Model& model, size_t view,
                                                bool keepQuantised) {
    const tinygltf::BufferView& v = model.bufferViews[view];
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(model.buffers[size_t(v.buffer)].data.data() + v.byteOffset),
                v.byteLength);
    draco::Decoder decoder;
    if (keepQuantised)
        for (draco::GeometryAttribute::Type type : kKeptQuantised)
            decoder.SetSkipAttributeTransform(type);
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok())
        return fail("its Draco data (buffer view " + num(view) +
                    ") cannot be decoded: " + decoded.status().error_msg_string());
    return std::move(decoded).value();
}

// The Draco mesh in the extension's buffer view, its quantised attributes of kKeptQuantised types left
// quantised. A mesh whose integer attributes lost their type that way is decoded again whole.
Result<std::unique_ptr<draco::Mesh>> decodeMesh(const tinygltf::Model& model, const tinygltf::Value& ext) {
    Result<size_t> view = unsignedField(ext, "bufferView", 2147483647.0);
    if (!view) return fail("its " + std::string(kDraco) + " " + view.error());
    if (view.value() >= model.bufferViews.size())
        return fail("its Draco data refers to buffer view " + num(view.value()) + ", which does not exist");
    Result<std::unique_ptr<draco::Mesh>> mesh = decodeView(model, view.value(), true);
    if (mesh && lostIntegerType(*mesh.value())) return decodeView(model, view.value(), false);
    return mesh;
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

// Copies the values of `att`, `bytes` each and already of the accessor's type, to every point. With
// `Fixed` the size of a value is known when compiled, so that each copy is a few moves instead of a
// call to memcpy.
template <size_t Fixed>
bool copyValues(const draco::PointAttribute& att, size_t points, size_t bytes, unsigned char* out) {
    const size_t size = Fixed ? Fixed : bytes;
    if (points == 0) return true;
    const uint8_t* values = att.GetAddress(draco::AttributeValueIndex(0));
    if (att.is_mapping_identity()) {
        if (points > att.size()) return false;
        std::memcpy(out, values, points * size);
        return true;
    }
    for (draco::PointIndex p(0); p < points; ++p, out += size) {
        const uint32_t i = att.mapped_index(p).value();
        if (i >= att.size()) return false;
        std::memcpy(out, values + size_t(i) * size, size);
    }
    return true;
}

bool copyValues(const draco::PointAttribute& att, size_t points, size_t bytes, unsigned char* out) {
    switch (bytes) {
    case 4:
        return copyValues<4>(att, points, bytes, out);
    case 8:
        return copyValues<8>(att, points, bytes, out);
    case 12:
        return copyValues<12>(att, points, bytes, out);
    case 16:
        return copyValues<16>(att, points, bytes, out);
    default:
        return copyValues<0>(att, points, bytes, out);
    }
}

template <class T>
bool writeValues(const draco::PointAttribute& att, const draco::Mesh& mesh, int components,
                 unsigned char* out) {
    const size_t bytes = sizeof(T) * size_t(components);
    // Values already of this type and width are copied as they are; others converted one by one.
    if (att.data_type() == dracoType<T>() && att.num_components() == components &&
        size_t(att.byte_stride()) == bytes)
        return copyValues(att, mesh.num_points(), bytes, out);
    T value[16];
    for (draco::PointIndex p(0); p < mesh.num_points(); ++p, out += bytes) {
        const draco::AttributeValueIndex i = att.mapped_index(p);
        if (i.value() >= att.size() || !att.ConvertValue<T>(i, int8_t(components), value)) return false;
        std::memcpy(out, value, bytes);
    }
    return true;
}

// Writes `components` floats for every point of `mesh` from the int32 values of its entry of `att`:
// decode(entry, floats) gives the entry's floats, those past them stay zero as ConvertValue leaves
// them. With `N` the number of floats a point is known when compiled (see copyValues).
template <int N, class Decode>
bool decodePoints(const draco::PointAttribute& att, const draco::Mesh& mesh, int components,
                  unsigned char* out, Decode decode) {
    const size_t n = att.num_components(), bytes = sizeof(float) * size_t(N ? N : components);
    if (att.data_type() != draco::DT_INT32 || size_t(att.byte_stride()) != sizeof(int32_t) * n) return false;
    if (mesh.num_points() == 0) return true;
    const auto* values = reinterpret_cast<const int32_t*>(att.GetAddress(draco::AttributeValueIndex(0)));
    float value[256] = {}; // room for any entry (at most 255 components) and any accessor (16)
    for (draco::PointIndex p(0); p < mesh.num_points(); ++p, out += bytes) {
        const uint32_t i = att.mapped_index(p).value();
        if (i >= att.size()) return false;
        decode(values + size_t(i) * n, value);
        std::memcpy(out, value, bytes);
    }
    return true;
}

// Dequantises the `Width` components of each point (all of `min` when 0): see decodePoints for `N`.
template <size_t Width, int N>
bool dequantisePoints(const draco::PointAttribute& att, const draco::Mesh& mesh, int components,
                      unsigned char* out, const draco::Dequantizer& dequantizer,
                      const std::vector<float>& min) {
    return decodePoints<N>(att, mesh, components, out, [&](const int32_t* q, float* v) {
        for (size_t c = 0; c < (Width ? Width : min.size()); ++c)
            v[c] = dequantizer.DequantizeFloat(q[c]) + min[c];
    });
}

template <int N>
bool dequantise(const draco::PointAttribute& att, const draco::Mesh& mesh, int components,
                unsigned char* out) {
    // What libdraco's AttributeQuantizationTransform and AttributeOctahedronTransform compute, through
    // the same Dequantizer and OctahedronToolBox, so that the floats are the same to the bit.
    if (att.GetAttributeTransformData()->transform_type() == draco::ATTRIBUTE_OCTAHEDRON_TRANSFORM) {
        draco::AttributeOctahedronTransform transform;
        draco::OctahedronToolBox normals;
        if (!transform.InitFromAttribute(att) ||
            !normals.SetQuantizationBits(transform.quantization_bits()) || att.num_components() != 2)
            return false;
        return decodePoints<N>(att, mesh, components, out, [&](const int32_t* st, float* v) {
            normals.QuantizedOctahedralCoordsToUnitVector(st[0], st[1], v);
        });
    }
    draco::AttributeQuantizationTransform transform;
    draco::Dequantizer dequantizer;
    if (!transform.InitFromAttribute(att) ||
        !dequantizer.Init(transform.range(), int32_t((1u << uint32_t(transform.quantization_bits())) - 1)))
        return false;
    const std::vector<float>& min = transform.min_values();
    return N && min.size() == size_t(N)
               ? dequantisePoints<N, N>(att, mesh, components, out, dequantizer, min)
               : dequantisePoints<0, N>(att, mesh, components, out, dequantizer, min);
}

// The floats libdraco would have decoded from `att`, whose values it left quantised, for every point
// of `mesh`, `components` each.
Result<std::vector<unsigned char>> dequantisedBytes(const draco::PointAttribute& att, const draco::Mesh& mesh,
                                                    int components) {
    std::vector<unsigned char> bytes(size_t(mesh.num_points()) * sizeof(float) * size_t(components));
    const bool ok = components == 2   ? dequantise<2>(att, mesh, components, bytes.data())
                    : components == 3 ? dequantise<3>(att, mesh, components, bytes.data())
                                      : dequantise<0>(att, mesh, components, bytes.data());
    if (!ok) return fail("has quantised Draco values that cannot be dequantised");
    return bytes;
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
    // Floats decoded for an integer accessor stay floats: Draco dequantizes them.
    tinygltf::Accessor target = source;
    const bool quantised = keptQuantised(*att);
    if (quantised || att->data_type() == draco::DT_FLOAT32 || att->data_type() == draco::DT_FLOAT64) {
        target.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
        target.normalized = false;
    }
    Result<std::vector<unsigned char>> bytes =
        quantised ? dequantisedBytes(*att, mesh, components)
                  : attributeBytes(*att, mesh, target.componentType, components);
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
