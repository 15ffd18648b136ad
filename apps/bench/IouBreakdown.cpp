#include "IouBreakdown.hpp"

#include "spatter/core/DecalRefit.hpp"
#include "spatter/placement/DecalSystem.hpp"

namespace spatter::bench {

namespace {

// Which fields of the render-placed decal a variant takes.
struct Taken {
    bool centre = false, frame = false, slant = false, depth = false;
    bool onlyBoth = false; // no decal where the render mesh places none
};

// Each shot's decal in both systems (nothing where a system places none).
struct ShotDecals {
    std::vector<std::optional<Decal>> proxy, render;
};

ShotDecals placeBoth(DecalSystem& proxy, DecalSystem& render, const std::vector<Ray>& shots) {
    ShotDecals out;
    for (const Ray& shot : shots) {
        const SpawnResult p = proxy.spawn(shot, 0), r = render.spawn(shot, 0);
        out.proxy.push_back(p.placed() ? std::optional<Decal>(*proxy.get(p.handle)) : std::nullopt);
        out.render.push_back(r.placed() ? std::optional<Decal>(*render.get(r.handle)) : std::nullopt);
    }
    return out;
}

std::vector<Decal> variant(const ShotDecals& decals, const Taken& taken) {
    std::vector<Decal> out;
    for (size_t i = 0; i < decals.proxy.size(); ++i) {
        if (!decals.proxy[i] || (taken.onlyBoth && !decals.render[i])) continue;
        Decal d = *decals.proxy[i];
        if (const std::optional<Decal>& r = decals.render[i]) {
            if (taken.centre) d.center = r->center;
            if (taken.frame) d.packedFrame = r->packedFrame;
            if (taken.slant) d.slant = r->slant;
            if (taken.depth) d.halfDepth = r->halfDepth;
        }
        out.push_back(d);
    }
    return out;
}

// Whether the camera at `eye` sees `point` on the drawn surface: nothing of `drawn` lies between them.
bool seenFrom(const glm::dvec3& eye, const glm::dvec3& point, const CollisionWorld& drawn) {
    const glm::dvec3 to = point - eye;
    Ray sight;
    sight.origin = eye;
    sight.direction = to;
    sight.tnear = 0.0;
    sight.tfar = 1.0;
    const std::optional<Hit> hit = drawn.intersect(sight);
    return !hit || (1.0 - hit->t) * glm::length(to) <= 1e-4 * glm::length(to);
}

// Decal `d` as a decal pass reading the drawn surface would draw it: the line through its centre
// along its projection axis, within its box, meets the drawn surface (traced in `drawn`, as the depth
// buffer gives it where the camera sees that point), and the decal is laid again there (relaidDecal),
// its box `halfDepth` deep; it stays as it is where the drawn normal cannot take it, or, with `eye`,
// where the camera there does not see the meet. Nothing where the line meets no drawn surface in the
// box: the pass would drop the decal.
std::optional<Decal> onDrawnSurface(const Decal& d, const CollisionWorld& drawn, const glm::dmat4& toWorld,
                                    float halfDepth, const std::optional<glm::dvec3>& eye) {
    const glm::dvec3 reach(d.boxToObject()[2]);
    Ray line;
    line.origin = glm::dvec3(toWorld * glm::dvec4(glm::dvec3(d.center) + reach, 1.0));
    line.direction = glm::dvec3(toWorld * glm::dvec4(-2.0 * reach, 0.0));
    line.tnear = 0.0;
    line.tfar = 1.0;
    const std::optional<Hit> hit = drawn.intersect(line);
    if (eye && !seenFrom(*eye, hit ? hit->position : line.origin + line.direction * 0.5, drawn)) return d;
    if (!hit) return std::nullopt;
    return relaidDecal(d, glm::dmat3(toWorld), glm::vec3(hit->localPosition), glm::vec3(hit->localNormal),
                       halfDepth)
        .value_or(d);
}

// The proxy-placed decals as a decal pass reading the drawn surface would draw them (onDrawnSurface),
// each as shallow as the render-placed decal of its shot where there is one.
std::vector<Decal> drawnProbe(const ShotDecals& decals, const CollisionWorld& drawn, const Scene& scene,
                              const std::optional<glm::dvec3>& eye) {
    std::vector<Decal> out;
    for (size_t i = 0; i < decals.proxy.size(); ++i) {
        if (!decals.proxy[i]) continue;
        const Decal& d = *decals.proxy[i];
        const float halfDepth = decals.render[i] ? decals.render[i]->halfDepth : d.halfDepth;
        if (std::optional<Decal> probed =
                onDrawnSurface(d, drawn, scene.objects[d.object].transform, halfDepth, eye))
            out.push_back(*probed);
    }
    return out;
}

} // namespace

Result<IouBreakdown> iouBreakdown(CoverageProbe& probe, const Camera& camera, const Scene& scene,
                                  const std::vector<std::optional<Proxy>>& proxies,
                                  const std::vector<Ray>& shots, const DecalType& type, double diagonal,
                                  uint64_t seed, const std::vector<uint8_t>& reference) {
    Result<DecalSystem> proxy = coverageSystem(CollisionWorld::build(scene, proxies), type, diagonal, seed);
    if (!proxy) return fail(proxy.error());
    Result<DecalSystem> render = coverageSystem(CollisionWorld::build(scene), type, diagonal, seed);
    if (!render) return fail(render.error());
    const ShotDecals decals = placeBoth(proxy.value(), render.value(), shots);
    IouBreakdown b;
    const std::pair<double*, Taken> variants[] = {{&b.centre, {true, false, false, false}},
                                                  {&b.frame, {false, true, false, false}},
                                                  {&b.frameSlant, {false, true, true, false}},
                                                  {&b.allButDepth, {true, true, true, false}},
                                                  {&b.all, {true, true, true, true}},
                                                  {&b.centreDepth, {true, false, false, true}},
                                                  {&b.allPlacedByBoth, {true, true, true, true, true}}};
    for (const auto& [into, taken] : variants) {
        Result<std::vector<uint8_t>> mask = probe.mask(camera, variant(decals, taken));
        if (!mask) return fail(mask.error());
        *into = iou(reference, mask.value());
    }
    const std::pair<double*, std::optional<glm::dvec3>> probes[] = {{&b.drawnProbe, std::nullopt},
                                                                    {&b.drawnProbeSeen, camera.eye}};
    for (const auto& [into, eye] : probes) {
        Result<std::vector<uint8_t>> probed =
            probe.mask(camera, drawnProbe(decals, render.value().world(), scene, eye));
        if (!probed) return fail(probed.error());
        *into = iou(reference, probed.value());
    }
    return b;
}

} // namespace spatter::bench
