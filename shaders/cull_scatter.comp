// GPU culling, pass 3 of 3: each work group writes its decals' indices into the visible list in
// decal order, outside decals first and inside decals after all of them (as the CPU's list).

layout(local_size_x = 256) in;
layout(location = 0) uniform uint u_count;

layout(std430, binding = 0) readonly buffer Classes {
    uint classes[];
};
layout(std430, binding = 2) readonly buffer GroupFirsts {
    uvec2 groupFirsts[];
};
layout(std430, binding = 5) readonly buffer Draws {
    uvec4 draws[2];
    uvec4 totals; // x: outside, y: inside
};
layout(std430, binding = 6) writeonly buffer VisibleOut {
    uint visibleOut[];
};

shared uvec2 ranks[256];

void main() {
    uint t = gl_LocalInvocationIndex, i = gl_GlobalInvocationID.x;
    uint c = i < u_count ? classes[i] : 0u;
    uvec2 mine = uvec2(c == 1u ? 1u : 0u, c == 2u ? 1u : 0u);
    ranks[t] = mine;
    barrier();
    for (uint offset = 1u; offset < 256u; offset <<= 1) {
        uvec2 v = t >= offset ? ranks[t - offset] : uvec2(0u);
        barrier();
        ranks[t] += v;
        barrier();
    }
    uvec2 place = groupFirsts[gl_WorkGroupID.x] + ranks[t] - mine;
    if (c == 1u) visibleOut[place.x] = i;
    if (c == 2u) visibleOut[totals.x + place.y] = i;
}
