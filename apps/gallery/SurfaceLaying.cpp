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
    if (freshSystem_ != sim.systemNumber()) fresh_.clear();
    freshSystem_ = sim.systemNumber();
    if (shot.result.placed() ||
        (shot.result.refusedByCollisionSurface() && !sim.decals().type(shot.type)->volumetric))
        fresh_.push_back(shot);
}

bool SurfaceLaying::addDecalLines(const GallerySim::Shot& shot, const GallerySim& sim,
                                  const Renderer& renderer, std::vector<SurfaceLine>& lines,
                                  Searched& searched) const {
    const DecalSystem& decals = sim.decals();
    const std::optional<DecalAxisLine> line = decals.axisLine(shot.result.handle);
    if (!line) return false;
    const Decal& d = *decals.get(shot.result.handle);
    // Craters keep the proxy's hit, decals on skinned targets lie on the drawn surface already, and
    // those on a texture-space object are in its texture once splatted.
    if (decals.type(d.type)->volumetric || decals.world().deforms(d.object) ||
        renderer.objectDecalMode(d.object) == DecalMode::TextureSpace)
        return false;
    searched.box = lines.size();
    lines.push_back({line->from, line->to, line->objectId});
    if (line->alongShot) {
        searched.beforeBox = lines.size();
        lines.push_back({shot.ray.origin, line->from, 0, true});
    }
    return true;
}

Status SurfaceLaying::search(Renderer& renderer, const GallerySim& sim) {
    if (freshSystem_ != sim.systemNumber()) fresh_.clear();
    Search s;
    std::vector<SurfaceLine> lines;
    const bool anyRefused = std::any_of(fresh_.begin(), fresh_.end(),
                                        [](const GallerySim::Shot& f) { return !f.result.placed(); });
    const DBounds all = anyRefused ? worldBounds(sim.decals().world()) : DBounds{};
    for (GallerySim::Shot& shot : std::exchange(fresh_, {})) {
        Searched searched{shot};
        if (!shot.result.placed()) {
            searched.refused = lines.size();
            lines.push_back(shotLine(shot.ray, all));
        } else if (!addDecalLines(shot, sim, renderer, lines, searched)) {
            continue;
        }
        s.shots.push_back(std::move(searched));
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

void SurfaceLaying::layDecal(const Search& s, DecalHandle h, const SurfacePoint& p, GallerySim& sim) {
    const Decal* d = sim.decals().get(h);
    if (!d) return;
    const SurfacePoint now =
        carried(p, s.transforms[d->object], sim.decals().world().object(d->object)->transform);
    const Result<DrawnSurfaceLaying> laid = sim.layOnDrawnSurface(h, now.point, now.normal);
    if (laid) ++(laid.value() == DrawnSurfaceLaying::Laid ? laid_ : removed_);
}

SurfacePoint SurfaceLaying::withItsTarget(const Search& s, const SurfacePoint& p,
                                          const GallerySim& sim) const {
    const std::vector<uint8_t> ids = sim.decals().objectIds();
    const auto object = std::find(ids.begin(), ids.end(), p.objectId);
    if (p.objectId == 0 || object == ids.end()) return p;
    const uint32_t k = uint32_t(object - ids.begin());
    return carried(p, s.transforms[k], sim.decals().world().object(k)->transform);
}

void SurfaceLaying::take(const Search& s, const Searched& shot, const std::vector<SurfacePoint>& points,
                         GallerySim& sim) {
    auto found = [&](size_t line) { return line != kNoLine && points[line].found; };
    if (found(shot.refused)) {
        const SurfacePoint now = withItsTarget(s, points[shot.refused], sim);
        if (sim.spawnOnDrawnSurface(shot.shot, now.point, now.normal).placed()) ++spawned_;
        return;
    }
    if (found(shot.beforeBox)) {
        const SurfacePoint now = withItsTarget(s, points[shot.beforeBox], sim);
        const SpawnResult r = sim.replaceOnDrawnSurface(shot.shot, now.point, now.normal);
        if (r.placed() || r.status == SpawnStatus::GrazingAngle) {
            ++(r.placed() ? replaced_ : removed_);
            return;
        }
    }
    if (found(shot.box)) layDecal(s, shot.shot.result.handle, points[shot.box], sim);
}

void SurfaceLaying::lay(Renderer& renderer, GallerySim& sim, bool wait) {
    while (!searches_.empty()) {
        const Search& s = searches_.front();
        const std::optional<std::vector<SurfacePoint>> points = renderer.surfaceFound(s.request, wait);
        if (!points && !wait && s.system == sim.systemNumber()) return; // not answered yet
        for (size_t i = 0; points && s.system == sim.systemNumber() && i < s.shots.size(); ++i)
            take(s, s.shots[i], *points, sim);
        searches_.pop_front();
    }
}

} // namespace spatter::gallery
