#pragma once
// RenderOptions: what one Renderer::render call shows besides the scene: the view, line overlays
// drawn after lighting, and debug switches of the decal pass. The defaults render the plain frame;
// every overlay and switch left at its default costs nothing (no pass, no shader code).

#include "spatter/render/View.hpp"

namespace spatter {

// Line overlays, drawn into the output image after lighting (or the debug view), one instanced or
// indexed draw per kind, with lines one pixel wide. Both kinds are coloured by object decal ID: a
// dynamic object's ID gets the colour the ids view gives it, static geometry (ID 0) a fixed colour
// (wireframes green, decal boxes amber).
struct RenderOverlays {
    // The meshes given to Renderer::setOverlayMeshes (the collision proxies), each drawn with its
    // object's current transform, so a moving target's wireframe moves with it.
    bool proxyWireframe = false;
    // The 12 edges of the box of every decal drawn this frame (decals culled or invalid have none).
    bool decalBoxes = false;
    // false: lines are depth-tested against the scene, so surfaces hide what lies behind them;
    // true: lines are drawn over everything.
    bool alwaysOnTop = false;
    // Depth-tested lines are pulled towards the eye by this fraction of their distance (in [0, 0.5];
    // it moves no line on screen), so that lines lying on a surface are not hidden by it.
    float depthBias = 0.002f;
};

// Debug switches of the decal pass (the coverage view follows them too). Turning one off compiles a
// decal shader variant without that test.
struct DecalSwitches {
    // false: decals ignore object decal IDs, so a decal on a moving target also shows on the wall
    // behind it wherever its box reaches.
    bool idClipping = true;
    // false: no pixel is rejected for the angle between its normal and the decal axis, so a box
    // reaching through a thin wall marks its back, and grazing surfaces get smears.
    bool angleReject = true;
};

struct RenderOptions {
    View view = View::Final;
    RenderOverlays overlays;
    DecalSwitches decals;
};

} // namespace spatter
