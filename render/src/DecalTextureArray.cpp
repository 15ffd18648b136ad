#include "DecalTextureArray.hpp"

#include "DecalCutout.hpp"

#include "spatter/render/DecalTextures.hpp"

#include <algorithm>
#include <cmath>

namespace spatter::render_detail {

namespace {

constexpr int kMaxLayers = 256;

GlTexture makeArray(GLenum format, int size, int layers, const std::vector<Image>& images) {
    GlTexture t = createTexture(GL_TEXTURE_2D_ARRAY);
    const int levels = 1 + int(std::floor(std::log2(double(size))));
    glTextureStorage3D(t.get(), levels, format, size, size, layers);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    std::vector<uint8_t> flipped(size_t(size) * size_t(size) * 4);
    for (int l = 0; l < layers; ++l) {
        // Texture coordinate t = 0 is the first row uploaded: the image's bottom row (-y edge).
        const Image& im = images[size_t(l)];
        const size_t row = size_t(size) * 4;
        for (int y = 0; y < size; ++y)
            std::copy_n(&im.rgba[size_t(size - 1 - y) * row], row, &flipped[size_t(y) * row]);
        glTextureSubImage3D(t.get(), 0, 0, 0, l, size, size, 1, GL_RGBA, GL_UNSIGNED_BYTE, flipped.data());
    }
    glGenerateTextureMipmap(t.get());
    glTextureParameteri(t.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(t.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

Image flatNormal(int size) {
    Image im;
    im.width = im.height = size;
    im.name = "flat normal";
    im.rgba.resize(size_t(size) * size_t(size) * 4);
    for (size_t i = 0; i < im.rgba.size(); i += 4) {
        im.rgba[i] = 128;
        im.rgba[i + 1] = 128;
        im.rgba[i + 2] = 255;
        im.rgba[i + 3] = 255;
    }
    return im;
}

} // namespace

Status DecalTextureArray::create(int size) {
    if (size < 16 || size > 2048 || (size & (size - 1)) != 0)
        return fail("decal textures: layer size " + std::to_string(size) +
                    " is not a power of two in [16, 2048]");
    size_ = size;
    albedo_.clear();
    normal_.clear();
    cutouts_.clear();
    for (int k = 0; k < int(DecalTexture::Count); ++k) {
        DecalTextureImages im = makeBuiltinDecalTexture(DecalTexture(k), size);
        cutouts_.push_back(decalCutout(im.albedo));
        albedo_.push_back(std::move(im.albedo));
        normal_.push_back(std::move(im.normal));
    }
    upload();
    return {};
}

Result<int> DecalTextureArray::add(const Image& albedo, const Image& normal) {
    if (layers() >= kMaxLayers)
        return fail("decal textures: at most " + std::to_string(kMaxLayers) + " layers");
    Result<Image> a = resizeImage(albedo, size_, size_);
    if (!a) return fail("decal texture: " + a.error());
    Image n = flatNormal(size_);
    if (!normal.empty() || !normal.rgba.empty()) {
        Result<Image> r = resizeImage(normal, size_, size_);
        if (!r) return fail("decal normal map: " + r.error());
        n = std::move(r.value());
    }
    cutouts_.push_back(decalCutout(a.value()));
    albedo_.push_back(std::move(a.value()));
    normal_.push_back(std::move(n));
    upload();
    return layers() - 1;
}

void DecalTextureArray::upload() {
    albedoTex_ = makeArray(GL_SRGB8_ALPHA8, size_, layers(), albedo_);
    normalTex_ = makeArray(GL_RGBA8, size_, layers(), normal_);
}

} // namespace spatter::render_detail
