// Decal pass (Krassnigg, "A Deferred Decal Rendering Technique"): the box is a window onto the
// host's G-buffer. Each fragment reads the host's depth, rebuilds the camera-relative position (in
// the host's conventions, projector.glsl), moves it into the unit box and keeps it only when
//   - it lies inside the box,
//   - the pixel's object decal ID equals the decal's (IDS; left out when the scene has no dynamic
//     objects or ID clipping is switched off),
//   - the pixel's normal is within the decal's largest angle of both its normal and the axis its box
//     is projected along (depth_axis.glsl; NO_ANGLE: the angle rejection is switched off),
//   - (WRAP) the footprint, with texture coordinates pushed outward by the surface slope
//     (Listing 20.4), lies inside the decal's rectangle.
// COVERAGE writes 1 for every such pixel (location 0, the host's coverage texture); otherwise the decal's albedo is blended by its alpha
// (texture alpha x tint x opacity x depth fade), its normal map is blended into the G-buffer normal
// (Whiteout) in the decal frame (or, with DEPTH_FRAME, in a per-pixel frame from depth
// derivatives), and roughness is replaced where the type sets one. Normals are read from a copy of
// the G-buffer taken before the pass, so every decal tests the surface, not other decals. With
// NO_NORMALS (the host has none) the surface normal comes from depth derivatives and nothing writes
// normals. Roughness goes to every colour channel of location 2; the colour mask picks the host's.
// ROUGHNESS_ALPHA writes only roughness, into an alpha channel (a pass of its own, DecalProjector).
// DBUFFER writes the same outputs into the projector's decal buffers (normals world space, signed);
// their blend state keeps, in alpha, how much of the surface shows through (dbuffer.glsl).
#include "projector.glsl"
#include "depth_axis.glsl"

layout(binding = 0) uniform sampler2D s_depth;
layout(binding = 1) uniform sampler2D s_normal;
layout(binding = 2) uniform usampler2D s_ids;
layout(binding = 3) uniform sampler2DArray s_decalAlbedo;
layout(binding = 4) uniform sampler2DArray s_decalNormal;

flat in vec4 v_worldToBox[3];
flat in vec4 v_tangent;
flat in vec4 v_bitangent;
flat in vec4 v_normal;
flat in vec3 v_axis;
flat in vec4 v_tint;
flat in uvec4 v_info;
flat in vec2 v_params;

#if defined(COVERAGE)
layout(location = 0) out vec4 o_coverage;
#elif defined(ROUGHNESS_ALPHA)
// Roughness in an alpha channel, its own pass: dual-source blending weighs it by the decal's alpha.
layout(location = 0, index = 0) out vec4 o_roughness; // a: roughness * weight
layout(location = 0, index = 1) out vec4 o_weight;    // a: weight
#else
layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_material;
#endif

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(s_depth, pixel, 0).r;
    bool surface = !isBackground(depth);
#ifdef DEPTH_LINEAR
    vec3 p = hostPosition(gl_FragCoord.xy, surface ? depth : 1.0);
#else
    vec3 p = hostPosition(gl_FragCoord.xy, surface ? depth : 0.5);
#endif
    vec4 ph = vec4(p, 1.0);
    vec3 box = vec3(dot(v_worldToBox[0], ph), dot(v_worldToBox[1], ph), dot(v_worldToBox[2], ph));
#ifdef NO_NORMALS
    vec3 geometric = cross(dFdx(p), dFdy(p));
    vec3 n = dot(geometric, geometric) > 1e-30 ? normalize(geometric) : normalize(-p);
    if (dot(n, -p) < 0.0) n = -n;
#else
    vec3 n = decodeHostNormal(texelFetch(s_normal, pixel, 0));
#endif
    uint flags = v_info.z;

    vec2 uv = box.xy;
#ifdef WRAP
    if ((flags & SPATTER_DECAL_WRAP) != 0u) {
        // Listing 20.4 in metric decal space: the slope of the surface relative to the decal plane
        // moves the texture coordinates outward by the distance to the plane.
        vec3 halfSize = vec3(v_tangent.w, v_bitangent.w, v_normal.w);
        vec3 q = box * halfSize;
        vec2 slope = vec2(dot(n, v_tangent.xyz), dot(n, v_bitangent.xyz));
        uv = (q.xy - q.z * slope) / halfSize.xy;
    }
#endif
    vec2 tc = uv * 0.5 + 0.5;
#ifndef COVERAGE
    // Derivatives before any discard, while the whole quad still runs.
    vec2 tcdx = dFdx(tc);
    vec2 tcdy = dFdy(tc);
#ifdef DEPTH_FRAME
    vec3 dpx = dFdx(p);
    vec3 dpy = dFdy(p);
#endif
#endif

    bool keep = surface && all(lessThanEqual(abs(box), vec3(1.0))) && all(lessThanEqual(abs(uv), vec2(1.0)));
#ifndef COVERAGE
    keep = keep && spatterInCutout(tc, v_info.w);
#endif
#ifdef IDS
    keep = keep && texelFetch(s_ids, pixel, 0).r == v_info.x;
#endif
#ifndef NO_ANGLE
    keep = keep && spatterWithinAngle(n, v_normal.xyz, v_axis, flags, v_params.x);
#endif
    if (!keep) discard;

#ifdef COVERAGE
    o_coverage = vec4(1.0);
#else
    float fade = 1.0;
#ifdef FADE
    float f = clamp((1.0 - abs(box.z)) / max(1.0 - u_params.x, 1e-4), 0.0, 1.0);
    if ((flags & SPATTER_DECAL_FADE_LINEAR) != 0u) fade = f;
    else if ((flags & SPATTER_DECAL_FADE_SMOOTH) != 0u) fade = f * f * (3.0 - 2.0 * f);
#endif
    vec3 layer = vec3(tc, float(v_info.y));
    vec4 tex = textureGrad(s_decalAlbedo, layer, tcdx, tcdy);
    float alpha = clamp(tex.a * v_tint.a * fade, 0.0, 1.0);
    if (alpha <= 0.0) discard; // clear: every blend would keep what is there
#ifdef ROUGHNESS_ALPHA
    float weight = (flags & SPATTER_DECAL_ROUGHNESS) != 0u ? alpha : 0.0;
    o_roughness = vec4(0.0, 0.0, 0.0, v_params.y * weight);
    o_weight = vec4(0.0, 0.0, 0.0, weight);
#else
    o_albedo = vec4(tex.rgb * v_tint.rgb, alpha);
    o_normal = vec4(0.0);
#ifdef NORMAL_MAP
    if ((flags & SPATTER_DECAL_NORMAL_MAP) != 0u) {
        vec3 detail = normalize(textureGrad(s_decalNormal, layer, tcdx, tcdy).xyz * 2.0 - 1.0);
        vec3 T = v_tangent.xyz;
        vec3 B = v_bitangent.xyz;
        vec3 N = v_normal.xyz;
#ifdef DEPTH_FRAME
        // Per-pixel frame from the depth buffer: the geometric normal of the drawn surface, with the
        // decal's tangent projected into its plane.
        vec3 g = cross(dpx, dpy);
        float gl = length(g);
        N = gl > 1e-20 ? g / gl : n;
        if (dot(N, -p) < 0.0) N = -N;
        if (dot(N, n) < 0.2) N = n; // depth edge: the derivatives straddle two surfaces
        vec3 t = v_tangent.xyz - N * dot(N, v_tangent.xyz);
        if (dot(t, t) < 1e-8) t = v_bitangent.xyz - N * dot(N, v_bitangent.xyz);
        T = normalize(t);
        B = cross(N, T);
#endif
        vec3 base = vec3(dot(n, T), dot(n, B), dot(n, N));
        vec3 r = normalize(vec3(base.xy + detail.xy, base.z * detail.z));
        vec3 blended = normalize(T * r.x + B * r.y + N * r.z);
        o_normal = vec4(encodeHostNormal(blended).xyz, alpha);
    }
#endif
    o_material = vec4(vec3(v_params.y), (flags & SPATTER_DECAL_ROUGHNESS) != 0u ? alpha : 0.0);
#endif
#endif
}
