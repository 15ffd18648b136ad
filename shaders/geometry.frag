// Geometry pass: fills the G-buffer. Surfaces are two-sided: a back face gets the reversed normal.
// Objects with texture-space decals (info.z) lay their decal texture over the material: albedo is
// premultiplied with coverage in alpha, the normal layer holds the decal's normal in the surface's
// tangent frame (premultiplied by its own coverage), so both follow any deformation of the mesh; the
// coverage target gets 1 where that layer shows.
#include "common.glsl"

layout(location = 0) uniform uint u_object;
layout(location = 1) uniform uint u_material;
layout(location = 3) uniform uint u_faceNormals; // 1: the G-buffer has the face normal target

layout(binding = 0) uniform sampler2D s_baseColor;
layout(binding = 1) uniform sampler2D s_normalMap;
layout(binding = 2) uniform sampler2D s_decalLayerAlbedo;
layout(binding = 3) uniform sampler2D s_decalLayerNormal;

in vec3 v_normal;
in vec2 v_uv;
in vec4 v_tangent;
in vec3 v_position;

layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_material;
layout(location = 3) out uint o_id;
layout(location = 4) out vec4 o_coverage;
layout(location = 5) out vec4 o_faceNormal; // the triangle's own normal, from the position's slopes

void main() {
    ObjectData o = objects[u_object];
    MaterialData m = materials[u_material];
    vec4 base = m.baseColor;
    if (m.flags.x != 0u) base *= texture(s_baseColor, v_uv);

    bool front = gl_FrontFacing != (o.info.y != 0u);
    vec3 n = normalize(v_normal);
    if (!front) n = -n;
    if (m.flags.y != 0u) {
        vec3 t = v_tangent.xyz - n * dot(n, v_tangent.xyz);
        float tl = length(t);
        if (tl > 1e-6) {
            t /= tl;
            vec3 b = cross(n, t) * (v_tangent.w < 0.0 ? -1.0 : 1.0);
            vec3 tn = texture(s_normalMap, v_uv).xyz * 2.0 - 1.0;
            tn.xy *= m.params.z;
            vec3 mapped = t * tn.x + b * tn.y + n * max(tn.z, 1e-3);
            n = normalize(mapped);
        }
    }

    float decalCoverage = 0.0;
    if (o.info.z != 0u) {
        vec4 layer = texture(s_decalLayerAlbedo, v_uv);
        decalCoverage = layer.a > 0.0 ? 1.0 : 0.0;
        base.rgb = base.rgb * (1.0 - layer.a) + layer.rgb;
        vec4 ln = texture(s_decalLayerNormal, v_uv);
        if (ln.a > 1e-3) {
            vec3 ng = normalize(v_normal);
            if (!front) ng = -ng;
            vec3 t = v_tangent.xyz - ng * dot(ng, v_tangent.xyz);
            if (dot(t, t) < 1e-12) t = abs(ng.x) < 0.9 ? cross(ng, vec3(1, 0, 0)) : cross(ng, vec3(0, 1, 0));
            t = normalize(t);
            vec3 b = cross(ng, t) * (v_tangent.w < 0.0 ? -1.0 : 1.0);
            vec3 tn = ln.rgb / ln.a * 2.0 - 1.0;
            vec3 mapped = normalize(t * tn.x + b * tn.y + ng * tn.z);
            n = normalize(mix(n, mapped, clamp(ln.a, 0.0, 1.0)));
        }
    }

    o_albedo = base;
    o_normal = vec4(encodeNormal(n), 0.0, 0.0);
    o_material = vec4(clamp(m.params.x, 0.02, 1.0), clamp(m.params.y, 0.0, 1.0), 0.0, 0.0);
    o_id = o.info.x;
    o_coverage = vec4(decalCoverage); // texture-space decals; the decal pass adds the projected ones
    if (u_faceNormals != 0u) {
        vec3 face = cross(dFdx(v_position), dFdy(v_position));
        o_faceNormal = vec4(dot(face, face) > 0.0 ? encodeNormal(normalize(face)) : vec2(0.0), 0.0, 0.0);
    }
}
