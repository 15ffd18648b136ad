#include "CharacterBench.hpp"

#include "BenchSupport.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SkinnedDummy.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/render/GlContext.hpp"
#include "spatter/render/Renderer.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace spatter::bench {

namespace {

const char* kCharactersCommand = "characters";

const char* kCharactersUsage =
    R"(usage: spatter-bench characters [--characters LIST] [--decals N] [--frames N] [--size WxH]
                                [--quick] [--json FILE]

The frame cost of decals on animated characters: rows of skinned dummies (generated in code, about
2,000 triangles each) on a floor, N decals shot onto each, walking through their animation at 60
frames a second. Every frame, on one thread: the animation evaluated once; DecalSystem::setPose per
character (its collision mesh skinned and refitted, its decals moved with the skin); the renderer
given only the decals that changed (updateDecals) and posed (GPU skinning); one frame rendered.
Medians over the frames after ten of warm-up:

  setPose ms      CPU, DecalSystem::setPose of every character
  update ms       CPU, Renderer::updateDecals with the changes since the last frame
  render ms       CPU, Renderer::render
  decal pass ms   GPU, the decal pass (FrameStats::gpu.decalsMs)
  frame ms        GPU, the whole frame
and the same characters without decals in the same run (the baseline: frame ms, and setPose ms of
the collision meshes alone), so that the cost of the characters' decals reads as the difference.

--characters LIST  character counts, one row each (default 1,10; --quick 1)
--decals N         decals per character (default 100)
--frames N         frames a row after the warm-up (default 300; --quick 20)
--size WxH         frame size (default 1920x1080; --quick 640x360)
--json FILE        {"machine", "gl_renderer", "rows": [{"characters", "decals", "setpose_ms", "update_ms",
                   "render_ms", "decal_pass_ms", "frame_ms", "baseline_setpose_ms", "baseline_frame_ms"}]}
)";

constexpr int kWarmUp = 10;

struct Options {
    std::vector<double> characters{1, 10};
    size_t decals = 100;
    size_t frames = 300;
    int width = 1920, height = 1080;
};

// Characters in rows of five, a metre apart, facing +Z, on a floor.
Scene charactersScene(size_t count) {
    Scene s;
    s.source = "bench:characters";
    s.objects.push_back(makeSceneObject("floor", makeBox(glm::vec3(8.0f, 0.05f, 8.0f), 2),
                                        glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, -0.05, 0.0))));
    for (size_t i = 0; i < count; ++i) {
        const double x = double(i % 5) - 2.0, z = -double(i / 5);
        addSkinnedDummy(s, glm::translate(glm::dmat4(1.0), glm::dvec3(x, 0.0, z)));
    }
    return s;
}

Camera frontCamera(size_t count) {
    Camera c;
    c.eye = glm::dvec3(0.0, 1.4, 4.0 + 0.6 * double((count + 4) / 5));
    c.target = glm::dvec3(0.0, 1.0, -0.5 * double((count - 1) / 5));
    return c;
}

// Poses every character at frame `frame` through `system`; the skin's index is the character's.
void poseCharacters(DecalSystem& system, const Scene& scene, SceneEvaluator& evaluator, size_t frame) {
    const double duration = scene.animation.animations[0].duration;
    evaluator.evaluate(0, std::fmod(double(frame) / 60.0, duration));
    for (uint32_t o = 1; o < scene.objects.size(); ++o)
        system.setPose(o, evaluator.objectTransform(o),
                       evaluator.jointMatrices(size_t(scene.objects[o].skin)), {});
}

// `perCharacter` bullet holes on each character, shot from just in front of it (so that no other
// character takes them) at random points of its current bounds.
void shootCharacters(DecalSystem& system, const Scene& scene, uint16_t type, size_t perCharacter) {
    Rng rng(7);
    for (uint32_t o = 1; o < scene.objects.size(); ++o) {
        const DBounds b = system.world().worldBounds(o);
        size_t placed = 0;
        for (size_t attempt = 0; placed < perCharacter && attempt < 20 * perCharacter; ++attempt) {
            const glm::dvec3 aim = b.min + glm::dvec3(rng.uniform(), rng.uniform(), 0.5) * (b.max - b.min);
            Ray r;
            r.origin = glm::dvec3(aim.x, aim.y, b.max.z + 0.1);
            r.direction = glm::dvec3(0.0, 0.0, -1.0);
            const SpawnResult s = system.spawn(r, type);
            placed += s.placed() && system.get(s.handle)->object == o;
        }
    }
}

struct CharactersRow {
    size_t characters = 0, decals = 0;
    double setPoseMs = 0, updateMs = 0, renderMs = 0, decalPassMs = 0, frameMs = 0;
    double baselineSetPoseMs = 0, baselineFrameMs = 0;
};

struct Timings {
    std::vector<double> setPose, update, render, decalPass, frame;
};

// Plays `frames` frames (after the warm-up) of the characters with or without decals.
Result<Timings> play(Renderer& renderer, DecalSystem& system, const Scene& scene, const Camera& camera,
                     size_t frames) {
    SceneEvaluator evaluator(scene);
    Timings t;
    uint64_t version = system.version();
    renderer.setDecals(system.decals());
    for (size_t f = 0; f < frames + kWarmUp; ++f) {
        const double t0 = now();
        poseCharacters(system, scene, evaluator, f);
        const double t1 = now();
        renderer.updateDecals(system.decals(), system.changesSince(version));
        version = system.version();
        const double t2 = now();
        if (Status s = renderer.setPose(evaluator); !s) return fail(s.error());
        Result<FrameStats> st = renderer.render(camera, View::Final);
        if (!st) return fail(st.error());
        if (f < size_t(kWarmUp)) continue;
        t.setPose.push_back(1e3 * (t1 - t0));
        t.update.push_back(1e3 * (t2 - t1));
        t.render.push_back(st->cpuMs);
        t.decalPass.push_back(st->gpu.decalsMs);
        t.frame.push_back(st->gpu.totalMs());
    }
    return t;
}

Result<CharactersRow> measure(GlContext& gl, const Options& o, size_t count) {
    const Scene scene = charactersScene(count);
    RendererSettings settings;
    settings.width = o.width;
    settings.height = o.height;
    settings.waitForTimers = true;
    Result<Renderer> renderer = Renderer::create(gl, settings);
    if (!renderer) return fail(renderer.error());
    if (Status s = renderer->setScene(scene); !s) return fail(s.error());
    DecalType hole;
    hole.name = "hole";
    hole.size = glm::vec2(0.06f);
    renderer->setDecalTypes({hole});
    const Camera camera = frontCamera(count);
    CharactersRow row;
    row.characters = count;
    for (const bool withDecals : {false, true}) {
        DecalSettings ds;
        ds.budget = uint32_t(count * o.decals * 20 + 1); // room for the shots that miss onto the floor
        ds.maxPerCell = ds.maxPerObject = ds.budget;
        Result<DecalSystem> system = DecalSystem::create(scene, ds);
        if (!system) return fail(system.error());
        const uint16_t type = system->registerType(hole).value();
        if (Status s = renderer->setObjectIds(system->objectIds()); !s) return fail(s.error());
        SceneEvaluator evaluator(scene);
        poseCharacters(system.value(), scene, evaluator, 0);
        if (withDecals) shootCharacters(system.value(), scene, type, o.decals);
        Result<Timings> t = play(renderer.value(), system.value(), scene, camera, o.frames);
        if (!t) return fail(t.error());
        if (!withDecals) {
            row.baselineSetPoseMs = median(t->setPose);
            row.baselineFrameMs = median(t->frame);
            continue;
        }
        for (const Decal& d : system->decals())
            row.decals += d.object != 0; // on the characters, not the floor
        row.setPoseMs = median(t->setPose);
        row.updateMs = median(t->update);
        row.renderMs = median(t->render);
        row.decalPassMs = median(t->decalPass);
        row.frameMs = median(t->frame);
    }
    return row;
}

Result<Options> parseOptions(const Args& args) {
    Options o;
    const bool quick = args.has("--quick");
    Result<std::vector<double>> list =
        parseNumberList(args.value("--characters", quick ? "1" : "1,10"), "--characters");
    if (!list) return fail(list.error());
    for (double c : list.value())
        if (!(c >= 1.0 && c <= 200.0 && c == std::floor(c)))
            return fail("--characters needs whole numbers from 1 to 200");
    o.characters = list.value();
    Result<uint64_t> decals = parseCount(args.value("--decals", "100"), "--decals");
    Result<uint64_t> frames = parseCount(args.value("--frames", quick ? "20" : "300"), "--frames");
    if (!decals) return fail(decals.error());
    if (!frames || frames.value() == 0 || decals.value() > 100000)
        return fail("--frames needs a positive count and --decals at most 100000");
    o.decals = decals.value();
    o.frames = frames.value();
    const std::string size = args.value("--size", quick ? "640x360" : "1920x1080");
    if (std::sscanf(size.c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width < 16 || o.height < 16 ||
        o.width > 8192 || o.height > 8192)
        return fail("--size needs WxH, 16 to 8192 each");
    return o;
}

Json toJson(const CharactersRow& r) {
    return {{"characters", r.characters},
            {"decals", r.decals},
            {"setpose_ms", number(r.setPoseMs)},
            {"update_ms", number(r.updateMs)},
            {"render_ms", number(r.renderMs)},
            {"decal_pass_ms", number(r.decalPassMs)},
            {"frame_ms", number(r.frameMs)},
            {"baseline_setpose_ms", number(r.baselineSetPoseMs)},
            {"baseline_frame_ms", number(r.baselineFrameMs)}};
}

} // namespace

int runCharactersCommand(int argc, char** argv) {
    int exitCode = 0;
    const std::optional<Args> parsed =
        commandArgs(argc, argv, kCharactersCommand, kCharactersUsage,
                    {"--characters", "--decals", "--frames", "--size", "--json"}, {"--quick"}, exitCode);
    if (!parsed) return exitCode;
    Result<Options> options = parseOptions(*parsed);
    if (!options) return usageError(kCharactersCommand, options.error());
    Result<GlContext> gl = GlContext::createHeadless();
    if (!gl) {
        std::fprintf(stderr, "spatter-bench characters: no OpenGL 4.5 context: %s\n", gl.error().c_str());
        return 1;
    }
    const MachineInfo machine = machineInfo();
    std::printf("spatter-bench characters: %s\n", describe(machine).c_str());
    std::vector<std::vector<std::string>> table;
    Json rows = Json::array();
    for (double count : options->characters) {
        Result<CharactersRow> r = measure(gl.value(), options.value(), size_t(count));
        if (!r) {
            std::fprintf(stderr, "spatter-bench characters: %s\n", r.error().c_str());
            return 1;
        }
        table.push_back({std::to_string(r->characters), std::to_string(r->decals), fixed(r->setPoseMs, 3),
                         fixed(r->baselineSetPoseMs, 3), fixed(r->updateMs, 3), fixed(r->renderMs, 3),
                         fixed(r->decalPassMs, 3), fixed(r->frameMs, 3), fixed(r->baselineFrameMs, 3)});
        rows.push_back(toJson(r.value()));
    }
    printTable({"characters", "decals", "setPose ms", "(no decals)", "update ms", "render ms",
                "decal pass ms", "frame ms", "(no decals)"},
               table);
    if (parsed->has("--json")) {
        Json j{{"command", kCharactersCommand},
               {"machine", toJson(machine)},
               {"gl_renderer", gl->info().renderer},
               {"rows", rows}};
        if (Status s = writeJson(j, parsed->value("--json")); !s) {
            std::fprintf(stderr, "spatter-bench characters: %s\n", s.error().c_str());
            return 1;
        }
    }
    return 0;
}

} // namespace spatter::bench
