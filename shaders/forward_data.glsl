// The forward path's buffers, written by the projector's binning (DecalProjector::bin) and read by a
// host's forward shader (forward.glsl). Binding points default to those of ForwardBindings; a host
// that uses them for its own buffers defines SPATTER_FORWARD_DECALS_BINDING,
// SPATTER_FORWARD_TILES_BINDING and SPATTER_FORWARD_ITEMS_BINDING before this text and passes the
// same numbers to DecalProjector::bindForward. Mirrored on the C++ side by
// render/src/ProjectorLayouts.hpp (ForwardDecalGpu, ForwardGridGpu).
#ifndef SPATTER_FORWARD_DECALS_BINDING
#define SPATTER_FORWARD_DECALS_BINDING 5
#endif
#ifndef SPATTER_FORWARD_TILES_BINDING
#define SPATTER_FORWARD_TILES_BINDING 6
#endif
#ifndef SPATTER_FORWARD_ITEMS_BINDING
#define SPATTER_FORWARD_ITEMS_BINDING 7
#endif
#ifdef SPATTER_FORWARD_WRITE
#define SPATTER_FORWARD_ACCESS
#else
#define SPATTER_FORWARD_ACCESS readonly
#endif

// A visible decal in camera-relative world space (world minus the frame's eye).
struct SpatterForwardDecal {
    vec4 worldToBox[3]; // rows: camera-relative world -> unit box [-1, 1]^3
    vec4 tangent;       // xyz: world unit tangent; w: half width
    vec4 bitangent;     // w: half height
    vec4 normal;        // xyz: world unit decal normal; w: half depth
    vec4 tint;          // rgb tint; a: tint alpha * opacity
    uvec4 info;         // x: object decal ID, y: texture layer, z: SPATTER_DECAL_* flags, w: the
                        // texture layer's cutout (spatterInCutout)
    vec4 params;        // x: cosine of the largest accepted angle, y: roughness written
    vec4 axis;          // xyz: world unit axis the box is projected along (depth_axis.glsl)
};

// One per visible decal, in drawing order.
layout(std430, binding = SPATTER_FORWARD_DECALS_BINDING) SPATTER_FORWARD_ACCESS buffer SpatterForwardDecals {
    SpatterForwardDecal spatterForwardDecals[];
};

// The screen's tiles, row by row from the viewport's lower left corner: for each, its decals as a run
// of spatterTileItems (first, count), in drawing order. Binned on the GPU, a tile with more decals
// than its run holds gets a run over every decal binned (the items 0, 1, 2, ... kept after the
// tiles' runs).
layout(std430, binding = SPATTER_FORWARD_TILES_BINDING) SPATTER_FORWARD_ACCESS buffer SpatterForwardTiles {
    ivec4 spatterTileGrid;     // x, y: the viewport's lower left corner (pixels); z: tiles per row; w: rows
    ivec4 spatterTileInfo;     // x: tile size (pixels); y: 1 when normal maps take their frame from
                               // the surface's position derivatives (DecalNormalFrame::DepthDerivatives);
                               // z: 1 when the binning culled on the GPU left decals out (more
                               // in view than its buffers held); w: culled on the GPU, the most
                               // decals one tile holds
    vec4 spatterForwardParams; // x: fade start (fraction of the half-depth)
    uvec2 spatterTiles[];
};

layout(std430, binding = SPATTER_FORWARD_ITEMS_BINDING) SPATTER_FORWARD_ACCESS buffer SpatterForwardItems {
    uint spatterTileItems[]; // indices into spatterForwardDecals
};
