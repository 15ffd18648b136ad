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
    // Banners wave on the GPU: banner_0 takes texture-space decals, which follow the cloth; the
    // others keep projected decals, which the cloth slides under.
    for (uint32_t i = 0; i < sim.scene().objects.size(); ++i) {
        const SceneObject& o = sim.scene().objects[i];
        if (!isBanner(o)) continue;
        Deformation wave;
        wave.amplitude = 0.07f;
        wave.frequency = 4.0f;
        wave.phase = 1.7f * float(i);
        wave.speed = 2.5f;
        wave.waveDirection = glm::vec3(0.8f, -0.6f, 0.0f);
        if (Status s = renderer.setObjectDeformation(i, wave); !s) return s;
        if (o.name == "banner_0")
            if (Status s = renderer.setObjectDecalMode(i, DecalMode::TextureSpace, 512); !s) return s;
    }
    renderer.setDecalTypes(sim.types());
    return renderer.setObjectIds(sim.objectIds());
}

void syncRenderer(Renderer& renderer, const GallerySim& sim) {
    renderer.setTime(sim.time());
    if (sim.evaluator()) renderer.setPose(*sim.evaluator()); // before the rails, which it would undo
    for (const Rail& rail : sim.rails())
        renderer.setObjectTransform(rail.object, sim.transform(rail.object));
    const DecalSystem& decals = sim.decals();
    renderer.setDecals(decals.decals(), [&decals](size_t i) { return decals.craterClips(i); });
}

} // namespace spatter::gallery
