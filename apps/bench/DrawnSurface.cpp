#include "DrawnSurface.hpp"

namespace spatter::bench {

namespace {

// What one search found for one shot: its decal laid again (or removed), or a decal placed where the
// shot that the proxy refused meets the drawn surface.
void takePoint(DecalSystem& system, const SpawnResult& placed, const Ray& shot, const SurfacePoint& p,
               DrawnSurfaceCounts& counts) {
    if (!p.found) return;
    if (!placed.placed()) {
        if (system.spawnOnDrawnSurface(shot, p.point, p.normal, 0).placed()) ++counts.spawned;
        return;
    }
    const Result<DrawnSurfaceLaying> r = system.layOnDrawnSurface(placed.handle, p.point, p.normal);
    if (r) ++(r.value() == DrawnSurfaceLaying::Laid ? counts.laid : counts.removed);
}

} // namespace

Result<DrawnSurfaceCounts> layOnDrawnSurface(DecalSystem& system, const std::vector<Ray>& shots,
                                             const std::vector<SpawnResult>& placed, Renderer& renderer,
                                             const Camera& camera, glm::ivec2 probeSize, double shotReach) {
    const int width = renderer.settings().width, height = renderer.settings().height;
    std::vector<size_t> which;
    std::vector<SurfaceLine> lines;
    for (size_t i = 0; i < placed.size(); ++i) {
        const SpawnResult& r = placed[i];
        if (r.refusedByCollisionSurface()) {
            const glm::dvec3 dir = glm::normalize(shots[i].direction);
            lines.push_back({shots[i].origin, shots[i].origin + dir * shotReach, 0, true});
            which.push_back(i);
            continue;
        }
        const std::optional<DecalAxisLine> line = r.placed() ? system.axisLine(r.handle) : std::nullopt;
        if (!line) continue;
        which.push_back(i);
        lines.push_back({line->from, line->to, line->objectId});
    }
    if (Status s = renderer.resize(probeSize.x, probeSize.y); !s) return fail(s.error());
    renderer.setDecals({});
    Result<FrameStats> frame = renderer.render(camera, View::Final);
    Result<uint64_t> request = frame ? renderer.findSurface(lines) : Result<uint64_t>(fail(frame.error()));
    std::optional<std::vector<SurfacePoint>> points;
    if (request) points = renderer.surfaceFound(request.value(), true);
    if (Status s = renderer.resize(width, height); !s) return fail(s.error());
    if (!request) return fail(request.error());
    if (!points) return fail("the surface search gave no result");
    DrawnSurfaceCounts counts;
    for (size_t k = 0; k < which.size(); ++k)
        takePoint(system, placed[which[k]], shots[which[k]], (*points)[k], counts);
    return counts;
}

} // namespace spatter::bench
