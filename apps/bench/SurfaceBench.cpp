#include "SurfaceBench.hpp"

#include "BenchSupport.hpp"
#include "DecalField.hpp"

#include "spatter/core/Random.hpp"
#include "spatter/render/GlContext.hpp"

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace spatter::bench {

namespace {

const char* kSurfaceCommand = "surface";

const char* kSurfaceUsage =
    R"(usage: spatter-bench surface [--repetitions N] [--quick] [--json FILE]

What searching the drawn surface along lines costs (Renderer::findSurface, DecalProjector::findSurface):
what a game pays the frame after its shots to lay their decals on the drawn surface. The render
benchmarks' floor at 1080p, seen from above; lines 0.1 long through random points of the floor in
view, as a decal's axis line runs through its box. For 1 to 100,000 lines: the wall time from the
request to its points on the CPU (findSurface, then surfaceFound waiting for the GPU: the search,
its upload and its read-back), median of N repetitions, against the GPU time of the whole frame
searched (geometry, decal and lighting passes, 100 decals in view) measured in the same run, and
the lines whose meet was found.

--repetitions N  timed searches per count (default 15)     --quick  2 repetitions, up to 10,000 lines
--json FILE      {"frame_gpu_ms", "rows": [{"lines", "ms", "over_frame", "found"}], ...}
)";

struct Row {
    size_t lines = 0;
    double ms = 0.0;
    size_t found = 0;
};

// `count` vertical lines through random points of the floor in `view`.
std::vector<SurfaceLine> floorLines(const DecalFieldView& view, size_t count) {
    Rng rng(11);
    std::vector<SurfaceLine> lines(count);
    for (SurfaceLine& l : lines) {
        const glm::dvec3 p(view.halfWidth * 0.95 * double(rng.uniform(-1.0f, 1.0f)), 0.0,
                           view.halfHeight * 0.95 * double(rng.uniform(-1.0f, 1.0f)));
        l.from = p + glm::dvec3(0.0, 0.05, 0.0);
        l.to = p - glm::dvec3(0.0, 0.05, 0.0);
    }
    return lines;
}

// The median time from a search of `lines` to its points, over `repetitions` searches.
Result<Row> timeSearch(Renderer& r, const std::vector<SurfaceLine>& lines, size_t repetitions) {
    Row row;
    row.lines = lines.size();
    std::vector<double> ms;
    for (size_t i = 0; i <= repetitions; ++i) { // the first one warms up
        const double start = now();
        Result<uint64_t> request = r.findSurface(lines);
        if (!request) return fail(request.error());
        const std::optional<std::vector<SurfacePoint>> points = r.surfaceFound(request.value(), true);
        if (!points) return fail("no points for a search");
        if (i > 0) ms.push_back(1e3 * (now() - start));
        row.found = 0;
        for (const SurfacePoint& p : *points)
            row.found += p.found ? 1 : 0;
    }
    row.ms = median(ms);
    return row;
}

} // namespace

int runSurfaceCommand(int argc, char** argv) {
    int exitCode = 0;
    const std::optional<Args> parsed = commandArgs(argc, argv, kSurfaceCommand, kSurfaceUsage,
                                                   {"--repetitions", "--json"}, {"--quick"}, exitCode);
    if (!parsed) return exitCode;
    const Args& args = *parsed;
    if (!args.positional.empty()) return usageError(kSurfaceCommand, "no positional arguments");
    const bool quick = args.has("--quick");
    Result<uint64_t> repetitions =
        parseCount(args.value("--repetitions", quick ? "2" : "15"), "--repetitions");
    if (!repetitions) return usageError(kSurfaceCommand, repetitions.error());
    if (repetitions.value() == 0) return usageError(kSurfaceCommand, "--repetitions must be positive");

    const MachineInfo machine = machineInfo();
    std::printf("spatter-bench surface\nmachine: %s\n", describe(machine).c_str());
    Result<GlContext> gl = GlContext::createHeadless();
    if (!gl) {
        std::cerr << "spatter-bench surface: no OpenGL context: " << gl.error() << "\n";
        return 1;
    }
    RendererSettings rs;
    rs.width = 1920;
    rs.height = 1080;
    rs.waitForTimers = true;
    Result<Renderer> r = Renderer::create(gl.value(), rs);
    const DecalFieldView view = decalFieldView(16.0 / 9.0);
    if (r) {
        if (Status s = r->setScene(decalFieldScene(view, false)); !s) r = fail(s.error());
    }
    if (!r) {
        std::cerr << "spatter-bench surface: " << r.error() << "\n";
        return 1;
    }
    std::printf("GL: %s\n", gl->info().renderer.c_str());
    DecalType type;
    type.name = "default";
    r->setDecalTypes({type});
    r->setDecals(decalField(view, 100, 100, 0.015, 0, 1));
    Result<FrameTimes> frame = timeFrames(r.value(), view.camera, RenderOptions{}, 1, 7, 30.0);
    if (!frame) {
        std::cerr << "spatter-bench surface: " << frame.error() << "\n";
        return 1;
    }

    std::vector<Row> rows;
    std::vector<std::vector<std::string>> table;
    for (size_t count : {size_t(1), size_t(100), size_t(1000), size_t(10000), size_t(100000)}) {
        if (quick && count > 10000) break;
        Result<Row> row = timeSearch(r.value(), floorLines(view, count), repetitions.value());
        if (!row) {
            std::cerr << "spatter-bench surface: " << row.error() << "\n";
            return 1;
        }
        rows.push_back(row.value());
        table.push_back({std::to_string(row->lines), fixed(row->ms, 3),
                         fixed(row->ms / frame->totalMs, 3) + "x", std::to_string(row->found)});
    }
    std::printf("frame searched: %.3f ms of GPU (1080p, 100 decals in view)\n\n", frame->totalMs);
    printTable({"lines", "ms to the points", "over the frame", "found"}, table);

    if (args.has("--json")) {
        Json j;
        j["command"] = "surface";
        j["machine"] = toJson(machine);
        j["gl_renderer"] = gl->info().renderer;
        j["frame_gpu_ms"] = number(frame->totalMs);
        j["rows"] = Json::array();
        for (const Row& row : rows)
            j["rows"].push_back(Json{{"lines", row.lines},
                                     {"ms", number(row.ms)},
                                     {"over_frame", number(row.ms / frame->totalMs)},
                                     {"found", row.found}});
        if (Status s = writeJson(j, args.value("--json")); !s) {
            std::cerr << "spatter-bench surface: " << s.error() << "\n";
            return 1;
        }
    }
    return 0;
}

} // namespace spatter::bench
