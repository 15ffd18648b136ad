#include "IouBreakdown.hpp"

#include "BenchSupport.hpp"

#include "spatter/core/DecalRefit.hpp"
#include "spatter/core/MeshDistance.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <cmath>
#include <limits>
#include <tuple>

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

// How the drawn probe reads the drawn surface: exactly (no camera), or as a decal pass reading the
// depth buffer of `camera` at `width` x `height` would: only where the camera sees the meet and, with
// `depthNormal`, with the normal the pixels around it give.
struct ProbeView {
    const Camera* camera = nullptr;
    int width = 0, height = 0;
    bool depthNormal = false;
};

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

// The world normal the depth buffer of `view` gives at the pixel `point` falls in: the cross product of
// the steps to the pixels beside and below, each taken on the side whose depth is nearer the pixel's
// own (as a shader keeps a silhouette out of it), facing the camera; nothing off screen or where those
// pixels see no surface.
std::optional<glm::dvec3> depthNormal(const ProbeView& view, const glm::dvec3& point,
                                      const CollisionWorld& drawn) {
    const Camera& c = *view.camera;
    const CameraBasis basis = cameraBasis(c);
    const double t = std::tan(0.5 * c.fovYDeg * kPi / 180.0);
    const double aspect = double(view.width) / double(view.height);
    const glm::dvec3 d = point - c.eye;
    const double depth = -glm::dot(d, basis.back);
    if (!(depth > 0.0)) return std::nullopt;
    const int i = int(std::floor((glm::dot(d, basis.right) / (depth * t * aspect) + 1.0) * 0.5 * view.width));
    const int j = int(std::floor((1.0 - glm::dot(d, basis.up) / (depth * t)) * 0.5 * view.height));
    auto at = [&](int di, int dj) -> std::optional<glm::dvec3> {
        Ray r;
        r.origin = c.eye;
        r.direction = pixelDirection(c, view.width, view.height, i + di, j + dj);
        const std::optional<Hit> h = drawn.intersect(r);
        return h ? std::optional<glm::dvec3>(h->position) : std::nullopt;
    };
    const std::optional<glm::dvec3> p = at(0, 0), right = at(1, 0), left = at(-1, 0), down = at(0, 1),
                                    up = at(0, -1);
    if (!p) return std::nullopt;
    auto step = [&](const std::optional<glm::dvec3>& ahead, const std::optional<glm::dvec3>& behind) {
        auto gap = [&](const std::optional<glm::dvec3>& q) {
            return q ? std::abs(glm::dot(*q - *p, basis.back)) : std::numeric_limits<double>::infinity();
        };
        if (!ahead && !behind) return glm::dvec3(0.0);
        return gap(ahead) <= gap(behind) ? *ahead - *p : *p - *behind;
    };
    glm::dvec3 n = glm::cross(step(right, left), step(down, up));
    if (!(glm::length(n) > 0.0)) return std::nullopt;
    n = glm::normalize(n);
    return glm::dot(n, c.eye - *p) < 0.0 ? -n : n;
}

// Decal `d` as a decal pass reading the drawn surface would draw it: the line through its centre
// along its projection axis, within its box, meets the drawn surface (traced in `drawn`), and the
// decal is laid again there (relaidDecal) with the drawn triangle's normal or, by `view`, the depth
// buffer's, its box `halfDepth` deep; it stays as it is where the normal cannot take it, or, with a
// camera, where the camera does not see the meet. Nothing where the line meets no drawn surface in the
// box (the pass would drop the decal), nor where its shot meets the drawn surface more than
// `maxAngleDeg` from its normal (DecalSystem::layOnDrawnSurface removes such a decal).
std::optional<Decal> onDrawnSurface(const Decal& d, const CollisionWorld& drawn, const glm::dmat4& toWorld,
                                    float halfDepth, float maxAngleDeg, const ProbeView& view) {
    const glm::dvec3 reach(d.boxToObject()[2]);
    Ray line;
    line.origin = glm::dvec3(toWorld * glm::dvec4(glm::dvec3(d.center) + reach, 1.0));
    line.direction = glm::dvec3(toWorld * glm::dvec4(-2.0 * reach, 0.0));
    line.tnear = 0.0;
    line.tfar = 1.0;
    const std::optional<Hit> hit = drawn.intersect(line);
    if (view.camera &&
        !seenFrom(view.camera->eye, hit ? hit->position : line.origin + line.direction * 0.5, drawn))
        return d;
    if (!hit) return std::nullopt;
    glm::dvec3 normal = hit->localNormal;
    if (view.depthNormal) {
        const std::optional<glm::dvec3> seen = depthNormal(view, hit->position, drawn);
        if (!seen) return d;
        normal = glm::transpose(glm::dmat3(toWorld)) * *seen; // world normals to object space
    }
    const std::optional<Decal> laid =
        relaidDecal(d, glm::dmat3(toWorld), glm::vec3(hit->localPosition), glm::vec3(normal), halfDepth);
    if (!laid) return d;
    const std::optional<double> angle = laidShotAngleDeg(d, *laid, glm::dmat3(toWorld));
    if (angle && *angle > double(maxAngleDeg)) return std::nullopt;
    return laid;
}

// The proxy-placed decals as a decal pass reading the drawn surface would draw them (onDrawnSurface),
// each as shallow as the render-placed decal of its shot where there is one; and for each shot that
// the proxy refused, the decal placed where it meets the drawn surface (DecalSystem::spawnOnDrawnSurface):
// the render mesh's, where a camera, if any, sees it.
std::vector<Decal> drawnProbe(const ShotDecals& decals, const CollisionWorld& drawn, const Scene& scene,
                              float maxAngleDeg, const ProbeView& view) {
    std::vector<Decal> out;
    for (size_t i = 0; i < decals.proxy.size(); ++i) {
        // A shot that the proxy refused: its decal where the shot meets the drawn surface
        // (DecalSystem::spawnOnDrawnSurface), the render mesh's, laid as the others on what is seen.
        const std::optional<Decal>& placed = decals.proxy[i] ? decals.proxy[i] : decals.render[i];
        if (!placed) continue;
        const Decal& d = *placed;
        const glm::dmat4& toWorld = scene.objects[d.object].transform;
        if (!decals.proxy[i] && view.camera &&
            !seenFrom(view.camera->eye, glm::dvec3(toWorld * glm::dvec4(glm::dvec3(d.center), 1.0)), drawn))
            continue;
        const float halfDepth = decals.render[i] ? decals.render[i]->halfDepth : d.halfDepth;
        if (std::optional<Decal> probed = onDrawnSurface(d, drawn, toWorld, halfDepth, maxAngleDeg, view))
            out.push_back(*probed);
    }
    return out;
}

// The proxy-placed decals with their frames laid on the face normal of the render triangle nearest
// to each centre (relaidDecal), their centres and depths kept: what placement could draw with, for
// each part of a proxy triangle, the normal of the render surface it stands for.
Result<std::vector<Decal>> nearestFaceFrames(const ShotDecals& decals, const Scene& scene) {
    std::vector<std::optional<ClosestPointQuery>> queries(scene.objects.size());
    std::vector<Decal> out;
    for (const std::optional<Decal>& placed : decals.proxy) {
        if (!placed) continue;
        const Decal& d = *placed;
        const Mesh& m = *scene.objects[d.object].mesh;
        if (!queries[d.object]) {
            Result<ClosestPointQuery> q = ClosestPointQuery::create(m);
            if (!q) return fail(q.error());
            queries[d.object] = std::move(q).value();
        }
        const std::optional<ClosestPoint> near = queries[d.object]->closest(glm::dvec3(d.center));
        if (!near) {
            out.push_back(d);
            continue;
        }
        const uint32_t* c = &m.indices[3 * size_t(near->triangle)];
        const glm::vec3 n =
            glm::cross(m.positions[c[1]] - m.positions[c[0]], m.positions[c[2]] - m.positions[c[0]]);
        out.push_back(relaidDecal(d, glm::dmat3(scene.objects[d.object].transform), d.center, n, d.halfDepth)
                          .value_or(d));
    }
    return out;
}

} // namespace

Result<IouBreakdown> iouBreakdown(CoverageProbe& probe, const Camera& camera, const Scene& scene,
                                  const std::vector<std::shared_ptr<const Proxy>>& proxies,
                                  const std::vector<Ray>& shots, const DecalType& type, double diagonal,
                                  uint64_t seed, const std::vector<uint8_t>& reference) {
    Result<DecalSystem> proxy = coverageSystem(CollisionWorld::build(scene, proxies), type, diagonal, seed);
    if (!proxy) return fail(proxy.error());
    Result<DecalSystem> render = coverageSystem(CollisionWorld::build(scene), type, diagonal, seed);
    if (!render) return fail(render.error());
    const ShotDecals decals = placeBoth(proxy.value(), render.value(), shots);
    IouBreakdown b;
    auto add = [&](const char* column, const char* key, const std::vector<Decal>& drawn) -> Status {
        Result<std::vector<uint8_t>> mask = probe.mask(camera, drawn);
        if (!mask) return fail(mask.error());
        b.push_back({column, key, iou(reference, mask.value())});
        return {};
    };
    const std::tuple<const char*, const char*, Taken> taken[] = {
        {"centre", "centre", {true, false, false, false}},
        {"frame", "frame", {false, true, false, false}},
        {"frame+slant", "frame_slant", {false, true, true, false}},
        {"centre+frame+slant", "centre_frame_slant", {true, true, true, false}},
        {"+depth", "all", {true, true, true, true}},
        {"centre+depth", "centre_depth", {true, false, false, true}},
        {"all, both placed", "all_placed_by_both", {true, true, true, true, true}}};
    for (const auto& [column, key, fields] : taken)
        if (Status st = add(column, key, variant(decals, fields)); !st) return fail(st.error());
    const int width = probe.renderer().settings().width, height = probe.renderer().settings().height;
    const std::tuple<const char*, const char*, ProbeView> views[] = {
        {"drawn probe", "drawn_probe", ProbeView{}},
        {"seen", "drawn_probe_seen", ProbeView{&camera, width, height, false}},
        {"depth normal", "drawn_probe_depth_normal", ProbeView{&camera, width, height, true}}};
    for (const auto& [column, key, view] : views)
        if (Status st =
                add(column, key, drawnProbe(decals, render.value().world(), scene, type.maxAngleDeg, view));
            !st)
            return fail(st.error());
    Result<std::vector<Decal>> faced = nearestFaceFrames(decals, scene);
    if (!faced) return fail(faced.error());
    if (Status st = add("nearest face", "nearest_face_frame", faced.value()); !st) return fail(st.error());
    return b;
}

} // namespace spatter::bench
