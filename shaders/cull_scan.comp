// GPU culling, pass 2 of 3: one work group turns the groups' visible counts into each group's first
// place in the visible list (an exclusive prefix sum, in draw order), and writes the indirect draw
// (the cube's 36 indices, the list's length as instance count).
layout(local_size_x = 256) in;
layout(location = 0) uniform uint u_groups;

layout(std430, binding = 2) buffer GroupCounts {
    uint groupCounts[]; // in: counts; out: first places
};

struct DrawElementsIndirect {
    uint count, instanceCount, firstIndex, baseVertex, baseInstance;
};
layout(std430, binding = 5) writeonly buffer Draws {
    DrawElementsIndirect draw;
};

shared uint partial[256];

void main() {
    uint t = gl_LocalInvocationIndex;
    uint per = (u_groups + 255u) / 256u;
    uint begin = min(t * per, u_groups), end = min(begin + per, u_groups);
    uint sum = 0u;
    for (uint g = begin; g < end; ++g) sum += groupCounts[g];
    partial[t] = sum;
    barrier();
    for (uint offset = 1u; offset < 256u; offset <<= 1) { // inclusive scan (Hillis and Steele)
        uint v = t >= offset ? partial[t - offset] : 0u;
        barrier();
        partial[t] += v;
        barrier();
    }
    uint first = partial[t] - sum;
    for (uint g = begin; g < end; ++g) {
        uint c = groupCounts[g];
        groupCounts[g] = first;
        first += c;
    }
    if (t == 255u) draw = DrawElementsIndirect(36u, partial[255], 0u, 0u, 0u);
}
