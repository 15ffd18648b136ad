#pragma once
// Decal textures on the CPU: the built-in procedural decals (bullet hole, blood splat, paint splat,
// scorch mark), generated in code so that nothing must be loaded, and the conversions that turn any
// image into a layer of the renderer's decal texture array.
//
// Layout of a decal texture (both images): column u runs along the decal's tangent, from its -x
// edge at the left to its +x edge at the right; rows run along the bitangent, row 0 (the top) at
// the +y edge. Albedo is sRGB colour with straight (not premultiplied) alpha, 0 outside the mark.
// The normal map is tangent-space, OpenGL convention (+y up the image): rgb = n * 0.5 + 0.5.

#include "spatter/core/DecalType.hpp"
#include "spatter/core/Image.hpp"
#include "spatter/core/Result.hpp"

#include <cstdint>
#include <vector>

namespace spatter {

struct DecalTextureImages {
    Image albedo; // RGBA8: sRGB colour, straight alpha
    Image normal; // RGBA8: tangent-space normal in rgb, alpha 255
};

// The built-in decal `kind` at size x size pixels (size clamped to [16, 2048]). Deterministic: same
// kind and size, same bytes. Alpha is 0 along the whole border, so no decal shows its square edge.
// DecalTexture::Count, or a value out of range, gives empty images.
DecalTextureImages makeBuiltinDecalTexture(DecalTexture kind, int size);

// Tangent-space normal map (layout above) from a height field of width x height samples (row 0 at
// the top, heights in texels times `strength`), by central differences clamped at the border.
// Returns an empty image when the sizes do not match or are not positive.
Image normalMapFromHeight(const std::vector<float>& heights, int width, int height, float strength);

// `image` resampled to width x height (area average when shrinking, bilinear when enlarging). Returns
// an error naming the image when it is empty or its pixel count does not match its size.
Result<Image> resizeImage(const Image& image, int width, int height);

} // namespace spatter
