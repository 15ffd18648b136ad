#include "spatter/core/Image.hpp"

#include <stb_image.h>
#include <stb_image_write.h>

#include <climits>
#include <fstream>
#include <iterator>

namespace spatter {

static constexpr int kMaxImageSide = 16384;

Result<Image> decodeImage(const uint8_t* bytes, size_t size, const std::string& name) {
    if (!bytes || size == 0) return fail(name + ": image data is empty");
    if (size > size_t(INT_MAX)) return fail(name + ": image data is too large");
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes, int(size), &w, &h, &comp))
        return fail(name + ": not a decodable image (" + std::string(stbi_failure_reason()) + ")");
    if (w <= 0 || h <= 0 || w > kMaxImageSide || h > kMaxImageSide)
        return fail(name + ": image size " + std::to_string(w) + "x" + std::to_string(h) +
                    " is out of range");
    unsigned char* pixels = stbi_load_from_memory(bytes, int(size), &w, &h, &comp, 4);
    if (!pixels) return fail(name + ": image decoding failed (" + std::string(stbi_failure_reason()) + ")");
    Image image;
    image.width = w;
    image.height = h;
    image.name = name;
    image.rgba.assign(pixels, pixels + size_t(w) * size_t(h) * 4);
    stbi_image_free(pixels);
    return image;
}

Result<Image> loadImage(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return fail(path + ": cannot open image file");
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return decodeImage(bytes.data(), bytes.size(), path);
}

Status writePng(const std::string& path, const Image& image) {
    if (image.empty() || image.rgba.size() != size_t(image.width) * size_t(image.height) * 4)
        return fail(path + ": image to write is empty or its pixel buffer has the wrong size");
    if (!stbi_write_png(path.c_str(), image.width, image.height, 4, image.rgba.data(), image.width * 4))
        return fail(path + ": cannot write PNG");
    return {};
}

} // namespace spatter
