#pragma once
// DecalField: the render benchmarks' scene. A large flat floor seen straight from above, and decals
// laid on it directly (no ray tracing): a chosen number inside the view, the rest outside the view
// frustum, each covering a chosen fraction of the screen height. Optionally a small dynamic object in
// view, which gives the scene an object-ID target (the renderer's IDS variant).

#include "BenchSupport.hpp"

#include "spatter/core/Decal.hpp"
#include "spatter/core/DecalType.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/FrameStats.hpp"
#include "spatter/render/RenderOptions.hpp"
#include "spatter/render/Renderer.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace spatter::bench {

struct DecalFieldView {
    Camera camera;        // above the origin, looking straight down
    double halfWidth = 0; // half extents of the floor area in view (x, z), for the aspect given
    double halfHeight = 0;
};

// The view of the floor from 10 units up with a 60 degree vertical field of view.
DecalFieldView decalFieldView(double aspect);

// The floor (object 0, static, 2 triangles, 200 view widths across) and, with `dynamicObject`, a
// dynamic 1-unit cube standing on it near a corner of the view (object 1). With `roof`, a roof 2 units
// above the floor (the next object) hides the middle of the view: nine tenths of the floor in view.
Scene decalFieldScene(const DecalFieldView& view, bool dynamicObject, bool roof = false);

// `total` decals of `type` on the floor, `visible` of them with centres inside the view (their boxes
// entirely in it), the others entirely outside the frustum. Each is a square of `screenFraction`
// times the visible floor height, randomly turned about the floor normal, half-depth a quarter of its
// size. Same seed, same decals; visible decals come first.
std::vector<Decal> decalField(const DecalFieldView& view, size_t total, size_t visible, double screenFraction,
                              uint16_t type, uint64_t seed);

// GPU pass times of frames rendered with RendererSettings::waitForTimers: medians over the frames.
struct FrameTimes {
    double decalsMs = 0, geometryMs = 0, lightingMs = 0, totalMs = 0, cpuMs = 0;
    ProjectorStageTimes decalStages; // medians of the frames (RendererSettings::decalStageTimers)
    size_t frames = 0;
    bool capped = false; // stopped by the time limit before the frames asked for
    FrameStats last;     // the stats of the last frame
};

// Renders `warmup` frames (more, up to 20, until 0.3 s have passed), then up to `frames` frames,
// stopping once `maxSeconds` of wall time have passed (at least one timed frame). Fails when a frame
// fails.
Result<FrameTimes> timeFrames(Renderer& renderer, const Camera& camera, const RenderOptions& options,
                              size_t warmup, size_t frames, double maxSeconds);

// Times measured in several rounds as one: each figure the median of the rounds' figures (each a
// median of its round's frames), the frames of all rounds, capped when a round was, the last round's
// stats.
FrameTimes medianOverRounds(const std::vector<FrameTimes>& rounds);

// Resolutions by name: 720p, 1080p, 4k (16:9).
bool resolutionByName(const std::string& name, int& width, int& height);

} // namespace spatter::bench
