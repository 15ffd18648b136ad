#include "DrawnSurface.hpp"

#include <limits>

namespace spatter::bench {

namespace {

constexpr size_t kNoLine = std::numeric_limits<size_t>::max();

// The lines searched for one shot (indices into the search's lines): a placed decal's axis line
// through its box and, for a decal along its shot, the shot from its origin to the box; or the shot
// itself where the proxy refused it.
struct ShotLines {
    size_t box = kNoLine, beforeBox = kNoLine, shot = kNoLine;
};

bool found(const std::vector<SurfacePoint>& points, size_t line) {
    return line != kNoLine && points[line].found;
}

// What one search found for one shot: a decal placed where the shot that the proxy refused meets the
// drawn surface; a decal that gives way to the shot's decal where the shot met the drawn surface
// before its box (or is removed, the shot meeting it too steeply); else the decal laid again where
// its axis meets the drawn surface (or removed there).
void takePoints(DecalSystem& system, const SpawnResult& placed, const Ray& shot, const ShotLines& at,
                const std::vector<SurfacePoint>& points, DrawnSurfaceCounts& counts) {
    if (found(points, at.shot)) {
        const SurfacePoint& p = points[at.shot];
        if (system.spawnOnDrawnSurface(shot, p.point, p.normal, 0).placed()) ++counts.spawned;
        return;
    }
    if (found(points, at.beforeBox)) {
        const SurfacePoint& p = points[at.beforeBox];
        const SpawnResult r = system.replaceOnDrawnSurface(placed.handle, shot, p.point, p.normal);
        if (r.placed() || r.status == SpawnStatus::GrazingAngle) {
            ++(r.placed() ? counts.moved : counts.removed);
            return;
        }
    }
    if (!found(points, at.box)) return;
    const Result<DrawnSurfaceLaying> r =
        system.layOnDrawnSurface(placed.handle, points[at.box].point, points[at.box].normal);
    if (r) ++(r.value() == DrawnSurfaceLaying::Laid ? counts.laid : counts.removed);
}

// The lines to search for `shots` and their results `placed`, and which are whose.
std::vector<SurfaceLine> searchLines(const DecalSystem& system, const std::vector<Ray>& shots,
                                     const std::vector<SpawnResult>& placed, double shotReach,
                                     std::vector<ShotLines>& at) {
    std::vector<SurfaceLine> lines;
    at.assign(placed.size(), ShotLines{});
    for (size_t i = 0; i < placed.size(); ++i) {
        const Ray& shot = shots[i];
        if (placed[i].refusedByCollisionSurface()) {
            at[i].shot = lines.size();
            lines.push_back({shot.origin, shot.origin + glm::normalize(shot.direction) * shotReach, 0, true});
            continue;
        }
        const std::optional<DecalAxisLine> line =
            placed[i].placed() ? system.axisLine(placed[i].handle) : std::nullopt;
        if (!line) continue;
        at[i].box = lines.size();
        lines.push_back({line->from, line->to, line->objectId});
        if (!line->alongShot) continue;
        at[i].beforeBox = lines.size();
        lines.push_back({shot.origin, line->from, 0, true});
    }
    return lines;
}

} // namespace

Result<DrawnSurfaceCounts> layOnDrawnSurface(DecalSystem& system, const std::vector<Ray>& shots,
                                             const std::vector<SpawnResult>& placed, Renderer& renderer,
                                             const Camera& camera, glm::ivec2 probeSize, double shotReach) {
    const int width = renderer.settings().width, height = renderer.settings().height;
    std::vector<ShotLines> at;
    const std::vector<SurfaceLine> lines = searchLines(system, shots, placed, shotReach, at);
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
    for (size_t i = 0; i < placed.size(); ++i)
        takePoints(system, placed[i], shots[i], at[i], *points, counts);
    return counts;
}

} // namespace spatter::bench
