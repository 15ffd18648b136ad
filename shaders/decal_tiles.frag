// Tiled decal resolve: the deferred paths' decals applied by one pass over the screen tiles that have
// decals (decal_tiles.vert) instead of a box per decal. The forward path's binning
// (DecalProjector::bin) has sorted the visible decals into the tiles; each pixel reads the host's
// G-buffer once, runs through its tile's decals in drawing order with the same tests and the same
// blending as decal.frag, and writes once what all of them made of it. Blending a decal over another, c' = mix(c, decal, a), composes: after decals 1..k the pixel is
//   c * T + S,  T = prod(1 - a_i),  S = sum(decal_i * a_i * prod_{j > i}(1 - a_j)),
// so one output (S / (1 - T), 1 - T) through the box pass's blend state (or the DBuffer's) gives what
// the boxes would have given one by one. Normals are read where they are written: each pixel reads
// and writes only its own texel, once, after a texture barrier, so no copy is taken.
#include "projector.glsl"
#include "decal_flags.glsl"
#include "forward_data.glsl"

layout(binding = 0) uniform sampler2D s_depth;
layout(binding = 1) uniform sampler2D s_normal;
layout(binding = 2) uniform usampler2D s_ids;
layout(binding = 3) uniform sampler2DArray s_decalAlbedo;
layout(binding = 4) uniform sampler2DArray s_decalNormal;

#if defined(COVERAGE)
layout(location = 0) out vec4 o_coverage;
#elif defined(ROUGHNESS_ALPHA)
layout(location = 0, index = 0) out vec4 o_roughness; // a: the composed roughness, S
layout(location = 0, index = 1) out vec4 o_weight;    // a: 1 - T
#else
layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_material;
#endif

// What the pixel's decals add to each target (rgb or x: S) and how much of what was there shows
// through (a or y: T).
struct Layer {
    vec4 albedo;
    vec4 normal;
    vec2 roughness;
};

void over(inout vec4 acc, vec3 value, float alpha) {
    acc = vec4(acc.rgb * (1.0 - alpha) + value * alpha, acc.a * (1.0 - alpha));
}

void over(inout vec2 acc, float value, float alpha) {
    acc = vec2(acc.x * (1.0 - alpha) + value * alpha, acc.y * (1.0 - alpha));
}

// The blend-state output that turns `dst` into dst * T + S.
vec4 composed(vec4 acc) {
    float a = 1.0 - acc.a;
    return a > 0.0 ? vec4(acc.rgb / a, a) : vec4(0.0);
}

// The tile run of the pixel, or an empty one outside the grid.
uvec2 tileRun(ivec2 pixel) {
    ivec2 p = pixel - spatterTileGrid.xy;
    if (p.x < 0 || p.y < 0) return uvec2(0u);
    ivec2 t = p / spatterTileInfo.x;
    if (t.x >= spatterTileGrid.z || t.y >= spatterTileGrid.w) return uvec2(0u);
    return spatterTiles[t.y * spatterTileGrid.z + t.x];
}

// The decal's normal map blended (Whiteout) into `n`, in its frame or (DEPTH_FRAME) in one from the
// surface's position derivatives.
vec3 mappedNormal(SpatterForwardDecal d, vec3 detail, vec3 p, vec3 dpx, vec3 dpy, vec3 n) {
    vec3 T = d.tangent.xyz, B = d.bitangent.xyz, N = d.normal.xyz;
#ifdef DEPTH_FRAME
    vec3 g = cross(dpx, dpy);
    float gl = length(g);
    N = gl > 1e-20 ? g / gl : n;
    if (dot(N, -p) < 0.0) N = -N;
    if (dot(N, n) < 0.2) N = n; // depth edge: the derivatives straddle two surfaces
    vec3 t = d.tangent.xyz - N * dot(N, d.tangent.xyz);
    if (dot(t, t) < 1e-8) t = d.bitangent.xyz - N * dot(N, d.bitangent.xyz);
    T = normalize(t);
    B = cross(N, T);
#endif
    vec3 base = vec3(dot(n, T), dot(n, B), dot(n, N));
    vec3 r = normalize(vec3(base.xy + detail.xy, base.z * detail.z));
    return normalize(T * r.x + B * r.y + N * r.z);
}

// The texture position in [-1, 1]^2 of the point at `box` with normal `n`: the box's x and y, or for a
// wrap-around decal (Krassnigg's Listing 20.4 in metric decal space) pushed outward by the surface's
// slope relative to the decal plane.
vec2 textureUv(SpatterForwardDecal d, vec3 box, vec3 n) {
#ifdef WRAP
    if ((d.info.z & SPATTER_DECAL_WRAP) != 0u) {
        vec3 halfSize = vec3(d.tangent.w, d.bitangent.w, d.normal.w);
        vec3 q = box * halfSize;
        return (q.xy - q.z * vec2(dot(n, d.tangent.xyz), dot(n, d.bitangent.xyz))) / halfSize.xy;
    }
#endif
    return box.xy;
}

// Whether decal `d` keeps a point inside its box with texture position `uv`, normal `n` and object
// ID `id`.
bool keeps(SpatterForwardDecal d, vec2 uv, vec3 n, uint id) {
    bool keep = all(lessThanEqual(abs(uv), vec2(1.0)));
#ifdef IDS
    keep = keep && id == d.info.x;
#endif
#ifndef NO_ANGLE
    keep = keep && dot(n, d.normal.xyz) >= d.params.x;
#endif
    return keep;
}

// The point's neighbours across its 2x2 quad, as the boxes' derivatives see them: their positions'
// and normals' differences (dFdx and dFdy of the position and of the normal).
struct Neighbours {
    vec3 dpx, dpy, dnx, dny;
};

// Texture coordinate derivatives: for a wrap-around decal the difference of the texture position
// between the point and its neighbour across the quad (the wrap moves it with the normal); else
// the position's derivatives carried into the box (exact, the box being linear).
void textureDerivatives(SpatterForwardDecal d, vec3 box, vec2 uv, vec3 n, Neighbours q, out vec2 tcdx,
                        out vec2 tcdy) {
    vec3 bx = vec3(dot(d.worldToBox[0].xyz, q.dpx), dot(d.worldToBox[1].xyz, q.dpx), dot(d.worldToBox[2].xyz, q.dpx));
    vec3 by = vec3(dot(d.worldToBox[0].xyz, q.dpy), dot(d.worldToBox[1].xyz, q.dpy), dot(d.worldToBox[2].xyz, q.dpy));
    tcdx = 0.5 * bx.xy;
    tcdy = 0.5 * by.xy;
#ifdef WRAP
    if ((d.info.z & SPATTER_DECAL_WRAP) != 0u) {
        bool left = (int(gl_FragCoord.x) & 1) == 0, bottom = (int(gl_FragCoord.y) & 1) == 0;
        tcdx = 0.5 * (left ? textureUv(d, box + bx, n + q.dnx) - uv : uv - textureUv(d, box - bx, n - q.dnx));
        tcdy = 0.5 * (bottom ? textureUv(d, box + by, n + q.dny) - uv : uv - textureUv(d, box - by, n - q.dny));
    }
#endif
}

// Blends decal `d` into `layer` at `box` with texture position `uv`.
void blend(SpatterForwardDecal d, vec3 box, vec2 uv, vec3 p, vec3 n, Neighbours q, inout Layer layer) {
    uint flags = d.info.z;
    float fade = 1.0;
#ifdef FADE
    float f = clamp((1.0 - abs(box.z)) / max(1.0 - u_params.x, 1e-4), 0.0, 1.0);
    if ((flags & SPATTER_DECAL_FADE_LINEAR) != 0u) fade = f;
    else if ((flags & SPATTER_DECAL_FADE_SMOOTH) != 0u) fade = f * f * (3.0 - 2.0 * f);
#endif
    vec2 tcdx, tcdy;
    textureDerivatives(d, box, uv, n, q, tcdx, tcdy);
    vec3 coord = vec3(uv * 0.5 + 0.5, float(d.info.y));
    vec4 tex = textureGrad(s_decalAlbedo, coord, tcdx, tcdy);
    float alpha = clamp(tex.a * d.tint.a * fade, 0.0, 1.0);
    if ((flags & SPATTER_DECAL_ROUGHNESS) != 0u) over(layer.roughness, d.params.y, alpha);
#ifndef ROUGHNESS_ALPHA
    over(layer.albedo, tex.rgb * d.tint.rgb, alpha);
#ifdef NORMAL_MAP
    if ((flags & SPATTER_DECAL_NORMAL_MAP) != 0u) {
        vec3 detail = normalize(textureGrad(s_decalNormal, coord, tcdx, tcdy).xyz * 2.0 - 1.0);
        over(layer.normal, encodeHostNormal(mappedNormal(d, detail, p, q.dpx, q.dpy, n)).xyz, alpha);
    }
#endif
#endif
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(s_depth, pixel, 0).r;
    bool surface = !isBackground(depth);
#ifdef DEPTH_LINEAR
    vec3 p = hostPosition(gl_FragCoord.xy, surface ? depth : 1.0);
#else
    vec3 p = hostPosition(gl_FragCoord.xy, surface ? depth : 0.5);
#endif
    // Derivatives first, in uniform control flow.
    Neighbours q;
    q.dpx = dFdx(p);
    q.dpy = dFdy(p);
#ifdef NO_NORMALS
    vec3 geometric = cross(q.dpx, q.dpy);
    vec3 n = dot(geometric, geometric) > 1e-30 ? normalize(geometric) : normalize(-p);
    if (dot(n, -p) < 0.0) n = -n;
#else
    vec3 n = decodeHostNormal(texelFetch(s_normal, pixel, 0));
#endif
    q.dnx = dFdx(n);
    q.dny = dFdy(n);
    uvec2 run = tileRun(pixel);
    if (!surface || run.y == 0u) discard;
    uint id = texelFetch(s_ids, pixel, 0).r;

    Layer layer = Layer(vec4(0.0, 0.0, 0.0, 1.0), vec4(0.0, 0.0, 0.0, 1.0), vec2(0.0, 1.0));
    bool any = false;
    vec4 ph = vec4(p, 1.0);
    for (uint k = 0u; k < run.y; ++k) {
        uint index = spatterTileItems[run.x + k];
        vec3 box = vec3(dot(spatterForwardDecals[index].worldToBox[0], ph),
                        dot(spatterForwardDecals[index].worldToBox[1], ph),
                        dot(spatterForwardDecals[index].worldToBox[2], ph));
        if (!all(lessThanEqual(abs(box), vec3(1.0)))) continue; // most candidates end here
        SpatterForwardDecal d = spatterForwardDecals[index];
        vec2 uv = textureUv(d, box, n);
        if (!keeps(d, uv, n, id)) continue;
        any = true;
#ifndef COVERAGE
        blend(d, box, uv, p, n, q, layer);
#endif
    }
    if (!any) discard;
#if defined(COVERAGE)
    o_coverage = vec4(1.0);
#elif defined(ROUGHNESS_ALPHA)
    o_roughness = vec4(0.0, 0.0, 0.0, layer.roughness.x);
    o_weight = vec4(0.0, 0.0, 0.0, 1.0 - layer.roughness.y);
#else
    o_albedo = composed(layer.albedo);
    o_normal = composed(layer.normal);
    o_material = composed(vec4(vec3(layer.roughness.x), layer.roughness.y));
#endif
}
