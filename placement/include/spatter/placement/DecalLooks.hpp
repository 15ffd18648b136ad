#pragma once
// DecalLooks: the built-in looks that spatter's tools and example hosts give the decals they load or
// place, one per built-in decal texture (DecalTexture), chosen by name, or "mixed": the four in
// turn, decal by decal.
//
//   Result<int> look = parseDecalLook("blood");            // a DecalTexture value
//   DecalType t = withLook(base, lookOf(look.value(), k));  // the look of the k-th decal

#include "spatter/core/DecalType.hpp"
#include "spatter/core/Result.hpp"

#include <cstddef>
#include <string>

namespace spatter {

// The look that gives each decal the next built-in texture in turn (lookOf).
constexpr int kMixedLooks = -1;

// The look named `name`: "bullet_hole", "blood", "paint" or "scorch" give their DecalTexture value,
// "mixed" gives kMixedLooks. Any other name fails with an error that quotes it and lists the names.
Result<int> parseDecalLook(const std::string& name);

// `base` with the look of built-in texture `texture` (a DecalTexture value): that texture, a white
// tint (paint: yellow) and the roughness the look writes (blood 0.25, scorch 0.95; the others keep
// the surface's). Placement settings and everything else of `base` are kept.
DecalType withLook(DecalType base, int texture);

// The texture of the k-th decal under `look`: `look` itself, or with kMixedLooks the built-in
// textures in turn (k modulo DecalTexture::Count).
int lookOf(int look, size_t k);

} // namespace spatter
