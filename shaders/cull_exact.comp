// GPU culling, pass 3 (GpuCulling): invocations striding over the candidates cull.comp listed
// (work groups the CPU dispatches directly, sized by an earlier frame's counts, so that it need not
// read this frame's). It tests each box corner by corner against the view, as DecalBatch::cull does
// on the CPU, with margins that keep float rounding from culling a box the CPU would keep, and, with
// a depth pyramid of the host's frame (DepthPyramid), culls the boxes hidden behind the scene. A
// visible place sets its class bit and counts in its group and in the indirect draw.
#include "projector.glsl"
#include "cull_layout.glsl"

const uint kCandidateGroup = 64u;
layout(local_size_x = kCandidateGroup) in;
layout(location = 0) uniform uint u_groups; // of the draw order
layout(location = 1) uniform vec4 u_camera; // y: 1 reversed Z; z: 1 clip depth -1..1
// x: the depth pyramid's levels (0: no occlusion test); y: 0 window depth standard Z, 1 reversed Z,
// 2 view distance; z, w: its level 0's size.
layout(location = 2) uniform ivec4 u_occlusion;
layout(binding = 0) uniform sampler2D s_pyramid;
const int kPyramidTexelPixels = 4; // a level-0 texel's pixels a side (depth_pyramid.comp)

layout(std430, binding = 0) coherent buffer Classes {
    uint classBits[];
};
layout(std430, binding = 7) buffer Candidates {
    uint candidates[]; // places; each left holding its decal's index (cull.comp)
};

shared uint sVisible, sOccluded;

const uint kCulled = 0u, kVisible = 1u, kOccluded = 2u;

// The box's eight corners in clip space.
void boxCorners(DecalData d, ProjectorObject o, out vec4 corners[8]) {
    for (int c = 0; c < 8; ++c) {
        vec4 local = vec4((c & 1) != 0 ? 1.0 : -1.0, (c & 2) != 0 ? 1.0 : -1.0, (c & 4) != 0 ? 1.0 : -1.0, 1.0);
        vec3 p = vec3(dot(d.boxToObject[0], local), dot(d.boxToObject[1], local), dot(d.boxToObject[2], local));
        corners[c] = u_viewProj * (o.model * vec4(p, 1.0));
    }
}

// Whether the box, corner by corner in clip space, lies beyond one of the view's planes.
bool outsideFrustum(vec4 corners[8]) {
    int beyond[6] = int[6](0, 0, 0, 0, 0, 0);
    bool reversed = u_camera.y != 0.0;
    for (int c = 0; c < 8; ++c) {
        vec4 clip = corners[c];
        float w = clip.w, slack = 1e-4 * abs(w) + 1e-30;
        float low = u_camera.z != 0.0 ? -w : 0.0;
        beyond[0] += clip.x < -w - slack ? 1 : 0;
        beyond[1] += clip.x > w + slack ? 1 : 0;
        beyond[2] += clip.y < -w - slack ? 1 : 0;
        beyond[3] += clip.y > w + slack ? 1 : 0;
        beyond[4] += (reversed ? clip.z > w + slack : clip.z < low - slack) ? 1 : 0;
        beyond[5] += (reversed ? clip.z < low - slack : clip.z > w + slack) ? 1 : 0;
    }
    for (int k = 0; k < 6; ++k)
        if (beyond[k] == 8) return true;
    return false;
}

// How far the clip-space point lies, in the depth pyramid's farness (depth_pyramid.comp).
float farness(vec4 clip) {
    if (u_occlusion.y == 2) return clip.w;
    float z = clip.z / clip.w;
    if (u_camera.z != 0.0) z = z * 0.5 + 0.5;
    return u_occlusion.y == 1 ? -z : z;
}

// Whether the box lies wholly beyond the scene: its nearest point farther than the farthest surface
// of every pyramid texel under its screen rectangle (a box that reaches behind the eye is not tested).
bool hidden(vec4 corners[8]) {
    vec2 lo = vec2(1e30), hi = vec2(-1e30);
    float near = 1e30;
    for (int c = 0; c < 8; ++c) {
        vec4 clip = corners[c];
        if (!(clip.w > 1e-6)) return false;
        vec2 ndc = clip.xy / clip.w;
        lo = min(lo, ndc);
        hi = max(hi, ndc);
        near = min(near, farness(clip));
    }
    // Level-0 texels (kPyramidTexelPixels a side) under the rectangle, a pixel wider for rounding.
    vec2 pixels = 1.0 / u_viewport.zw;
    vec2 a = clamp((lo * 0.5 + 0.5) * pixels - 1.0, vec2(0.0), pixels - 1.0);
    vec2 b = clamp((hi * 0.5 + 0.5) * pixels + 1.0, vec2(0.0), pixels - 1.0);
    ivec2 t0 = ivec2(a) / kPyramidTexelPixels, t1 = ivec2(b) / kPyramidTexelPixels;
    int extent = max(t1.x - t0.x, t1.y - t0.y);
    int level = min(extent == 0 ? 0 : findMSB(extent) + 1, u_occlusion.x - 1);
    t0 >>= level;
    t1 >>= level;
    float far = -1e30;
    for (int y = t0.y; y <= t1.y; ++y)
        for (int x = t0.x; x <= t1.x; ++x)
            far = max(far, texelFetch(s_pyramid, ivec2(x, y), level).r);
    return near > far + 1e-5 * abs(far) + 1e-30;
}

// Whether decal `entry` is drawn (kVisible), out of view (kCulled) or hidden behind the scene
// (kOccluded).
uint test(uint entry) {
    DecalRecord r = decalRecord(entry);
    ProjectorObject o = objects[r.info.x];
    vec4 corners[8];
    boxCorners(unpackDecal(r), o, corners);
    if (outsideFrustum(corners)) return kCulled;
    if (u_occlusion.x > 0 && hidden(corners)) return kOccluded;
    return kVisible;
}

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        sVisible = 0u;
        sOccluded = 0u;
    }
    barrier();
    uint stride = gl_NumWorkGroups.x * kCandidateGroup, count = candidateCount;
    for (uint i = gl_GlobalInvocationID.x; i < count; i += stride) {
        uint place = candidates[i], entry = drawOrder[place];
        candidates[i] = entry;
        uint c = test(entry);
        if (c == kVisible) {
            atomicAdd(sVisible, 1u);
            atomicOr(classBits[place / 32u], 1u << (place % 32u));
            uint group = place / kGroupPlaces;
            if (u_groups > kBlockGroups) // with one block the scatter reads no block's sum
                atomicAdd(groupData[u_groups + group / kBlockGroups], 1u);
            atomicAdd(groupData[group], 1u);
        } else if (c == kOccluded) {
            atomicAdd(sOccluded, 1u);
        }
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        if (sVisible != 0u) atomicAdd(draw.instanceCount, sVisible);
        if (sOccluded != 0u) atomicAdd(occludedCount, sOccluded);
    }
}
