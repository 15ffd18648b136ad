// GPU culling, pass 3 of 3: each work group writes its visible decals' indices into the visible list
// in draw order.
layout(local_size_x = 256) in;
layout(location = 0) uniform uint u_count;

layout(std430, binding = 0) readonly buffer Classes {
    uint classBits[]; // bit k of word w: entry 32 w + k is visible
};
layout(std430, binding = 2) readonly buffer GroupFirsts {
    uint groupFirsts[];
};
layout(std430, binding = 6) readonly buffer DrawOrder {
    uint drawOrder[];
};
layout(std430, binding = 7) writeonly buffer VisibleOut {
    uint visibleOut[];
};

shared uint ranks[256];

void main() {
    uint t = gl_LocalInvocationIndex, place = gl_GlobalInvocationID.x;
    uint mine = place < u_count ? (classBits[place / 32u] >> (place % 32u)) & 1u : 0u;
    ranks[t] = mine;
    barrier();
    for (uint offset = 1u; offset < 256u; offset <<= 1) {
        uint v = t >= offset ? ranks[t - offset] : 0u;
        barrier();
        ranks[t] += v;
        barrier();
    }
    if (mine != 0u) visibleOut[groupFirsts[gl_WorkGroupID.x] + ranks[t] - 1u] = drawOrder[place];
}
