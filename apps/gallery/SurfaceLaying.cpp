#include "SurfaceLaying.hpp"

#include <algorithm>
#include <utility>

namespace spatter::gallery {

namespace {

// The bounds of every object of `world`.
DBounds worldBounds(const CollisionWorld& world) {
    DBounds all;
    for (uint32_t i = 0; i < world.objectCount(); ++i)
        all.extend(world.worldBounds(i));
    return all;
}

// The part of `ray` that can meet the surfaces within `all`: from its start to the farthest corner of
// `all` (or its end, when nearer), any object's surface counting.
SurfaceLine shotLine(const Ray& ray, const DBounds& all) {
    double reach = 0.0;
    for (int corner = 0; corner < 8 && !all.empty(); ++corner) {
        const glm::dvec3 c((corner & 1) ? all.max.x : all.min.x, (corner & 2) ? all.max.y : all.min.y,
                           (corner & 4) ? all.max.z : all.min.z);
        reach = std::max(reach, glm::length(c - ray.origin));
    }
    const glm::dvec3 dir = glm::normalize(ray.direction);
    const double scale = glm::length(ray.direction); // tnear and tfar count in the direction's length
    const double from = ray.tnear * scale, to = std::min(ray.tfar * scale, reach);
    return {ray.origin + dir * from, ray.origin + dir * std::max(from, to), 0, true};
}

// `p` carried with an object from transform `then`, where the frame drew it, to `now` (normals by the
// inverse transpose).
SurfacePoint carried(SurfacePoint p, const glm::dmat4& then, const glm::dmat4& now) {
    const glm::dmat4 move = now * glm::inverse(then);
    p.point = glm::dvec3(move * glm::dvec4(p.point, 1.0));
    p.normal = glm::transpose(glm::inverse(glm::dmat3(move))) * p.normal;
    return p;
}

// The transform of every object of `sim`'s world.
std::vector<glm::dmat4> objectTransforms(const GallerySim& sim) {
    const CollisionWorld& world = sim.decals().world();
    std::vector<glm::dmat4> out(world.objectCount());
    for (uint32_t i = 0; i < world.objectCount(); ++i)
        out[i] = world.object(i)->transform;
    return out;
}

} // namespace

void SurfaceLaying::shot(const GallerySim::Shot& shot, const GallerySim& sim) {
    if (freshSystem_ != sim.systemNumber()) {
        fresh_.clear();
        freshRefused_.clear();
    }
    freshSystem_ = sim.systemNumber();
    if (shot.result.placed())
        fresh_.push_back(shot.result.handle);
    else if (shot.result.refusedByCollisionSurface() && !sim.decals().type(shot.type)->volumetric)
        freshRefused_.push_back(shot);
}

Status SurfaceLaying::search(Renderer& renderer, const GallerySim& sim) {
    Search s;
    std::vector<SurfaceLine> lines;
    const DecalSystem& decals = sim.decals();
    if (freshSystem_ != sim.systemNumber()) {
        fresh_.clear();
        freshRefused_.clear();
    }
    for (DecalHandle h : std::exchange(fresh_, {})) {
        const std::optional<DecalAxisLine> line = decals.axisLine(h);
        if (!line) continue;
        const Decal& d = *decals.get(h);
        // Craters keep the proxy's hit, decals on skinned targets lie on the drawn surface already, and
        // those on a texture-space object are in its texture once splatted.
        if (decals.type(d.type)->volumetric || decals.world().deforms(d.object) ||
            renderer.objectDecalMode(d.object) == DecalMode::TextureSpace)
            continue;
        lines.push_back({line->from, line->to, line->objectId});
        s.handles.push_back(h);
    }
    const DBounds all = freshRefused_.empty() ? DBounds{} : worldBounds(decals.world());
    for (GallerySim::Shot& shot : std::exchange(freshRefused_, {})) {
        lines.push_back(shotLine(shot.ray, all));
        s.refused.push_back(std::move(shot));
    }
    if (lines.empty()) return {};
    Result<uint64_t> request = renderer.findSurface(lines);
    if (!request) return fail(request.error());
    s.request = request.value();
    s.system = sim.systemNumber();
    s.transforms = objectTransforms(sim);
    searches_.push_back(std::move(s));
    return {};
}

void SurfaceLaying::layDecal(const Search& s, size_t i, const SurfacePoint& p, GallerySim& sim) {
    const Decal* d = sim.decals().get(s.handles[i]);
    if (!d) return;
    const SurfacePoint now =
        carried(p, s.transforms[d->object], sim.decals().world().object(d->object)->transform);
    const Result<DrawnSurfaceLaying> laid = sim.layOnDrawnSurface(s.handles[i], now.point, now.normal);
    if (laid) ++(laid.value() == DrawnSurfaceLaying::Laid ? laid_ : removed_);
}

void SurfaceLaying::spawnRefused(const Search& s, size_t i, const SurfacePoint& p, GallerySim& sim) {
    // Carried with the moving target whose ID the frame showed there; static surfaces (ID 0) stay.
    SurfacePoint now = p;
    const std::vector<uint8_t> ids = sim.decals().objectIds();
    const auto object = std::find(ids.begin(), ids.end(), p.objectId);
    if (p.objectId != 0 && object != ids.end()) {
        const uint32_t k = uint32_t(object - ids.begin());
        now = carried(p, s.transforms[k], sim.decals().world().object(k)->transform);
    }
    if (sim.spawnOnDrawnSurface(s.refused[i], now.point, now.normal).placed()) ++spawned_;
}

void SurfaceLaying::lay(Renderer& renderer, GallerySim& sim, bool wait) {
    while (!searches_.empty()) {
        const Search& s = searches_.front();
        const std::optional<std::vector<SurfacePoint>> points = renderer.surfaceFound(s.request, wait);
        if (!points && !wait && s.system == sim.systemNumber()) return; // not answered yet
        for (size_t i = 0; points && s.system == sim.systemNumber() && i < points->size(); ++i) {
            const SurfacePoint& p = (*points)[i];
            if (!p.found) continue;
            if (i < s.handles.size())
                layDecal(s, i, p, sim);
            else
                spawnRefused(s, i - s.handles.size(), p, sim);
        }
        searches_.pop_front();
    }
}

} // namespace spatter::gallery
