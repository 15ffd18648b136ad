#include "Mismatch.hpp"

#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/placement/CollisionWorld.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace spatter::test {

namespace {

constexpr double kRadToDeg = 57.295779513082320876;
constexpr double kAllowance = 1e-6; // rounding allowance, relative to the object's diagonal

glm::dvec3 randomUnit(Rng& rng) {
    for (;;) {
        const glm::dvec3 v(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f));
        const double l2 = glm::dot(v, v);
        if (l2 > 1e-4 && l2 <= 1.0) return v / std::sqrt(l2);
    }
}

// Area-weighted random points on a mesh's surface (object space).
class SurfaceSampler {
public:
    explicit SurfaceSampler(const Mesh& mesh) : mesh_(mesh) {
        double total = 0.0;
        for (size_t t = 0; t < mesh.triangleCount(); ++t) {
            total += 0.5 * glm::length(glm::cross(corner(t, 1) - corner(t, 0), corner(t, 2) - corner(t, 0)));
            cumulative_.push_back(total);
        }
    }
    bool empty() const { return cumulative_.empty() || cumulative_.back() <= 0.0; }
    glm::dvec3 sample(Rng& rng) const {
        const double pick = double(rng.uniform()) * cumulative_.back();
        size_t t =
            size_t(std::upper_bound(cumulative_.begin(), cumulative_.end(), pick) - cumulative_.begin());
        t = std::min(t, cumulative_.size() - 1);
        double u = rng.uniform(), v = rng.uniform();
        if (u + v > 1.0) {
            u = 1.0 - u;
            v = 1.0 - v;
        }
        return corner(t, 0) + u * (corner(t, 1) - corner(t, 0)) + v * (corner(t, 2) - corner(t, 0));
    }

private:
    glm::dvec3 corner(size_t t, int k) const { return glm::dvec3(mesh_.positions[mesh_.indices[3 * t + k]]); }
    const Mesh& mesh_;
    std::vector<double> cumulative_;
};

// The rays of one object: from outside its world bounding sphere, half at random points of its world
// bounds, half at random points of its render surface. Unit directions, so t is a world distance.
std::vector<Ray> raysAt(const SceneObject& object, const DBounds& bounds, uint32_t count, Rng& rng) {
    std::vector<Ray> rays;
    const double radius = 0.5 * bounds.diagonal();
    if (!(radius > 0.0)) return rays;
    const SurfaceSampler surface(*object.mesh);
    const glm::dvec3 centre = bounds.center(), extent = bounds.extent();
    for (uint32_t k = 0; k < count; ++k) {
        const glm::dvec3 origin = centre + 1.5 * radius * randomUnit(rng);
        glm::dvec3 target;
        if (k % 2 == 0 || surface.empty()) {
            target = centre + glm::dvec3(rng.uniform(-0.5f, 0.5f), rng.uniform(-0.5f, 0.5f),
                                         rng.uniform(-0.5f, 0.5f)) *
                                  extent;
        } else {
            target = glm::dvec3(object.transform * glm::dvec4(surface.sample(rng), 1.0));
        }
        Ray r;
        r.origin = origin;
        r.direction = glm::normalize(target - origin);
        rays.push_back(r);
    }
    return rays;
}

// Whether the box of `d` holds the render surface point nearest to its centre; `depthUse` and
// `lateralUse` get |z| / half_depth and max(|x| / (w/2), |y| / (h/2)) of that point.
bool boxHoldsNearestRenderPoint(const Decal& d, const ClosestPointQuery& render, double allowance,
                                double& depthUse, double& lateralUse) {
    const glm::dvec3 centre(d.center);
    const std::optional<ClosestPoint> cp = render.closest(centre);
    if (!cp) return false;
    const glm::dvec3 v = cp->point - centre;
    const double x = std::fabs(glm::dot(v, glm::dvec3(d.frame().tangent)));
    const double y = std::fabs(glm::dot(v, glm::dvec3(d.frame().bitangent)));
    const double z = std::fabs(glm::dot(v, glm::dvec3(d.frame().normal)));
    const double hw = 0.5 * double(d.size.x), hh = 0.5 * double(d.size.y), hd = double(d.halfDepth);
    depthUse = z / hd;
    lateralUse = std::max(x / hw, y / hh);
    return x <= hw + allowance && y <= hh + allowance && z <= hd + allowance;
}

// `point` (object space) in the unit box of `d` (a slanted box's own coordinates): `depthUse` gets
// |w|, `lateralUse` max(|u|, |v|).
void boxCoordinates(const Decal& d, const glm::dvec3& point, double& depthUse, double& lateralUse) {
    const glm::dmat4 toBox = glm::inverse(glm::dmat4(d.boxToObject()));
    const glm::dvec3 b(toBox * glm::dvec4(point, 1.0));
    depthUse = std::fabs(b.z);
    lateralUse = std::max(std::fabs(b.x), std::fabs(b.y));
}

Result<DecalSystem> makeSystem(const Scene& scene, const std::vector<std::shared_ptr<const Proxy>>& proxies,
                               const WorldSettings& worldSettings, uint64_t seed, float depthMargin) {
    Result<CollisionWorld> world = CollisionWorld::build(scene, proxies, worldSettings);
    if (!world) return fail("proxy world: " + world.error());
    DecalSettings s;
    s.seed = seed;
    s.depthMargin = depthMargin;
    s.maxPerCell = std::numeric_limits<uint32_t>::max();
    s.budget = std::numeric_limits<uint32_t>::max();
    s.maxPerObject = std::numeric_limits<uint32_t>::max();
    return DecalSystem::create(std::move(world).value(), s);
}

double angleDegrees(const glm::dvec3& a, const glm::dvec3& b) {
    return kRadToDeg * std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

} // namespace

Distribution summarize(std::vector<double> values) {
    Distribution d;
    d.count = values.size();
    if (values.empty()) return d;
    std::sort(values.begin(), values.end());
    auto rank = [&](double q) { return values[size_t(std::ceil(q * double(values.size()))) - 1]; };
    d.p50 = rank(0.5);
    d.p99 = rank(0.99);
    d.max = values.back();
    return d;
}

double referencedDiagonal(const Mesh& mesh) {
    DBounds b;
    for (uint32_t i : mesh.indices)
        if (i < mesh.positions.size()) b.extend(glm::dvec3(mesh.positions[i]));
    return b.diagonal();
}

Result<std::vector<ObjectMismatch>> measureMismatch(const Scene& scene,
                                                    const std::vector<std::shared_ptr<const Proxy>>& proxies,
                                                    const MismatchSettings& settings) {
    const std::string where = "mismatch of '" + scene.source + "': ";
    WorldSettings worldSettings;
    worldSettings.useColliders = false;
    Result<CollisionWorld> renderWorld = CollisionWorld::build(scene, {}, worldSettings);
    if (!renderWorld) return fail(where + "render world: " + renderWorld.error());
    Result<DecalSystem> loose =
        makeSystem(scene, proxies, worldSettings, settings.seed, DecalSettings{}.depthMargin);
    if (!loose) return fail(where + loose.error());
    Result<DecalSystem> tight =
        makeSystem(scene, proxies, worldSettings, settings.seed, settings.tightMargin);
    if (!tight) return fail(where + tight.error());
    const CollisionWorld& proxyWorld = loose->world();

    std::vector<ObjectMismatch> out;
    std::vector<size_t> slot(scene.objects.size(), SIZE_MAX);
    std::vector<ClosestPointQuery> render;
    std::vector<uint16_t> type(scene.objects.size(), 0), tightType(scene.objects.size(), 0),
        shotType(scene.objects.size(), 0);
    std::vector<double> worldDiagonal(scene.objects.size(), 0.0);
    std::vector<Ray> rays;
    std::vector<uint32_t> aimedAt;
    for (uint32_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& o = scene.objects[i];
        const CollisionObject* co = proxyWorld.object(i);
        if (!co || !co->inWorld) continue;
        Result<ClosestPointQuery> q = ClosestPointQuery::create(*o.mesh);
        if (!q) return fail(where + "object '" + o.name + "': " + q.error());
        render.push_back(std::move(q).value());
        slot[i] = out.size();

        ObjectMismatch m;
        m.name = o.name;
        m.object = i;
        m.errorBound = co->errorBound;
        m.diagonal = referencedDiagonal(*o.mesh);
        m.renderTriangles = o.mesh->triangleCount();
        m.proxyTriangles = co->triangles;
        const DBounds bounds = renderWorld->worldBounds(i);
        worldDiagonal[i] = bounds.diagonal();
        const float decalSize = float(std::max(double(settings.decalSizeFraction) * worldDiagonal[i],
                                               4.0 * proxyWorld.worldErrorBound(i)));
        DecalType t;
        t.name = "decal on " + o.name + " #" + std::to_string(i);
        t.size = glm::vec2(decalSize);
        t.maxAngleDeg = 90.0f;
        t.projection = Projection::Normal;
        Result<uint16_t> a = loose->registerType(t);
        Result<uint16_t> b = tight->registerType(t);
        t.name += " along the shot";
        t.projection = Projection::Shot;
        Result<uint16_t> c = loose->registerType(t);
        if (!a || !b || !c) return fail(where + (!a ? a.error() : !b ? b.error() : c.error()));
        type[i] = a.value();
        tightType[i] = b.value();
        shotType[i] = c.value();

        Rng rng(settings.seed * 0x9E3779B97F4A7C15ULL + i);
        for (const Ray& r : raysAt(o, bounds, settings.raysPerObject, rng)) {
            rays.push_back(r);
            aimedAt.push_back(i);
        }
        out.push_back(std::move(m));
    }

    const std::vector<std::optional<Hit>> proxyHits = proxyWorld.intersectBatch(rays);
    const std::vector<std::optional<Hit>> renderHits = renderWorld->intersectBatch(rays);
    for (size_t k = 0; k < rays.size(); ++k) {
        const std::optional<Hit>& hp = proxyHits[k];
        const std::optional<Hit>& hr = renderHits[k];
        const uint32_t counted = hp ? hp->object : hr ? hr->object : aimedAt[k];
        ObjectMismatch& m = out[slot[counted]];
        m.rays++;
        if (!hp) {
            if (hr) m.renderOnly++;
            continue;
        }
        m.proxyHits++;
        if (!hr) {
            m.proxyOnly++;
        } else if (hr->object != hp->object) {
            m.otherObject++;
        } else {
            m.offsets.push_back(std::fabs(hp->t - hr->t) / worldDiagonal[counted]);
            m.angles.push_back(angleDegrees(hp->normal, hr->normal));
        }

        const ClosestPointQuery& surface = render[slot[counted]];
        const double allowance = kAllowance * m.diagonal;
        if (const std::optional<ClosestPoint> cp = surface.closest(hp->localPosition)) {
            m.maxHitDistance = std::max(m.maxHitDistance, cp->distance);
            if (cp->distance > m.errorBound + allowance) m.hitsBeyondBound++;
        } else {
            m.hitsBeyondBound++;
        }

        double depthUse = 0.0, lateralUse = 0.0;
        const SpawnResult a = loose->spawn(rays[k], type[counted]);
        if (a.placed()) {
            const Decal& d = *loose->get(a.handle);
            m.decals++;
            if (d.object == counted) {
                if (boxHoldsNearestRenderPoint(d, surface, allowance, depthUse, lateralUse))
                    m.decalsHolding++;
                m.defaultDepthUse = std::max(m.defaultDepthUse, depthUse);
            }
        }
        const SpawnResult shot = loose->spawn(rays[k], shotType[counted]);
        const bool steep = angleDegrees(-rays[k].direction, hp->normal) > kMaxSlantDeg;
        if (shot.placed() && hr && hr->object == counted && !steep) {
            const Decal& d = *loose->get(shot.handle);
            m.shotDecals++;
            boxCoordinates(d, hr->localPosition, depthUse, lateralUse);
            m.shotDepthUse = std::max(m.shotDepthUse, depthUse);
            if (depthUse <= 1.0) {
                m.shotInSlab++;
                m.shotLateralUse = std::max(m.shotLateralUse, lateralUse);
            }
        }
        const SpawnResult b = tight->spawn(rays[k], tightType[counted]);
        if (b.placed()) {
            const Decal& d = *tight->get(b.handle);
            m.tightDecals++;
            if (d.object == counted) {
                if (boxHoldsNearestRenderPoint(d, surface, allowance, depthUse, lateralUse)) m.tightHolding++;
                m.tightDepthUse = std::max(m.tightDepthUse, depthUse);
                m.lateralUse = std::max(m.lateralUse, lateralUse);
            }
        }
    }
    return out;
}

} // namespace spatter::test
