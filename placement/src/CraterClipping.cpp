#include "CraterClipping.hpp"

#include "spatter/core/CraterMesh.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace spatter {

namespace {

constexpr int kSideRays = 8;
constexpr int kMaxCrossings = 16;   // faces one ray may cross before the walk gives up
constexpr double kStep = 1e-6;      // past a face before tracing on, in crater units
constexpr double kRimMargin = 1.05; // side rays reach this far: the rim is within radius 1
constexpr double kSameCos = 0.97;   // candidates closer than about 14 degrees are one plane

struct Plane {
    glm::dvec3 normal; // crater space, unit, out of the solid
    double offset;     // kept: dot(normal, p) <= offset
};

// Crater space (CraterClip.hpp) to world.
struct CraterSpace {
    glm::dmat4 toWorld;
    glm::dmat3 linear;

    glm::dvec3 point(const glm::dvec3& q) const { return glm::dvec3(toWorld * glm::dvec4(q, 1.0)); }
    // The plane through world point `p` with world normal `n`, in crater space.
    std::optional<Plane> plane(const glm::dvec3& p, const glm::dvec3& n) const {
        const glm::dvec3 nq = glm::transpose(linear) * n;
        const double l = glm::length(nq);
        if (!(l > 0.0) || !std::isfinite(l)) return std::nullopt;
        return Plane{nq / l, glm::dot(n, p - glm::dvec3(toWorld[3])) / l};
    }
};

// Walks the ray from crater point `from` along crater direction `dir` up to t = `tfar`, `depth`
// solids deep at the start, and returns the face where it leaves the last one, unless another begins
// within `gap` (crater units) beyond. `skipFirst`: the first face met is the decal's own surface,
// entered whichever way it is wound.
std::optional<Hit> solidExit(const CollisionWorld& world, const CraterSpace& cs, const glm::dvec3& from,
                             const glm::dvec3& dir, double tfar, int depth, double gap, bool skipFirst) {
    Ray ray;
    ray.origin = cs.point(from);
    ray.direction = cs.linear * dir;
    ray.tfar = tfar;
    for (int k = 0; k < kMaxCrossings && ray.tnear < tfar; ++k) {
        const std::optional<Hit> hit = world.intersect(ray);
        if (!hit) return std::nullopt;
        depth = (k == 0 && skipFirst) || hit->frontFace ? depth + 1 : depth - 1;
        ray.tnear = hit->t + kStep;
        if (depth > 0) continue;
        Ray beyond = ray;
        beyond.tfar = hit->t + gap;
        const std::optional<Hit> next = world.intersect(beyond);
        if (!next || !next->frontFace) return hit;
        depth = 1;
        ray.tnear = next->t + kStep;
    }
    return std::nullopt;
}

void addCandidate(std::vector<Plane>& planes, const Plane& p) {
    for (Plane& q : planes)
        if (glm::dot(q.normal, p.normal) > kSameCos) {
            if (p.offset < q.offset) q = p;
            return;
        }
    planes.push_back(p);
}

} // namespace

CraterClips findCraterClips(const CollisionWorld& world, const glm::dmat4& objectToWorld, double errorBound,
                            const Decal& decal) {
    CraterClips clips;
    const glm::dmat4 toWorld = objectToWorld * craterToObject(decal);
    const CraterSpace cs{toWorld, glm::dmat3(toWorld)};
    // One crater unit along the normal, in world units: the scale of h and of the gap in crater space.
    const double unit = glm::length(cs.linear[2]);
    if (!(unit > 0.0) || !std::isfinite(unit)) return clips;
    const double h = errorBound / unit;
    const double gap = 2.0 * h + 0.02;
    const double depthBound = double(craterDepthBound());

    std::vector<Plane> planes;
    auto consider = [&](const std::optional<Hit>& exit) {
        if (!exit) return;
        // The ray leaves through a back face: its outward normal points along the ray, against the
        // hit normal (which faces the ray).
        if (std::optional<Plane> p = cs.plane(exit->position, -exit->normal)) addCandidate(planes, *p);
    };

    // Back: from in front of the surface (the render surface may lie h in front of the proxy) through
    // it, as deep as a crater goes.
    const double front = h + 0.01;
    const std::optional<Hit> back = solidExit(world, cs, glm::dvec3(0.0, 0.0, front),
                                              glm::dvec3(0.0, 0.0, -1.0), front + depthBound, 0, gap, true);
    consider(back);
    const double solidDepth = back ? back->t - front : depthBound;
    const glm::dvec3 start(0.0, 0.0, -0.5 * std::min(depthBound, solidDepth));
    for (int i = 0; i < kSideRays; ++i) {
        const double a = 2.0 * 3.14159265358979323846 * double(i) / double(kSideRays);
        consider(solidExit(world, cs, start, glm::dvec3(std::cos(a), std::sin(a), 0.0), kRimMargin, 1, gap,
                           false));
    }

    std::sort(planes.begin(), planes.end(),
              [](const Plane& a, const Plane& b) { return a.offset < b.offset; });
    for (size_t i = 0; i < planes.size() && i < 2; ++i)
        clips.planes[i] = packCraterClip(glm::vec3(planes[i].normal), float(planes[i].offset));
    return clips;
}

} // namespace spatter
