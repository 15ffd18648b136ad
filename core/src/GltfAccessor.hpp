#pragma once
// The glTF loader's shared reading helpers: index and range checks, message pieces, component types,
// and checked views of accessors. Internal to spatter::core (GltfLoader.cpp, GltfAnimation.cpp).

#include "spatter/core/Result.hpp"

#include <tiny_gltf.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace spatter::gltf {

// --- small helpers ------------------------------------------------------------------------------

inline std::string num(size_t value) {
    return std::to_string(value);
}

inline std::string named(const char* kind, size_t index, const std::string& name) {
    const std::string s = std::string(kind) + " " + num(index);
    return name.empty() ? s : s + " (" + name + ")";
}

inline bool validIndex(int index, size_t count) {
    return index >= 0 && size_t(index) < count;
}

// True when [begin, begin + length) lies inside [0, size), without overflow.
inline bool rangeInside(size_t begin, size_t length, size_t size) {
    return begin <= size && length <= size - begin;
}

// out = a * b + c; false on overflow.
inline bool mulAdd(size_t a, size_t b, size_t c, size_t& out) {
    if (b != 0 && a > (std::numeric_limits<size_t>::max() - c) / b) return false;
    out = a * b + c;
    return true;
}

template <class T> T load(const unsigned char* p) {
    T value;
    std::memcpy(&value, p, sizeof value);
    return value;
}

template <int N> bool finite(const glm::vec<N, float>& v) {
    for (int i = 0; i < N; ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}

// --- component types ----------------------------------------------------------------------------

inline size_t componentSize(int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return 4;
    default:
        return 0; // INT and DOUBLE are not glTF 2.0 component types
    }
}

constexpr unsigned componentBit(int componentType) {
    return 1u << unsigned(componentType - 5120);
}

constexpr unsigned kIndexTypes = componentBit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) |
                                 componentBit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) |
                                 componentBit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
constexpr unsigned kVertexTypes =
    componentBit(TINYGLTF_COMPONENT_TYPE_FLOAT) | componentBit(TINYGLTF_COMPONENT_TYPE_BYTE) |
    componentBit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) | componentBit(TINYGLTF_COMPONENT_TYPE_SHORT) |
    componentBit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);

inline int componentCount(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR:
        return 1;
    case TINYGLTF_TYPE_VEC2:
        return 2;
    case TINYGLTF_TYPE_VEC3:
        return 3;
    case TINYGLTF_TYPE_VEC4:
        return 4;
    case TINYGLTF_TYPE_MAT4:
        return 16;
    default:
        return 0;
    }
}

inline std::string typeName(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR:
        return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
        return "VEC2";
    case TINYGLTF_TYPE_VEC3:
        return "VEC3";
    case TINYGLTF_TYPE_VEC4:
        return "VEC4";
    case TINYGLTF_TYPE_MAT2:
        return "MAT2";
    case TINYGLTF_TYPE_MAT3:
        return "MAT3";
    case TINYGLTF_TYPE_MAT4:
        return "MAT4";
    default:
        return "type " + std::to_string(type);
    }
}

// --- accessors ----------------------------------------------------------------------------------

// Upper bound on the elements of an accessor without a buffer view: its zeros cost memory that the
// file does not pay for.
constexpr size_t kMaxBufferlessElements = size_t(1) << 22;

// The elements of one accessor, after its byte range was checked against its buffer view and buffer:
// every read stays inside the buffer. A sparse accessor, or one without a buffer view, is copied into
// `owned` first (its elements tightly packed), and `data` points there.
struct AccessorView {
    const unsigned char* data = nullptr; // element 0
    size_t count = 0;
    size_t stride = 0;
    int componentType = 0;
    bool normalized = false;
    bool present = false; // false for an attribute the primitive does not have
    std::shared_ptr<const std::vector<unsigned char>> owned; // the elements when copied, else null

    // Component `c` of element `i` as a float; normalized integers map to [0, 1] or [-1, 1].
    float component(size_t i, int c) const {
        const unsigned char* p = data + i * stride + size_t(c) * componentSize(componentType);
        switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const float v = load<int8_t>(p);
            return normalized ? std::max(v / 127.0f, -1.0f) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            const float v = load<uint8_t>(p);
            return normalized ? v / 255.0f : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const float v = load<int16_t>(p);
            return normalized ? std::max(v / 32767.0f, -1.0f) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            const float v = load<uint16_t>(p);
            return normalized ? v / 65535.0f : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return float(load<uint32_t>(p));
        default:
            return load<float>(p);
        }
    }

    template <int N> glm::vec<N, float> vec(size_t i) const {
        glm::vec<N, float> v;
        for (int c = 0; c < N; ++c)
            v[c] = component(i, c);
        return v;
    }

    // Element `i` of an unsigned integer scalar accessor.
    uint32_t index(size_t i) const {
        const unsigned char* p = data + i * stride;
        switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return load<uint8_t>(p);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return load<uint16_t>(p);
        default:
            return load<uint32_t>(p);
        }
    }
};

// Checks accessor `index` for use as `role` (type and allowed component types) and that every
// element it reads lies inside its buffer view. An accessor without a buffer view reads as zeros (at
// most kMaxBufferlessElements of them); a sparse accessor's values replace the elements its indices
// name (strictly increasing, inside the accessor). Buffer views must have been checked against their
// buffers. The error names the accessor, the role and the problem.
Result<AccessorView> viewAccessor(const tinygltf::Model& model, int index, const char* role, int type,
                                  unsigned allowedComponentTypes);

// Every element of VEC3 accessor `index`, used as `role`, which must have `count` elements: dense,
// zero-filled (no buffer view) and sparse (its indices strictly increasing and inside the accessor,
// its values replacing the elements they index) alike; integer components as AccessorView reads them.
// Every element must be finite. Buffer views must have been checked against their buffers. The error
// names the accessor, the role and the problem.
Result<std::vector<glm::vec3>> readVec3(const tinygltf::Model& model, int index, const char* role,
                                        unsigned allowedComponentTypes, size_t count);

} // namespace spatter::gltf
