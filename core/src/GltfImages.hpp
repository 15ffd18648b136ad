#pragma once
// The images of a glTF file: decoded to RGBA8 while tinygltf parses (decodeGltfImage), then made scene
// images (convertImage). An image that cannot be read or decoded fails the load, unless only an
// image extension (KHR_texture_basisu, EXT_texture_webp, MSFT_texture_dds, EXT_texture_avif) uses
// it: the texture then falls back to its core image, or to none. Internal to spatter::core.

#include "spatter/core/Image.hpp"
#include "spatter/core/Result.hpp"

#include <tiny_gltf.h>

#include <map>
#include <string>
#include <vector>

namespace spatter::gltf {

// What the image callback needs and finds: the model being filled (its buffers and buffer views are
// parsed before its images) and why each image that did not decode failed.
struct ImageDecoding {
    const tinygltf::Model* model = nullptr;
    std::map<int, std::string> errors; // by image index
};

// "image N (uri or name)".
std::string imageName(const tinygltf::Image& image, int index);

// tinygltf's image callback: decodes to RGBA8 with decodeImage. `user` is an ImageDecoding. An image
// whose buffer view lies outside its buffer is refused; one that does not decode is left empty and
// its reason kept in the ImageDecoding for convertImage.
bool decodeGltfImage(tinygltf::Image* image, int index, std::string* err, std::string* warn, int width,
                     int height, const unsigned char* bytes, int size, void* user);

// Image `index` of `model` as a scene image (its pixels moved out of the model). One that could not be
// read or decoded (`decodeErrors`) is an error naming it, unless only image extensions use it: then a
// 1x1 white image stands in for it and a line in `warnings` says so.
Result<Image> convertImage(tinygltf::Model& model, size_t index,
                           const std::map<int, std::string>& decodeErrors,
                           std::vector<std::string>& warnings);

} // namespace spatter::gltf
