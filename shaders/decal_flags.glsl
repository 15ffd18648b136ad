// The decal type's features, as bits of DecalData::info.z (and of SpatterForwardDecal::info.z), and
// its texture layer's cutout (DecalData::info.w, SpatterForwardDecal::info.w). Mirrored on the C++
// side by render/src/GpuLayouts.hpp (DecalFlag) and render/src/DecalCutout.hpp.
const uint SPATTER_DECAL_WRAP = 1u;
const uint SPATTER_DECAL_NORMAL_MAP = 2u;
const uint SPATTER_DECAL_FADE_LINEAR = 4u;
const uint SPATTER_DECAL_FADE_SMOOTH = 8u;
const uint SPATTER_DECAL_ROUGHNESS = 16u;
const uint SPATTER_DECAL_MIRRORED = 32u;
// Projected along its shot, off its normal (a slant that is not zero): the angle test takes the
// projection axis as well as the normal (depth_axis.glsl).
const uint SPATTER_DECAL_SLANTED = 64u;

// A decal texture layer's cutout (DecalProjector::decalTextureCutouts), packed as four 8-bit
// fractions: min u, min v, max u, max v.
vec4 spatterCutout(uint cutout) {
    return unpackUnorm4x8(cutout);
}

// Whether texture coordinates `tc` lie inside the cutout: outside it the layer is clear at every mip
// level, and nothing of a decal shows.
bool spatterInCutout(vec2 tc, uint cutout) {
    vec4 c = spatterCutout(cutout);
    return all(greaterThanEqual(tc, c.xy)) && all(lessThanEqual(tc, c.zw));
}
