#pragma once
// DecalCutout: the part of a decal texture layer that can show. Outside the rectangle where its
// albedo's alpha is not zero (at full resolution, widened by a margin) every decal of the layer is
// clear: the shaders take its alpha as zero there at every mip level, and the boxes are drawn only
// over that rectangle, so most of a bullet hole's square is never rasterised.

#include "spatter/core/Image.hpp"

#include <glm/vec4.hpp>

#include <cstdint>

namespace spatter::render_detail {

// The margin around the visible texels, as a fraction of the layer's size (layers are square).
constexpr float kCutoutMargin = 1.0f / 16.0f;

// The cutout of an albedo image (row 0 at the top, as Image keeps it) in texture coordinates: min u,
// min v, max u, max v, with v = 0 at the image's bottom row as the layers are uploaded, on a grid of
// 1/255 rounded outward. An image with no visible texel (or without its pixels) gives an empty cutout
// (min above max).
glm::vec4 decalCutout(const Image& albedo);

// The cutout as four 8-bit fractions (GLSL unpackUnorm4x8 gives it back exactly).
uint32_t packCutout(glm::vec4 cutout);

} // namespace spatter::render_detail
