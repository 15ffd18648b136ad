#pragma once
// The headless run's check that decals stay on a skinned target: a decal on the animated dummy (or on
// any skinned or morphed target of the scene) is followed across a second of animation. Each frame
// the point of the render surface it was placed on is posed on the CPU (posedPositions) and projected,
// and the decal alone is drawn on the GPU-skinned mesh with a centre marker for texture
// (DecalMarker.hpp); the drift is how far the drawn centre lies from that point in the image (frames
// where the marker does not show whole are left out), and how far the decal's centre is from it in the
// world.

#include "GallerySim.hpp"

#include "spatter/render/Renderer.hpp"

#include <nlohmann/json.hpp>

namespace spatter::gallery {

Result<nlohmann::ordered_json> trackSkinnedDecal(GallerySim& sim, Renderer& renderer, const Camera& camera);

} // namespace spatter::gallery
