// Debug views of the G-buffer (see render/include/spatter/render/View.hpp). Albedo is sRGB-encoded;
// the others are written as raw values.
#include "common.glsl"
#include "gbuffer.glsl"

layout(location = 0) uniform int u_viewMode; // 1 albedo, 2 normal, 3 depth, 4 ids, 5 coverage

in vec2 v_uv;
layout(location = 0) out vec4 o_color;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(s_depth, pixel, 0).r;
    bool background = depth <= 0.0;
    vec3 c = vec3(0.0);
    if (u_viewMode == 1) {
        c = linearToSrgb(texelFetch(s_albedo, pixel, 0).rgb);
    } else if (u_viewMode == 2) {
        if (!background) c = decodeNormal(texelFetch(s_normal, pixel, 0).rg) * 0.5 + 0.5;
    } else if (u_viewMode == 3) {
        if (!background) {
            float dist = length(viewPositionFromDepth(gl_FragCoord.xy, depth));
            float range = max(u_depthRange.y - u_depthRange.x, 1e-6);
            c = vec3(clamp(1.0 - (dist - u_depthRange.x) / range, 0.0, 1.0));
        }
    } else if (u_viewMode == 4) {
        if (!background) c = idColor(texelFetch(s_ids, pixel, 0).r);
    } else if (u_viewMode == 5) {
        c = vec3(texelFetch(s_coverage, pixel, 0).r > 0.5 ? 1.0 : 0.0);
    }
    o_color = vec4(c, 1.0);
}
