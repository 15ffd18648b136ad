#pragma once
// The headless run's check that decals stay on a skinned target: a decal on the animated dummy (or on
// any skinned or morphed target of the scene) is followed across a second of animation. Each frame
// the point of the render surface it was placed on is posed on the CPU (posedPositions) and projected,
// and the decal alone is drawn in the coverage view on the GPU-skinned mesh; the drift is how far the
// centre of the decal's pixels moves unlike that point (motions compared, since the curved surface
// may clip the decal), and how far its centre is from the point in the world.

#include "GallerySim.hpp"

#include "spatter/render/Renderer.hpp"

#include <nlohmann/json.hpp>

namespace spatter::gallery {

Result<nlohmann::ordered_json> trackSkinnedDecal(GallerySim& sim, Renderer& renderer, const Camera& camera);

} // namespace spatter::gallery
