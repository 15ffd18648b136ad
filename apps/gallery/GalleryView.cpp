#include "GalleryView.hpp"

#include <cmath>

namespace spatter::gallery {

Camera startCamera(const Scene& scene) {
    Camera camera;
    if (scene.source == "builtin:gallery") {
        camera.eye = {0.0, 1.7, 4.2};
        camera.target = {0.0, 1.3, -3.6};
        return camera;
    }
    const DBounds b = scene.worldBounds();
    const glm::dvec3 c = b.center(), e = b.extent();
    const double radius = std::max(0.5 * glm::length(e), 1e-3);
    camera.target = c;
    camera.eye = c + glm::dvec3(0.0, 0.35 * radius, 1.9 * radius);
    camera.nearPlane = std::max(1e-4, 0.01 * radius);
    return camera;
}

Ray rayThrough(const Camera& camera, double aspect, double x, double y) {
    const CameraBasis basis = cameraBasis(camera);
    const double t = std::tan(glm::radians(camera.fovYDeg) * 0.5);
    Ray ray;
    ray.origin = camera.eye;
    ray.direction = -basis.back + basis.right * (x * t * aspect) + basis.up * (y * t);
    return ray;
}

Status prepareRenderer(Renderer& renderer, const GallerySim& sim) {
    if (Status s = renderer.setScene(sim.scene()); !s) return s;
    if (Status s = renderer.setOverlayMeshes(sim.proxyMeshes()); !s) return s;
    renderer.setDecalTypes(sim.types());
    return renderer.setObjectIds(sim.objectIds());
}

void syncRenderer(Renderer& renderer, const GallerySim& sim) {
    for (const Rail& rail : sim.rails())
        renderer.setObjectTransform(rail.object, sim.transform(rail.object));
    renderer.setDecals(sim.decals().decals());
}

} // namespace spatter::gallery
