// Forward binning, pass 4: sorts each tile's item run into drawing order, so that overlapping decals
// blend as the deferred paths blend them. Where the fullest tile holds a few decals (the caller's
// choice), one invocation a tile sorts its run by insertion (a work group takes 64 tiles); otherwise
// (SORT_BY_TILE) one work group a tile sorts a run of up to kSharedRun items by rank: it reads the
// run into shared memory, and each item goes to the place the number of smaller items gives it (the
// items of a run are distinct decals); a longer run, which only culling on the CPU or a
// forwardTileCapacity above kSharedRun makes, is sorted by insertion. Culled on the GPU, a tile with
// more decals than its run holds, up to u_mostPerTile, gets a run over every decal binned instead
// (the identity items at u_everyDecal, in drawing order already); past that the decals past its run
// are left out.
#define SPATTER_FORWARD_WRITE 1
#include "forward_data.glsl"

layout(local_size_x = 64) in;

#ifdef FORWARD_CULLED
// Culled on the GPU, each tile's run starts at t * u_tileCapacity; pass 1 counted its decals.
layout(location = 1) uniform uint u_tileCapacity;
layout(location = 2) uniform uint u_count;       // the most decals the buffers hold
layout(location = 3) uniform uint u_mostPerTile; // ProjectorSettings::forwardTileCapacity
layout(location = 4) uniform uint u_everyDecal;  // the first of the items 0, 1, 2, ...
layout(std430, binding = 2) buffer TileCounts {
    uint tileCounts[]; // zeroed here once read, for the next binning
};
// The GPU culling's indirect draw: its instance count is the length of the visible list.
layout(std430, binding = 0) readonly buffer CulledDraw {
    uint drawIndices, visibleCount, drawFirstIndex, drawBaseVertex, drawBaseInstance;
};
// What the CPU reads back (ForwardBins::tileInfo_): 1 when decals were left out for want of room in
// the buffers, 2 when a tile past u_mostPerTile left them out (zeroed by pass 1); the most decals of
// a tile.
layout(std430, binding = 10) writeonly buffer TileReadback {
    uint tileReadback[2];
};
#endif

// Tile t's run, which `writer` sets from the tile's count when culled on the GPU; (0, 0) for a run
// that needs no sorting.
uvec2 tileRun(uint t, bool writer) {
#ifdef FORWARD_CULLED
    uint count = tileCounts[t];
    if (t == 0u && writer) tileReadback[1] = uint(spatterTileInfo.w); // pass 1 has found the most
    if (count > u_tileCapacity && count <= u_mostPerTile) {
        if (writer) spatterTiles[t] = uvec2(u_everyDecal, min(visibleCount, u_count));
        return uvec2(0u);
    }
    if (count > u_tileCapacity && writer) { // the decals past the run are left out
        spatterTileInfo.z = 1;
        tileReadback[0] = 2u; // a tile overflowed, not the buffers (ForwardBins::kTileOverflowed)
    }
    uvec2 run = uvec2(t * u_tileCapacity, min(count, u_tileCapacity));
    if (writer) spatterTiles[t] = run;
    return run;
#else
    return spatterTiles[t];
#endif
}

void insertionSort(uvec2 run) {
    for (uint k = run.x + 1u; k < run.x + run.y; ++k) {
        uint item = spatterTileItems[k];
        uint j = k;
        for (; j > run.x && spatterTileItems[j - 1u] > item; --j) spatterTileItems[j] = spatterTileItems[j - 1u];
        spatterTileItems[j] = item;
    }
}

#ifdef SORT_BY_TILE
const uint kSharedRun = 256u;
shared uint sItems[kSharedRun];

void main() {
    uint t = gl_WorkGroupID.y * uint(spatterTileGrid.z) + gl_WorkGroupID.x, k0 = gl_LocalInvocationIndex;
    uvec2 run = tileRun(t, k0 == 0u);
#ifdef FORWARD_CULLED
    barrier(); // every invocation has read the count
    if (k0 == 0u) tileCounts[t] = 0u;
#endif
    if (run.y <= 1u) return; // uniform in the work group
    if (run.y > kSharedRun) {
        if (k0 == 0u) insertionSort(run);
        return;
    }
    for (uint k = k0; k < run.y; k += 64u) sItems[k] = spatterTileItems[run.x + k];
    barrier();
    for (uint k = k0; k < run.y; k += 64u) {
        uint item = sItems[k], rank = 0u;
        for (uint j = 0u; j < run.y; ++j) rank += sItems[j] < item ? 1u : 0u;
        spatterTileItems[run.x + rank] = item;
    }
}
#else
layout(location = 0) uniform uint u_tiles;

void main() {
    uint t = gl_GlobalInvocationID.x;
    if (t >= u_tiles) return;
    insertionSort(tileRun(t, true));
#ifdef FORWARD_CULLED
    tileCounts[t] = 0u;
#endif
}
#endif
