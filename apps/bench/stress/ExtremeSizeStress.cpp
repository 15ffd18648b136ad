// Extreme sizes: decals from 1e-4 to 1e4 times the scene's size, in scenes from a centimetre to a
// kilometre across. Placement must give valid frames, sizes equal to the type's, half-depths by the
// formula and invertible boxes; the renderer must draw each as a clean footprint (a huge decal
// covers the visible surface, a tiny one a few pixels at most, nothing changes outside it).

#include "StressCase.hpp"
#include "StressSupport.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/Renderer.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

namespace spatter::stress {

namespace {

// Decal size factors (times the scene's width), 10^-4 .. 10^4.
std::vector<double> sizeFactors(bool full) {
    std::vector<double> f;
    for (int k = -8; k <= 8; k += full ? 1 : 2)
        f.push_back(std::pow(10.0, 0.5 * k));
    return f;
}

std::string sizeLabel(double factor) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", factor);
    return buf;
}

} // namespace

StressResult runExtremeSizes(const StressConfig& cfg) {
    StressResult r;
    r.technique = "sizes and half-depth kept in float as products (no differences of large values); the "
                  "box inverse taken in double; frames independent of size";
    const std::vector<double> scales =
        cfg.full ? std::vector<double>{1e-3, 1e-2, 1.0, 1e2, 1e3} : std::vector<double>{1e-2, 1.0, 1e2};
    const std::vector<double> factors = sizeFactors(cfg.full);
    const size_t perSize = cfg.full ? 400 : 40;
    DecalCheck check;
    size_t wrong = 0, attempts = 0;
    Rng rng(cfg.seed + 5);
    for (double s : scales) {
        // A plane 10 s wide, a static sphere of radius s above it, a dynamic one scaled by s.
        Scene scene = planeScene(5.0 * s);
        scene.objects.push_back(makeSceneObject("sphere", makeSphere(float(s), 16, 32),
                                                glm::translate(glm::dmat4(1.0), glm::dvec3(0, 2 * s, 0))));
        glm::dmat4 dyn = glm::translate(glm::dmat4(1.0), glm::dvec3(3 * s, 1.5 * s, 0));
        dyn = glm::scale(glm::rotate(dyn, 0.4, glm::dvec3(0, 0, 1)), glm::dvec3(s));
        scene.objects.push_back(makeSceneObject("dynamic_sphere", makeSphere(1.0f, 16, 32), dyn, true));
        Result<DecalSystem> sys = DecalSystem::create(scene, unlimitedSettings(cfg.seed));
        if (!sys) {
            r.failure(sys.error());
            wrong++;
            continue;
        }
        const double width = 10.0 * s;
        for (double f : factors) {
            const DecalType type = makeType("size " + sizeLabel(f), float(width * f), 80.0f, 0.25f);
            Result<uint16_t> ti = sys->registerType(type);
            if (!ti) {
                wrong++;
                r.failure("scene " + num(s) + ", factor " + num(f) + ": " + ti.error());
                continue;
            }
            auto inspect = [&](const SpawnResult& res, const char* what) {
                attempts++;
                if (res.status == SpawnStatus::GrazingAngle || res.status == SpawnStatus::Missed) return;
                if (!res.placed()) {
                    wrong++;
                    r.failure(std::string(what) + " (scene " + num(s) + ", factor " + num(f) +
                              "): " + toString(res.status) + " " + res.reason);
                    return;
                }
                const std::string why =
                    checkDecal(sys.value(), *sys->get(res.handle), type, check, 1e-6, 1e-5);
                if (!why.empty())
                    r.failure(std::string(what) + " (scene " + num(s) + ", factor " + num(f) + "): " + why);
                sys->remove(res.handle);
            };
            for (size_t i = 0; i < perSize; ++i) {
                // Rays at the plane within 60 degrees of its normal, at the spheres from anywhere.
                const glm::dvec3 aim(uniform(rng, -4.5, 4.5) * s, 0.0, uniform(rng, -4.5, 4.5) * s);
                const double theta = uniform(rng, 0.0, 60.0) * kPi / 180.0,
                             phi = uniform(rng, 0.0, 2.0 * kPi);
                const glm::dvec3 d(std::sin(theta) * std::cos(phi), -std::cos(theta),
                                   std::sin(theta) * std::sin(phi));
                const SpawnResult onPlane = sys->spawn(Ray{aim - d * (20.0 * s), d}, ti.value());
                if (onPlane.status == SpawnStatus::Missed) {
                    wrong++;
                    r.failure("ray at the plane missed (scene " + num(s) + ", factor " + num(f) + ")");
                }
                inspect(onPlane, "spawn on the plane");
                const glm::dvec3 centre = i % 2 ? glm::dvec3(0, 2 * s, 0) : glm::dvec3(3 * s, 1.5 * s, 0);
                const glm::dvec3 from = centre + randomUnit(rng) * (6.0 * s);
                inspect(sys->spawn(Ray{from, centre + randomUnit(rng) * (0.5 * s) - from}, ti.value()),
                        "spawn at a sphere");
                inspect(sys->spawnAt(aim, glm::dvec3(0, 1, 0) + 0.3 * randomUnit(rng), ti.value()),
                        "spawnAt");
                inspect(sys->spawnAttached(uint32_t(1 + i % 2),
                                           glm::vec3(randomUnit(rng)) * (i % 2 ? float(s) : 1.0f),
                                           glm::vec3(randomUnit(rng)), ti.value()),
                        "spawnAttached");
            }
        }
    }
    r.row("spawns with an unexpected status or a missed plane (count)", double(wrong), 0.0, attempts);
    r.row("placed: frame error (object and world space)", check.frameError, 1e-6, check.checked);
    r.row("placed: decals with a NaN or Inf (count)", double(check.nonFinite), 0.0, check.checked);
    r.row("placed: |size / type size - 1| beyond the jitter", check.sizeError, 1e-5, check.checked);
    r.row("placed: |half-depth / (h + 0.25 max(w, h)) - 1|", check.depthError, 1e-5, check.checked);
    r.row("placed: |box * box^-1 - I|", check.boxInverse, 1e-5, check.checked);
    return r;
}

StressResult runExtremeSizesRender(const StressConfig& cfg) {
    StressResult r;
    r.technique = "decal instances in object space, box inverse in double on the CPU, camera-relative "
                  "positions; the decal pass clips each pixel to the box";
    const int width = cfg.full ? 320 : 128, height = cfg.full ? 240 : 96;
    Result<Renderer> renderer = caseRenderer(cfg, width, height, r);
    if (!renderer) return r;
    Result<Renderer> gpuCulled = caseRenderer(cfg, width, height, r, 0); // the same, culled on the GPU
    if (!gpuCulled) return r;
    const Scene scene = planeScene(5.0); // 10 m wide
    Camera cam;
    cam.eye = {0.0, 4.0, 9.0};
    cam.target = {0.0, 0.0, -1.0};
    Result<DecalSystem> sys = DecalSystem::create(scene, unlimitedSettings(cfg.seed));
    if (!sys || !renderer->setScene(scene) || !gpuCulled->setScene(scene)) {
        r.failure(sys ? "setScene failed" : sys.error());
        r.row("scene", INFINITY, 0.0, 0);
        return r;
    }

    // The plane's pixels and a pixel's hit point, by rays through the pixel centres.
    const size_t pixels = size_t(width) * size_t(height);
    std::vector<glm::dvec3> hitPoint(pixels);
    std::vector<uint8_t> plane(pixels, 0);
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) {
            const glm::dvec3 d = pixelDirection(cam, width, height, i, j);
            if (!(d.y < 0.0)) continue;
            const glm::dvec3 p = cam.eye + d * (-cam.eye.y / d.y);
            if (std::fabs(p.x) > 5.0 || std::fabs(p.z) > 5.0) continue;
            plane[size_t(j) * size_t(width) + size_t(i)] = 1;
            hitPoint[size_t(j) * size_t(width) + size_t(i)] = p;
        }
    auto frameOf = [&](Renderer& through, const std::vector<Decal>& decals,
                       const std::vector<DecalType>& types, View view, FrameStats* stats) -> Result<Image> {
        through.setDecalTypes(types);
        through.setDecals(decals);
        Result<FrameStats> fs = through.render(cam, view);
        if (!fs) return fail(fs.error());
        if (stats) *stats = fs.value();
        return through.readback();
    };
    auto frame = [&](const std::vector<Decal>& decals, const std::vector<DecalType>& types, View view,
                     FrameStats* stats) { return frameOf(renderer.value(), decals, types, view, stats); };
    Result<Image> bare = frame({}, {}, View::Final, nullptr);
    if (!bare) {
        r.failure(bare.error());
        r.row("render", INFINITY, 0.0, 0);
        return r;
    }

    double hugeMismatch = 0.0, midMismatch = 0.0;
    size_t tinyPixels = 0, invalid = 0, outside = 0, renders = 0, unlikeGpu = 0;
    for (double f : sizeFactors(cfg.full)) {
        const DecalType type = makeType("render " + sizeLabel(f), float(10.0 * f), 80.0f);
        const uint16_t ti = sys->registerType(type).value();
        const SpawnResult res = sys->spawn(Ray{cam.eye, glm::dvec3(0.3, 0.0, 0.5) - cam.eye}, ti);
        if (!res.placed()) {
            r.failure("factor " + num(f) + ": " + res.reason);
            invalid++;
            continue;
        }
        const Decal decal = *sys->get(res.handle);
        const WorldDecal w = sys->worldBox(decal);
        sys->remove(res.handle);
        std::vector<DecalType> types(size_t(ti) + 1, type);
        FrameStats stats;
        Result<Image> coverage = frame({decal}, types, View::Coverage, &stats);
        Result<Image> lit = coverage ? frame({decal}, types, View::Final, nullptr) : coverage;
        Result<Image> gpuCoverage =
            lit ? frameOf(gpuCulled.value(), {decal}, types, View::Coverage, nullptr) : lit;
        if (!lit || !gpuCoverage) {
            r.failure(!lit ? lit.error() : gpuCoverage.error());
            invalid++;
            continue;
        }
        renders++;
        invalid += stats.decalsInvalid;
        // The CPU reference: plane pixels whose hit point lies inside the box (the angle is 0).
        std::vector<uint8_t> ref(pixels, 0), cov(pixels, 0);
        size_t refCount = 0, covCount = 0, inter = 0, uni = 0, interPlane = 0, uniPlane = 0;
        for (size_t p = 0; p < pixels; ++p) {
            cov[p] = coverage->rgba[4 * p] > 127 ? 1 : 0;
            unlikeGpu += (gpuCoverage->rgba[4 * p] > 127 ? 1 : 0) != cov[p] ? 1 : 0;
            if (plane[p]) {
                const glm::dvec3 q = hitPoint[p] - w.center;
                ref[p] = std::fabs(glm::dot(q, glm::dvec3(w.frame.tangent))) <= 0.5 * w.size.x &&
                                 std::fabs(glm::dot(q, glm::dvec3(w.frame.bitangent))) <= 0.5 * w.size.y &&
                                 std::fabs(glm::dot(q, glm::dvec3(w.frame.normal))) <= w.halfDepth
                             ? 1
                             : 0;
            }
            refCount += ref[p];
            covCount += cov[p];
            inter += ref[p] & cov[p];
            uni += ref[p] | cov[p];
            interPlane += plane[p] & cov[p];
            uniPlane += plane[p] | cov[p];
        }
        if (f >= 10.0) {
            const double m = 1.0 - double(interPlane) / double(std::max<size_t>(uniPlane, 1));
            hugeMismatch = worse(hugeMismatch, m);
            if (!(m <= 0.01))
                r.failure("factor " + num(f) + ": covers " + std::to_string(covCount) + " of " +
                          std::to_string(uniPlane) + " plane pixels");
        } else if (refCount >= 50) {
            const double m = 1.0 - double(inter) / double(std::max<size_t>(uni, 1));
            midMismatch = worse(midMismatch, m);
            if (!(m <= 0.02))
                r.failure("factor " + num(f) + ": IoU " + num(1.0 - m) + " against the reference");
        } else if (refCount <= 1) {
            tinyPixels = std::max(tinyPixels, covCount);
            if (covCount > 4)
                r.failure("factor " + num(f) + ": a tiny decal covers " + std::to_string(covCount) +
                          " pixels");
        }
        // Nothing may change outside the footprint (coverage or reference, grown by a pixel).
        for (int j = 0; j < height; ++j)
            for (int i = 0; i < width; ++i) {
                const size_t p = size_t(j) * size_t(width) + size_t(i);
                bool near = false;
                for (int dj = -1; dj <= 1 && !near; ++dj)
                    for (int di = -1; di <= 1 && !near; ++di) {
                        const int x = i + di, y = j + dj;
                        if (x < 0 || y < 0 || x >= width || y >= height) continue;
                        const size_t q = size_t(y) * size_t(width) + size_t(x);
                        near = ref[q] || cov[q];
                    }
                if (near) continue;
                if (std::memcmp(&lit->rgba[4 * p], &bare->rgba[4 * p], 4) != 0) {
                    outside++;
                    r.failure("factor " + num(f) + ": pixel " + std::to_string(i) + "," + std::to_string(j) +
                              " changed outside the decal");
                }
            }
    }
    r.row("decals the renderer rejected as invalid, or failed renders (count)", double(invalid), 0.0,
          renders);
    r.row("huge decals (>= 10x the scene): 1 - IoU of coverage and the visible plane", hugeMismatch, 0.01,
          renders);
    r.row("mid-sized decals (>= 50 px): 1 - IoU against the CPU reference", midMismatch, 0.02, renders);
    r.row("tiny decals (<= 1 px in the reference): pixels covered", double(tinyPixels), 4.0, renders);
    r.row("final image: pixels changed outside the decal's footprint (count)", double(outside), 0.0,
          renders * pixels);
    r.row("coverage culled on the GPU: pixels unlike the CPU culling's (count)", double(unlikeGpu), 0.0,
          renders * pixels);
    return r;
}

} // namespace spatter::stress
