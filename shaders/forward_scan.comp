// Forward binning, pass 2 of 4: one work group turns the tiles' decal counts into runs of the item
// list (first, count), an exclusive prefix sum, and leaves each tile's first item in its counter for
// the fill.
#define SPATTER_FORWARD_WRITE 1
#include "forward_data.glsl"

layout(local_size_x = 256) in;
layout(location = 0) uniform uint u_tiles;

layout(std430, binding = 2) buffer TileCounts {
    uint tileCounts[];
};

shared uint partial[256];

void main() {
    uint t = gl_LocalInvocationID.x;
    uint per = (u_tiles + 255u) / 256u;
    uint begin = min(t * per, u_tiles), end = min(begin + per, u_tiles);
    uint sum = 0u;
    for (uint k = begin; k < end; ++k) sum += tileCounts[k];
    partial[t] = sum;
    barrier();
    for (uint offset = 1u; offset < 256u; offset <<= 1) { // inclusive scan (Hillis and Steele)
        uint v = t >= offset ? partial[t - offset] : 0u;
        barrier();
        partial[t] += v;
        barrier();
    }
    uint first = partial[t] - sum;
    for (uint k = begin; k < end; ++k) {
        uint count = tileCounts[k];
        spatterTiles[k] = uvec2(first, count);
        tileCounts[k] = first;
        first += count;
    }
}
