// Lighting pass: one directional light with GGX specular (height-correlated Smith visibility,
// Schlick Fresnel), hemispherical ambient, ACES tone mapping, sRGB encoding.
#include "common.glsl"
#include "gbuffer.glsl"

in vec2 v_uv;
layout(location = 0) out vec4 o_color;

const float PI = 3.14159265358979;

vec3 toneMap(vec3 x) {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(s_depth, pixel, 0).r;
    vec3 dir = normalize(mat3(u_invView) * viewPositionFromDepth(gl_FragCoord.xy, 1.0));
    if (depth <= 0.0) {
        vec3 sky = mix(u_groundAmbient.rgb, u_skyAmbient.rgb * 1.6, smoothstep(-0.2, 0.4, dir.y));
        o_color = vec4(linearToSrgb(toneMap(sky * u_lightColor.w)), 1.0);
        return;
    }
    vec3 albedo = texelFetch(s_albedo, pixel, 0).rgb;
    vec3 n = decodeNormal(texelFetch(s_normal, pixel, 0).rg);
    vec2 mat = texelFetch(s_material, pixel, 0).rg;
    float rough = clamp(mat.x, 0.04, 1.0);
    float metal = clamp(mat.y, 0.0, 1.0);

    vec3 V = -dir;
    vec3 L = u_lightDirection.xyz;
    vec3 H = normalize(V + L);
    float NdotL = max(dot(n, L), 0.0);
    float NdotV = max(dot(n, V), 1e-4);
    float NdotH = max(dot(n, H), 0.0);
    float VdotH = max(dot(V, H), 0.0);

    float a = rough * rough;
    float a2 = a * a;
    float dd = NdotH * NdotH * (a2 - 1.0) + 1.0;
    float D = a2 / (PI * dd * dd);
    float vis = 0.5 / (NdotL * sqrt(NdotV * NdotV * (1.0 - a2) + a2) + NdotV * sqrt(NdotL * NdotL * (1.0 - a2) + a2) + 1e-7);
    vec3 F0 = mix(vec3(0.04), albedo, metal);
    vec3 F = F0 + (1.0 - F0) * pow(1.0 - VdotH, 5.0);

    vec3 radiance = u_lightColor.rgb * u_lightDirection.w;
    vec3 diffuse = (1.0 - F) * (1.0 - metal) * albedo / PI;
    vec3 color = (diffuse + D * vis * F) * radiance * NdotL;

    vec3 ambient = mix(u_groundAmbient.rgb, u_skyAmbient.rgb, n.y * 0.5 + 0.5);
    vec3 Fa = F0 + (max(vec3(1.0 - rough), F0) - F0) * pow(1.0 - NdotV, 5.0);
    color += ambient * (albedo * (1.0 - metal) + Fa * (1.0 - 0.7 * rough));

    o_color = vec4(linearToSrgb(toneMap(color * u_lightColor.w)), 1.0);
}
