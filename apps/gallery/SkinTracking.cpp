#include "SkinTracking.hpp"

#include "GalleryView.hpp"
#include "Tracking.hpp"

#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/VertexDeformation.hpp"

#include <algorithm>

namespace spatter::gallery {

namespace {

constexpr int kFrames = 30;
constexpr double kFrameSeconds = 1.0 / 30.0;

bool deforms(const SceneObject& o) {
    return o.skin >= 0 || !o.morphTargets.empty();
}

// A point of an object's render surface: a triangle and barycentric coordinates.
struct SurfacePoint {
    uint32_t triangle = 0;
    glm::dvec3 bary{0.0};
};

// The object's render mesh in the pose the sim holds, in its object space.
Mesh posedMesh(const GallerySim& sim, uint32_t object) {
    return withPositions(sim.scene().objects[object].mesh,
                         posedPositions(sim.scene(), object, *sim.evaluator()));
}

Result<SurfacePoint> nearestPoint(const Mesh& mesh, const glm::dvec3& local) {
    Result<ClosestPointQuery> query = ClosestPointQuery::create(mesh);
    if (!query) return fail(query.error());
    const std::optional<ClosestPoint> c = query->closest(local);
    if (!c) return fail("the skinned target has no surface");
    const uint32_t* k = &mesh.indices[3 * size_t(c->triangle)];
    return SurfacePoint{c->triangle,
                        barycentric(c->point, glm::dvec3(mesh.positions[k[0]]),
                                    glm::dvec3(mesh.positions[k[1]]), glm::dvec3(mesh.positions[k[2]]))};
}

glm::dvec3 worldPoint(const GallerySim& sim, uint32_t object, const SurfacePoint& p) {
    const Mesh m = posedMesh(sim, object);
    const uint32_t* k = &m.indices[3 * size_t(p.triangle)];
    const glm::dvec3 local = p.bary.x * glm::dvec3(m.positions[k[0]]) +
                             p.bary.y * glm::dvec3(m.positions[k[1]]) +
                             p.bary.z * glm::dvec3(m.positions[k[2]]);
    return glm::dvec3(sim.transform(object) * glm::dvec4(local, 1.0));
}

// The newest fully opaque flat decal on a deforming target, or null. (A volumetric crater keeps the
// box it was clipped in, off the drawn surface by up to the proxy's bound, so it is not followed.)
const Decal* newestOnSkin(const GallerySim& sim) {
    const Decal* found = nullptr;
    for (const Decal& d : sim.decals().decals())
        if (deforms(sim.scene().objects[d.object]) && !sim.types()[d.type].volumetric && d.opacity >= 1.0f &&
            (!found || d.spawnTime > found->spawnTime))
            found = &d;
    return found;
}

} // namespace

Result<nlohmann::ordered_json> trackSkinnedDecal(GallerySim& sim, Renderer& renderer, const Camera& camera) {
    if (!sim.evaluator()) return fail("the scene has no animation");
    const Decal* followed = newestOnSkin(sim);
    if (!followed) return fail("no decal landed on a skinned target to follow");
    const uint32_t id = followed->id, object = followed->object;
    const uint16_t type = followed->type;
    const glm::vec2 size = sim.decals().worldBox(*followed).size;
    Result<SurfacePoint> placedOn = nearestPoint(posedMesh(sim, object), glm::dvec3(followed->center));
    if (!placedOn) return fail(placedOn.error());
    const int w = renderer.settings().width, h = renderer.settings().height;

    double worldDrift = 0.0, imageDrift = 0.0, moved = 0.0, sizePx = 0.0;
    std::optional<glm::dvec2> firstImaged, firstProjected;
    for (int frame = 0; frame <= kFrames; ++frame) {
        if (frame > 0) sim.advance(kFrameSeconds);
        const Decal* decal = findDecal(sim.decals(), id);
        if (!decal) return fail("the followed decal disappeared while its target moved");
        syncRenderer(renderer, sim);
        Result<std::optional<glm::dvec2>> centroid = decalCentroid(renderer, camera, *decal);
        if (!centroid) return fail(centroid.error());
        const glm::dvec3 point = worldPoint(sim, object, placedOn.value());
        worldDrift = std::max(worldDrift, glm::length(sim.decals().worldBox(*decal).center - point));
        const std::optional<glm::dvec2> imaged = centroid.value();
        if (!imaged) continue; // turned away from the camera this frame
        const glm::dvec2 projected = project(camera, w, h, point);
        if (!firstImaged) {
            firstImaged = imaged;
            firstProjected = projected;
            const WorldDecal box = sim.decals().worldBox(*decal);
            sizePx = glm::length(
                project(camera, w, h, point + double(box.size.x) * glm::dvec3(box.frame.tangent)) -
                projected);
            continue;
        }
        moved = std::max(moved, glm::length(*imaged - *firstImaged));
        imageDrift =
            std::max(imageDrift, glm::length((*imaged - *firstImaged) - (projected - *firstProjected)));
    }
    if (!firstImaged) return fail("the followed decal was never visible");
    nlohmann::ordered_json out;
    out["object"] = sim.scene().objects[object].name;
    out["decal_id"] = id;
    out["type"] = sim.types()[type].name;
    out["frames"] = kFrames;
    out["image_moved_px"] = moved;
    out["image_drift_px"] = imageDrift;
    out["world_drift_m"] = worldDrift;
    out["decal_size_m"] = double(std::max(size.x, size.y));
    out["decal_size_px"] = sizePx;
    return out;
}

} // namespace spatter::gallery
