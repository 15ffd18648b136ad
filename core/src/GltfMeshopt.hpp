#pragma once
// EXT_meshopt_compression: buffer views whose bytes are meshoptimizer's vertex or index codec, over a
// fallback buffer that may have no data at all. Internal to spatter::core.

#include "spatter/core/Result.hpp"

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

namespace spatter::gltf {

// Gives each fallback buffer of the extension in the glTF document `doc` a one-byte placeholder for
// its uri: only compressed views refer to such a buffer, so its data (no uri, or a file that need not
// exist) is never read. True when it changed something.
bool addMeshoptPlaceholders(nlohmann::json& doc);

// Decodes every buffer view that has the extension (meshopt_decodeVertexBuffer, IndexBuffer or
// IndexSequence, then the OCTAHEDRAL, QUATERNION or EXPONENTIAL filter) into a buffer of its own, and
// points the view at it. Runs before the buffer views are checked against their buffers. The error
// names the buffer view and the problem: a field out of range, compressed bytes past the end of their
// buffer, data that does not decode, or a decoded size beyond kMaxMeshoptRatio times the compressed one.
Status decodeMeshoptViews(tinygltf::Model& model);

// meshoptimizer's codecs spend at least two bits on 16 bytes of vertex data and a byte on a triangle:
// a view that claims to decode to more than this many times its compressed bytes is refused before
// anything is allocated.
constexpr size_t kMaxMeshoptRatio = 128;

} // namespace spatter::gltf
