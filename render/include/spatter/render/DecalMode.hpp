#pragma once
// DecalMode: how the decals of one scene object are drawn.

namespace spatter {

enum class DecalMode {
    // Deferred decal boxes over the G-buffer, every frame (the default). Works on any mesh; a decal
    // costs a draw each frame for as long as it lives, and it stays where its box is: a surface that
    // deforms slides under it.
    Projected,
    // Each decal is rendered once into the object's own decal texture through the mesh's UVs
    // ("splatted"), and the geometry pass samples that texture like any other layer: the decal then
    // costs nothing per frame and follows every deformation of the surface (a skinned or morphed
    // object is splatted in the pose given to Renderer::setPose, which should be the pose the decal
    // system placed the decal against). Needs a UV layout without
    // overlaps inside [0, 1]^2 (findUvOverlaps); texel density follows the layout; the textures cost
    // memory per object (FrameStats::textureSpaceBytes). A splatted decal is permanent: removing it
    // from the list given to setDecals does not erase it (Renderer::clearObjectDecals does).
    TextureSpace,
};

} // namespace spatter
