#pragma once
// What the headless run's trackers of decals share: a decal found by its ID, and the centre of the
// pixels a decal covers in the coverage view. (DecalMarker.hpp finds where a decal's centre is drawn.)

#include "spatter/core/Image.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/Renderer.hpp"

#include <glm/glm.hpp>
#include <optional>

namespace spatter::gallery {

// The live decal with ID `id`, or null.
const Decal* findDecal(const DecalSystem& system, uint32_t id);

// Centre of the pixels that `decal` alone adds to the renderer's coverage view from `camera`, or
// nothing when it adds none. (Decals splatted earlier into texture-space objects show in that view
// too: a frame without `decal` tells them apart.) Leaves the renderer drawing `decal` alone.
Result<std::optional<glm::dvec2>> decalCentroid(Renderer& renderer, const Camera& camera, const Decal& decal);

} // namespace spatter::gallery
