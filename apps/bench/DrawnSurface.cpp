#include "DrawnSurface.hpp"

namespace spatter::bench {

Result<size_t> layOnDrawnSurface(DecalSystem& system, const std::vector<SpawnResult>& placed,
                                 Renderer& renderer, const Camera& camera, glm::ivec2 probeSize) {
    const int width = renderer.settings().width, height = renderer.settings().height;
    std::vector<DecalHandle> handles;
    std::vector<SurfaceLine> lines;
    for (const SpawnResult& r : placed) {
        const std::optional<DecalAxisLine> line = r.placed() ? system.axisLine(r.handle) : std::nullopt;
        if (!line) continue;
        handles.push_back(r.handle);
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
    size_t laid = 0;
    for (size_t i = 0; i < handles.size(); ++i) {
        if (!(*points)[i].found) continue;
        const Result<DrawnSurfaceLaying> r =
            system.layOnDrawnSurface(handles[i], (*points)[i].point, (*points)[i].normal);
        if (r && r.value() == DrawnSurfaceLaying::Laid) ++laid;
    }
    return laid;
}

} // namespace spatter::bench
