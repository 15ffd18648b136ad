#pragma once
// Reading the JSON objects of glTF extensions as tinygltf hands them over (tinygltf::Value), with every
// field checked, and adding the data a decoder produced to the model. Internal to spatter::core.

#include "spatter/core/Result.hpp"

#include <tiny_gltf.h>

#include <cmath>
#include <string>
#include <vector>

namespace spatter::gltf {

// The object of extension `name` in `extensions`, or null when absent.
inline const tinygltf::Value* findExtension(const tinygltf::ExtensionMap& extensions, const char* name) {
    const auto it = extensions.find(name);
    return it == extensions.end() ? nullptr : &it->second;
}

// Field `key` of `object` as an integer in [0, max]: `fallback` when absent (a negative fallback makes
// the field required). The error names the field.
inline Result<size_t> unsignedField(const tinygltf::Value& object, const char* key, double max,
                                    long long fallback = -1) {
    if (!object.IsObject() || !object.Has(key)) {
        if (fallback < 0) return fail(std::string("lacks \"") + key + "\"");
        return size_t(fallback);
    }
    const tinygltf::Value& v = object.Get(key);
    const double d = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
    if (!(d >= 0.0 && d <= max) || d != std::floor(d))
        return fail(std::string("\"") + key + "\" is not an integer from 0 to " +
                    std::to_string((long long)max));
    return size_t(d);
}

// Field `key` of `object` as a string; `fallback` when absent or not a string.
inline std::string stringField(const tinygltf::Value& object, const char* key, const std::string& fallback) {
    if (!object.IsObject() || !object.Has(key) || !object.Get(key).IsString()) return fallback;
    return object.Get(key).Get<std::string>();
}

// Field `key` of `object` as a finite number; `fallback` when absent or not a number.
inline double numberField(const tinygltf::Value& object, const char* key, double fallback) {
    if (!object.IsObject() || !object.Has(key) || !object.Get(key).IsNumber()) return fallback;
    const double d = object.Get(key).GetNumberAsDouble();
    return std::isfinite(d) ? d : fallback;
}

// Appends `bytes` to `model` as a buffer of its own and a buffer view over all of it; returns the view.
inline int addDecodedView(tinygltf::Model& model, std::vector<unsigned char> bytes, size_t stride = 0) {
    tinygltf::Buffer buffer;
    buffer.data = std::move(bytes);
    tinygltf::BufferView view;
    view.buffer = int(model.buffers.size());
    view.byteOffset = 0;
    view.byteLength = buffer.data.size();
    view.byteStride = stride;
    model.buffers.push_back(std::move(buffer));
    model.bufferViews.push_back(view);
    return int(model.bufferViews.size()) - 1;
}

} // namespace spatter::gltf
