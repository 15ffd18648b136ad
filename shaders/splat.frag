// Texture-space decals: projects the decal box through the texel's object-space position and
// discards texels outside it (the same inclusion rule as the decal pass: inside the box, normal
// within the type's angle of the decal's normal and of its projection axis, wrapped footprint
// inside the rectangle). Writes the decal's albedo (premultiplied by blending, coverage in alpha)
// and its normal expressed in the surface's tangent frame, so that the geometry pass can apply it
// on the deformed surface.
// MASK writes 1 for every texel a triangle covers (the UV coverage mask).
#include "common.glsl"
#include "depth_axis.glsl"

in vec3 v_position;
in vec3 v_normal;
in vec4 v_tangent;
flat in uint v_decal;

#ifdef MASK
layout(location = 0) out vec4 o_mask;

void main() {
    o_mask = vec4(1.0);
}
#else
layout(binding = 3) uniform sampler2DArray s_decalAlbedo;
layout(binding = 4) uniform sampler2DArray s_decalNormal;

layout(location = 1) uniform float u_fadeStart;

layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;

void main() {
    DecalData d = decalData(v_decal);
    vec4 ph = vec4(v_position, 1.0);
    vec3 box = vec3(dot(d.objectToBox[0], ph), dot(d.objectToBox[1], ph), dot(d.objectToBox[2], ph));
    vec3 n = normalize(v_normal);
    uint flags = d.info.z;

    vec2 uv = box.xy;
    if ((flags & SPATTER_DECAL_WRAP) != 0u) {
        vec3 halfSize = vec3(d.tangent.w, d.bitangent.w, d.normal.w);
        vec3 q = box * halfSize;
        vec2 slope = vec2(dot(n, d.tangent.xyz), dot(n, d.bitangent.xyz));
        uv = (q.xy - q.z * slope) / halfSize.xy;
    }
    vec2 tc = uv * 0.5 + 0.5;
    vec2 tcdx = dFdx(tc);
    vec2 tcdy = dFdy(tc);

    // The projection axis, which only a slanted decal's angle test reads.
    vec3 axis = (flags & SPATTER_DECAL_SLANTED) != 0u
                    ? spatterDepthAxis(d.objectToBox[0].xyz, d.objectToBox[1].xyz, d.normal.xyz)
                    : d.normal.xyz;
    bool keep = all(lessThanEqual(abs(box), vec3(1.0))) && all(lessThanEqual(abs(uv), vec2(1.0))) &&
                spatterInCutout(tc, d.info.w) && spatterWithinAngle(n, d.normal.xyz, axis, flags, d.params.x);
    if (!keep) discard;

    float fade = 1.0;
    float f = clamp((1.0 - abs(box.z)) / max(1.0 - u_fadeStart, 1e-4), 0.0, 1.0);
    if ((flags & SPATTER_DECAL_FADE_LINEAR) != 0u) fade = f;
    else if ((flags & SPATTER_DECAL_FADE_SMOOTH) != 0u) fade = f * f * (3.0 - 2.0 * f);

    vec3 layer = vec3(tc, float(d.info.y));
    vec4 tex = textureGrad(s_decalAlbedo, layer, tcdx, tcdy);
    float alpha = clamp(tex.a * d.tint.a * fade, 0.0, 1.0);
    o_albedo = vec4(tex.rgb * d.tint.rgb, alpha);
    o_normal = vec4(0.0);
    if ((flags & SPATTER_DECAL_NORMAL_MAP) != 0u) {
        vec3 detail = normalize(textureGrad(s_decalNormal, layer, tcdx, tcdy).xyz * 2.0 - 1.0);
        vec3 T = d.tangent.xyz, B = d.bitangent.xyz, N = d.normal.xyz;
        vec3 base = vec3(dot(n, T), dot(n, B), dot(n, N));
        vec3 r = normalize(vec3(base.xy + detail.xy, base.z * detail.z));
        vec3 blended = normalize(T * r.x + B * r.y + N * r.z);
        // The surface's tangent frame, built as the geometry pass builds it.
        vec3 t = v_tangent.xyz - n * dot(n, v_tangent.xyz);
        if (dot(t, t) < 1e-12) t = abs(n.x) < 0.9 ? cross(n, vec3(1, 0, 0)) : cross(n, vec3(0, 1, 0));
        t = normalize(t);
        vec3 b = cross(n, t) * (v_tangent.w < 0.0 ? -1.0 : 1.0);
        vec3 ts = vec3(dot(blended, t), dot(blended, b), dot(blended, n));
        o_normal = vec4(ts * 0.5 + 0.5, alpha);
    }
}
#endif
