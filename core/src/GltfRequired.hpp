#pragma once
// Names a required glTF 2.0 property that a document lacks. tinygltf refuses some such documents
// (a skin without "joints", for one) without saying why; the loader then reports what this finds.
// Internal to spatter::core.

#include <cstddef>
#include <string>

namespace spatter::gltf {

// The first required property missing from the glTF JSON `text` (`size` bytes), as "skin 0 lacks
// the required property \"joints\"", or an empty string when the text is not JSON or nothing
// required is missing. Reads only the given bytes.
std::string missingRequiredProperty(const char* text, size_t size);

// "buffer N has no uri and the file is not a .glb" for the first buffer of the glTF JSON `text` that
// has no uri (only a .glb's binary chunk can stand in for one), or an empty string when every buffer
// has one or the text is not JSON.
std::string bufferWithoutUri(const char* text, size_t size);

} // namespace spatter::gltf
