// Forward binning, pass 1 of 4 (DecalProjector::bin): one invocation per visible decal writes its
// camera-relative world form (SpatterForwardDecal) and counts it in every tile of its screen
// rectangle (computed on the CPU with the culling, in tiles: x0 | y0 << 16, x1 | y1 << 16, inclusive).
#define SPATTER_FORWARD_WRITE 1
#include "projector.glsl"
#include "forward_data.glsl"

layout(local_size_x = 64) in;
layout(location = 0) uniform uint u_count; // visible decals

layout(std430, binding = 0) readonly buffer TileRects {
    uvec2 tileRects[];
};
layout(std430, binding = 2) buffer TileCounts {
    uint tileCounts[];
};

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    DecalData d = decalData(visibleDecals[i]);
    WorldDecal w = worldDecal(d, objects[d.info.x]);
    SpatterForwardDecal f;
    f.worldToBox = w.worldToBox;
    f.tangent = w.tangent;
    f.bitangent = w.bitangent;
    f.normal = w.normal;
    f.tint = d.tint;
    f.info = uvec4(d.info.y, d.info.z, d.info.w, 0u);
    f.params = d.params;
    spatterForwardDecals[i] = f;
    uvec2 r = tileRects[i];
    for (uint y = r.x >> 16; y <= (r.y >> 16); ++y)
        for (uint x = r.x & 0xffffu; x <= (r.y & 0xffffu); ++x)
            atomicAdd(tileCounts[y * uint(spatterTileGrid.z) + x], 1u);
}
