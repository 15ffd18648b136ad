// GPU culling, the last pass (GpuCulling): for each group of the draw order with a visible place, its
// first place in the visible list, the visible places of the groups before it (those of the blocks
// before its block, and of its block's groups before it), and its visible decals' indices written
// there in draw order: an invocation per 32-place word of the group's class bits, from the word's
// first place in the list (the visible places of the words before it) on. Dispatched directly, at a
// number of work groups the CPU sizes by an earlier frame's counts (a software rasteriser pays for
// every work group): work group w looks at the groups cull_groups.comp listed (only they can hold a
// visible place; every group where cull.comp tested every group) w, w + W, w + 2 W, ... (W work
// groups), an invocation a group, 64 at a time, and
// writes those that have a visible place one after the other, so that groups in view side by side go
// to different work groups. The first work group also writes the counts the CPU reads back.
#include "cull_layout.glsl"

layout(local_size_x = 64) in;
layout(location = 0) uniform uint u_groups;
layout(location = 1) uniform uint u_every; // 1: cull.comp tested every group, listing none

layout(std430, binding = 0) readonly buffer Classes {
    uint classBits[];
};
layout(std430, binding = 1) writeonly buffer Readback {
    uint readback[5]; // the visible, occluded, invalid and host-drawn counts, the groups tested by place
};
layout(std430, binding = 7) writeonly buffer VisibleOut {
    uint visibleOut[];
};

const uint kWords = kGroupPlaces / 32u; // of class bits a group
shared uint partial[64];
shared uint words[kWords];
shared uint sFound, sGroups[64]; // of the groups looked at in a round, those with a visible place

// Writes the visible decals of `group`, which has one; all the work group's invocations take part.
void writeGroup(uint group, uint t) {
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
    if (t < kWords) {
        uint bits = words[t], at = partial[0];
        for (uint w = 0u; w < t; ++w) at += uint(bitCount(words[w]));
        for (; bits != 0u; bits &= bits - 1u)
            visibleOut[at++] = drawOrder[group * kGroupPlaces + t * 32u + uint(findLSB(bits))];
    }
    barrier(); // the next group reuses the shared arrays
}

void main() {
    uint t = gl_LocalInvocationIndex, w = gl_NumWorkGroups.x;
    if (gl_WorkGroupID.x == 0u && t == 0u)
        readback = uint[5](draw.instanceCount, occludedCount, invalidCount, hostDrawnCount,
                           u_every != 0u ? u_groups - tested.groupsX : tested.groupsX);
    uint listed = u_every != 0u ? u_groups : tested.groupsX, start = listStart(u_groups);
    for (uint first = gl_WorkGroupID.x; first < listed; first += 64u * w) {
        if (t == 0u) sFound = 0u;
        barrier();
        uint k = first + t * w, group = k >= listed ? 0u : u_every != 0u ? k : groupData[start + k];
        if (k < listed && groupData[group] != 0u) sGroups[atomicAdd(sFound, 1u)] = group;
        barrier();
        uint found = sFound;
        for (uint i = 0u; i < found; ++i)
            writeGroup(sGroups[i], t);
    }
}
