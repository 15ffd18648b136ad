// Forward binning, pass 4 of 4: one invocation per tile sorts its item run into drawing order
// (insertion sort: runs are short), so that overlapping decals blend as
// the deferred paths blend them.
#define SPATTER_FORWARD_WRITE 1
#include "forward_data.glsl"

layout(local_size_x = 64) in;
layout(location = 0) uniform uint u_tiles;

void main() {
    uint t = gl_GlobalInvocationID.x;
    if (t >= u_tiles) return;
    uvec2 run = spatterTiles[t];
    for (uint k = run.x + 1u; k < run.x + run.y; ++k) {
        uint item = spatterTileItems[k];
        uint j = k;
        for (; j > run.x && spatterTileItems[j - 1u] > item; --j) spatterTileItems[j] = spatterTileItems[j - 1u];
        spatterTileItems[j] = item;
    }
}
