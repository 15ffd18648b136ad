#pragma once
// Scenes with known geometry and exact comparisons shared by the placement tests.

#include "spatter/core/Decal.hpp"
#include "spatter/core/DeformingProxy.hpp"
#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/placement/CollisionWorld.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <embree3/rtcore.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace spatter::test {

constexpr double kPi = 3.14159265358979323846;

inline CollisionWorld buildWorld(const Scene& scene,
                                 const std::vector<std::shared_ptr<const Proxy>>& proxies = {},
                                 const WorldSettings& settings = {}) {
    Result<CollisionWorld> w = CollisionWorld::build(scene, proxies, settings);
    EXPECT_TRUE(w.ok()) << w.error();
    return std::move(w).value();
}

inline DecalSystem makeSystem(const Scene& scene, const DecalSettings& settings = {}) {
    Result<DecalSystem> s = DecalSystem::create(scene, settings);
    EXPECT_TRUE(s.ok()) << s.error();
    return std::move(s).value();
}

inline uint16_t addType(DecalSystem& s, const DecalType& t) {
    Result<uint16_t> r = s.registerType(t);
    EXPECT_TRUE(r.ok()) << r.error();
    return r.ok() ? r.value() : uint16_t(0);
}

inline Ray ray(glm::dvec3 o, glm::dvec3 d) {
    Ray r;
    r.origin = o;
    r.direction = d;
    return r;
}

// One static box [-0.5, 0.5]^3 at the origin, faces cut into 2 x 2 squares.
inline Scene boxScene() {
    Scene s;
    s.source = "test:box";
    s.objects.push_back(makeSceneObject("box", makeBox(glm::vec3(0.5f), 2)));
    return s;
}

// A static unit sphere at the origin.
inline Scene sphereScene(int rings = 48, int segments = 96) {
    Scene s;
    s.source = "test:sphere";
    s.objects.push_back(makeSceneObject("sphere", makeSphere(1.0f, rings, segments)));
    return s;
}

// A static floor (box 20 x 0.2 x 20, top at y = 0), a static wall (top of the floor, z = -5) and
// `targets` dynamic boxes of 0.5 in a row at z = 0, x = 2 * i, centre height 1, rotated and scaled.
inline Scene rangeScene(int targets = 3) {
    Scene s;
    s.source = "test:range";
    s.objects.push_back(makeSceneObject("floor", makeBox(glm::vec3(10.0f, 0.1f, 10.0f), 4),
                                        glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, -0.1, 0.0))));
    s.objects.push_back(makeSceneObject("wall", makeBox(glm::vec3(10.0f, 2.0f, 0.1f), 4),
                                        glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 2.0, -5.1))));
    for (int i = 0; i < targets; ++i) {
        glm::dmat4 t = glm::translate(glm::dmat4(1.0), glm::dvec3(2.0 * i, 1.0, 0.0));
        t = glm::rotate(t, 0.3 + 0.2 * i, glm::dvec3(0.0, 1.0, 0.0));
        t = glm::scale(t, glm::dvec3(0.5 + 0.25 * i));
        s.objects.push_back(
            makeSceneObject("target_" + std::to_string(i), makeBox(glm::vec3(0.5f), 1), t, true));
    }
    return s;
}

// The deforming proxy (buildDeformingProxy) of `scene`'s object 0 at `tolerance` of its diagonal,
// its bound over the animation certified at `samples` poses.
inline Result<DeformingProxy> deformingProxy(const Scene& scene, float tolerance, int samples) {
    ProxySettings settings;
    settings.tolerance = tolerance;
    settings.toleranceRelative = true;
    return buildDeformingProxy(scene, 0, settings, samples);
}

// A proxy as the proxy builder would hand it over: a mesh and its error bound h.
// `point` (object space) in the unit box of `d`.
inline glm::dvec3 inBox(const Decal& d, const glm::dvec3& point) {
    return glm::dvec3(glm::inverse(glm::dmat4(d.boxToObject())) * glm::dvec4(point, 1.0));
}

// The reversed shot `degrees` from the +Y normal, turned about it by `azimuth` radians.
inline glm::dvec3 shotFrom(double degrees, double azimuth) {
    const double a = degrees * kPi / 180.0;
    return glm::dvec3(std::sin(a) * std::cos(azimuth), std::cos(a), std::sin(a) * std::sin(azimuth));
}

// The plane y = z tan(tiltDeg) + lift over [-2, 2]^2 (two triangles).
inline Mesh tiltedPlane(double tiltDeg, float lift = 0.0f) {
    Mesh m = makeGrid({-2.0f, 2.0f}, {-2.0f, 2.0f});
    for (glm::vec3& p : m.positions)
        p.y = p.z * float(std::tan(tiltDeg * kPi / 180.0)) + lift;
    return m;
}

// An object transform that turns and scales unevenly.
inline glm::dmat4 turnedTransform() {
    return glm::scale(glm::rotate(glm::dmat4(1.0), 0.3, glm::dvec3(0.2, 1.0, 0.4)),
                      glm::dvec3(1.5, 0.8, 1.2));
}

inline Proxy makeProxy(Mesh mesh, double errorBound) {
    Proxy p;
    p.mesh = std::move(mesh);
    p.errorBound = errorBound;
    return p;
}

inline bool sameBits(const void* a, const void* b, size_t n) {
    return std::memcmp(a, b, n) == 0;
}

// Every field of two decals equal bit for bit.
inline ::testing::AssertionResult sameDecal(const Decal& a, const Decal& b) {
    const bool same = a.packedFrame == b.packedFrame && sameBits(&a.center, &b.center, sizeof(glm::vec3)) &&
                      sameBits(&a.size, &b.size, sizeof(glm::vec2)) &&
                      sameBits(&a.halfDepth, &b.halfDepth, sizeof(float)) && a.object == b.object &&
                      a.objectId == b.objectId && a.id == b.id && a.type == b.type &&
                      sameBits(&a.spawnTime, &b.spawnTime, sizeof(double)) &&
                      a.opacity.bits() == b.opacity.bits() && a.slant == b.slant;
    if (same) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "decals differ: id " << a.id << " vs " << b.id << ", object " << a.object << " vs " << b.object
           << ", centre (" << a.center.x << ", " << a.center.y << ", " << a.center.z << ") vs (" << b.center.x
           << ", " << b.center.y << ", " << b.center.z << ")";
}

inline ::testing::AssertionResult sameDecals(const std::vector<Decal>& a, const std::vector<Decal>& b) {
    if (a.size() != b.size()) return ::testing::AssertionFailure() << a.size() << " decals vs " << b.size();
    for (size_t i = 0; i < a.size(); ++i)
        if (::testing::AssertionResult r = sameDecal(a[i], b[i]); !r) return r << " (decal " << i << ")";
    return ::testing::AssertionSuccess();
}

inline ::testing::AssertionResult sameHit(const std::optional<Hit>& a, const std::optional<Hit>& b) {
    if (a.has_value() != b.has_value())
        return ::testing::AssertionFailure() << (a ? "hit" : "miss") << " vs " << (b ? "hit" : "miss");
    if (!a) return ::testing::AssertionSuccess();
    const bool same = a->object == b->object && a->primitive == b->primitive &&
                      sameBits(&a->t, &b->t, sizeof(double)) &&
                      sameBits(&a->position, &b->position, sizeof(glm::dvec3)) &&
                      sameBits(&a->normal, &b->normal, sizeof(glm::dvec3)) &&
                      sameBits(&a->localPosition, &b->localPosition, sizeof(glm::dvec3)) &&
                      sameBits(&a->localNormal, &b->localNormal, sizeof(glm::dvec3));
    if (same) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "hits differ: object " << a->object << "/" << b->object << ", primitive " << a->primitive << "/"
           << b->primitive << ", t " << a->t << "/" << b->t;
}

// A random point in the unit ball, not too near its centre.
inline glm::dvec3 inUnitBall(Rng& rng) {
    glm::dvec3 d;
    do {
        d = glm::dvec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    } while (glm::dot(d, d) > 1.0 || glm::dot(d, d) < 1e-3);
    return d;
}

// Rays from random points on a sphere of radius `radius` around `center` towards random points
// within `spread` of it.
inline std::vector<Ray> rayFan(size_t count, const glm::dvec3& center, double radius, double spread,
                               uint64_t seed) {
    Rng rng(seed);
    std::vector<Ray> rays;
    for (size_t i = 0; i < count; ++i) {
        const glm::dvec3 from = center + glm::normalize(inUnitBall(rng)) * radius;
        const glm::dvec3 to =
            center + spread * glm::dvec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        Ray r;
        r.origin = from;
        r.direction = (to - from) * double(0.5f + rng.uniform()); // not unit length
        rays.push_back(r);
    }
    return rays;
}

// `count` bursts of `perBurst` rays, each from one point at distance `radius` of `center`, aimed at a
// random point within `spread` of `center`, spread over a cone of `coneDeg` degrees (the apex angle).
inline std::vector<Ray> bursts(size_t count, size_t perBurst, const glm::dvec3& center, double radius,
                               double spread, double coneDeg, uint64_t seed) {
    Rng rng(seed);
    const double tanHalf = std::tan(0.5 * glm::radians(coneDeg));
    std::vector<Ray> rays;
    for (size_t b = 0; b < count; ++b) {
        const glm::dvec3 from = center + glm::normalize(inUnitBall(rng)) * radius;
        const glm::dvec3 aim = glm::normalize(center + spread * inUnitBall(rng) - from);
        const glm::dvec3 side = glm::normalize(
            glm::cross(aim, std::fabs(aim.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
        const glm::dvec3 up = glm::cross(aim, side);
        for (size_t i = 0; i < perBurst; ++i) {
            const double r = tanHalf * std::sqrt(double(rng.uniform())),
                         phi = 6.283185307179586 * rng.uniform();
            rays.push_back(Ray{from, (aim + r * (std::cos(phi) * side + std::sin(phi) * up)) * 3.0});
        }
    }
    return rays;
}

inline DecalType plainType(const std::string& name = "hole", glm::vec2 size = glm::vec2(0.1f)) {
    DecalType t;
    t.name = name;
    t.size = size;
    return t;
}

// The same scene traced with nothing but Embree: world-space float triangles, rtcIntersect1; what
// CollisionWorld and the decal system are checked against.
struct RawEmbree {
    RTCDevice device = rtcNewDevice(nullptr);
    RTCScene scene = rtcNewScene(device);
    std::vector<uint32_t> geomToObject;

    explicit RawEmbree(const Scene& s) {
        rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
        for (size_t i = 0; i < s.objects.size(); ++i) {
            const SceneObject& o = s.objects[i];
            RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
            auto* v =
                static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                            3 * sizeof(float), o.mesh->positions.size()));
            for (size_t k = 0; k < o.mesh->positions.size(); ++k) {
                const glm::dvec3 p =
                    glm::dvec3(o.transform * glm::dvec4(glm::dvec3(o.mesh->positions[k]), 1.0));
                v[3 * k] = float(p.x);
                v[3 * k + 1] = float(p.y);
                v[3 * k + 2] = float(p.z);
            }
            auto* ix = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0,
                                                                      RTC_FORMAT_UINT3, 3 * sizeof(uint32_t),
                                                                      o.mesh->triangleCount()));
            std::copy(o.mesh->indices.begin(), o.mesh->indices.end(), ix);
            rtcCommitGeometry(g);
            const unsigned id = rtcAttachGeometry(scene, g);
            rtcReleaseGeometry(g);
            geomToObject.resize(std::max<size_t>(geomToObject.size(), id + 1));
            geomToObject[id] = uint32_t(i);
        }
        rtcCommitScene(scene);
    }
    ~RawEmbree() {
        rtcReleaseScene(scene);
        rtcReleaseDevice(device);
    }

    struct RawHit {
        uint32_t object, primitive;
        float t;
        glm::dvec3 position, normal;
    };
    std::optional<RawHit> intersect(const Ray& r) const {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRayHit rh;
        rh.ray.org_x = float(r.origin.x);
        rh.ray.org_y = float(r.origin.y);
        rh.ray.org_z = float(r.origin.z);
        rh.ray.dir_x = float(r.direction.x);
        rh.ray.dir_y = float(r.direction.y);
        rh.ray.dir_z = float(r.direction.z);
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = std::numeric_limits<float>::infinity();
        rh.ray.time = 0.0f;
        rh.ray.mask = 0xFFFFFFFFu;
        rh.ray.id = 0;
        rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &ctx, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
        RawHit h;
        h.object = geomToObject[rh.hit.geomID];
        h.primitive = rh.hit.primID;
        h.t = rh.ray.tfar;
        h.position = r.origin + double(rh.ray.tfar) * r.direction;
        h.normal = glm::normalize(glm::dvec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
        if (glm::dot(h.normal, r.direction) > 0.0) h.normal = -h.normal;
        return h;
    }
};

} // namespace spatter::test
