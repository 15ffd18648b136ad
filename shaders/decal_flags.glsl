// The decal type's features, as bits of DecalData::info.z (and of SpatterForwardDecal::info.z).
// Mirrored on the C++ side by render/src/GpuLayouts.hpp (DecalFlag).
const uint SPATTER_DECAL_WRAP = 1u;
const uint SPATTER_DECAL_NORMAL_MAP = 2u;
const uint SPATTER_DECAL_FADE_LINEAR = 4u;
const uint SPATTER_DECAL_FADE_SMOOTH = 8u;
const uint SPATTER_DECAL_ROUGHNESS = 16u;
const uint SPATTER_DECAL_MIRRORED = 32u;
// Projected along its shot, off its normal (a slant that is not zero): the angle test takes the
// projection axis as well as the normal (depth_axis.glsl).
const uint SPATTER_DECAL_SLANTED = 64u;
