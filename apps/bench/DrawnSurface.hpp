#pragma once
// DrawnSurface: decals placed through collision proxies, laid again on the surface a renderer drew,
// as a game does a frame after its shots: each decal's axis line is searched in the depth of a frame
// from `camera` (Renderer::findSurface, DecalProjector::findSurface) and the decal is laid where the
// line meets the drawn surface (DecalSystem::layOnDrawnSurface). Decals whose meet the camera does not
// see stay as placed.

#include "spatter/core/Result.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/Renderer.hpp"

#include <glm/glm.hpp>
#include <vector>

namespace spatter::bench {

// Lays the decals of `placed` (the results of their spawns in `system`) on the surface `renderer`
// draws from `camera` at `probeSize` pixels, then gives the renderer its size back. Returns how many
// were laid again (those whose shot meets the drawn surface too steeply for their type are removed).
Result<size_t> layOnDrawnSurface(DecalSystem& system, const std::vector<SpawnResult>& placed,
                                 Renderer& renderer, const Camera& camera, glm::ivec2 probeSize);

} // namespace spatter::bench
