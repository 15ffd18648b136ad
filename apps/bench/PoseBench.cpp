#include "PoseBench.hpp"

#include "BenchSupport.hpp"

#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SceneLoader.hpp"

#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace spatter::bench {

namespace {

const char* kPoseCommand = "pose";

const char* kPoseUsage =
    R"(usage: spatter-bench pose [--scene SCENE] [--frames N] [--repeat R] [--quick] [--json FILE]

The CPU cost of one frame of animation on one core (thread CPU time, the median of R runs of N
frames each; frame i is at i / 60 s of animation 0, looped over its duration, so that no two
consecutive frames share a time):

  evaluate          SceneEvaluator::evaluate: every channel sampled, node world transforms in
                    double, joint matrices of every skin, morph weights
  evaluate cached   evaluate again at the time already posed (what a second caller pays)
  posed positions   evaluate, then posedPositions for every skinned or morphed object (the CPU
                    skinning and morphing in double that refitting a proxy to the pose starts from)

Target: evaluating CesiumMan (19 joints, 57 channels) at most 20 us a frame.

--scene SCENE  an animated glTF file, or one in the shared data (default gltf/CesiumMan/CesiumMan.glb)
--frames N     frames a run (default 20000)     --repeat R  runs per row (default 5)
--quick        2,000 frames, 3 runs (smoke test)
--json FILE    {"scene", "nodes", "joints", "channels", "deforming_vertices", "frames", "rows": [...]}
)";

// Median over `runs` of the thread CPU time of `frames` calls of `frame(i)`, per call, seconds.
double perFrame(size_t runs, size_t frames, const std::function<void(size_t)>& frame) {
    std::vector<double> times;
    for (size_t r = 0; r < runs; ++r) {
        const double t0 = threadCpuNow();
        for (size_t i = 0; i < frames; ++i)
            frame(i);
        times.push_back((threadCpuNow() - t0) / double(frames));
    }
    return median(times);
}

struct SceneCounts {
    size_t joints = 0, channels = 0, deformingVertices = 0;
};

SceneCounts counts(const Scene& scene) {
    SceneCounts c;
    for (const Skin& s : scene.animation.skins)
        c.joints += s.joints.size();
    c.channels = scene.animation.animations[0].channels.size();
    for (const SceneObject& o : scene.objects)
        if (o.deforms()) c.deformingVertices += o.mesh->vertexCount();
    return c;
}

} // namespace

int runPoseCommand(int argc, char** argv) {
    int exitCode = 0;
    const std::optional<Args> parsed =
        commandArgs(argc, argv, kPoseCommand, kPoseUsage, {"--scene", "--frames", "--repeat", "--json"},
                    {"--quick"}, exitCode);
    if (!parsed) return exitCode;
    const Args& args = *parsed;
    if (!args.positional.empty()) return usageError(kPoseCommand, "no positional arguments");
    const bool quick = args.has("--quick");
    Result<uint64_t> frameCount = parseCount(args.value("--frames", quick ? "2000" : "20000"), "--frames");
    if (!frameCount) return usageError(kPoseCommand, frameCount.error());
    Result<uint64_t> repeat = parseCount(args.value("--repeat", quick ? "3" : "5"), "--repeat");
    if (!repeat) return usageError(kPoseCommand, repeat.error());
    const size_t frames = frameCount.value(), runs = repeat.value();
    if (frames == 0 || runs == 0) return usageError(kPoseCommand, "--frames and --repeat must be positive");
    const std::string spec = args.value("--scene", "gltf/CesiumMan/CesiumMan.glb");
    const std::string path = resolveInput(spec);
    if (path.empty()) {
        std::fprintf(stderr, "spatter-bench pose: '%s' not found (nor in the shared data '%s')\n",
                     spec.c_str(), sharedDataDir().c_str());
        return 1;
    }
    Result<Scene> loaded = loadScene(path);
    if (!loaded || loaded->animation.animations.empty()) {
        std::fprintf(stderr, "spatter-bench pose: %s\n",
                     loaded ? (path + ": the scene has no animation").c_str() : loaded.error().c_str());
        return 1;
    }
    const Scene& scene = loaded.value();
    const SceneCounts c = counts(scene);
    const MachineInfo machine = machineInfo();
    std::printf(
        "spatter-bench pose: %s, %zu nodes, %zu joints, %zu channels, %zu deforming vertices; %zu frames, "
        "%zu runs a row\nmachine: %s\n\n",
        spec.c_str(), scene.animation.nodes.size(), c.joints, c.channels, c.deformingVertices, frames, runs,
        describe(machine).c_str());

    const double duration = scene.animation.animations[0].duration;
    auto timeOf = [&](size_t i) { return duration > 0.0 ? std::fmod(double(i) / 60.0, duration) : 0.0; };
    SceneEvaluator evaluator(scene);
    double sink = 0.0; // keeps the posed positions observable
    std::vector<std::pair<std::string, double>> rows;
    rows.emplace_back("evaluate",
                      perFrame(runs, frames, [&](size_t i) { evaluator.evaluate(0, timeOf(i)); }));
    rows.emplace_back("evaluate cached",
                      perFrame(runs, frames, [&](size_t) { evaluator.evaluate(0, timeOf(7)); }));
    rows.emplace_back("posed positions", perFrame(runs, std::max<size_t>(1, frames / 20), [&](size_t i) {
                          evaluator.evaluate(0, timeOf(i));
                          for (size_t o = 0; o < scene.objects.size(); ++o)
                              if (scene.objects[o].deforms())
                                  sink += posedPositions(scene, o, evaluator)[0].x;
                      }));
    if (!std::isfinite(sink)) std::printf("(posed positions are not finite)\n");

    Json j;
    j["command"] = kPoseCommand;
    j["machine"] = toJson(machine);
    j["scene"] = spec;
    j["nodes"] = scene.animation.nodes.size();
    j["joints"] = c.joints;
    j["channels"] = c.channels;
    j["deforming_vertices"] = c.deformingVertices;
    j["frames"] = frames;
    j["runs"] = runs;
    j["clock"] = "thread CPU time";
    j["target_us"] = 20;
    Json jrows = Json::array();
    std::vector<std::vector<std::string>> table;
    for (const auto& [name, seconds] : rows) {
        table.push_back(
            {name, fixed(seconds * 1e6, 2), name == "evaluate" ? (seconds <= 20e-6 ? "yes" : "no") : ""});
        Json row;
        row["operation"] = name;
        row["us_per_frame"] = number(seconds * 1e6);
        jrows.push_back(row);
    }
    j["rows"] = jrows;
    printTable({"operation", "us per frame", "within 20 us"}, table);
    if (args.has("--json"))
        if (Status s = writeJson(j, args.value("--json")); !s) {
            std::fprintf(stderr, "spatter-bench pose: %s\n", s.error().c_str());
            return 1;
        }
    return 0;
}

} // namespace spatter::bench
