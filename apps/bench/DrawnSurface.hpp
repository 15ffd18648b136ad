#pragma once
// DrawnSurface: decals placed through collision proxies, laid again on the surface a renderer drew,
// as a game does a frame after its shots: each decal's axis line is searched in the depth of a frame
// from `camera` (Renderer::findSurface, DecalProjector::findSurface) and the decal is laid where the
// line meets the drawn surface (DecalSystem::layOnDrawnSurface). A decal along its shot whose shot,
// searched from its origin, met the drawn surface before the box gives way to the shot's decal there
// (DecalSystem::replaceOnDrawnSurface). Decals whose meet the camera does not see stay as placed.

#include "spatter/core/Result.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/Renderer.hpp"

#include <glm/glm.hpp>
#include <vector>

namespace spatter::bench {

// What layOnDrawnSurface did with the decals of a batch of shots.
struct DrawnSurfaceCounts {
    size_t laid = 0;    // laid again where their axis meets the drawn surface
    size_t removed = 0; // removed: their shot meets it too steeply for their type
    size_t spawned = 0; // of shots the proxy refused (missed or grazed), placed where the shot meets
                        // the drawn surface
    size_t moved = 0;   // replaced by their shot's decal where it met the drawn surface before the box
};

// Lays the decals of `placed` (the results of spawning `shots` in `system`, type 0) on the surface
// `renderer` draws from `camera` at `probeSize` pixels, and places the decals of the shots that the
// collision surface refused (SpawnResult::refusedByCollisionSurface) where they meet it within
// `shotReach` of their origin (DecalSystem::spawnOnDrawnSurface); then gives the renderer its size
// back.
Result<DrawnSurfaceCounts> layOnDrawnSurface(DecalSystem& system, const std::vector<Ray>& shots,
                                             const std::vector<SpawnResult>& placed, Renderer& renderer,
                                             const Camera& camera, glm::ivec2 probeSize, double shotReach);

} // namespace spatter::bench
