// The depth pyramid of the host's frame for occlusion culling (DepthPyramid): R32F levels of
// "farness", each texel the farthest surface under it, so that a box whose nearest point lies beyond
// the farness of every texel its screen rectangle touches is hidden behind the scene. Farness grows
// with distance whatever the host's convention: window depth as it is (STANDARD_Z), its negation
// (reversed Z), or the view distance (DEPTH_LINEAR, background infinitely far). Level 0 holds the
// farthest of each 4x4 block of the viewport's pixels; every level above, the farthest of 2x2 below.
// Texels past the viewport are infinitely far: they never hide anything.
layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler2D s_depth;
layout(r32f, binding = 0) uniform writeonly image2D u_dst;
layout(r32f, binding = 1) uniform readonly image2D u_src;
layout(location = 0) uniform ivec4 u_viewport; // the host's viewport: x, y, width, height (level 0)
layout(location = 1) uniform int u_level;      // 0: from the depth texture, else from u_src

const float kFar = 3.0e38;
const int kTexelPixels = 4; // a level-0 texel's pixels a side (DepthPyramid.hpp, cull_exact.comp)

float farness(ivec2 pixel) {
    if (pixel.x >= u_viewport.z || pixel.y >= u_viewport.w) return kFar;
    float d = texelFetch(s_depth, u_viewport.xy + pixel, 0).r;
#if defined(DEPTH_LINEAR)
    return d > 0.0 ? d : kFar;
#elif defined(STANDARD_Z)
    return d;
#else
    return -d;
#endif
}

void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(u_dst);
    if (t.x >= size.x || t.y >= size.y) return;
    float f;
    if (u_level == 0) {
        f = -kFar;
        for (int y = 0; y < kTexelPixels; ++y)
            for (int x = 0; x < kTexelPixels; ++x)
                f = max(f, farness(kTexelPixels * t + ivec2(x, y)));
    } else {
        f = max(max(imageLoad(u_src, 2 * t).r, imageLoad(u_src, 2 * t + ivec2(1, 0)).r),
                max(imageLoad(u_src, 2 * t + ivec2(0, 1)).r, imageLoad(u_src, 2 * t + ivec2(1, 1)).r));
    }
    imageStore(u_dst, t, vec4(f));
}
