#include "VolumetricBench.hpp"

#include "BenchSupport.hpp"
#include "DecalField.hpp"

#include "spatter/render/GlContext.hpp"

#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace spatter::bench {

namespace {

const char* kVolumetricCommand = "volumetric";

const char* kVolumetricUsage = R"(usage: spatter-bench volumetric [--frames N] [--quick] [--json FILE]

GPU time of volumetric decals (a stencil hole and a crater each, drawn instanced: two draws per
crater variant and winding) against the same number of flat decals, on the render benchmarks' decal
field at 1080p (a floor seen from above, every decal in view, each 2% of the screen height), for 1,
64, 256, 1024 and 4096 decals, with the frame without decals as the baseline. GPU ms are medians of
all passes; "pass" is the decal pass (flat) or the volumetric pass (volumetric) of the last frame.

--frames N  timed frames per row (default 15)   --quick  fewer counts and frames
--json FILE {"rows": [{"decals", "flat_ms", "flat_draws", "flat_pass_ms", "volumetric_ms",
            "volumetric_draws", "volumetric_pass_ms", "ratio"}], "empty_ms", ...}
)";

struct VolumetricRow {
    size_t decals = 0;
    FrameTimes flat, volumetric;
};

} // namespace

int runVolumetricCommand(int argc, char** argv) {
    int exitCode = 0;
    const std::optional<Args> parsed = commandArgs(argc, argv, kVolumetricCommand, kVolumetricUsage,
                                                   {"--frames", "--json"}, {"--quick"}, exitCode);
    if (!parsed) return exitCode;
    const Args& args = *parsed;
    if (!args.positional.empty()) return usageError(kVolumetricCommand, "no positional arguments");
    const bool quick = args.has("--quick");
    Result<uint64_t> frames = parseCount(args.value("--frames", quick ? "3" : "15"), "--frames");
    if (!frames) return usageError(kVolumetricCommand, frames.error());
    if (frames.value() == 0) return usageError(kVolumetricCommand, "--frames must be positive");
    const std::vector<size_t> counts =
        quick ? std::vector<size_t>{1, 256} : std::vector<size_t>{1, 64, 256, 1024, 4096};

    const MachineInfo machine = machineInfo();
    std::printf("spatter-bench volumetric\nmachine: %s\n", describe(machine).c_str());
    Result<GlContext> gl = GlContext::createHeadless();
    if (!gl) {
        std::cerr << "spatter-bench volumetric: " << gl.error() << "\n";
        return 1;
    }
    std::printf("GL: %s\n", gl->info().renderer.c_str());
    std::fflush(stdout);
    RendererSettings rs;
    rs.width = 1920;
    rs.height = 1080;
    rs.waitForTimers = true;
    Result<Renderer> r = Renderer::create(gl.value(), rs);
    if (!r) {
        std::cerr << "spatter-bench volumetric: " << r.error() << "\n";
        return 1;
    }
    const DecalFieldView view = decalFieldView(16.0 / 9.0);
    if (Status s = r->setScene(decalFieldScene(view, false)); !s) {
        std::cerr << "spatter-bench volumetric: " << s.error() << "\n";
        return 1;
    }
    DecalType flat;
    flat.name = "flat";
    DecalType hole = flat;
    hole.name = "hole";
    hole.volumetric = true;
    r->setDecalTypes({flat, hole});
    auto time = [&](const std::vector<Decal>& decals) {
        r->setDecals(decals);
        return timeFrames(r.value(), view.camera, RenderOptions{}, 2, frames.value(), 60.0);
    };

    const Result<FrameTimes> empty = time({});
    if (!empty) {
        std::cerr << "spatter-bench volumetric: " << empty.error() << "\n";
        return 1;
    }
    std::vector<VolumetricRow> rows;
    for (const size_t n : counts) {
        const Result<FrameTimes> f = time(decalField(view, n, n, 0.02, 0, 7));
        const Result<FrameTimes> v = time(decalField(view, n, n, 0.02, 1, 7));
        if (!f || !v) {
            std::cerr << "spatter-bench volumetric: " << (!f ? f.error() : v.error()) << "\n";
            return 1;
        }
        rows.push_back({n, f.value(), v.value()});
    }

    std::vector<std::vector<std::string>> table;
    for (const VolumetricRow& row : rows)
        table.push_back({std::to_string(row.decals), fmt(row.flat.totalMs, 3),
                         std::to_string(row.flat.last.drawCalls), fmt(row.flat.last.gpu.decalsMs, 3),
                         fmt(row.volumetric.totalMs, 3), std::to_string(row.volumetric.last.drawCalls),
                         fmt(row.volumetric.last.gpu.volumetricMs, 3),
                         fixed(row.volumetric.totalMs / row.flat.totalMs, 2) + "x"});
    std::printf("\nno decals: %s GPU ms\n\n", fmt(empty->totalMs, 3).c_str());
    printTable({"decals", "flat ms", "flat draws", "flat pass ms", "volumetric ms", "volumetric draws",
                "volumetric pass ms", "volumetric/flat"},
               table);

    if (args.has("--json")) {
        Json j;
        j["command"] = kVolumetricCommand;
        j["machine"] = toJson(machine);
        j["gl_renderer"] = gl->info().renderer;
        j["empty_ms"] = number(empty->totalMs);
        j["rows"] = Json::array();
        for (const VolumetricRow& row : rows)
            j["rows"].push_back({{"decals", row.decals},
                                 {"flat_ms", number(row.flat.totalMs)},
                                 {"flat_draws", row.flat.last.drawCalls},
                                 {"flat_pass_ms", number(row.flat.last.gpu.decalsMs)},
                                 {"volumetric_ms", number(row.volumetric.totalMs)},
                                 {"volumetric_draws", row.volumetric.last.drawCalls},
                                 {"volumetric_pass_ms", number(row.volumetric.last.gpu.volumetricMs)},
                                 {"ratio", number(row.volumetric.totalMs / row.flat.totalMs)}});
        if (Status s = writeJson(j, args.value("--json")); !s) {
            std::cerr << "spatter-bench volumetric: " << s.error() << "\n";
            return 1;
        }
    }
    return 0;
}

} // namespace spatter::bench
