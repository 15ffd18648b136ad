// spatter's forward path, in a host's forward fragment shader: DecalProjector::bin sorts the visible
// decals into screen tiles; spatterApplyForwardDecals() applies those of the pixel's tile to the surface the
// host is shading, in drawing order, as the deferred paths would blend them. The host pastes this text
// (DecalProjector::hostShader("forward.glsl")) after its #version line, binds the projector's buffers
// and decal textures (DecalProjector::bindForward) and calls the function before its lighting.
// Texture units default to ForwardBindings'; a host defines SPATTER_DECAL_ALBEDO_UNIT and
// SPATTER_DECAL_NORMAL_UNIT before this text to move them (and the buffers: forward_data.glsl).
#include "decal_flags.glsl"
#include "depth_axis.glsl"
#include "forward_data.glsl"

#ifndef SPATTER_DECAL_ALBEDO_UNIT
#define SPATTER_DECAL_ALBEDO_UNIT 14
#endif
#ifndef SPATTER_DECAL_NORMAL_UNIT
#define SPATTER_DECAL_NORMAL_UNIT 15
#endif
layout(binding = SPATTER_DECAL_ALBEDO_UNIT) uniform sampler2DArray spatterDecalAlbedo;
layout(binding = SPATTER_DECAL_NORMAL_UNIT) uniform sampler2DArray spatterDecalNormal;

// What the decals change of the surface being shaded.
struct SpatterSurface {
    vec3 albedo;     // linear RGB
    vec3 normal;     // world-space unit normal (the shading normal)
    float roughness; // [0, 1]
};

// Normal map of decal `d` blended (Whiteout) into the surface normal `n`, in the decal's frame or,
// with spatterTileInfo.y, in a frame from the surface's position derivatives.
vec3 spatterDecalNormalMap(SpatterForwardDecal d, vec3 detail, vec3 position, vec3 dpdx, vec3 dpdy, vec3 n) {
    vec3 T = d.tangent.xyz, B = d.bitangent.xyz, N = d.normal.xyz;
    if (spatterTileInfo.y != 0) {
        vec3 g = cross(dpdx, dpdy);
        float gl = length(g);
        N = gl > 1e-20 ? g / gl : n;
        if (dot(N, -position) < 0.0) N = -N;
        if (dot(N, n) < 0.2) N = n;
        vec3 t = d.tangent.xyz - N * dot(N, d.tangent.xyz);
        if (dot(t, t) < 1e-8) t = d.bitangent.xyz - N * dot(N, d.bitangent.xyz);
        T = normalize(t);
        B = cross(N, T);
    }
    vec3 base = vec3(dot(n, T), dot(n, B), dot(n, N));
    vec3 r = normalize(vec3(base.xy + detail.xy, base.z * detail.z));
    return normalize(T * r.x + B * r.y + N * r.z);
}

// The point `position` (camera-relative world) in the unit box of decal `index`.
vec3 spatterBoxPosition(uint index, vec3 position) {
    vec4 ph = vec4(position, 1.0);
    return vec3(dot(spatterForwardDecals[index].worldToBox[0], ph), dot(spatterForwardDecals[index].worldToBox[1], ph),
                dot(spatterForwardDecals[index].worldToBox[2], ph));
}

// What decal `d` gives the point at `box` (the shaded point in its unit box; `n` its surface normal,
// `dpdx`, `dpdy` its position's screen derivatives) when the point belongs to the object with decal ID
// `objectId`, faces the decal within its angle and, for wrap-around types, its wrapped footprint lies
// inside the decal's rectangle: its colour and alpha (zero outside the texture's cutout, where the
// texture is not read), and where its textures are read; false otherwise.
struct SpatterDecalLook {
    vec4 colour; // rgb: texture x tint; a: texture alpha x tint alpha x depth fade, in [0, 1]
    vec3 layer;  // texture coordinates and array layer
    vec2 tcdx, tcdy;
};

bool spatterDecalLook(SpatterForwardDecal d, vec3 box, vec3 dpdx, vec3 dpdy, uint objectId, vec3 n,
                      out SpatterDecalLook look) {
    uint flags = d.info.z;
    vec2 uv = box.xy;
    if ((flags & SPATTER_DECAL_WRAP) != 0u) { // Krassnigg's Listing 20.4 in metric decal space
        vec3 halfSize = vec3(d.tangent.w, d.bitangent.w, d.normal.w);
        vec3 q = box * halfSize;
        uv = (q.xy - q.z * vec2(dot(n, d.tangent.xyz), dot(n, d.bitangent.xyz))) / halfSize.xy;
    }
    bool keep = all(lessThanEqual(abs(uv), vec2(1.0))) && objectId == d.info.x &&
                spatterWithinAngle(n, d.normal.xyz, d.axis.xyz, flags, d.params.x);
    if (!keep) return false;

    float f = clamp((1.0 - abs(box.z)) / max(1.0 - spatterForwardParams.x, 1e-4), 0.0, 1.0);
    float fade = 1.0;
    if ((flags & SPATTER_DECAL_FADE_LINEAR) != 0u) fade = f;
    else if ((flags & SPATTER_DECAL_FADE_SMOOTH) != 0u) fade = f * f * (3.0 - 2.0 * f);
    // Texture coordinate derivatives from the position's: this runs in non-uniform control flow.
    look.tcdx = 0.5 * vec2(dot(d.worldToBox[0].xyz, dpdx), dot(d.worldToBox[1].xyz, dpdx));
    look.tcdy = 0.5 * vec2(dot(d.worldToBox[0].xyz, dpdy), dot(d.worldToBox[1].xyz, dpdy));
    look.layer = vec3(uv * 0.5 + 0.5, float(d.info.y));
    vec4 tex = spatterInCutout(look.layer.xy, d.info.w)
                   ? textureGrad(spatterDecalAlbedo, look.layer, look.tcdx, look.tcdy)
                   : vec4(0.0);
    look.colour = vec4(tex.rgb * d.tint.rgb, clamp(tex.a * d.tint.a * fade, 0.0, 1.0));
    return true;
}

// The normal map of the decal whose look is `look`, as a tangent-space unit vector.
vec3 spatterDecalDetail(SpatterDecalLook look) {
    return normalize(textureGrad(spatterDecalNormal, look.layer, look.tcdx, look.tcdy).xyz * 2.0 - 1.0);
}

// Applies decal `d` to `s` at `box` when spatterDecalLook keeps the point; returns whether it did.
bool spatterApplyDecal(SpatterForwardDecal d, vec3 box, vec3 position, vec3 dpdx, vec3 dpdy, uint objectId, vec3 n,
                       inout SpatterSurface s) {
    SpatterDecalLook look;
    if (!spatterDecalLook(d, box, dpdx, dpdy, objectId, n, look)) return false;
    float alpha = look.colour.a;
    if (alpha <= 0.0) return true; // clear: every mix below would keep what is there
    s.albedo = mix(s.albedo, look.colour.rgb, alpha);
    if ((d.info.z & SPATTER_DECAL_NORMAL_MAP) != 0u)
        s.normal = mix(s.normal, spatterDecalNormalMap(d, spatterDecalDetail(look), position, dpdx, dpdy, n), alpha);
    if ((d.info.z & SPATTER_DECAL_ROUGHNESS) != 0u) s.roughness = mix(s.roughness, d.params.y, alpha);
    return true;
}

#ifndef SPATTER_FORWARD_HELPERS_ONLY // the projector's compute resolve takes the helpers above alone
// Applies the decals of the pixel at `fragCoord` (gl_FragCoord.xy) to `s` and returns how many changed
// it (0: none; a coverage view shows > 0). `position`: the shaded point in camera-relative world space
// (world position minus the eye given to bin()); `objectId`: the object's 8-bit decal ID (0 for static
// geometry), as given to setObjects. Call it in uniform control flow: it takes derivatives.
int spatterApplyForwardDecals(vec2 fragCoord, vec3 position, uint objectId, inout SpatterSurface s) {
    vec3 dpdx = dFdx(position), dpdy = dFdy(position);
    ivec2 p = ivec2(floor(fragCoord)) - spatterTileGrid.xy;
    if (p.x < 0 || p.y < 0) return 0;
    ivec2 t = p / spatterTileInfo.x;
    if (t.x >= spatterTileGrid.z || t.y >= spatterTileGrid.w) return 0;
    uvec2 run = spatterTiles[t.y * spatterTileGrid.z + t.x];
    vec3 n = s.normal; // every decal tests the surface, not the decals before it
    int changed = 0;
    for (uint k = 0u; k < run.y; ++k) {
        uint index = spatterTileItems[run.x + k];
        vec3 box = spatterBoxPosition(index, position); // most candidates end here: only the box is read
        if (!all(lessThanEqual(abs(box), vec3(1.0)))) continue;
        if (spatterApplyDecal(spatterForwardDecals[index], box, position, dpdx, dpdy, objectId, n, s)) ++changed;
    }
    if (changed > 0) s.normal = normalize(s.normal);
    return changed;
}
#endif
