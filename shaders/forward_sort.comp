// Forward binning, pass 4: one invocation per tile sorts its item run into drawing order
// (insertion sort: runs are short), so that overlapping decals blend as
// the deferred paths blend them. Culled on the GPU, a tile with more decals than its run holds, up to
// u_mostPerTile, gets a run over every decal binned instead (the identity items at u_everyDecal, in
// drawing order already); past that the decals past its run are left out. The most decals of a tile
// is kept for the CPU, which sizes the next runs by it.
#define SPATTER_FORWARD_WRITE 1
#include "forward_data.glsl"

layout(local_size_x = 64) in;
layout(location = 0) uniform uint u_tiles;

#ifdef FORWARD_CULLED
// Culled on the GPU, each tile's run starts at t * u_tileCapacity; pass 1 counted its decals.
layout(location = 1) uniform uint u_tileCapacity;
layout(location = 2) uniform uint u_count;       // the most decals the buffers hold
layout(location = 3) uniform uint u_mostPerTile; // ProjectorSettings::forwardTileCapacity
layout(location = 4) uniform uint u_everyDecal;  // the first of the items 0, 1, 2, ...
layout(std430, binding = 2) readonly buffer TileCounts {
    uint tileCounts[];
};
// The GPU culling's indirect draw: its instance count is the length of the visible list.
layout(std430, binding = 0) readonly buffer CulledDraw {
    uint drawIndices, visibleCount, drawFirstIndex, drawBaseVertex, drawBaseInstance;
};

shared uint groupMost; // the most decals of a tile of this work group

// The most decals of a tile into spatterTileInfo.w: a work group's most first, then one atomic a group.
void keepMost(uint count) {
    if (gl_LocalInvocationIndex == 0u) groupMost = 0u;
    barrier();
    atomicMax(groupMost, count);
    barrier();
    if (gl_LocalInvocationIndex == 0u) atomicMax(spatterTileInfo.w, int(groupMost));
}
#endif

void main() {
    uint t = gl_GlobalInvocationID.x;
#ifdef FORWARD_CULLED
    uint count = t < u_tiles ? tileCounts[t] : 0u;
    keepMost(count); // in uniform control flow: before any invocation returns
    if (t >= u_tiles) return;
    if (count > u_tileCapacity && count <= u_mostPerTile) {
        spatterTiles[t] = uvec2(u_everyDecal, min(visibleCount, u_count));
        return;
    }
    if (count > u_tileCapacity) spatterTileInfo.z = 1; // the decals past the run are left out
    uvec2 run = uvec2(t * u_tileCapacity, min(count, u_tileCapacity));
    spatterTiles[t] = run;
#else
    if (t >= u_tiles) return;
    uvec2 run = spatterTiles[t];
#endif
    for (uint k = run.x + 1u; k < run.x + run.y; ++k) {
        uint item = spatterTileItems[k];
        uint j = k;
        for (; j > run.x && spatterTileItems[j - 1u] > item; --j) spatterTileItems[j] = spatterTileItems[j - 1u];
        spatterTileItems[j] = item;
    }
}
