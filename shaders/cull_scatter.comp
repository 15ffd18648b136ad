// GPU culling, pass 3 of 3 (GpuCulling): one work group per group of the draw order, dispatched
// directly (a group without a visible place returns at once: cheaper than listing the groups that
// have one and dispatching over that list). It finds the group's first place in the visible list, the visible places of the groups before it (those of the blocks before its block,
// and of its block's groups before it), and writes its visible decals' indices there in draw order:
// an invocation per 32-place word of the group's class bits, from the word's first place in the list
// (the visible places of the words before it) on. The first work group also writes the counts the
// CPU reads back.
#include "cull_layout.glsl"

layout(local_size_x = 64) in;
layout(location = 0) uniform uint u_groups;

layout(std430, binding = 0) readonly buffer Classes {
    uint classBits[];
};
layout(std430, binding = 1) writeonly buffer Readback {
    uint readback[4]; // the visible, occluded, invalid and host-drawn counts (GpuCulling::counts_)
};
layout(std430, binding = 7) writeonly buffer VisibleOut {
    uint visibleOut[];
};

const uint kWords = kGroupPlaces / 32u; // of class bits a group
shared uint partial[64];
shared uint words[kWords];

void main() {
    uint t = gl_LocalInvocationIndex;
    if (gl_WorkGroupID.x == 0u && t == 0u)
        readback = uint[4](draw.instanceCount, occludedCount, invalidCount, hostDrawnCount);
    uint group = gl_WorkGroupID.x;
    if (groupData[group] == 0u) return; // the work group's one group has no visible place
    uint block = group / kBlockGroups, sum = 0u; // the visible places of the blocks and groups before
    for (uint b = t; b < block; b += 64u) sum += groupData[u_groups + b];
    for (uint g = block * kBlockGroups + t; g < group; g += 64u) sum += groupData[g];
    partial[t] = sum;
    if (t < kWords) words[t] = classBits[group * kWords + t];
    barrier();
    for (uint stride = 32u; stride > 0u; stride >>= 1) {
        if (t < stride) partial[t] += partial[t + stride];
        barrier();
    }
    if (t >= kWords) return;
    uint bits = words[t], at = partial[0];
    for (uint w = 0u; w < t; ++w) at += uint(bitCount(words[w]));
    for (; bits != 0u; bits &= bits - 1u)
        visibleOut[at++] = drawOrder[group * kGroupPlaces + t * 32u + uint(findLSB(bits))];
}
