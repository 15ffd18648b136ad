// Forward binning, pass 4: one invocation per tile sorts its item run into drawing order
// (insertion sort: runs are short), so that overlapping decals blend as
// the deferred paths blend them.
#define SPATTER_FORWARD_WRITE 1
#include "forward_data.glsl"

layout(local_size_x = 64) in;
layout(location = 0) uniform uint u_tiles;

#ifdef FORWARD_CULLED
// Culled on the GPU, each tile's run starts at t * u_tileCapacity; pass 1 counted its decals.
layout(location = 1) uniform uint u_tileCapacity;
layout(std430, binding = 2) readonly buffer TileCounts {
    uint tileCounts[];
};
#endif

void main() {
    uint t = gl_GlobalInvocationID.x;
    if (t >= u_tiles) return;
#ifdef FORWARD_CULLED
    uvec2 run = uvec2(t * u_tileCapacity, min(tileCounts[t], u_tileCapacity));
    spatterTiles[t] = run;
    if (tileCounts[t] > u_tileCapacity) spatterTileInfo.z = 1; // the decals past the run are left out
#else
    uvec2 run = spatterTiles[t];
#endif
    for (uint k = run.x + 1u; k < run.x + run.y; ++k) {
        uint item = spatterTileItems[k];
        uint j = k;
        for (; j > run.x && spatterTileItems[j - 1u] > item; --j) spatterTileItems[j] = spatterTileItems[j - 1u];
        spatterTileItems[j] = item;
    }
}
