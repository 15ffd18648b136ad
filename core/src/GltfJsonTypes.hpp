#pragma once
// The JSON types of the glTF properties the loader uses. tinygltf takes an optional property of the
// wrong type ("translation": "abc", "byteOffset": -4 or 4.0, "skin": "1") as if it were absent, so
// that such a file loaded as a different scene; the loader checks their types on the JSON itself
// before tinygltf parses it. Internal to spatter::core.

#include "spatter/core/Result.hpp"

#include <cstddef>

namespace spatter::gltf {

// Checks the glTF JSON `json` (`size` bytes). A document that is not JSON passes: tinygltf says why.
Status checkPropertyTypes(const char* json, size_t size);

} // namespace spatter::gltf
