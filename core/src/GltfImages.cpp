#include "GltfImages.hpp"

#include "GltfAccessor.hpp"
#include "GltfExtension.hpp"

namespace spatter::gltf {

std::string imageName(const tinygltf::Image& image, int index) {
    return named("image", size_t(index), image.uri.empty() ? image.name : image.uri);
}

namespace {

// Image extensions whose texture names its own source (in a format the core images may lack).
const char* const kImageExtensions[] = {"KHR_texture_basisu", "EXT_texture_webp", "MSFT_texture_dds",
                                        "EXT_texture_avif"};

// True when image `index` is the source of some texture only through an image extension, never as a
// texture's core source: a scene can do without it.
bool usedOnlyByExtensions(const tinygltf::Model& model, int index) {
    bool byExtension = false;
    for (const tinygltf::Texture& t : model.textures) {
        if (t.source == index) return false;
        for (const char* name : kImageExtensions)
            if (const tinygltf::Value* ext = findExtension(t.extensions, name))
                byExtension = byExtension || numberField(*ext, "source", -1.0) == double(index);
    }
    return byExtension;
}

} // namespace

// Image `index` of `model` as a scene image. One that could not be read or decoded (`decodeErrors`)
// is an error, unless only image extensions use it: then a 1x1 white image stands in for it and a
// warning says so.
Result<Image> convertImage(tinygltf::Model& model, size_t index,
                           const std::map<int, std::string>& decodeErrors,
                           std::vector<std::string>& warnings) {
    tinygltf::Image& source = model.images[index];
    Image image;
    image.name = !source.uri.empty()    ? source.uri
                 : !source.name.empty() ? source.name
                                        : "image " + num(index);
    if (source.image.empty()) {
        const auto error = decodeErrors.find(int(index));
        // tinygltf only warns when an external image file is missing; here it is an error.
        const std::string why =
            error != decodeErrors.end()
                ? error->second
                : imageName(source, int(index)) + " cannot be read (missing or unreadable file)";
        if (!usedOnlyByExtensions(model, int(index))) return fail(why);
        warnings.push_back(why + "; only an image extension uses it, so the texture falls back to its core "
                                 "image, or to none");
        image.width = image.height = 1;
        image.rgba = {255, 255, 255, 255};
        return image;
    }
    image.width = source.width;
    image.height = source.height;
    image.rgba = std::move(source.image);
    return image;
}

bool decodeGltfImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                     const unsigned char* bytes, int size, void* user) {
    auto& decoding = *static_cast<ImageDecoding*>(user);
    const auto& model = *decoding.model;
    const std::string name = imageName(*image, index);
    auto reject = [&](const std::string& message) {
        if (err) *err += message + "\n";
        return false;
    };
    if (image->bufferView >= 0) {
        // tinygltf passes the view's bytes without checking that the view lies inside its buffer.
        const int v = image->bufferView;
        const bool inside =
            validIndex(v, model.bufferViews.size()) &&
            validIndex(model.bufferViews[size_t(v)].buffer, model.buffers.size()) &&
            rangeInside(model.bufferViews[size_t(v)].byteOffset, model.bufferViews[size_t(v)].byteLength,
                        model.buffers[size_t(model.bufferViews[size_t(v)].buffer)].data.size());
        if (!inside)
            return reject(name + ": buffer view " + std::to_string(v) + " reads past the end of its buffer");
    }
    Result<Image> decoded = size <= 0 ? Result<Image>(fail(name + ": image data is empty"))
                                      : decodeImage(bytes, size_t(size), name);
    if (!decoded) {
        decoding.errors[index] = decoded.error();
        return true;
    }
    image->width = decoded->width;
    image->height = decoded->height;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image = std::move(decoded->rgba);
    return true;
}

} // namespace spatter::gltf
