#include "decal_flags.glsl"

// The axis a decal's box is projected along, in the space of the box's rows (world space in the decal
// pass, object space for texture-space splats): the direction along which the box's first two
// coordinates stay the same, on the side of the decal's normal. It is the reversed shot for a decal
// projected along its shot and the normal otherwise (DecalProjection.hpp).
//
// A pixel takes a decal only where its normal lies within the type's largest angle of both the
// decal's normal and this axis: the first keeps a decal off the faces turned away from the one it was
// placed on (the far side of a corner); the second is the rule placement applies to the shot itself,
// so that a decal does not paint the surface its shot could not reach, whichever facet of the
// collision proxy the shot met. Only a decal off its normal (SPATTER_DECAL_SLANTED) needs the second.
vec3 spatterDepthAxis(vec3 rowT, vec3 rowB, vec3 normal) {
    vec3 axis = normalize(cross(rowT, rowB));
    return dot(axis, normal) < 0.0 ? -axis : axis;
}

// Whether a surface of unit normal `n` takes a decal (of `flags`, SPATTER_DECAL_*) by the angle test
// above: within the angle of cosine `minCos` of its `normal` and, off its normal, of its `axis`.
bool spatterWithinAngle(vec3 n, vec3 normal, vec3 axis, uint flags, float minCos) {
    return dot(n, normal) >= minCos && ((flags & SPATTER_DECAL_SLANTED) == 0u || dot(n, axis) >= minCos);
}
