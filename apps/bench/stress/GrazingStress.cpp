// Grazing rays: rays meeting a plane and the faces of a rotated box at 80 to 89.999 degrees from the
// surface normal. Every ray is either placed with a valid frame and a sane box or rejected as
// GrazingAngle (by the type's largest angle); never missed, never NaN.

#include "StressCase.hpp"
#include "StressSupport.hpp"

#include "spatter/core/Frame.hpp"
#include "spatter/core/MeshBuilder.hpp"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace spatter::stress {

namespace {

// A surface patch to aim at: centre, unit normal, two unit in-plane axes, half extent.
struct Patch {
    glm::dvec3 centre, normal, u, v;
    double half;
};

struct Shot {
    Ray ray;
    glm::dvec3 target{0.0};
    glm::dvec3 normal{0.0};
    double angleDeg = 0.0;
    double length = 0.0;
};

} // namespace

StressResult runGrazing(const StressConfig& cfg) {
    StressResult r;
    r.technique = "hit refined in double on the hit triangle (t from its plane, geometric normal); angle "
                  "check against the type's maxAngleDeg; half-depth h + 0.25 max(w, h)";

    // A 10 x 10 plane at y = 0, and on its own (so that neither shadows the other) a 2 m box turned
    // about a skew axis.
    glm::dmat4 boxXf = glm::translate(glm::dmat4(1.0), glm::dvec3(0.5, 3.0, -0.25));
    boxXf = glm::rotate(boxXf, 0.9, glm::normalize(glm::dvec3(1.0, 1.0, 0.3)));
    boxXf = glm::scale(boxXf, glm::dvec3(2.0));
    Scene boxScene;
    boxScene.source = "stress:box";
    boxScene.objects.push_back(makeSceneObject("box", makeUnitCube(), boxXf));
    const Scene scenes[2] = {planeScene(5.0), boxScene};

    std::vector<Patch> patches; // patch 0 on the plane, 1..6 on the box
    patches.push_back({glm::dvec3(0.0), glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1), 4.0});
    const glm::dmat3 rot(boxXf);
    for (int axis = 0; axis < 3; ++axis)
        for (double s : {-1.0, 1.0}) {
            glm::dvec3 n(0.0), u(0.0), v(0.0);
            n[axis] = s;
            u[(axis + 1) % 3] = 1.0;
            v[(axis + 2) % 3] = 1.0;
            const glm::dvec3 c(boxXf * glm::dvec4(0.5 * n, 1.0));
            patches.push_back(
                {c, glm::normalize(rot * n), glm::normalize(rot * u), glm::normalize(rot * v), 0.8});
        }

    const std::vector<DecalType> types = {makeType("any", 0.1f, 90.0f), makeType("steep", 0.25f, 85.0f, 0.3f),
                                          makeType("tight", 0.05f, 89.9f, 0.1f)};
    std::vector<DecalSystem> systems;
    double sceneSize[2];
    for (int k = 0; k < 2; ++k) {
        Result<DecalSystem> sys = DecalSystem::create(scenes[k], unlimitedSettings(cfg.seed));
        if (!sys) {
            r.failure("decal system: " + sys.error());
            r.row("grazing: placed or rejected as grazing", INFINITY, 0.0, 0);
            return r;
        }
        for (const DecalType& t : types)
            sys->registerType(t);
        systems.push_back(std::move(sys).value());
        sceneSize[k] = scenes[k].worldBounds().diagonal();
    }

    Rng rng(cfg.seed ^ 0x9e3779b97f4a7c15ULL);
    const std::vector<double> exact = {80.0, 85.0, 89.0, 89.9, 89.99, 89.999};
    const size_t count = cfg.full ? 1'000'000 : 30'000;
    const size_t chunk = 4096;
    size_t wrongStatus = 0, placed = 0, grazing = 0;
    double offPlane = 0.0, alongRay = 0.0;
    DecalCheck check;
    std::vector<SpawnResult> batch;
    std::vector<Shot> shots;
    std::vector<Ray> rays;
    for (size_t first = 0, c = 0; first < count; first += chunk, ++c) {
        // Chunks alternate between the plane and the box, and cycle through the types.
        const int target = int(c % 2);
        DecalSystem& sys = systems[size_t(target)];
        const uint16_t ti = uint16_t((c / 2) % types.size());
        const DecalType& type = types[ti];
        const size_t n = std::min(chunk, count - first);
        shots.clear();
        rays.clear();
        for (size_t k = 0; k < n; ++k) {
            const Patch& p = patches[target == 0 ? 0 : 1 + k % 6];
            Shot s;
            s.angleDeg = k < exact.size() * 6 ? exact[k % exact.size()] : uniform(rng, 80.0, 89.999);
            const double theta = s.angleDeg * kPi / 180.0, phi = uniform(rng, 0.0, 2.0 * kPi);
            s.target = p.centre + p.u * uniform(rng, -p.half, p.half) + p.v * uniform(rng, -p.half, p.half);
            s.normal = p.normal;
            const glm::dvec3 inPlane = p.u * std::cos(phi) + p.v * std::sin(phi);
            const glm::dvec3 d = inPlane * std::sin(theta) - p.normal * std::cos(theta);
            s.length = std::pow(10.0, uniform(rng, -1.0, 2.0));
            s.ray.origin = s.target - d * s.length;
            s.ray.direction = d * std::pow(10.0, uniform(rng, -3.0, 3.0)); // any length
            shots.push_back(s);
            rays.push_back(s.ray);
        }
        sys.spawnBatch(rays, ti, batch);
        for (size_t k = 0; k < n; ++k) {
            const Shot& s = shots[k];
            const SpawnResult& res = batch[k];
            const double alpha = double(type.maxAngleDeg);
            const bool mayPlace = s.angleDeg <= alpha + 1e-6, mayReject = s.angleDeg >= alpha - 1e-6;
            const bool ok =
                (res.placed() && mayPlace) || (res.status == SpawnStatus::GrazingAngle && mayReject);
            if (!ok) {
                wrongStatus++;
                r.failure("ray at " + num(s.angleDeg) + " degrees (type allows " + num(alpha) +
                          "): " + toString(res.status) + " " + res.reason + " aimed at " + vec(s.target));
                continue;
            }
            if (!res.placed()) {
                grazing++;
                continue;
            }
            placed++;
            const Decal& d = *sys.get(res.handle);
            const std::string why = checkDecal(sys, d, type, check, 1e-6, 1e-6);
            if (!why.empty()) r.failure("ray at " + num(s.angleDeg) + " degrees: " + why);
            const WorldDecal w = sys.worldBox(d);
            // Off the surface: exact in double. Along the surface: a grazing ray's float rounding moves
            // the hit along the ray; scaled by cos(angle) it is the equivalent offset across the surface.
            const double size = sceneSize[target];
            const double off = std::fabs(glm::dot(w.center - s.target, s.normal)) / size;
            const double along = glm::length(w.center - s.target) * std::cos(s.angleDeg * kPi / 180.0) / size;
            offPlane = worse(offPlane, off);
            alongRay = worse(alongRay, along);
            if (!(off <= 1e-6) || !(along <= 1e-6))
                r.failure("ray at " + num(s.angleDeg) + " degrees: centre " + vec(w.center) +
                          " for the aimed " + vec(s.target));
            sys.remove(res.handle);
        }
    }
    r.row("rays neither placed nor rejected as grazing (count)", double(wrongStatus), 0.0, count,
          std::to_string(placed) + " placed, " + std::to_string(grazing) + " grazing");
    r.row("placed: frame error (object and world space)", check.frameError, 1e-6, check.checked);
    r.row("placed: decals with a NaN or Inf (count)", double(check.nonFinite), 0.0, check.checked);
    r.row("placed: |size / type size - 1| beyond the jitter", check.sizeError, 1e-6, check.checked);
    r.row("placed: |half-depth / (h + 0.25 max(w, h)) - 1|", check.depthError, 1e-6, check.checked);
    r.row("placed: centre off the surface / scene size", offPlane, 1e-6, check.checked);
    r.row("placed: centre offset from the aim point x cos(angle) / scene size", alongRay, 1e-6,
          check.checked);

    // spawnAt with normals 80..89.999 degrees from the surface normal (the decal faces the given normal).
    DecalCheck atCheck;
    size_t atWrong = 0;
    const size_t atCount = cfg.full ? 100'000 : 5'000;
    for (size_t i = 0; i < atCount; ++i) {
        const Patch& p = patches[i % 7];
        DecalSystem& sys = systems[i % 7 == 0 ? 0 : 1];
        const uint16_t ti = uint16_t(i % types.size());
        const double deg = i < exact.size() ? exact[i] : uniform(rng, 80.0, 89.999);
        const double theta = deg * kPi / 180.0, phi = uniform(rng, 0.0, 2.0 * kPi);
        const glm::dvec3 n =
            p.normal * std::cos(theta) + (p.u * std::cos(phi) + p.v * std::sin(phi)) * std::sin(theta);
        const glm::dvec3 at =
            p.centre + p.u * uniform(rng, -0.5, 0.5) * p.half + p.v * uniform(rng, -0.5, 0.5) * p.half;
        const SpawnResult res = sys.spawnAt(at, n, ti);
        const double alpha = double(types[ti].maxAngleDeg);
        // The probe runs along n over +-max(size): at a grazing angle it may also miss the patch.
        const bool ok = (res.placed() && deg <= alpha + 1e-6) ||
                        (res.status == SpawnStatus::GrazingAngle && deg >= alpha - 1e-6) ||
                        res.status == SpawnStatus::Missed;
        if (!ok) {
            atWrong++;
            r.failure("spawnAt at " + num(deg) + " degrees: " + toString(res.status) + " " + res.reason);
            continue;
        }
        if (!res.placed()) continue;
        const std::string why = checkDecal(sys, *sys.get(res.handle), types[ti], atCheck, 1e-6, 1e-6);
        if (!why.empty()) r.failure("spawnAt at " + num(deg) + " degrees: " + why);
        sys.remove(res.handle);
    }
    r.row("spawnAt, normal 80..89.999 deg off: wrong status (count)", double(atWrong), 0.0, atCount);
    r.row("spawnAt placed: frame error", atCheck.frameError, 1e-6, atCheck.checked);
    r.row("spawnAt placed: NaN/Inf, size or half-depth errors (count)",
          double(atCheck.nonFinite) + (atCheck.sizeError > 1e-6 ? 1.0 : 0.0) +
              (atCheck.depthError > 1e-6 ? 1.0 : 0.0),
          0.0, atCheck.checked);
    return r;
}

} // namespace spatter::stress
