#pragma once
// What the headless run and the window share: the starting camera over a scene, aiming, and
// handing the simulation's state to the renderer each frame.

#include "GallerySim.hpp"

#include "spatter/placement/Ray.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/Renderer.hpp"

namespace spatter::gallery {

// The player's view: the gallery's firing line for builtin:gallery, otherwise a view of the whole
// scene from the front (+Z) and a little above.
Camera startCamera(const Scene& scene);

// The ray from the camera through normalised device coordinates (x, y) in [-1, 1].
Ray rayThrough(const Camera& camera, double aspect, double x, double y);

// Uploads the scene, the proxy wireframes, the types and the object IDs (again after the proxies
// are rebuilt).
Status prepareRenderer(Renderer& renderer, const GallerySim& sim);
// Uploads the moving targets' transforms and the live decals for the next frame.
void syncRenderer(Renderer& renderer, const GallerySim& sim);

} // namespace spatter::gallery
