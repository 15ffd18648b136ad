#include "DecalField.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/Random.hpp"

#include <algorithm>
#include <cmath>

namespace spatter::bench {

namespace {

constexpr double kHeight = 10.0; // camera height above the floor
constexpr double kFovDeg = 60.0;

} // namespace

DecalFieldView decalFieldView(double aspect) {
    DecalFieldView v;
    v.camera.eye = glm::dvec3(0.0, kHeight, 0.0);
    v.camera.target = glm::dvec3(0.0, 0.0, 0.0);
    v.camera.up = glm::dvec3(0.0, 0.0, -1.0);
    v.camera.fovYDeg = kFovDeg;
    v.camera.nearPlane = 0.05;
    v.halfHeight = kHeight * std::tan(0.5 * kFovDeg * kPi / 180.0);
    v.halfWidth = v.halfHeight * aspect;
    return v;
}

Scene decalFieldScene(const DecalFieldView& view, bool dynamicObject, bool roof) {
    Scene scene;
    scene.source = dynamicObject ? "decal field with a dynamic cube" : "decal field";
    const float extent = float(200.0 * view.halfWidth);
    SceneObject floor;
    floor.name = "floor";
    floor.mesh = shareMesh(makeGrid({-extent, extent}, {-extent, extent}));
    scene.objects.push_back(std::move(floor));
    if (dynamicObject) {
        SceneObject cube;
        cube.name = "cube";
        cube.mesh = shareMesh(makeUnitCube());
        cube.dynamic = true;
        cube.transform[3] = glm::dvec4(0.8 * view.halfWidth, 0.5, 0.8 * view.halfHeight, 1.0);
        scene.objects.push_back(std::move(cube));
    }
    if (roof) { // its edges seen from the eye, 10 units up, 8 above it, fall on sqrt(0.9) of the floor's
        const double s = std::sqrt(0.9) * 0.8;
        SceneObject slab;
        slab.name = "roof";
        slab.mesh = shareMesh(makeGrid({float(-s * view.halfWidth), float(s * view.halfWidth)},
                                       {float(-s * view.halfHeight), float(s * view.halfHeight)}));
        slab.transform[3] = glm::dvec4(0.0, 2.0, 0.0, 1.0);
        scene.objects.push_back(std::move(slab));
    }
    return scene;
}

std::vector<Decal> decalField(const DecalFieldView& view, size_t total, size_t visible, double screenFraction,
                              uint16_t type, uint64_t seed) {
    std::vector<Decal> decals;
    decals.reserve(total);
    const double size = screenFraction * 2.0 * view.halfHeight;
    const double reach = 0.75 * size; // beyond the half-diagonal of the square, rotated
    Rng rng(seed);
    for (size_t i = 0; i < total; ++i) {
        double x, z;
        if (i < visible) {
            x = double(rng.uniform(-1.0f, 1.0f)) * std::max(0.0, view.halfWidth - reach);
            z = double(rng.uniform(-1.0f, 1.0f)) * std::max(0.0, view.halfHeight - reach);
        } else {
            // Beyond the right edge of the view: outside the frustum, box and all.
            x = view.halfWidth * (2.0 + 80.0 * double(rng.uniform())) + reach;
            z = view.halfHeight * 80.0 * double(rng.uniform(-1.0f, 1.0f));
        }
        const double angle = 2.0 * kPi * double(rng.uniform());
        Decal d;
        d.setFrame(frameFromNormalAndHint(glm::vec3(0.0f, 1.0f, 0.0f),
                                          glm::vec3(float(std::cos(angle)), 0.0f, float(std::sin(angle)))));
        d.center = glm::vec3(float(x), 0.0f, float(z));
        d.size = glm::vec2(float(size));
        d.halfDepth = float(0.25 * size);
        d.object = 0;
        d.objectId = 0;
        d.id = rng.next();
        d.type = type;
        decals.push_back(d);
    }
    return decals;
}

Result<FrameTimes> timeFrames(Renderer& renderer, const Camera& camera, const RenderOptions& options,
                              size_t warmup, size_t frames, double maxSeconds) {
    FrameTimes t;
    const double start = now();
    // Warm-up: `warmup` frames, and more (up to 20) until 0.3 s have passed, so that a GPU leaves its
    // idle clocks; a slow renderer stops after the first once half the time is spent.
    for (size_t i = 0; i < warmup || (i < 20 && now() - start < 0.3); ++i) {
        Result<FrameStats> s = renderer.render(camera, options);
        if (!s) return fail(s.error());
        if (now() - start > 0.5 * maxSeconds) break;
    }
    std::vector<double> decals, geometry, lighting, total, cpu, cull, bin, draw, readBack;
    for (size_t i = 0; i < frames; ++i) {
        if (i > 0 && now() - start > maxSeconds) {
            t.capped = true;
            break;
        }
        Result<FrameStats> s = renderer.render(camera, options);
        if (!s) return fail(s.error());
        decals.push_back(s->gpu.decalsMs);
        geometry.push_back(s->gpu.geometryMs);
        lighting.push_back(s->gpu.lightingMs);
        total.push_back(s->gpu.totalMs());
        cpu.push_back(s->cpuMs);
        cull.push_back(s->decalStages.cullMs);
        bin.push_back(s->decalStages.binMs);
        draw.push_back(s->decalStages.drawMs);
        readBack.push_back(s->decalStages.readBackMs);
        t.last = s.value();
    }
    t.frames = decals.size();
    t.decalsMs = median(decals);
    t.geometryMs = median(geometry);
    t.lightingMs = median(lighting);
    t.totalMs = median(total);
    t.cpuMs = median(cpu);
    t.decalStages = {median(cull), median(bin), median(draw), median(readBack), t.last.decalStages.frame};
    return t;
}

FrameTimes medianOverRounds(const std::vector<FrameTimes>& rounds) {
    FrameTimes out;
    if (rounds.empty()) return out;
    auto over = [&](double FrameTimes::*field) {
        return medianOf(rounds, [field](const FrameTimes& r) { return r.*field; });
    };
    auto overStage = [&](double ProjectorStageTimes::*field) {
        return medianOf(rounds, [field](const FrameTimes& r) { return r.decalStages.*field; });
    };
    out.decalsMs = over(&FrameTimes::decalsMs);
    out.geometryMs = over(&FrameTimes::geometryMs);
    out.lightingMs = over(&FrameTimes::lightingMs);
    out.totalMs = over(&FrameTimes::totalMs);
    out.cpuMs = over(&FrameTimes::cpuMs);
    out.decalStages = {overStage(&ProjectorStageTimes::cullMs), overStage(&ProjectorStageTimes::binMs),
                       overStage(&ProjectorStageTimes::drawMs), overStage(&ProjectorStageTimes::readBackMs),
                       rounds.back().decalStages.frame};
    for (const FrameTimes& r : rounds) {
        out.frames += r.frames;
        out.capped = out.capped || r.capped;
    }
    out.last = rounds.back().last;
    return out;
}

bool resolutionByName(const std::string& name, int& width, int& height) {
    if (name == "720p") {
        width = 1280;
        height = 720;
    } else if (name == "1080p") {
        width = 1920;
        height = 1080;
    } else if (name == "4k" || name == "4K" || name == "2160p") {
        width = 3840;
        height = 2160;
    } else {
        return false;
    }
    return true;
}

} // namespace spatter::bench
