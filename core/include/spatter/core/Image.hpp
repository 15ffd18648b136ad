#pragma once
// Image: 8-bit RGBA pixels, row 0 at the top.

#include "spatter/core/Result.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace spatter {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba; // width * height * 4 bytes
    std::string name;          // file name or a description, for messages

    bool empty() const { return width <= 0 || height <= 0; }
};

// Decodes PNG, JPEG, TGA or BMP bytes (stb_image) into RGBA8. Rejects images over 16384 pixels a side.
Result<Image> decodeImage(const uint8_t* bytes, size_t size, const std::string& name);
// Reads and decodes an image file.
Result<Image> loadImage(const std::string& path);
// Writes a PNG (stb_image_write). The error names the path.
Status writePng(const std::string& path, const Image& image);

} // namespace spatter
