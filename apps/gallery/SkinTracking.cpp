#include "SkinTracking.hpp"

#include "DecalMarker.hpp"
#include "GalleryView.hpp"
#include "Tracking.hpp"

#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/VertexDeformation.hpp"

#include <algorithm>

namespace spatter::gallery {

namespace {

constexpr int kFrames = 30;
constexpr double kFrameSeconds = 1.0 / 30.0;

// A point of an object's render surface: a triangle and barycentric coordinates.
struct SkinPoint {
    uint32_t triangle = 0;
    glm::dvec3 bary{0.0};
};

// The object's render mesh in the pose the sim holds, in its object space.
Mesh posedMesh(const GallerySim& sim, uint32_t object) {
    return withPositions(*sim.scene().objects[object].mesh,
                         posedPositions(sim.scene(), object, *sim.evaluator()));
}

Result<SkinPoint> nearestPoint(const Mesh& mesh, const glm::dvec3& local) {
    Result<ClosestPointQuery> query = ClosestPointQuery::create(mesh);
    if (!query) return fail(query.error());
    const std::optional<ClosestPoint> c = query->closest(local);
    if (!c) return fail("the skinned target has no surface");
    const uint32_t* k = &mesh.indices[3 * size_t(c->triangle)];
    return SkinPoint{c->triangle,
                     barycentric(c->point, glm::dvec3(mesh.positions[k[0]]), glm::dvec3(mesh.positions[k[1]]),
                                 glm::dvec3(mesh.positions[k[2]]))};
}

// A surface point as the sim's pose puts it: in the world, and how squarely it faces `eye`.
struct SeenPoint {
    glm::dvec3 world{0.0};
    double cosine = 0.0;
};

SeenPoint seenPoint(const GallerySim& sim, uint32_t object, const SkinPoint& p, const glm::dvec3& eye) {
    const Mesh m = posedMesh(sim, object);
    const uint32_t* k = &m.indices[3 * size_t(p.triangle)];
    glm::dvec3 c[3];
    for (int i = 0; i < 3; ++i)
        c[i] = glm::dvec3(sim.transform(object) * glm::dvec4(glm::dvec3(m.positions[k[i]]), 1.0));
    const glm::dvec3 world = p.bary.x * c[0] + p.bary.y * c[1] + p.bary.z * c[2];
    return {world, tracking::facingCosine(c[0], c[1], c[2], world, eye)};
}

// The newest fully opaque flat decal on a deforming target, or null. (A volumetric crater keeps the
// box it was clipped in, off the drawn surface by up to the proxy's bound, so it is not followed.)
const Decal* newestOnSkin(const GallerySim& sim) {
    const Decal* found = nullptr;
    for (const Decal& d : sim.decals().decals())
        if (sim.scene().objects[d.object].deforms() && !sim.types()[d.type].volumetric && d.opacity >= 1.0f &&
            (!found || d.spawnTime > found->spawnTime))
            found = &d;
    return found;
}

// The index of a copy of type `of` drawn with the centre marker, appended to the renderer's types (for
// as long as the tracker runs).
Result<uint16_t> addMarkerType(Renderer& renderer, const std::vector<DecalType>& types, uint16_t of) {
    Result<DecalType> marker = tracking::markerType(renderer, types[of]);
    if (!marker) return fail(marker.error());
    std::vector<DecalType> withMarker = types;
    withMarker.push_back(marker.value());
    renderer.setDecalTypes(withMarker);
    return uint16_t(types.size());
}

} // namespace

Result<nlohmann::ordered_json> trackSkinnedDecal(GallerySim& sim, Renderer& renderer, const Camera& camera) {
    if (!sim.evaluator()) return fail("the scene has no animation");
    const Decal* followed = newestOnSkin(sim);
    if (!followed) return fail("no decal landed on a skinned target to follow");
    const uint32_t id = followed->id, object = followed->object;
    const uint16_t type = followed->type;
    const glm::vec2 worldSize = sim.decals().worldBox(*followed).size;
    const double size = double(std::max(worldSize.x, worldSize.y));
    Result<SkinPoint> placedOn = nearestPoint(posedMesh(sim, object), glm::dvec3(followed->center));
    if (!placedOn) return fail(placedOn.error());
    Result<uint16_t> marker = addMarkerType(renderer, sim.types(), type);
    if (!marker) return fail(marker.error());
    const int w = renderer.settings().width, h = renderer.settings().height;

    double worldDrift = 0.0, imageDrift = 0.0, imageDriftPx = 0.0, moved = 0.0, sizePx = 0.0;
    int framesSeen = 0;
    std::optional<glm::dvec2> first;
    for (int frame = 0; frame <= kFrames; ++frame) {
        if (frame > 0) sim.advance(kFrameSeconds);
        const Decal* decal = findDecal(sim.decals(), id);
        if (!decal) return fail("the followed decal disappeared while its target moved");
        syncRenderer(renderer, sim);
        Decal marked = *decal;
        marked.type = marker.value();
        Result<Image> bare = tracking::drawAlone(renderer, camera, View::Albedo, {});
        if (!bare) return fail(bare.error());
        Result<Image> with = tracking::drawAlone(renderer, camera, View::Albedo, {marked});
        if (!with) return fail(with.error());
        const SeenPoint at = seenPoint(sim, object, placedOn.value(), camera.eye);
        const glm::dvec3& point = at.world;
        worldDrift = std::max(worldDrift, glm::length(sim.decals().worldBox(*decal).center - point));
        const tracking::Marker m = tracking::findMarker(with.value(), bare.value());
        const double across = tracking::pixelsAcross(camera, h, size, point);
        if (!tracking::showsWhole(m, at.cosine, across)) continue; // turned away or hidden this frame
        ++framesSeen;
        if (!first) first = m.centre;
        moved = std::max(moved, glm::length(m.centre - *first));
        sizePx = std::max(sizePx, across);
        const double off = glm::length(m.centre - tracking::pixelOf(camera, w, h, point));
        imageDriftPx = std::max(imageDriftPx, off);
        imageDrift = std::max(imageDrift, off / across);
    }
    renderer.setDecalTypes(sim.types());
    if (!first) return fail("the followed decal was never seen whole");
    nlohmann::ordered_json out;
    out["object"] = sim.scene().objects[object].name;
    out["decal_id"] = id;
    out["type"] = sim.types()[type].name;
    out["frames"] = kFrames;
    out["frames_seen"] = framesSeen;
    out["image_moved_px"] = moved;
    out["image_drift_px"] = imageDriftPx;
    out["image_drift_of_size"] = imageDrift;
    out["world_drift_m"] = worldDrift;
    out["decal_size_m"] = size;
    out["decal_size_px"] = sizePx;
    return out;
}

} // namespace spatter::gallery
