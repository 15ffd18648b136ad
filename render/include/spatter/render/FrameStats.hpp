#pragma once
// FrameStats: what one Renderer::render call did and how long its passes took on the GPU.

#include "spatter/render/DecalProjector.hpp"
#include "spatter/render/View.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

namespace spatter {

// GPU time of each pass in milliseconds (GL_TIME_ELAPSED queries). A pass that did not run this
// frame reads 0. The times are those of frame `frame` below: without RendererSettings::waitForTimers
// the renderer reads results only once the GPU has them, a frame or more later, and `frame` is -1
// until the first results arrive.
struct GpuPassTimes {
    int64_t frame = -1;
    double geometryMs = 0.0;   // G-buffer fill (receivers)
    double decalsMs = 0.0;     // normal copy and decal pass (or the coverage variant)
    double lateMs = 0.0;       // objects that receive no decals, drawn after the decals
    double lightingMs = 0.0;   // lighting and tone mapping, or the debug view
    double overlayMs = 0.0;    // line overlays (RenderOverlays)
    double splatMs = 0.0;      // texture-space decals rendered into their objects' textures, and dilation
    double volumetricMs = 0.0; // volumetric decals: footprints into the stencil, craters into the G-buffer
    double totalMs() const {
        return geometryMs + decalsMs + lateMs + lightingMs + overlayMs + splatMs + volumetricMs;
    }
};

struct FrameStats {
    uint64_t frame = 0; // 0 for the first render call
    int width = 0;
    int height = 0;
    View view = View::Final;

    size_t decals = 0;             // decals given to setDecals for the decal pass (neither volumetric nor
                                   // on a texture-space object)
    size_t decalsInvalid = 0;      // skipped: object or type out of range, degenerate or non-finite box
    size_t decalsCulled = 0;       // outside the view frustum (test of the box corners) or occluded
    size_t decalsDrawn = 0;        // instances drawn in the decal pass
    size_t decalsInside = 0;       // of those, boxes that may hold the eye or cross the near plane
                                   // (ProjectorStats::inside; 0 when culled on the GPU)
    size_t decalBytesUploaded = 0; // instance and visibility data sent to the GPU this frame
    bool decalPassSkipped = true;  // no visible decal: no normal copy, no decal pass
    std::string decalVariant;      // features of the decal shader used, e.g. "IDS WRAP NORMAL_MAP FADE"
    std::string decalNormalCopy; // ProjectorStats::normalCopy: "", "in-place", "rects", "boxes" or "viewport"
    size_t overlayLines = 0;     // line segments drawn by the overlays (RenderOverlays)

    // Texture-space decals (DecalMode::TextureSpace objects).
    size_t decalsTextureSpace = 0;  // decals given to setDecals that lie on texture-space objects
                                    // (not in `decals`: the decal pass never draws them)
    size_t decalsSplatted = 0;      // of those, rendered into their object's decal texture this frame
    size_t decalsVolumetric = 0;    // volumetric decals drawn (instanced; not counted in decals)
    size_t textureSpaceObjects = 0; // objects in texture-space mode
    size_t textureSpaceBytes = 0;   // GPU memory of their decal textures, UV masks and dilation scratch

    size_t drawCalls = 0; // every draw of the frame
    size_t triangles = 0; // scene triangles drawn in the geometry passes
    double cpuMs = 0.0;   // wall time of render() on the CPU
    GpuPassTimes gpu;
    ProjectorStageTimes decalStages; // the decal pass's stages (RendererSettings::decalStageTimers)

    std::string glRenderer;
    std::string glVendor;
    std::string glVersion;
};

// One JSON object with every field above ("gpu_ms": {"geometry", "decals", "late", "lighting",
// "overlay", "splat", "volumetric", "total", "frame"}; "decal_stages_ms": {"cull", "bin", "draw",
// "read_back", "frame"}).
std::string toJson(const FrameStats& stats);

} // namespace spatter
