// Forward binning, pass 3 of 4: one invocation per visible decal appends it to the item run of every
// tile of its rectangle (in any order; pass 4 sorts).
#define SPATTER_FORWARD_WRITE 1
#include "forward_data.glsl"

layout(local_size_x = 64) in;
layout(location = 0) uniform uint u_count;

layout(std430, binding = 0) readonly buffer TileRects {
    uvec2 tileRects[];
};
layout(std430, binding = 2) buffer TileCursors {
    uint tileCursors[];
};

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    uvec2 r = tileRects[i];
    for (uint y = r.x >> 16; y <= (r.y >> 16); ++y)
        for (uint x = r.x & 0xffffu; x <= (r.y & 0xffffu); ++x)
            spatterTileItems[atomicAdd(tileCursors[y * uint(spatterTileGrid.z) + x], 1u)] = i;
}
