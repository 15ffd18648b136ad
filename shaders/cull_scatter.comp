// GPU culling, pass 3 of 3 (GpuCulling): one work group per group of the draw order with a visible
// place (listed by cull_exact.comp), and at least one. It finds the group's first place in the visible list, the
// visible places of the groups before it (those of the blocks before its block, and of its block's
// groups before it), and writes its visible decals' indices there in draw order,
// each at that first place plus the visible places before it in the group (from the class bits). The
// first work group also writes the counts the CPU reads back.
#include "cull_layout.glsl"

layout(local_size_x = 256) in; // kGroupPlaces
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

shared uint partial[256];

void main() {
    uint t = gl_LocalInvocationIndex;
    if (gl_WorkGroupID.x == 0u && t == 0u)
        readback = uint[4](draw.instanceCount, occludedCount, invalidCount, hostDrawnCount);
    if (gl_WorkGroupID.x >= visibleGroupCount) return; // the one work group when none is visible
    uint group = groupData[u_groups + gl_WorkGroupID.x];
    uint block = group / kBlockGroups, sum = 0u; // the visible places of the blocks and groups before
    for (uint b = t; b < block; b += 256u) sum += groupData[2u * u_groups + b];
    if (block * kBlockGroups + t < group) sum += groupData[block * kBlockGroups + t];
    partial[t] = sum;
    barrier();
    for (uint stride = 128u; stride > 0u; stride >>= 1) { // the sum of the groups before this one
        if (t < stride) partial[t] += partial[t + stride];
        barrier();
    }
    uint place = group * kGroupPlaces + t, word = place / 32u, bit = place % 32u;
    uint bits = classBits[word];
    if ((bits & (1u << bit)) == 0u) return;
    uint rank = uint(bitCount(bits & ((1u << bit) - 1u)));
    for (uint w = group * (kGroupPlaces / 32u); w < word; ++w) rank += uint(bitCount(classBits[w]));
    visibleOut[partial[0] + rank] = drawOrder[place];
}
