// Texture-space decals: seam dilation. Texels the UV mask marks as covered pass through; an
// uncovered texel next to covered ones (8-neighbourhood) takes their average, so bilinear samples
// at the border of a UV island never blend with empty texels.
layout(binding = 0) uniform sampler2D s_albedo;
layout(binding = 1) uniform sampler2D s_normal;
layout(binding = 2) uniform sampler2D s_mask;

layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    if (texelFetch(s_mask, p, 0).r > 0.5) {
        o_albedo = texelFetch(s_albedo, p, 0);
        o_normal = texelFetch(s_normal, p, 0);
        return;
    }
    ivec2 size = textureSize(s_mask, 0);
    vec4 albedo = vec4(0.0), normal = vec4(0.0);
    float weight = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = p + ivec2(dx, dy);
            if ((dx == 0 && dy == 0) || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
            if (texelFetch(s_mask, q, 0).r > 0.5) {
                albedo += texelFetch(s_albedo, q, 0);
                normal += texelFetch(s_normal, q, 0);
                weight += 1.0;
            }
        }
    o_albedo = weight > 0.0 ? albedo / weight : vec4(0.0);
    o_normal = weight > 0.0 ? normal / weight : vec4(0.0);
}
