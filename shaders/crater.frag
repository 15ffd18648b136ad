// Volumetric decals, crater: writes the hole into the G-buffer. The material is the surface's,
// read from a copy of the G-buffer taken before the pass at the surface point above this crater
// point (its projection along the decal axis onto the rim plane), so the wall's texture continues
// into the hole; it darkens and roughens with depth. The normal is the crater's. The coverage view
// counts the hole as covered.
#include "common.glsl"
#include "crater.glsl"

layout(binding = 1) uniform sampler2D s_albedoCopy;
layout(binding = 3) uniform sampler2D s_materialCopy;

in vec3 v_world;
in vec3 v_normal;
in float v_depth;
flat in uint v_crater;

layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_material;
layout(location = 4) out vec4 o_coverage;

void main() {
    Crater c = craters[v_crater];
    vec3 above = v_world - c.plane.xyz * (dot(v_world, c.plane.xyz) - c.plane.w);
    vec4 clip = u_viewProj * vec4(above, 1.0);
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    if (clip.w > 0.0) {
        vec2 window = (clip.xy / clip.w * 0.5 + 0.5) * u_viewport.xy;
        pixel = clamp(ivec2(window), ivec2(0), ivec2(u_viewport.xy) - 1);
    }
    vec4 base = texelFetch(s_albedoCopy, pixel, 0);
    vec2 material = texelFetch(s_materialCopy, pixel, 0).rg;
    float t = clamp(v_depth / max(c.depth, 1e-6), 0.0, 1.0);
    o_albedo = vec4(base.rgb * mix(0.85, 0.45, t), base.a);
    o_normal = vec4(encodeNormal(normalize(v_normal)), 0.0, 0.0);
    o_material = vec4(clamp(material.r + 0.25 * t, 0.02, 1.0), material.g, 0.0, 0.0);
    o_coverage = vec4(1.0);
}
