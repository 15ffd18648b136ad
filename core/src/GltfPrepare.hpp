#pragma once
// Changes to a glTF document before tinygltf parses it, for valid glTF that tinygltf would refuse:
// meshopt fallback buffers without a uri, and primitive indices in an accessor without a buffer view
// (Draco-compressed, or zero-filled and sparse). Internal to spatter::core.

#include <tiny_gltf.h>

#include <optional>
#include <string>

namespace spatter::gltf {

// The glTF JSON `json` (`size` bytes) as tinygltf can parse it, or no value when it needs no change
// (or is not JSON: tinygltf then says why). Primitive indices that name an accessor without a buffer
// view are moved aside, into the primitive's extensions, for restoreMovedIndices.
std::optional<std::string> prepareJson(const char* json, size_t size);

// Puts back the indices prepareJson moved aside, once tinygltf has parsed the document.
void restoreMovedIndices(tinygltf::Model& model);

} // namespace spatter::gltf
