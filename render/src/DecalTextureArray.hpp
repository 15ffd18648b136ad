#pragma once
// DecalTextureArray: the decal textures as two 2D array textures of equal size and layer count:
// albedo (sRGB, straight alpha) and tangent-space normal maps. Layers 0..3 are the built-in
// procedural decals (DecalTexture); added images become further layers, resized to the layer size.
// Each layer has its cutout (DecalCutout.hpp).

#include "GlObjects.hpp"

#include "spatter/core/Image.hpp"
#include "spatter/core/Result.hpp"

#include <glm/vec4.hpp>
#include <vector>

namespace spatter::render_detail {

class DecalTextureArray {
public:
    // Builds the built-in layers at size x size.
    Status create(int size);
    // Appends a layer; `normal` may be empty (a flat normal map). Returns the layer index.
    Result<int> add(const Image& albedo, const Image& normal);

    int layers() const { return int(albedo_.size()); }
    const std::vector<glm::vec4>& cutouts() const { return cutouts_; } // one per layer
    GLuint albedoTexture() const { return albedoTex_.get(); }
    GLuint normalTexture() const { return normalTex_.get(); }

private:
    void upload();

    int size_ = 0;
    std::vector<Image> albedo_; // layer images, rows flipped so that row 0 is the +y edge at the top
    std::vector<Image> normal_;
    std::vector<glm::vec4> cutouts_;
    GlTexture albedoTex_, normalTex_;
};

} // namespace spatter::render_detail
