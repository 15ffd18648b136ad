#include "SurfaceLaying.hpp"

#include <utility>

namespace spatter::gallery {

void SurfaceLaying::placed(const SpawnResult& result, const GallerySim& sim) {
    if (freshSystem_ != sim.systemNumber()) fresh_.clear();
    freshSystem_ = sim.systemNumber();
    if (result.placed()) fresh_.push_back(result.handle);
}

Status SurfaceLaying::search(Renderer& renderer, const GallerySim& sim) {
    Search s;
    std::vector<SurfaceLine> lines;
    const DecalSystem& decals = sim.decals();
    if (freshSystem_ != sim.systemNumber()) fresh_.clear();
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
        s.transforms.push_back(decals.world().object(d.object)->transform);
    }
    if (lines.empty()) return {};
    Result<uint64_t> request = renderer.findSurface(lines);
    if (!request) return fail(request.error());
    s.request = request.value();
    s.system = sim.systemNumber();
    searches_.push_back(std::move(s));
    return {};
}

void SurfaceLaying::lay(Renderer& renderer, GallerySim& sim, bool wait) {
    while (!searches_.empty()) {
        const Search& s = searches_.front();
        const std::optional<std::vector<SurfacePoint>> points = renderer.surfaceFound(s.request, wait);
        if (!points && !wait && s.system == sim.systemNumber()) return; // not answered yet
        for (size_t i = 0; points && s.system == sim.systemNumber() && i < s.handles.size(); ++i) {
            const SurfacePoint& p = (*points)[i];
            const Decal* d = sim.decals().get(s.handles[i]);
            if (!p.found || !d) continue;
            // From the object as the frame drew it to the object now (normals by the inverse transpose).
            const glm::dmat4 now = sim.decals().world().object(d->object)->transform;
            const glm::dmat4 move = now * glm::inverse(s.transforms[i]);
            const glm::dvec3 point(move * glm::dvec4(p.point, 1.0));
            const glm::dvec3 normal = glm::transpose(glm::inverse(glm::dmat3(move))) * p.normal;
            const Result<DrawnSurfaceLaying> laid = sim.layOnDrawnSurface(s.handles[i], point, normal);
            if (laid) ++(laid.value() == DrawnSurfaceLaying::Laid ? laid_ : removed_);
        }
        searches_.pop_front();
    }
}

} // namespace spatter::gallery
