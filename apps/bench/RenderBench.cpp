#include "RenderBench.hpp"

#include "BenchSupport.hpp"
#include "DecalField.hpp"
#include "PathHost.hpp"

#include "spatter/render/GlContext.hpp"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace spatter::bench {

namespace {

const char* kRenderCommand = "render";

const char* kRenderUsage =
    R"(usage: spatter-bench render [--groups LIST] [--frames N] [--rounds N] [--max-seconds S] [--quick]
                            [--json FILE]

GPU time of the decal pass (GL_TIME_ELAPSED, RendererSettings::waitForTimers; median of the frames)
on a flat floor seen from above, with decals laid on it directly: a number in the world, a number
of them in view, each a square of a fraction of the screen height. Groups of rows:

  count        1080p, every decal in view: 100, 1,000, 10,000, 100,000, 1,000,000 decals
  visible      1080p, 10,000 and 1,000,000 decals in the world, 0.01% to 10% of them in view (the
               decals in view spawned first), and 1% of 1,000,000 spawned among the others
               (spread: one in view every hundred decals of the spawn order, as a world shot at
               over time holds them)
  coverage     1080p, 10,000 decals in view, each 0.5%, 1.5% or 5% of the screen height
  resolution   10,000 decals in view at 720p, 1080p and 4K
  features     1080p, 10,000 decals in view: minimal (no normal map, no fade), default (normal map
               and smooth fade), wrap-around, depth-derivative normal frame, object IDs (a dynamic
               object in the scene), angle rejection off, projected along a shot 45 degrees from
               the floor's normal
  cpu          1080p, 10,000 decals in view among 10,000 and among 1,000,000 in the world, and 600
               among 60,000 (fewer than ProjectorSettings::gpuCullingFrom: culled on the CPU): the
               wall time of render() when it does not wait for the GPU (a glFinish after each frame,
               outside the time), with the GPU times of an earlier frame
  occlusion    1080p, 1,000,000 decals in the world, 10,000 in the view's frustum, with and without
               occlusion culling (RendererSettings::occlusionCulling), with nothing hiding them and
               with a roof over nine tenths of them
  paths        1080p, 100, 10,000 and 100,000 decals in view, the same decals through spatter's
               renderer and through the projector in a host of its own with the frame layout of
               spatter-example-deferred (24-bit standard Z, RGB10A2 world normals, roughness in
               the albedo's alpha, object IDs): G-buffer blend, DBuffer and forward. A path's decal
               cost is the projector's pass plus what the decals add to the host's passes (the
               DBuffer applied in the lighting pass, the forward pass's decal loop)

Unless a group says otherwise decals cover 1.5% of the screen height (16 pixels at 1080p) and use the
default features. Targets (for a GPU; reported for whatever renderer runs): 10,000 decals in view at
1080p cost at most 0.5 ms in the decal pass; 1,000,000 in the world with 1% in view at most 1.1
times that; 10 in view at most 0.03 ms; per covered pixel (coverage group) at most 1.5 times the
lighting pass's cost per pixel; the projector's G-buffer blend in the host at most 1.1 times the
renderer's decal pass.

--groups LIST     comma-separated groups (default all)
--frames N        timed frames per row after one warm-up frame (default 7)
--rounds N        measure the rows N times over, one row after the other each time, and take each
                  figure's median over the rounds (each round's figure is the median of its frames):
                  where the machine's speed drifts, as a software renderer's does with the load on
                  its cores, every row then sees the same drift (default 1)
--max-seconds S   wall-time cap per row and round: fewer frames are timed when it is reached (default 20)
--forward-tile N  the forward path's tile size in pixels (ProjectorSettings::forwardTileSize, default 16)
--resolve MODE    how the G-buffer blend and the DBuffer are drawn (deferredResolve): auto (default:
                  one compute pass on a GPU from 256 decals in view, boxes otherwise), boxes or compute
--stages          also time the decal pass's stages (ProjectorSettings::stageTimers: GPU timestamps
                  after the culling, the binning, the drawing and the read-back of the counts; each
                  waits for the work before it, so the stages add up to a little more than decal ms)
                  and print them (JSON rows: "decal_stages_ms": {"cull", "bin", "draw", "read_back"})
--quick           720p and 1080p, at most 10,000 decals in view (100,000 in the world for the
                  occlusion group), 2 frames, 3 s per row (smoke test)
--json FILE       {"rows": [{"group", "resolution", "world", "visible", "decal_px", "feature",
                  "decal_ms", "ns_per_visible_decal", "projector_ms", "host_pass_ms",
                  "baseline_ms", "frames_compute", "frames_tiles_left_out", ...}], "targets":
                  {...}, "gl_renderer", ...}
)";

struct Feature {
    const char* name;
    bool normalMap = true;
    DepthFade fade = DepthFade::Smooth;
    bool wrap = false;
    bool depthFrame = false;
    bool ids = false;
    bool angleReject = true;
    bool wait = true;      // render() waits for the frame's GPU times; false: CPU time of render() alone
    bool occlusion = true; // RendererSettings::occlusionCulling
    bool shot = false;     // the decals projected along a shot 45 degrees from the floor's normal
    bool spread = false;   // the decals in view spread evenly through the spawn order (spreadVisible)
};

const std::vector<Feature>& features() {
    static const std::vector<Feature> all = {
        {"minimal", false, DepthFade::None, false, false, false, true},
        {"default", true, DepthFade::Smooth, false, false, false, true},
        {"wrap", true, DepthFade::Smooth, true, false, false, true},
        {"depth-frame", true, DepthFade::Smooth, false, true, false, true},
        {"ids", true, DepthFade::Smooth, false, false, true, true},
        {"no-angle", true, DepthFade::Smooth, false, false, false, false},
        {"no-wait", true, DepthFade::Smooth, false, false, false, true, false},
        {"no-occlusion", true, DepthFade::Smooth, false, false, false, true, true, false},
        {"shot", true, DepthFade::Smooth, false, false, false, true, true, true, true},
        {"spread", true, DepthFade::Smooth, false, false, false, true, true, true, false, true},
    };
    return all;
}

// `decals` (decalField's: the `visible` ones first) reordered so that the visible ones lie evenly
// through the others, one every decals.size() / visible places.
std::vector<Decal> spreadVisible(const std::vector<Decal>& decals, size_t visible) {
    std::vector<Decal> out;
    out.reserve(decals.size());
    const size_t every = visible ? decals.size() / visible : decals.size() + 1;
    size_t shown = 0, hidden = visible;
    for (size_t i = 0; i < decals.size(); ++i)
        out.push_back(i % every == 0 && shown < visible ? decals[shown++] : decals[hidden++]);
    return out;
}

const Feature& feature(const std::string& name) {
    for (const Feature& f : features())
        if (name == f.name) return f;
    return features()[1];
}

struct Config {
    std::string group;
    std::string resolution;
    size_t world = 0;
    size_t visible = 0;
    double size = 0.015; // of the screen height
    std::string feature = "default";
    bool roof = false; // the decal field's roof hides nine tenths of the floor in view

    auto key() const { return std::make_tuple(resolution, world, visible, size, feature, roof); }
};

std::vector<Config> configs(const std::vector<std::string>& groups, bool quick) {
    std::vector<Config> out;
    auto want = [&](const char* g) {
        return groups.empty() || std::find(groups.begin(), groups.end(), g) != groups.end();
    };
    if (want("count"))
        for (size_t n :
             quick ? std::vector<size_t>{100, 1000} : std::vector<size_t>{100, 1000, 10000, 100000, 1000000})
            out.push_back({"count", "1080p", n, n});
    if (want("visible")) {
        for (size_t v : quick ? std::vector<size_t>{100} : std::vector<size_t>{1000, 100, 10})
            out.push_back({"visible", "1080p", 10000, v});
        if (!quick)
            for (size_t v : {100000, 10000, 1000, 100})
                out.push_back({"visible", "1080p", 1000000, v});
        if (!quick) out.push_back({"visible", "1080p", 1000000, 10000, 0.015, "spread"});
    }
    if (want("coverage"))
        for (double s : quick ? std::vector<double>{0.015} : std::vector<double>{0.005, 0.015, 0.05})
            out.push_back({"coverage", "1080p", quick ? 1000u : 10000u, quick ? 1000u : 10000u, s});
    if (want("resolution"))
        for (const char* r :
             quick ? std::vector<const char*>{"720p"} : std::vector<const char*>{"720p", "1080p", "4k"})
            out.push_back({"resolution", r, quick ? 1000u : 10000u, quick ? 1000u : 10000u});
    // The features group's rows (the other features are rows of the visible, cpu and occlusion groups).
    const std::vector<const char*> featureRows =
        quick ? std::vector<const char*>{"minimal", "default"}
              : std::vector<const char*>{"minimal", "default",  "wrap", "depth-frame",
                                         "ids",     "no-angle", "shot"};
    if (want("features"))
        for (const char* f : featureRows)
            out.push_back({"features", "1080p", quick ? 1000u : 10000u, quick ? 1000u : 10000u, 0.015, f});
    if (want("cpu")) {
        for (size_t world : quick ? std::vector<size_t>{1000} : std::vector<size_t>{10000, 1000000})
            out.push_back({"cpu", "1080p", world, std::min<size_t>(world, 10000), 0.015, "no-wait"});
        if (!quick) out.push_back({"cpu", "1080p", 60000, 600, 0.015, "no-wait"}); // culled on the CPU
    }
    if (want("occlusion"))
        for (bool roof : {false, true})
            for (const char* f : {"default", "no-occlusion"})
                out.push_back({"occlusion", "1080p", quick ? 100000u : 1000000u, 10000, 0.015, f, roof});
    if (want("paths"))
        for (size_t n : quick ? std::vector<size_t>{100, 1000} : std::vector<size_t>{100, 10000, 100000})
            for (const char* path : {"renderer", "blend", "dbuffer", "forward"})
                out.push_back({"paths", "1080p", n, n, 0.015, path});
    return out;
}

struct RenderRow {
    Config config;
    int width = 0, height = 0;
    FrameTimes times; // for the projector's paths: decalsMs is the path's decal cost
    PathTimes path;   // the projector's paths: medians of the frames
    // The projector's paths: frames resolved by the compute pass, and frames whose binning left decals
    // out of the screen tiles (ProjectorStats::tilesLeftOut).
    size_t computeFrames = 0, leftOutFrames = 0;
    double setDecalsS = 0.0;
    std::string error;
};

bool projectorPath(const Config& c) {
    return c.group == "paths" && c.feature != "renderer";
}

HostPath hostPath(const std::string& name) {
    return name == "dbuffer"   ? HostPath::DBuffer
           : name == "forward" ? HostPath::Forward
                               : HostPath::GBufferBlend;
}

// One renderer per normal frame, resized and given scenes as the rows need them.
class Bench {
public:
    Bench(std::unique_ptr<GlContext> context, int forwardTile, DeferredResolve resolve, bool stages)
        : context_(std::move(context)), forwardTile_(forwardTile), resolve_(resolve), stages_(stages) {}
    const GlContext& context() const { return *context_; }

    Result<RenderRow> run(const Config& c, size_t frames, double maxSeconds) {
        if (projectorPath(c)) return runPath(c, frames, maxSeconds);
        RenderRow row;
        row.config = c;
        if (!resolutionByName(c.resolution, row.width, row.height))
            return fail("unknown resolution " + c.resolution);
        const Feature& f = feature(c.feature);
        const int slot = !f.wait ? 2 : f.depthFrame ? 1 : !f.occlusion ? 3 : 0;
        if (!renderers_[slot]) {
            RendererSettings rs;
            rs.width = row.width;
            rs.height = row.height;
            rs.waitForTimers = f.wait;
            rs.occlusionCulling = f.occlusion;
            rs.deferredResolve = resolve_;
            rs.decalStageTimers = stages_;
            rs.normalFrame = f.depthFrame ? DecalNormalFrame::DepthDerivatives : DecalNormalFrame::DecalAxes;
            Result<Renderer> r = Renderer::create(*context_, rs);
            if (!r) return fail(r.error());
            renderers_[slot].emplace(std::move(r).value());
            sceneIds_[slot] = -1;
        }
        Renderer& r = *renderers_[slot];
        if (r.settings().width != row.width || r.settings().height != row.height)
            if (Status s = r.resize(row.width, row.height); !s) return fail(s.error());
        const DecalFieldView view = decalFieldView(double(row.width) / double(row.height));
        const int sceneKey = int(f.ids) | int(c.roof) << 1;
        if (sceneIds_[slot] != sceneKey) {
            const Scene scene = decalFieldScene(view, f.ids, c.roof);
            if (Status s = r.setScene(scene); !s) return fail(s.error());
            if (f.ids)
                if (Status s = r.setObjectIds({0, 1}); !s) return fail(s.error());
            sceneIds_[slot] = sceneKey;
            decalsKey_[slot] = {};
        }
        DecalType type;
        type.name = "bench";
        type.normalMap = f.normalMap;
        type.depthFade = f.fade;
        type.wrapAround = f.wrap;
        r.setDecalTypes({type});
        const auto key = std::make_tuple(c.world, c.visible, c.size, f.shot, f.spread);
        if (decalsKey_[slot] != key) {
            std::vector<Decal> decals = decalField(view, c.world, c.visible, c.size, 0, 1);
            if (f.spread) decals = spreadVisible(decals, c.visible);
            if (f.shot)
                for (Decal& d : decals)
                    d.setProjectionAxis(glm::vec3(0.70710678f, 0.70710678f, 0.0f));
            const double start = now();
            r.setDecals(decals);
            row.setDecalsS = now() - start;
            decalsKey_[slot] = key;
        }
        RenderOptions options;
        options.decals.angleReject = f.angleReject;
        Result<FrameTimes> t = f.wait ? timeFrames(r, view.camera, options, 1, frames, maxSeconds)
                                      : cpuFrames(r, view.camera, options, frames);
        if (!t) return fail(t.error());
        row.times = t.value();
        return row;
    }

    // render()'s wall time without waiting for the GPU: each frame is finished outside the time.
    static Result<FrameTimes> cpuFrames(Renderer& r, const Camera& camera, const RenderOptions& options,
                                        size_t frames) {
        FrameTimes t;
        std::vector<double> cpu;
        for (size_t i = 0; i < frames + 1; ++i) { // the first frame warms up
            const double start = now();
            Result<FrameStats> s = r.render(camera, options);
            const double ms = 1e3 * (now() - start);
            if (!s) return fail(s.error());
            glFinish();
            if (i == 0) continue;
            cpu.push_back(ms);
            t.last = s.value();
            t.decalsMs = s->gpu.decalsMs; // of an earlier frame
            t.geometryMs = s->gpu.geometryMs;
            t.lightingMs = s->gpu.lightingMs;
        }
        t.frames = cpu.size();
        t.cpuMs = median(cpu);
        return t;
    }

private:
    // A row of the projector in the bench's own host (PathHost), on the floor of the decal field.
    Result<RenderRow> runPath(const Config& c, size_t frames, double maxSeconds) {
        RenderRow row;
        row.config = c;
        if (!resolutionByName(c.resolution, row.width, row.height))
            return fail("unknown resolution " + c.resolution);
        const DecalFieldView view = decalFieldView(double(row.width) / double(row.height));
        if (Status s = preparePath(row.width, row.height, view); !s) return fail(s.error());
        const auto key = std::make_tuple(c.world, c.visible, c.size);
        if (projectorKey_ != key) {
            const std::vector<Decal> decals = decalField(view, c.world, c.visible, c.size, 0, 1);
            const double start = now();
            projector_->setDecals(decals);
            row.setDecalsS = now() - start;
            projectorKey_ = key;
        }
        const HostPath path = hostPath(c.feature);
        const double start = now();
        std::vector<double> cost, projector, pass, baseline, cpu;
        for (size_t i = 0; i < frames + 1; ++i) { // the first frame warms up
            if (i > 1 && now() - start > maxSeconds) {
                row.times.capped = true;
                break;
            }
            const double frameStart = now();
            Result<PathTimes> t = pathHost_->frame(path, *projector_, view.camera);
            if (!t) return fail(t.error());
            if (i == 0) continue;
            cpu.push_back(1e3 * (now() - frameStart));
            cost.push_back(t->decalMs());
            projector.push_back(t->projectorMs);
            pass.push_back(t->hostPassMs);
            baseline.push_back(t->baselineMs);
            row.path.stats = t->stats;
            row.computeFrames += t->stats.variant.find("COMPUTE") != std::string::npos ? 1 : 0;
            row.leftOutFrames += t->stats.tilesLeftOut ? 1 : 0;
        }
        row.times.frames = cost.size();
        row.times.decalsMs = median(cost);
        row.times.cpuMs = median(cpu);
        row.times.last.decalVariant = row.path.stats.variant;
        row.times.last.decalsDrawn = row.path.stats.drawn;
        row.times.last.decalsCulled = row.path.stats.culled;
        row.times.last.decalPassSkipped = row.path.stats.skipped;
        row.path.projectorMs = median(projector);
        row.path.hostPassMs = median(pass);
        row.path.baselineMs = median(baseline);
        return row;
    }

    Status preparePath(int width, int height, const DecalFieldView& view) {
        if (!pathHost_ || pathSize_ != glm::ivec2(width, height)) {
            Result<PathHost> host = PathHost::create(width, height);
            if (!host) return fail(host.error());
            pathHost_.emplace(std::move(host).value());
            pathHost_->setScene(decalFieldScene(view, false));
            pathSize_ = glm::ivec2(width, height);
        }
        if (projector_) return {};
        ProjectorSettings ps;
        ps.waitForTimers = true;
        ps.forwardTileSize = forwardTile_;
        ps.deferredResolve = resolve_;
        Result<DecalProjector> p = DecalProjector::create(ps);
        if (!p) return fail(p.error());
        projector_.emplace(std::move(p).value());
        DecalType type;
        type.name = "bench";
        projector_->setDecalTypes({type});
        return projector_->setObjects({glm::dmat4(1.0)}, {0});
    }

    std::unique_ptr<GlContext> context_;
    int forwardTile_ = 16;
    DeferredResolve resolve_ = DeferredResolve::Auto;
    bool stages_ = false;
    std::optional<PathHost> pathHost_;
    glm::ivec2 pathSize_{0};
    std::optional<DecalProjector> projector_;
    std::tuple<size_t, size_t, double> projectorKey_;
    // Waiting for GPU times, with the depth frame, not waiting, without occlusion culling.
    std::optional<Renderer> renderers_[4];
    int sceneIds_[4] = {-1, -1, -1, -1};
    std::tuple<size_t, size_t, double, bool, bool> decalsKey_[4];
};

// The feature, and whether the roof hides most of the view.
std::string featureLabel(const Config& c) {
    return c.roof ? c.feature + "+roof" : c.feature;
}

// The decal pass's stages of the rows that timed them (--stages).
void printStages(const std::vector<RenderRow>& rows) {
    std::vector<std::vector<std::string>> table;
    for (const RenderRow& r : rows) {
        const ProjectorStageTimes& st = r.times.decalStages;
        if (!r.error.empty() || st.frame < 0) continue;
        const Config& c = r.config;
        table.push_back({c.group, c.resolution, std::to_string(c.world), std::to_string(c.visible),
                         fixed(c.size * r.height, 0), featureLabel(c), fixed(st.cullMs, 3),
                         fixed(st.binMs, 3), fixed(st.drawMs, 3), fixed(st.readBackMs, 3),
                         fixed(st.cullMs + st.binMs + st.drawMs + st.readBackMs, 3),
                         fixed(r.times.decalsMs, 3)});
    }
    std::printf("\ndecal pass stages (ms, medians; GPU timestamps between the stages)\n");
    printTable({"group", "res", "world", "visible", "px", "feature", "cull", "bin", "draw", "read-back",
                "sum", "decal ms"},
               table);
}

Json renderRowJson(const RenderRow& r) {
    const Config& c = r.config;
    Json j;
    j["group"] = c.group;
    j["resolution"] = c.resolution;
    j["width"] = r.width;
    j["height"] = r.height;
    j["world"] = c.world;
    j["visible"] = c.visible;
    j["visible_fraction"] = c.world ? double(c.visible) / double(c.world) : 0.0;
    j["decal_screen_fraction"] = c.size;
    j["decal_px"] = c.size * r.height;
    j["feature"] = c.feature;
    j["roof"] = c.roof;
    if (!r.error.empty()) {
        j["error"] = r.error;
        return j;
    }
    const FrameStats& s = r.times.last;
    j["variant"] = s.decalVariant;
    j["decals_drawn"] = s.decalsDrawn;
    j["decals_culled"] = s.decalsCulled;
    j["decal_pass_skipped"] = s.decalPassSkipped;
    j["decal_ms"] = r.times.decalsMs;
    j["ns_per_visible_decal"] = c.visible ? r.times.decalsMs * 1e6 / double(c.visible) : 0.0;
    j["geometry_ms"] = r.times.geometryMs;
    j["lighting_ms"] = r.times.lightingMs;
    j["total_ms"] = r.times.totalMs;
    j["cpu_ms"] = r.times.cpuMs;
    j["set_decals_s"] = r.setDecalsS;
    j["frames"] = r.times.frames;
    j["capped"] = r.times.capped;
    if (r.times.decalStages.frame >= 0) {
        const ProjectorStageTimes& st = r.times.decalStages;
        j["decal_stages_ms"] =
            Json{{"cull", st.cullMs}, {"bin", st.binMs}, {"draw", st.drawMs}, {"read_back", st.readBackMs}};
    }
    if (projectorPath(c)) {
        j["projector_ms"] = r.path.projectorMs;
        j["host_pass_ms"] = r.path.hostPassMs;
        j["baseline_ms"] = r.path.baselineMs;
        j["frames_compute"] = r.computeFrames;
        j["frames_tiles_left_out"] = r.leftOutFrames;
    }
    return j;
}

// The decal pass's cost per covered pixel (each decal a square of decal_px on the floor) over the
// lighting pass's per pixel of the same frame.
double perCoveredPixelRatio(const RenderRow& r) {
    const double side = r.config.size * double(r.height);
    const double covered = double(r.config.visible) * side * side;
    const double pixels = double(r.width) * double(r.height);
    return (r.times.decalsMs / covered) / (r.times.lightingMs / pixels);
}

// The targets of a world of persistent decals: few decals in view cost almost nothing, and a covered
// pixel costs at most 1.5 times a lit one.
void printScaleTargets(const std::vector<RenderRow>& rows, Json& targets) {
    for (const RenderRow& r : rows) {
        if (!r.error.empty()) continue;
        if (r.config.group == "visible" && r.config.visible == 10 && r.config.resolution == "1080p") {
            targets["visible_10_ms"] = r.times.decalsMs;
            targets["visible_10_met"] = r.times.decalsMs <= 0.03;
            std::printf("10 decals in view (%zu in the world): %.3f ms (target <= 0.03 ms: %s)\n",
                        r.config.world, r.times.decalsMs, r.times.decalsMs <= 0.03 ? "met" : "missed");
        }
        if (r.config.group != "coverage" || r.times.lightingMs <= 0.0) continue;
        const double ratio = perCoveredPixelRatio(r);
        const std::string key =
            "per_covered_pixel_" + std::to_string(int(std::lround(r.config.size * r.height))) + "px";
        targets[key] = ratio;
        targets[key + "_met"] = ratio <= 1.5;
        std::printf("per covered pixel, %zu decals of %.0f px: %.2fx the lighting pass's per pixel (target "
                    "<= 1.5x: %s)\n",
                    r.config.visible, r.config.size * r.height, ratio, ratio <= 1.5 ? "met" : "missed");
    }
}

// The occlusion group: the decal pass with occlusion culling against without, with nothing hidden
// (what the depth pyramid costs) and under the roof (what it saves).
void printOcclusion(const std::vector<RenderRow>& rows, Json& targets) {
    for (bool roof : {false, true}) {
        const RenderRow *on = nullptr, *off = nullptr;
        for (const RenderRow& r : rows)
            if (r.error.empty() && r.config.group == "occlusion" && r.config.roof == roof)
                (r.config.feature == "no-occlusion" ? off : on) = &r;
        if (!on || !off) continue;
        const std::string key = roof ? "occlusion_roof_ratio" : "occlusion_open_ratio";
        targets[key] = on->times.decalsMs / off->times.decalsMs;
        std::printf(
            "occlusion culling, %s: %.3f ms with it (%zu boxes drawn), %.3f ms without (%zu): %.2fx\n",
            roof ? "nine tenths under a roof" : "nothing hidden", on->times.decalsMs,
            on->times.last.decalsDrawn, off->times.decalsMs, off->times.last.decalsDrawn,
            on->times.decalsMs / off->times.decalsMs);
    }
}

// The million-decal row with the decals in view spread through the spawn order, against 10,000 in
// view: the same target as the row with them first.
void printSpread(const std::vector<RenderRow>& rows, const RenderRow* tenK, Json& targets) {
    for (const RenderRow& r : rows) {
        if (!tenK || !r.error.empty() || r.config.group != "visible" || r.config.feature != "spread")
            continue;
        const double ratio = r.times.decalsMs / tenK->times.decalsMs;
        targets["world_1m_spread_over_10k"] = ratio;
        targets["world_1m_spread_met"] = ratio <= 1.1;
        std::printf("1,000,000 in the world, 1%% in view spread through the spawn order: %.3f ms, %.3fx the "
                    "10,000 figure (target <= 1.1x: %s)\n",
                    r.times.decalsMs, ratio, ratio <= 1.1 ? "met" : "missed");
    }
}

const RenderRow* findRow(const std::vector<RenderRow>& rows, const std::string& resolution, size_t world,
                         size_t visible) {
    for (const RenderRow& r : rows)
        if (r.error.empty() && r.config.resolution == resolution && r.config.world == world &&
            r.config.visible == visible && r.config.size == 0.015 && r.config.feature == "default" &&
            !r.config.roof)
            return &r;
    return nullptr;
}

// The renderer's decal pass of the paths group at `visible` decals, or nothing.
const RenderRow* rendererRow(const std::vector<RenderRow>& rows, size_t visible) {
    for (const RenderRow& r : rows)
        if (r.error.empty() && r.config.group == "paths" && r.config.feature == "renderer" &&
            r.config.visible == visible)
            return &r;
    return nullptr;
}

// The paths group side by side, each path's decal cost against the renderer's decal pass, and the
// target: the projector's G-buffer blend in a host within 10% of the renderer's pass.
void printPaths(const std::vector<RenderRow>& rows, Json& targets) {
    std::vector<std::vector<std::string>> table;
    std::vector<std::string> verdicts;
    for (const RenderRow& r : rows) {
        const Config& c = r.config;
        if (c.group != "paths") continue;
        const RenderRow* renderer = rendererRow(rows, c.visible);
        if (!r.error.empty()) {
            table.push_back(
                {c.resolution, std::to_string(c.visible), c.feature, "-", "-", "-", "-", r.error});
            continue;
        }
        const bool own = projectorPath(c);
        const std::string ratio = renderer && renderer->times.decalsMs > 0.0
                                      ? fixed(r.times.decalsMs / renderer->times.decalsMs, 2)
                                      : "-";
        table.push_back({c.resolution, std::to_string(c.visible), c.feature, fixed(r.times.decalsMs, 3),
                         own ? fixed(r.path.projectorMs, 3) : "-",
                         own && c.feature != "blend"
                             ? fixed(r.path.hostPassMs, 3) + " / " + fixed(r.path.baselineMs, 3)
                             : "-",
                         ratio, r.times.last.decalVariant});
        if (c.feature == "blend" && renderer && renderer->times.decalsMs > 0.0) {
            const double q = r.times.decalsMs / renderer->times.decalsMs;
            const std::string key = "paths_blend_over_renderer_" + std::to_string(c.visible);
            targets[key] = q;
            targets[key + "_met"] = q <= 1.1;
            verdicts.push_back(
                "the projector's G-buffer blend in a host, " + std::to_string(c.visible) +
                " decals in view: " + fixed(q, 3) +
                "x the renderer's decal pass (target <= 1.1x: " + (q <= 1.1 ? "met" : "missed") + ")");
        }
    }
    if (table.empty()) return;
    std::printf(
        "\nThe same decals through spatter's renderer and through the projector's paths in a host:\n");
    printTable({"res", "visible", "path", "decal ms", "projector ms", "host pass / without decals ms",
                "vs renderer", "variant"},
               table);
    for (const std::string& v : verdicts)
        std::printf("%s\n", v.c_str());
}

// A row measured in several rounds: the first round's, its figures the medians over the rounds (a
// round that failed makes the row fail).
RenderRow overRounds(const std::vector<RenderRow>& rounds) {
    RenderRow out = rounds.front();
    std::vector<FrameTimes> times;
    for (const RenderRow& r : rounds) {
        if (!r.error.empty()) return r;
        times.push_back(r.times);
    }
    auto over = [&](double PathTimes::*field) {
        return medianOf(rounds, [field](const RenderRow& r) { return r.path.*field; });
    };
    out.times = medianOverRounds(times);
    out.path.projectorMs = over(&PathTimes::projectorMs);
    out.path.hostPassMs = over(&PathTimes::hostPassMs);
    out.path.baselineMs = over(&PathTimes::baselineMs);
    return out;
}

} // namespace

int runRenderCommand(int argc, char** argv) {
    int exitCode = 0;
    const std::optional<Args> parsed = commandArgs(
        argc, argv, kRenderCommand, kRenderUsage,
        {"--groups", "--frames", "--rounds", "--max-seconds", "--json", "--forward-tile", "--resolve"},
        {"--quick", "--stages"}, exitCode);
    if (!parsed) return exitCode;
    const Args& args = *parsed;
    if (!args.positional.empty()) return usageError(kRenderCommand, "no positional arguments");
    const bool quick = args.has("--quick");
    Result<uint64_t> frames = parseCount(args.value("--frames", quick ? "2" : "7"), "--frames");
    Result<double> maxSeconds = parseNumber(args.value("--max-seconds", quick ? "3" : "20"), "--max-seconds");
    if (!frames) return usageError(kRenderCommand, frames.error());
    Result<uint64_t> rounds = parseCount(args.value("--rounds", "1"), "--rounds");
    if (!rounds || rounds.value() == 0 || rounds.value() > 100)
        return usageError(kRenderCommand, "--rounds: a count from 1 to 100");
    if (!maxSeconds) return usageError(kRenderCommand, maxSeconds.error());
    Result<uint64_t> forwardTile = parseCount(args.value("--forward-tile", "16"), "--forward-tile");
    if (!forwardTile || forwardTile.value() > 64)
        return usageError(kRenderCommand, "--forward-tile: 8, 16, 32 or 64");
    const std::string resolveName = args.value("--resolve", "auto");
    const DeferredResolve resolve = resolveName == "boxes"     ? DeferredResolve::Boxes
                                    : resolveName == "compute" ? DeferredResolve::Compute
                                                               : DeferredResolve::Auto;
    if (resolveName != "auto" && resolveName != "boxes" && resolveName != "compute")
        return usageError(kRenderCommand, "--resolve: auto, boxes or compute");
    if (frames.value() == 0 || !(maxSeconds.value() > 0.0))
        return usageError(kRenderCommand, "--frames and --max-seconds must be positive");
    std::vector<std::string> groups;
    if (args.has("--groups")) {
        std::string list = args.value("--groups") + ",";
        for (size_t a = 0, b; (b = list.find(',', a)) != std::string::npos; a = b + 1) {
            const std::string g = list.substr(a, b - a);
            if (g != "count" && g != "visible" && g != "coverage" && g != "resolution" && g != "features" &&
                g != "paths" && g != "cpu" && g != "occlusion")
                return usageError(kRenderCommand, "unknown group '" + g + "'");
            groups.push_back(g);
        }
    }

    const MachineInfo machine = machineInfo();
    Result<GlContext> gl = GlContext::createHeadless();
    if (!gl) {
        std::cerr << "spatter-bench render: no OpenGL context: " << gl.error() << "\n";
        return 1;
    }
    Bench bench(std::make_unique<GlContext>(std::move(gl).value()), int(forwardTile.value()), resolve,
                args.has("--stages"));
    const ContextInfo& info = bench.context().info();
    std::printf("spatter-bench render: %s (%s), %s\nmachine: %s\n", info.renderer.c_str(),
                info.platform.c_str(), info.version.c_str(), describe(machine).c_str());
    std::fflush(stdout);

    std::vector<RenderRow> rows;
    std::map<decltype(Config().key()), RenderRow> done;
    // Frame time expected for a row, from the rows measured so far at its resolution: the slowest
    // decal-pass time per visible decal and per unit of decal area, plus the slowest other passes. A
    // row expected to take longer than --max-seconds per frame is skipped (software renderers).
    std::map<std::string, std::pair<double, double>> perArea; // resolution -> (ms per decal area, other ms)
    auto learn = [&](const RenderRow& r) {
        if (!r.error.empty() || r.config.visible == 0) return;
        auto& k = perArea[r.config.resolution];
        const double area = double(r.config.visible) * r.config.size * r.config.size;
        k.first = std::max(k.first, r.times.decalsMs / area);
        k.second = std::max(k.second, r.times.totalMs - r.times.decalsMs + r.times.cpuMs);
    };
    auto estimateMs = [&](const Config& c) {
        auto it = perArea.find(c.resolution);
        if (it == perArea.end()) return 0.0;
        return it->second.first * double(c.visible) * c.size * c.size + it->second.second;
    };
    // A row of this round: measured, skipped, or the same as a row of another group measured before.
    auto measure = [&](const Config& c) {
        RenderRow row;
        auto it = done.find(c.key());
        if (it != done.end()) {
            row = it->second;
            row.config = c;
        } else if (const double est = estimateMs(c); est > 1000.0 * maxSeconds.value()) {
            row.config = c;
            resolutionByName(c.resolution, row.width, row.height);
            row.error = "skipped: about " + fixed(est / 1000.0, 0) + " s per frame expected (--max-seconds " +
                        fmt(maxSeconds.value()) + ")";
            done[c.key()] = row;
        } else {
            Result<RenderRow> r = bench.run(c, frames.value(), maxSeconds.value());
            if (r) {
                row = r.value();
            } else {
                row.config = c;
                row.error = r.error();
            }
            done[c.key()] = row;
            learn(row);
        }
        std::fprintf(stderr, "  %s %s world %zu visible %zu size %g%% %s: %s\n", c.group.c_str(),
                     c.resolution.c_str(), c.world, c.visible, 100.0 * c.size, c.feature.c_str(),
                     row.error.empty() ? (fixed(row.times.decalsMs, 3) + " ms").c_str() : row.error.c_str());
        return row;
    };
    const std::vector<Config> all = configs(groups, quick);
    std::map<decltype(Config().key()), std::vector<RenderRow>> measured; // a row a round
    for (uint64_t round = 0; round < rounds.value(); ++round, done.clear())
        for (const Config& c : all) {
            const RenderRow row = measure(c);
            if (measured[c.key()].size() == round) measured[c.key()].push_back(row);
        }
    for (const Config& c : all) {
        RenderRow row = overRounds(measured[c.key()]);
        row.config = c;
        rows.push_back(row);
    }

    std::vector<std::vector<std::string>> table;
    for (const RenderRow& r : rows) {
        const Config& c = r.config;
        if (c.group == "paths") continue; // a table of their own
        if (!r.error.empty()) {
            table.push_back({c.group, c.resolution, std::to_string(c.world), std::to_string(c.visible),
                             fixed(c.size * r.height, 0), featureLabel(c), "-", "-", "-", "-", "-", "-",
                             r.error});
            continue;
        }
        table.push_back({c.group, c.resolution, std::to_string(c.world), std::to_string(c.visible),
                         fixed(c.size * r.height, 0), featureLabel(c), fixed(r.times.decalsMs, 3),
                         c.visible ? fixed(r.times.decalsMs * 1e6 / double(c.visible), 0) : "-",
                         fixed(r.times.geometryMs, 3), fixed(r.times.lightingMs, 3), fixed(r.times.cpuMs, 1),
                         std::to_string(r.times.frames) + (r.times.capped ? " (capped)" : ""),
                         r.times.last.decalVariant.empty() ? "-" : r.times.last.decalVariant});
    }
    std::printf("\n");
    printTable({"group", "res", "world", "visible", "px", "feature", "decal ms", "ns/decal", "geometry ms",
                "lighting ms", "cpu ms", "frames", "variant"},
               table);

    if (args.has("--stages")) printStages(rows);

    Json targets;
    printPaths(rows, targets);
    const RenderRow* tenK = findRow(rows, "1080p", 10000, 10000);
    const RenderRow* million = findRow(rows, "1080p", 1000000, 10000);
    if (tenK) {
        targets["visible_10k_1080p_ms"] = tenK->times.decalsMs;
        targets["visible_10k_1080p_met"] = tenK->times.decalsMs <= 0.5;
        std::printf("\n10,000 decals in view at 1080p: %.3f ms in the decal pass (target <= 0.5 ms: %s)\n",
                    tenK->times.decalsMs, tenK->times.decalsMs <= 0.5 ? "met" : "missed");
    }
    if (tenK && million) {
        const double ratio = million->times.decalsMs / tenK->times.decalsMs;
        targets["world_1m_visible_1pct_ms"] = million->times.decalsMs;
        targets["world_1m_over_10k"] = ratio;
        targets["world_1m_met"] = ratio <= 1.1;
        std::printf(
            "1,000,000 in the world, 1%% in view: %.3f ms, %.3fx the 10,000 figure (target <= 1.1x: %s)\n",
            million->times.decalsMs, ratio, ratio <= 1.1 ? "met" : "missed");
        // The geometry pass does the same work in both frames: the ratio of the decal passes in units
        // of it takes out a change of GPU clock between the two (a GPU left idle while the CPU culls a
        // million decals lowers its clock).
        const double normalized = (million->times.decalsMs / million->times.geometryMs) /
                                  (tenK->times.decalsMs / tenK->times.geometryMs);
        targets["world_1m_over_10k_per_geometry_pass"] = normalized;
        std::printf(
            "  in units of each frame's geometry pass (same work in both): %.2fx (geometry pass %.3f ms "
            "against %.3f ms; render() CPU %.1f ms against %.1f ms)\n",
            normalized, million->times.geometryMs, tenK->times.geometryMs, million->times.cpuMs,
            tenK->times.cpuMs);
    }

    printSpread(rows, tenK, targets);
    printScaleTargets(rows, targets);
    printOcclusion(rows, targets);

    if (args.has("--json")) {
        Json j;
        j["command"] = "render";
        j["machine"] = toJson(machine);
        j["gl_renderer"] = info.renderer;
        j["gl_vendor"] = info.vendor;
        j["gl_version"] = info.version;
        j["gl_platform"] = info.platform;
        j["frames"] = frames.value();
        j["rounds"] = rounds.value();
        j["max_seconds"] = maxSeconds.value();
        j["rows"] = Json::array();
        for (const RenderRow& r : rows)
            j["rows"].push_back(renderRowJson(r));
        j["targets"] = targets;
        if (Status s = writeJson(j, args.value("--json")); !s) {
            std::cerr << "spatter-bench render: " << s.error() << "\n";
            return 1;
        }
    }
    return 0;
}

} // namespace spatter::bench
