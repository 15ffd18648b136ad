// GPU culling, pass 2 of 3: one work group turns the groups' outside and inside counts into each
// group's first places in the two lists (exclusive prefix sums, in decal order), and writes the two
// indirect draws (36 vertices, the lists' lengths as instance counts) and the totals.
layout(local_size_x = 256) in;
layout(location = 0) uniform uint u_groups;

layout(std430, binding = 2) buffer GroupCounts {
    uvec2 groupCounts[]; // in: counts; out: first places
};

struct DrawArraysIndirect {
    uint count, instanceCount, first, baseInstance;
};
layout(std430, binding = 5) writeonly buffer Draws {
    DrawArraysIndirect draws[2]; // outside, inside
    uvec4 totals;                // x: outside, y: inside
};

shared uvec2 partial[256];

void main() {
    uint t = gl_LocalInvocationIndex;
    uint per = (u_groups + 255u) / 256u;
    uint begin = min(t * per, u_groups), end = min(begin + per, u_groups);
    uvec2 sum = uvec2(0u);
    for (uint g = begin; g < end; ++g) sum += groupCounts[g];
    partial[t] = sum;
    barrier();
    for (uint offset = 1u; offset < 256u; offset <<= 1) { // inclusive scan (Hillis and Steele)
        uvec2 v = t >= offset ? partial[t - offset] : uvec2(0u);
        barrier();
        partial[t] += v;
        barrier();
    }
    uvec2 first = partial[t] - sum;
    for (uint g = begin; g < end; ++g) {
        uvec2 c = groupCounts[g];
        groupCounts[g] = first;
        first += c;
    }
    if (t == 255u) {
        draws[0] = DrawArraysIndirect(36u, partial[255].x, 0u, 0u);
        draws[1] = DrawArraysIndirect(36u, partial[255].y, 0u, 0u);
        totals = uvec4(partial[255], 0u, 0u);
    }
}
