// Forward binning, pass 1 (DecalProjector::bin): one invocation per visible decal writes its
// camera-relative world form (SpatterForwardDecal) and enters it in every tile of its screen
// rectangle. Culled on the CPU, the rectangles come from it (in tiles: x0 | y0 << 16, x1 | y1 << 16,
// inclusive) and this pass counts each tile's decals for the scan and the fill (passes 2 and 3).
// Culled on the GPU (FORWARD_CULLED), it finds the rectangle from the box's corners itself and puts
// the decal straight into the tile's run of u_tileCapacity items; pass 4 sorts the runs.
#define SPATTER_FORWARD_WRITE 1
#include "projector.glsl"
#include "forward_data.glsl"
#include "depth_axis.glsl"

layout(local_size_x = 64) in;
layout(location = 0) uniform uint u_count; // visible decals (FORWARD_CULLED: the most the buffers hold)

layout(std430, binding = 2) buffer TileCounts {
    uint tileCounts[];
};

#ifdef FORWARD_CULLED
layout(location = 1) uniform uint u_tileCapacity; // items per tile

// The GPU culling's indirect draw: its instance count is the length of the visible list.
layout(std430, binding = 0) readonly buffer CulledDraw {
    uint drawIndices, visibleCount, drawFirstIndex, drawBaseVertex, drawBaseInstance;
};
// What the CPU reads back (ForwardBins::tileInfo_): 1 when decals were left out, the most decals of
// a tile (written by pass 4).
layout(std430, binding = 10) writeonly buffer TileReadback {
    uint tileReadback[2];
};

// The tiles of the box's screen rectangle (x0, y0, x1, y1, inclusive), a pixel wider on each side for
// the float rounding of the box test; every tile when a corner lies behind the eye. SHOWN_ONLY (the
// compute resolve): the rectangle of the part of the box that can show (shownCorner).
uvec4 tileRect(DecalData d, ProjectorObject o) {
    vec2 lo = vec2(1e30), hi = vec2(-1e30);
    for (int c = 0; c < 8; ++c) {
        vec3 corner = vec3((c & 1) != 0 ? 1.0 : -1.0, (c & 2) != 0 ? 1.0 : -1.0, (c & 4) != 0 ? 1.0 : -1.0);
#ifdef SHOWN_ONLY
        corner = shownCorner(d, corner);
#endif
        vec4 local = vec4(corner, 1.0);
        vec3 p = vec3(dot(d.boxToObject[0], local), dot(d.boxToObject[1], local), dot(d.boxToObject[2], local));
        vec4 clip = u_viewProj * (o.model * vec4(p, 1.0));
        if (!(clip.w > 1e-6)) return uvec4(0u, 0u, uvec2(spatterTileGrid.zw) - 1u);
        vec2 ndc = clamp(clip.xy / clip.w, vec2(-1.0), vec2(1.0));
        lo = min(lo, ndc);
        hi = max(hi, ndc);
    }
    vec2 size = 1.0 / u_viewport.zw;
    float tile = float(spatterTileInfo.x);
    ivec2 last = spatterTileGrid.zw - 1;
    ivec2 a = clamp(ivec2(floor(((lo * 0.5 + 0.5) * size - 1.0) / tile)), ivec2(0), last);
    ivec2 b = clamp(ivec2(floor(((hi * 0.5 + 0.5) * size + 1.0) / tile)), ivec2(0), last);
    return uvec4(a, b);
}
#else
layout(std430, binding = 0) readonly buffer TileRects {
    uvec2 tileRects[];
};
#endif

void main() {
    uint i = gl_GlobalInvocationID.x;
#ifdef FORWARD_CULLED
    if (i == 0u) { // decals past the buffers are left out
        bool leftOut = visibleCount > u_count;
        if (leftOut) spatterTileInfo.z = 1;
        tileReadback[0] = leftOut ? 1u : 0u;
    }
    if (i >= min(visibleCount, u_count)) return;
#else
    if (i >= u_count) return;
#endif
    DecalData d = decalData(visibleDecals[i]);
    ProjectorObject o = objects[d.info.x];
    WorldDecal w = worldDecal(d, o);
    SpatterForwardDecal f;
    f.worldToBox = w.worldToBox;
    f.tangent = w.tangent;
    f.bitangent = w.bitangent;
    f.normal = w.normal;
    f.tint = d.tint;
    f.info = uvec4(o.info.x, d.info.y, d.info.z, d.info.w);
    f.params = d.params;
    f.axis = vec4(spatterDepthAxis(w.worldToBox[0].xyz, w.worldToBox[1].xyz, w.normal.xyz), 0.0);
    spatterForwardDecals[i] = f;
#ifdef FORWARD_CULLED
    uvec4 r = tileRect(d, o);
    uint most = 0u; // of the decals in this decal's tiles, counting it
    for (uint y = r.y; y <= r.w; ++y)
        for (uint x = r.x; x <= r.z; ++x) {
            uint t = y * uint(spatterTileGrid.z) + x;
            uint slot = atomicAdd(tileCounts[t], 1u);
            if (slot < u_tileCapacity) spatterTileItems[t * u_tileCapacity + slot] = i;
            most = max(most, slot + 1u);
        }
    // The most decals of a tile, for the CPU, which sizes the next runs by it: an atomic only while
    // this decal's tiles hold more than the largest count seen yet.
    if (int(most) > spatterTileInfo.w) atomicMax(spatterTileInfo.w, int(most));
#else
    uvec2 r = tileRects[i];
    for (uint y = r.x >> 16; y <= (r.y >> 16); ++y)
        for (uint x = r.x & 0xffffu; x <= (r.y & 0xffffu); ++x)
            atomicAdd(tileCounts[y * uint(spatterTileGrid.z) + x], 1u);
#endif
}
