// Volumetric decals, mark: a footprint fragment sets the stencil (by the fixed-function stencil
// operation) only where the surface under it is visible: the G-buffer depth is within the crater's
// tolerance (view depth) of the footprint's, its normal is within the type's largest angle of the
// decal axis (which keeps the hole off an adjacent surface near a corner), and (IDS) the pixel's
// object decal ID is the decal's.
#include "common.glsl"
#include "crater.glsl"

layout(binding = 0) uniform sampler2D s_depth;
layout(binding = 1) uniform sampler2D s_normal;
layout(binding = 2) uniform usampler2D s_ids;

flat in uint v_crater;

void main() {
    Crater c = craters[v_crater];
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(s_depth, pixel, 0).r;
    if (depth <= 0.0) discard;
    float surface = -u_projection.w / (depth + u_projection.z);
    float footprint = -u_projection.w / (gl_FragCoord.z + u_projection.z);
    if (abs(surface - footprint) > c.tolerance) discard;
    if (dot(decodeNormal(texelFetch(s_normal, pixel, 0).rg), c.plane.xyz) < c.cosAngle) discard;
#ifdef IDS
    if (texelFetch(s_ids, pixel, 0).r != c.id) discard;
#endif
}
