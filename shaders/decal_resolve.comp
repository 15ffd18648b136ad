// Compute resolve of the G-buffer blend (ProjectorSettings::deferredResolve): the visible decals are
// binned into screen tiles by the forward path's binning, then one invocation a pixel applies the
// decals of its tile in drawing order with decal.frag's tests and blending, reading each of the host's
// targets once and writing it once (imageLoad, imageStore). Only its own invocation touches a pixel,
// so every decal tests the surface as it was before the pass, as the boxes do through the normal copy.
// Texture derivatives come from the positions of the neighbouring pixels. Albedo is blended in linear
// space (through an RGBA8 view of an sRGB target: ALBEDO_SRGB); normals in the host's encoding, as the
// blend state blends them; roughness in its channel (u_roughnessChannel, -1: none) of its own target
// or, with ROUGHNESS_ALBEDO_ALPHA, in the albedo's alpha. Target formats: NORMALS_RG16F,
// NORMALS_RGBA16F, NORMALS_RGB10A2, else RGBA8; ROUGHNESS_R8, ROUGHNESS_RG8, else RGBA8.
// DBUFFER resolves into the projector's decal buffers instead (dbuffer.glsl: RGB the decals'
// contribution, A how much of the surface shows through), which DecalBuffers::prepare cleared to RGB 0,
// A 1: the targets are then written, not read, and the host's normals are read through s_normal.
#define SPATTER_FORWARD_HELPERS_ONLY // spatterApplyForwardDecals takes derivatives, which compute lacks
#define SPATTER_DECAL_ALBEDO_UNIT 3
#define SPATTER_DECAL_NORMAL_UNIT 4
#include "projector.glsl"
#include "forward.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler2D s_depth;
layout(binding = 2) uniform usampler2D s_ids;
#ifdef DBUFFER
layout(binding = 1) uniform sampler2D s_normal;
#endif

layout(binding = 0, rgba8) uniform restrict image2D i_albedo;
#if defined(NORMALS_RG16F)
layout(binding = 1, rg16f) uniform restrict image2D i_normal;
#elif defined(NORMALS_RGBA16F)
layout(binding = 1, rgba16f) uniform restrict image2D i_normal;
#elif defined(NORMALS_RGB10A2)
layout(binding = 1, rgb10_a2) uniform restrict image2D i_normal;
#else
layout(binding = 1, rgba8) uniform restrict image2D i_normal;
#endif
#if defined(ROUGHNESS_R8)
layout(binding = 2, r8) uniform restrict image2D i_roughness;
#elif defined(ROUGHNESS_RG8)
layout(binding = 2, rg8) uniform restrict image2D i_roughness;
#else
layout(binding = 2, rgba8) uniform restrict image2D i_roughness;
#endif

layout(location = 0) uniform ivec4 u_region;        // the host's viewport: x, y, width, height (pixels)
layout(location = 1) uniform int u_roughnessChannel; // 0..2, or -1: roughness is not written

vec3 toLinear(vec3 c) {
#ifdef ALBEDO_SRGB
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
#else
    return c;
#endif
}

vec3 fromLinear(vec3 c) {
#ifdef ALBEDO_SRGB
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
#else
    return c;
#endif
}

// The change of the surface position from `pixel` (at `p`) to its neighbour `step` away or, where
// that one is nearer in space, to the one on the other side (the smaller step stays on the surface at
// a silhouette); zero where neither lies on a surface inside the viewport.
vec3 positionStep(ivec2 pixel, vec3 p, ivec2 step) {
    vec3 best = vec3(0.0);
    bool found = false;
    for (int side = 1; side >= -1; side -= 2) {
        ivec2 q = pixel + side * step;
        if (any(lessThan(q, u_region.xy)) || any(greaterThanEqual(q, u_region.xy + u_region.zw))) continue;
        float depth = texelFetch(s_depth, q, 0).r;
        if (isBackground(depth)) continue;
        vec3 d = float(side) * (hostPosition(vec2(q) + 0.5, depth) - p);
        if (!found || dot(d, d) < dot(best, best)) best = d;
        found = true;
    }
    return best;
}

// Whether a point at `box` in a decal's unit box lies inside it.
bool inBox(vec3 box) {
    return all(lessThanEqual(abs(box), vec3(1.0)));
}

// What the pixel's decals make of its targets, decal after decal as the blend state would.
struct Targets {
    vec3 albedo;    // linear
    vec4 normal;    // in the host's encoding (DBUFFER: world space, signed)
    float roughness;
#ifdef DBUFFER
    vec3 shows; // how much of the surface's albedo, normal and roughness shows through
#endif
};

// Blends decal `d` into `t` when spatterDecalLook keeps the point (IDS: clipped by the pixel's
// object ID `id`); returns whether it did.
bool blendDecal(SpatterForwardDecal d, vec3 box, vec3 p, vec3 dpdx, vec3 dpdy, vec3 n, uint id, inout Targets t) {
#ifndef IDS
    id = d.info.x; // no ID clipping
#endif
    SpatterDecalLook look;
    if (!spatterDecalLook(d, box, dpdx, dpdy, id, n, look)) return false;
    float alpha = look.colour.a;
    if (alpha <= 0.0) return true; // clear: every mix below would keep what is there
    t.albedo = mix(t.albedo, look.colour.rgb, alpha);
#ifdef DBUFFER
    vec3 covers = vec3(alpha, 0.0, 0.0); // what this decal hides of the surface's albedo, normal, roughness
#endif
#ifdef NORMAL_MAP
    if ((d.info.z & SPATTER_DECAL_NORMAL_MAP) != 0u) {
        vec4 mapped = encodeHostNormal(spatterDecalNormalMap(d, spatterDecalDetail(look), p, dpdx, dpdy, n));
#if defined(NORMAL_WORLD_SIGNED) || defined(NORMAL_WORLD_UNORM) || defined(NORMAL_VIEW_UNORM) || defined(DBUFFER)
        t.normal.xyz = mix(t.normal.xyz, mapped.xyz, alpha);
#else
        t.normal.xy = mix(t.normal.xy, mapped.xy, alpha); // octahedral: the third channel is kept
#endif
#ifdef DBUFFER
        covers.y = alpha;
#endif
    }
#endif
    if ((d.info.z & SPATTER_DECAL_ROUGHNESS) != 0u) {
        t.roughness = mix(t.roughness, d.params.y, alpha);
#ifdef DBUFFER
        covers.z = alpha;
#endif
    }
#ifdef DBUFFER
    t.shows *= 1.0 - covers;
#endif
    return true;
}

void main() {
    ivec2 pixel = u_region.xy + ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, u_region.xy + u_region.zw))) return;
    ivec2 tile = (pixel - spatterTileGrid.xy) / spatterTileInfo.x;
    uvec2 run = spatterTiles[tile.y * spatterTileGrid.z + tile.x];
    if (run.y == 0u) return;
    float depth = texelFetch(s_depth, pixel, 0).r;
    if (isBackground(depth)) return;
    vec3 p = hostPosition(vec2(pixel) + 0.5, depth);
#ifdef SPARSE_TILES
    // Runs of a few decals, most pixels in none of them: a pixel that no box holds stops before its
    // neighbours and targets are read.
    bool held = false;
    for (uint k = 0u; k < run.y && !held; ++k)
        held = inBox(spatterBoxPosition(spatterTileItems[run.x + k], p));
    if (!held) return;
#endif
    vec3 dpdx = positionStep(pixel, p, ivec2(1, 0)), dpdy = positionStep(pixel, p, ivec2(0, 1));
#ifdef DBUFFER
    Targets t = Targets(vec3(0.0), vec4(0.0), 0.0, vec3(1.0));
    vec3 n = decodeHostNormal(texelFetch(s_normal, pixel, 0));
#else
    vec4 albedo = imageLoad(i_albedo, pixel);
    Targets t;
    t.albedo = toLinear(albedo.rgb);
    t.normal = imageLoad(i_normal, pixel);
#ifdef ROUGHNESS_ALBEDO_ALPHA
    t.roughness = albedo.a;
#else
    vec4 material = u_roughnessChannel >= 0 ? imageLoad(i_roughness, pixel) : vec4(0.0);
    t.roughness = u_roughnessChannel >= 0 ? material[u_roughnessChannel] : 0.0;
#endif
    vec3 n = decodeHostNormal(t.normal);
#endif
    uint id = 0u;
#ifdef IDS
    id = texelFetch(s_ids, pixel, 0).r;
#endif
    bool changed = false;
    for (uint k = 0u; k < run.y; ++k) {
        uint index = spatterTileItems[run.x + k];
        vec3 box = spatterBoxPosition(index, p);
        if (!inBox(box)) continue;
        changed = blendDecal(spatterForwardDecals[index], box, p, dpdx, dpdy, n, id, t) || changed;
    }
    if (!changed) return;
#ifdef DBUFFER
    imageStore(i_albedo, pixel, vec4(fromLinear(t.albedo), t.shows.x));
    imageStore(i_roughness, pixel, vec4(vec3(t.roughness), t.shows.z));
#elif defined(ROUGHNESS_ALBEDO_ALPHA)
    imageStore(i_albedo, pixel, vec4(fromLinear(t.albedo), t.roughness));
#else
    imageStore(i_albedo, pixel, vec4(fromLinear(t.albedo), albedo.a));
    if (u_roughnessChannel >= 0) {
        material[u_roughnessChannel] = t.roughness;
        imageStore(i_roughness, pixel, material);
    }
#endif
#ifdef NORMAL_MAP
#ifdef DBUFFER
    imageStore(i_normal, pixel, vec4(t.normal.xyz, t.shows.y));
#else
    imageStore(i_normal, pixel, t.normal);
#endif
#endif
}
