// Frames: basisFromNormal, frameFromNormalAndHint, rotateAboutNormal and the decal system's frames
// (object and world space) on a million random normals, the six axis directions and normals 1e-9 to
// 1e-3 away from the poles. Bound: orthonormal and right-handed to 1e-6 (frameError), never NaN.

#include "StressCase.hpp"
#include "StressSupport.hpp"

#include "spatter/core/Frame.hpp"
#include "spatter/core/MeshBuilder.hpp"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

namespace spatter::stress {

namespace {

constexpr double kFrameBound = 1e-6;

struct FrameStat {
    double worst = 0.0;
    size_t samples = 0;
    size_t nonFinite = 0;
    std::string where;

    void add(const Frame& f, const glm::vec3& n, const char* what, StressResult& r) {
        samples++;
        const double e = frameErrorOf(f);
        if (!std::isfinite(e)) nonFinite++;
        // The frame must keep the normal it was given.
        const double drift = double(glm::length(f.normal - n));
        const double err = worse(e, drift);
        if (!(err <= worst)) {
            worst = err;
            where = std::string(what) + " n = " + vec(glm::dvec3(n));
        }
        if (!(err <= kFrameBound))
            r.failure(std::string(what) + ": error " + num(err) + " for n = " + vec(glm::dvec3(n)));
    }
};

glm::vec3 unitFloat(const glm::dvec3& v) {
    return glm::normalize(glm::vec3(v));
}

// Unit vectors 1e-9..1e-3 radians from each of the six poles, at 16 azimuths.
std::vector<glm::vec3> nearPoleNormals() {
    std::vector<glm::vec3> out;
    for (int axis = 0; axis < 3; ++axis) {
        for (double sign : {1.0, -1.0}) {
            glm::dvec3 pole(0.0), u(0.0), v(0.0);
            pole[axis] = sign;
            u[(axis + 1) % 3] = 1.0;
            v[(axis + 2) % 3] = 1.0;
            for (int k = 0; k <= 60; ++k) {
                const double e = std::pow(10.0, -9.0 + 0.1 * k);
                for (int a = 0; a < 16; ++a) {
                    const double phi = 2.0 * kPi * a / 16.0;
                    out.push_back(unitFloat(pole * std::cos(e) +
                                            (u * std::cos(phi) + v * std::sin(phi)) * std::sin(e)));
                }
            }
        }
    }
    return out;
}

std::vector<glm::vec3> axisDirections() {
    return {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
}

// Hints every frame construction must survive: the axes, zero, NaN, infinity, the normal itself,
// its opposite, and tiny and huge vectors.
std::vector<glm::vec3> awkwardHints(const glm::vec3& n) {
    std::vector<glm::vec3> h = axisDirections();
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    h.insert(h.end(), {glm::vec3(0.0f), glm::vec3(nan), glm::vec3(inf, 0, 0), n, -n, n * 1e-30f, n * 1e30f,
                       glm::vec3(1e-40f, 0.0f, 0.0f), glm::vec3(3e38f, 3e38f, 0.0f)});
    return h;
}

} // namespace

StressResult runFrames(const StressConfig& cfg) {
    StressResult r;
    r.technique = "Duff et al. 2017 (branchless, copysign) for the basis; projected hint with a "
                  "fallback below 0.01 and a final re-orthogonalisation";
    Rng rng(cfg.seed);

    // A million random normals (both sizes: it is plain arithmetic).
    const size_t count = 1'000'000;
    FrameStat basis, hinted, parallel, rotated;
    for (size_t i = 0; i < count; ++i) {
        const glm::vec3 n = unitFloat(randomUnit(rng));
        basis.add(basisFromNormal(n), n, "basisFromNormal", r);
        const Frame h = frameFromNormalAndHint(n, glm::vec3(randomUnit(rng)));
        hinted.add(h, n, "frameFromNormalAndHint", r);
        // Hints 1e-7..1e-1 radians from the normal, on both sides of the fallback threshold.
        const double off = std::pow(10.0, uniform(rng, -7.0, -1.0));
        const glm::vec3 near = glm::vec3(glm::dvec3(n) + off * randomUnit(rng));
        parallel.add(frameFromNormalAndHint(n, near), n, "hint near the normal", r);
        rotated.add(rotateAboutNormal(h, float(uniform(rng, -1e3, 1e3))), n, "rotateAboutNormal", r);
    }
    auto addRow = [&](const char* metric, const FrameStat& s) {
        r.row(metric, s.worst, kFrameBound, s.samples, s.where);
    };
    addRow("basisFromNormal: frame error, random unit normals", basis);
    addRow("frameFromNormalAndHint: frame error, random hints", hinted);
    addRow("frameFromNormalAndHint: frame error, hints 1e-7..1e-1 rad from n", parallel);
    addRow("rotateAboutNormal: frame error, angles in [-1e3, 1e3] rad", rotated);

    // The axes and the poles, with every awkward hint.
    FrameStat axes, poles;
    for (const glm::vec3& n : axisDirections()) {
        axes.add(basisFromNormal(n), n, "basisFromNormal (axis)", r);
        for (const glm::vec3& h : awkwardHints(n))
            axes.add(frameFromNormalAndHint(n, h), n, "frameFromNormalAndHint (axis)", r);
    }
    for (const glm::vec3& n : nearPoleNormals()) {
        poles.add(basisFromNormal(n), n, "basisFromNormal (near a pole)", r);
        for (const glm::vec3& h : awkwardHints(n))
            poles.add(frameFromNormalAndHint(n, h), n, "frameFromNormalAndHint (near a pole)", r);
    }
    addRow("axes +-X +-Y +-Z, every awkward hint: frame error", axes);
    addRow("normals 1e-9..1e-3 rad from the six poles: frame error", poles);

    // The decal system's full frame construction: spawnAttached with random and near-pole normals
    // on a rotated, non-uniformly scaled static sphere and a dynamic one; spawn and spawnAt.
    Scene scene;
    scene.source = "stress:spheres";
    glm::dmat4 a = glm::translate(glm::dmat4(1.0), glm::dvec3(-3.0, 1.0, 0.5));
    a = glm::rotate(a, 0.7, glm::normalize(glm::dvec3(1.0, 2.0, 3.0)));
    a = glm::scale(a, glm::dvec3(1.0, 2.0, 0.5));
    glm::dmat4 b = glm::translate(glm::dmat4(1.0), glm::dvec3(3.0, 0.0, -1.0));
    b = glm::rotate(b, -2.1, glm::normalize(glm::dvec3(-1.0, 0.5, 0.25)));
    b = glm::scale(b, glm::dvec3(1.5));
    scene.objects.push_back(makeSceneObject("static_sphere", makeSphere(1.0f, 24, 48), a));
    scene.objects.push_back(makeSceneObject("dynamic_sphere", makeSphere(1.0f, 24, 48), b, true));
    Result<DecalSystem> sys = DecalSystem::create(scene, unlimitedSettings(cfg.seed));
    if (!sys) {
        r.failure("decal system: " + sys.error());
        r.row("decal frames: frame error", INFINITY, kFrameBound, 0);
        return r;
    }
    const DecalType type = makeType("frame", 0.05f, 90.0f);
    const uint16_t ti = sys->registerType(type).value();
    const std::vector<glm::vec3> poleNormals = nearPoleNormals();
    const size_t attached = cfg.full ? 1'000'000 : 60'000, shots = cfg.full ? 200'000 : 20'000;
    DecalCheck check;
    size_t notPlaced = 0;
    auto inspect = [&](const SpawnResult& res, const char* what) {
        if (!res.placed()) {
            notPlaced++;
            r.failure(std::string(what) + " not placed: " + res.reason);
            return;
        }
        const std::string why =
            checkDecal(sys.value(), *sys->get(res.handle), type, check, kFrameBound, 1e-5);
        if (!why.empty()) r.failure(std::string(what) + ": " + why);
        // Only the frames matter here; keep the system small.
        sys->remove(res.handle);
    };
    for (size_t i = 0; i < attached; ++i) {
        const glm::vec3 p = unitFloat(randomUnit(rng));
        const glm::vec3 n =
            i % 4 == 0 ? poleNormals[(i / 4) % poleNormals.size()] : unitFloat(randomUnit(rng));
        inspect(sys->spawnAttached(uint32_t(i % 2), p, n, ti), "spawnAttached");
    }
    for (size_t i = 0; i < shots; ++i) {
        const glm::dvec3 centre = i % 2 ? glm::dvec3(3.0, 0.0, -1.0) : glm::dvec3(-3.0, 1.0, 0.5);
        const glm::dvec3 from = centre + 6.0 * randomUnit(rng);
        const glm::dvec3 aim = centre + 0.3 * randomUnit(rng);
        const SpawnResult res = sys->spawn(Ray{from, aim - from}, ti);
        if (res.status == SpawnStatus::Missed) continue; // the other sphere may shadow it
        inspect(res, "spawn");
        // A point of the sphere's surface and its normal, in world space.
        const glm::dmat4& m = i % 2 ? b : a;
        const glm::dvec3 local = randomUnit(rng);
        const glm::dvec3 onSurface(m * glm::dvec4(local, 1.0));
        const glm::dvec3 normal = glm::transpose(glm::inverse(glm::dmat3(m))) * local;
        inspect(sys->spawnAt(onSurface, normal, ti), "spawnAt");
    }
    r.row("decal frames (spawnAttached, spawn, spawnAt; object and world space): frame error",
          check.frameError, kFrameBound, check.checked);
    r.row("decal boxes: |box * box^-1 - I|", check.boxInverse, 1e-5, check.checked);
    const size_t nonFinite = basis.nonFinite + hinted.nonFinite + parallel.nonFinite + rotated.nonFinite +
                             axes.nonFinite + poles.nonFinite + check.nonFinite;
    r.row("frames or decals with a NaN or Inf (count)", double(nonFinite), 0.0,
          basis.samples + hinted.samples + parallel.samples + rotated.samples + axes.samples + poles.samples +
              check.checked);
    r.row("spawns that should have placed and did not (count)", double(notPlaced), 0.0, attached + shots);
    return r;
}

} // namespace spatter::stress
