#include "spatter/placement/CollisionWorld.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace spatter {

namespace {

constexpr unsigned kInvalidId = RTC_INVALID_GEOMETRY_ID;

struct ObjectData {
    CollisionObject info;
    std::vector<glm::vec3> positions; // collision mesh, object space
    std::vector<uint32_t> indices;
    std::vector<glm::vec3> traced; // the vertices Embree sees: float frame (static) or object space
    double reach = 0.0;            // largest |ray origin| in the space of `traced` that the boxes allow
    glm::dmat4 inverse{1.0};
    RTCScene scene = nullptr;     // dynamic objects: their own object-space scene
    unsigned geomId = kInvalidId; // static: geometry in the static scene; dynamic: instance in the top scene
};

// Embree's intersect context extended with the distance of the best hit so far of every ray of the
// call (indexed by RTCRay::id), and the slack the filter leaves in tfar beyond it.
struct TraceContext {
    RTCIntersectContext embree; // first member: Embree hands this pointer back to the filter
    float* bestT;
    float slack; // 1e-6 of the world's extent, see closestHitFilter
};

// Makes the closest hit independent of traversal order. Embree keeps the first of equally distant
// hits it meets, and the float bounds of instances can cull a surface lying exactly at the current
// tfar, so the outcome of a tie would depend on the order of traversal (single rays and streams
// differ). This filter keeps its own best hit, ordered by (t, instance, geometry, primitive), and
// leaves tfar a little beyond it (t + slack, slack far above the rounding of Embree's bounds), so
// that every surface at the best distance is still visited and offered to it.
void closestHitFilter(const RTCFilterFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const TraceContext*>(args->context);
    RTCRayN* ray = args->ray;
    RTCHitN* candidate = args->hit;
    const unsigned n = args->N;
    RTCHitN* committed = RTCRayHitN_HitN(reinterpret_cast<RTCRayHitN*>(ray), n);
    for (unsigned i = 0; i < n; ++i) {
        if (args->valid[i] == 0) continue;
        const float t = RTCRayN_tfar(ray, n, i); // the candidate's distance, during the filter
        float& best = ctx->bestT[RTCRayN_id(ray, n, i)];
        bool better = t < best || RTCHitN_geomID(committed, n, i) == kInvalidId;
        if (!better && t == best) {
            const unsigned c[3] = {RTCHitN_instID(candidate, n, i, 0), RTCHitN_geomID(candidate, n, i),
                                   RTCHitN_primID(candidate, n, i)};
            const unsigned k[3] = {RTCHitN_instID(committed, n, i, 0), RTCHitN_geomID(committed, n, i),
                                   RTCHitN_primID(committed, n, i)};
            better = std::lexicographical_compare(c, c + 3, k, k + 3);
        }
        if (!better) {
            args->valid[i] = 0; // Embree restores tfar to best + slack
            continue;
        }
        best = t;
        RTCRayN_tfar(ray, n, i) = t + ctx->slack;
    }
}

const char* errorName(RTCError code) {
    switch (code) {
    case RTC_ERROR_NONE:
        return "no error";
    case RTC_ERROR_INVALID_ARGUMENT:
        return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
        return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
        return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
        return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
        return "cancelled";
    default:
        return "unknown error";
    }
}

bool finiteMatrix(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

// Bottom row (0, 0, 0, 1).
bool affine(const glm::dmat4& m) {
    return m[0][3] == 0.0 && m[1][3] == 0.0 && m[2][3] == 0.0 && m[3][3] == 1.0;
}

// Object-to-frame transform as Embree's 3x4 column-major floats.
void toEmbreeTransform(const glm::dmat4& m, const glm::dvec3& origin, float out[12]) {
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            out[c * 3 + r] = float(m[c][r]);
    for (int r = 0; r < 3; ++r)
        out[9 + r] = float(m[3][r] - origin[r]);
}

DBounds transformBounds(const Bounds& b, const glm::dmat4& m) {
    DBounds out;
    if (b.empty()) return out;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 p((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                           (i & 4) ? b.max.z : b.min.z);
        out.extend(glm::dvec3(m * glm::dvec4(p, 1.0)));
    }
    return out;
}

// Bounds of the vertices the triangles use: an unreferenced vertex is no part of the surface and
// must not move the origin of the float frame (one far away would cost the geometry its precision).
Bounds meshBounds(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices) {
    Bounds b;
    for (uint32_t i : indices)
        b.extend(positions[i]);
    return b;
}

// The collision triangles are Embree user geometry intersected with the watertight test of Woop,
// Benthin and Wald 2013 ("Watertight Ray/Triangle Intersection", JCGT 2(1)). Embree 3's robust
// triangle test (Pluecker coordinates) is watertight along shared edges but not around shared
// vertices: when the ray starts far from a triangle compared with its size, rounding can reject the
// ray in every triangle around a vertex, and a ray aimed at the vertex passes through. Here every
// vertex is sheared into the ray's space in float, giving the same values in every triangle that
// shares it, and the edge functions are evaluated in double, where products of floats are exact: their
// signs are exact, so neighbouring triangles agree along every edge and around every vertex.
bool watertightHit(const glm::vec3& org, const glm::vec3& dir, const glm::vec3& p0, const glm::vec3& p1,
                   const glm::vec3& p2, float tnear, float tfar, float& t, float& u, float& v) {
    const glm::vec3 ad = glm::abs(dir);
    const int kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (dir[kz] < 0.0f) std::swap(kx, ky); // keeps the winding of the sheared triangle
    const float sx = dir[kx] / dir[kz], sy = dir[ky] / dir[kz], sz = 1.0f / dir[kz];
    const glm::vec3 a = p0 - org, b = p1 - org, c = p2 - org;
    const float ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
    const float bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
    const float cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];
    const double U = double(cx) * double(by) - double(cy) * double(bx);
    const double V = double(ax) * double(cy) - double(ay) * double(cx);
    const double W = double(bx) * double(ay) - double(by) * double(ax);
    if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
    const double det = U + V + W;
    if (det == 0.0) return false;
    const double T = U * (double(sz) * double(a[kz])) + V * (double(sz) * double(b[kz])) +
                     W * (double(sz) * double(c[kz]));
    const double hit = T / det;
    if (!(hit >= double(tnear) && hit <= double(tfar))) return false;
    t = float(hit);
    u = float(V / det);
    v = float(W / det);
    return true;
}

void triangleBounds(const RTCBoundsFunctionArguments* args) {
    const auto* od = static_cast<const ObjectData*>(args->geometryUserPtr);
    const uint32_t* tri = &od->indices[size_t(args->primID) * 3];
    const glm::vec3 p0 = od->traced[tri[0]], p1 = od->traced[tri[1]], p2 = od->traced[tri[2]];
    // Embree 3 traverses user geometry without its robust mode: a box test is off by a few float steps
    // of |box| + |ray origin|. Every box grows by 2^-18 of that (about 32 steps), with |ray origin| at
    // most `reach`, so that no rounding culls a ray through a corner or along an edge.
    const glm::vec3 lo = glm::min(glm::min(p0, p1), p2), hi = glm::max(glm::max(p0, p1), p2);
    const glm::vec3 grow = (glm::max(glm::abs(lo), glm::abs(hi)) + float(od->reach)) * std::ldexp(1.0f, -18);
    args->bounds_o->lower_x = lo.x - grow.x;
    args->bounds_o->lower_y = lo.y - grow.y;
    args->bounds_o->lower_z = lo.z - grow.z;
    args->bounds_o->upper_x = hi.x + grow.x;
    args->bounds_o->upper_y = hi.y + grow.y;
    args->bounds_o->upper_z = hi.z + grow.z;
}

// Intersects the rays of a packet with one triangle and offers each hit to closestHitFilter, as
// Embree offers the hits of its own triangles (tfar holds the candidate's distance meanwhile).
void intersectTriangle(const RTCIntersectFunctionNArguments* args) {
    constexpr unsigned kMaxPacket = 16; // Embree's widest packet
    const auto* od = static_cast<const ObjectData*>(args->geometryUserPtr);
    const uint32_t* tri = &od->indices[size_t(args->primID) * 3];
    const glm::vec3 p0 = od->traced[tri[0]], p1 = od->traced[tri[1]], p2 = od->traced[tri[2]];
    const unsigned n = args->N;
    if (n > kMaxPacket) return;
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, n);
    RTCHitN* committed = RTCRayHitN_HitN(args->rayhit, n);
    for (unsigned i = 0; i < n; ++i) {
        if (args->valid[i] == 0) continue;
        const glm::vec3 org(RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i));
        const glm::vec3 dir(RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i));
        float t, u, v;
        if (!watertightHit(org, dir, p0, p1, p2, RTCRayN_tnear(ray, n, i), RTCRayN_tfar(ray, n, i), t, u, v))
            continue;
        const glm::vec3 ng = glm::cross(p1 - p0, p2 - p0);
        alignas(64) unsigned char buffer[kMaxPacket * sizeof(RTCHit)];
        RTCHitN* candidate = reinterpret_cast<RTCHitN*>(buffer);
        RTCHitN_Ng_x(candidate, n, i) = ng.x;
        RTCHitN_Ng_y(candidate, n, i) = ng.y;
        RTCHitN_Ng_z(candidate, n, i) = ng.z;
        RTCHitN_u(candidate, n, i) = u;
        RTCHitN_v(candidate, n, i) = v;
        RTCHitN_primID(candidate, n, i) = args->primID;
        RTCHitN_geomID(candidate, n, i) = args->geomID;
        RTCHitN_instID(candidate, n, i, 0) = args->context->instID[0];
        int valid[kMaxPacket] = {};
        valid[i] = -1;
        const float previous = RTCRayN_tfar(ray, n, i);
        RTCRayN_tfar(ray, n, i) = t;
        RTCFilterFunctionNArguments filter;
        filter.valid = valid;
        filter.geometryUserPtr = args->geometryUserPtr;
        filter.context = args->context;
        filter.ray = ray;
        filter.hit = candidate;
        filter.N = n;
        closestHitFilter(&filter);
        if (valid[i] == 0) {
            RTCRayN_tfar(ray, n, i) = previous;
            continue;
        }
        RTCHitN_Ng_x(committed, n, i) = ng.x;
        RTCHitN_Ng_y(committed, n, i) = ng.y;
        RTCHitN_Ng_z(committed, n, i) = ng.z;
        RTCHitN_u(committed, n, i) = u;
        RTCHitN_v(committed, n, i) = v;
        RTCHitN_primID(committed, n, i) = args->primID;
        RTCHitN_geomID(committed, n, i) = args->geomID;
        RTCHitN_instID(committed, n, i, 0) = args->context->instID[0];
    }
}

// What a prepared ray needs to map Embree's answer back onto the caller's ray.
struct Prepared {
    double start = 0.0;  // distance along the unit direction where the traced ray starts
    double length = 1.0; // length of the caller's direction
};

} // namespace

struct CollisionWorld::Impl {
    RTCDevice device = nullptr;
    RTCScene top = nullptr;
    RTCScene statics = nullptr;
    unsigned staticInstance = kInvalidId;
    std::vector<ObjectData> objects;
    std::vector<uint32_t> staticGeomToObject; // by geometry ID in the static scene
    std::vector<uint32_t> instanceToObject;   // by geometry ID in the top scene
    glm::dvec3 origin{0.0};
    DBounds traceBounds; // frame coordinates, padded
    float slack = 0.0f;  // tfar slack of closestHitFilter: 1e-6 of the size of traceBounds
    size_t triangles = 0;
    std::string deviceError;

    ~Impl() {
        for (ObjectData& o : objects)
            if (o.scene) rtcReleaseScene(o.scene);
        if (statics) rtcReleaseScene(statics);
        if (top) rtcReleaseScene(top);
        if (device) rtcReleaseDevice(device);
    }

    static void onError(void* user, RTCError code, const char* message) {
        auto* self = static_cast<Impl*>(user);
        if (self->deviceError.empty())
            self->deviceError = std::string("Embree: ") + errorName(code) + ": " + (message ? message : "");
    }

    // The collision triangles of `od` as Embree user geometry (watertightHit), their vertices moved
    // into the float frame by `toFrame` (static objects) or left in object space (dynamic ones).
    RTCGeometry triangleGeometry(ObjectData& od, const glm::dmat4* toFrame) {
        od.traced.resize(od.positions.size());
        for (size_t i = 0; i < od.positions.size(); ++i) {
            glm::dvec3 p(od.positions[i]);
            if (toFrame) p = glm::dvec3(*toFrame * glm::dvec4(p, 1.0)) - origin;
            od.traced[i] = glm::vec3(p);
        }
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(g, unsigned(od.indices.size() / 3));
        rtcSetGeometryUserData(g, &od);
        rtcSetGeometryBoundsFunction(g, triangleBounds, nullptr);
        rtcSetGeometryIntersectFunction(g, intersectTriangle);
        rtcCommitGeometry(g);
        return g;
    }

    RTCScene newScene() {
        RTCScene s = rtcNewScene(device);
        rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST);
        return s;
    }

    void updateTraceBounds() {
        RTCBounds b;
        rtcGetSceneBounds(top, &b);
        traceBounds = DBounds();
        if (!(b.lower_x <= b.upper_x && b.lower_y <= b.upper_y && b.lower_z <= b.upper_z)) return;
        const glm::dvec3 lo(b.lower_x, b.lower_y, b.lower_z), hi(b.upper_x, b.upper_y, b.upper_z);
        const double size = glm::length(hi - lo);
        const double magnitude = std::max(glm::length(lo), glm::length(hi));
        const double pad = 1e-3 * size + 1e-5 * magnitude + 1e-6;
        traceBounds.extend(lo - pad);
        traceBounds.extend(hi + pad);
        slack = float(1e-6 * (size + magnitude) + 1e-30);
        regrowBoxes();
    }

    // Largest |ray origin| in the space of od.traced for a traced ray starting inside `frame` (frame
    // coordinates): the frame itself for static objects, object space for dynamic ones.
    double reachOf(const ObjectData& od, const DBounds& frame) const {
        double r = 0.0;
        for (int i = 0; i < 8; ++i) {
            const glm::dvec3 c((i & 1) ? frame.max.x : frame.min.x, (i & 2) ? frame.max.y : frame.min.y,
                               (i & 4) ? frame.max.z : frame.min.z);
            r = std::max(
                r, glm::length(od.info.dynamic ? glm::dvec3(od.inverse * glm::dvec4(c + origin, 1.0)) : c));
        }
        return r;
    }

    // Rays start inside traceBounds: the boxes of objects grown for a smaller world (see
    // triangleBounds) are grown again and their scenes rebuilt.
    void regrowBoxes() {
        bool staticsChanged = false, changed = false;
        for (ObjectData& od : objects) {
            if (!od.info.inWorld || od.geomId == kInvalidId) continue;
            const double needed = reachOf(od, traceBounds);
            if (needed <= od.reach) continue;
            od.reach = 2.0 * needed;
            changed = true;
            if (od.info.dynamic) {
                rtcCommitGeometry(rtcGetGeometry(od.scene, 0));
                rtcCommitScene(od.scene);
                rtcCommitGeometry(rtcGetGeometry(top, od.geomId));
            } else {
                rtcCommitGeometry(rtcGetGeometry(statics, od.geomId));
                staticsChanged = true;
            }
        }
        if (staticsChanged) {
            rtcCommitScene(statics);
            rtcCommitGeometry(rtcGetGeometry(top, staticInstance));
        }
        if (changed) rtcCommitScene(top);
    }

    // Normalises `ray`, clips it to the world bounds and moves it into the float frame. False when
    // it cannot reach any geometry.
    bool prepare(const Ray& ray, unsigned id, RTCRayHit& rh, Prepared& p) const {
        if (traceBounds.empty()) return false;
        const double length = glm::length(ray.direction);
        const glm::dvec3 u = ray.direction / length;
        const glm::dvec3 o = ray.origin - origin;
        double lo = ray.tnear * length, hi = ray.tfar * length;
        for (int a = 0; a < 3; ++a) {
            if (u[a] != 0.0) {
                const double t0 = (traceBounds.min[a] - o[a]) / u[a];
                const double t1 = (traceBounds.max[a] - o[a]) / u[a];
                lo = std::max(lo, std::min(t0, t1));
                hi = std::min(hi, std::max(t0, t1));
            } else if (o[a] < traceBounds.min[a] || o[a] > traceBounds.max[a]) {
                return false;
            }
        }
        // A clip distance that overflows (an origin near the double limit) cannot be traced: the hit
        // distance would not be representable either.
        if (!(lo <= hi) || !std::isfinite(hi)) return false;
        p.start = lo;
        p.length = length;
        const glm::dvec3 start = o + u * lo;
        rh.ray.org_x = float(start.x);
        rh.ray.org_y = float(start.y);
        rh.ray.org_z = float(start.z);
        // Embree takes ray origins within +-1.844e18 (its FLT_LARGE; beyond, an assertion aborts). A
        // start farther out (cancellation from an origin near 1e300, or geometry that far) is a miss.
        const float largest = 1.844e18f;
        if (!(std::fabs(rh.ray.org_x) <= largest && std::fabs(rh.ray.org_y) <= largest &&
              std::fabs(rh.ray.org_z) <= largest))
            return false;
        rh.ray.dir_x = float(u.x);
        rh.ray.dir_y = float(u.y);
        rh.ray.dir_z = float(u.z);
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = std::nextafter(float(hi - lo), std::numeric_limits<float>::infinity());
        rh.ray.time = 0.0f;
        rh.ray.mask = 0xFFFFFFFFu;
        rh.ray.id = id;
        rh.ray.flags = 0;
        rh.hit.geomID = kInvalidId;
        rh.hit.primID = kInvalidId;
        rh.hit.instID[0] = kInvalidId;
        return true;
    }

    // The hit Embree reported (at distance `embreeT` along the prepared ray), refined in double on
    // the hit triangle.
    std::optional<Hit> finish(const Ray& ray, const Prepared& p, const RTCRayHit& rh, float embreeT) const {
        if (rh.hit.geomID == kInvalidId) return std::nullopt;
        const unsigned inst = rh.hit.instID[0];
        uint32_t object;
        if (inst == staticInstance) {
            if (rh.hit.geomID >= staticGeomToObject.size()) return std::nullopt;
            object = staticGeomToObject[rh.hit.geomID];
        } else {
            if (inst >= instanceToObject.size()) return std::nullopt;
            object = instanceToObject[inst];
        }
        const ObjectData& od = objects[object];
        if (size_t(rh.hit.primID) * 3 + 2 >= od.indices.size()) return std::nullopt;
        const uint32_t* tri = &od.indices[size_t(rh.hit.primID) * 3];
        const glm::dvec3 v0(od.positions[tri[0]]), v1(od.positions[tri[1]]), v2(od.positions[tri[2]]);

        const glm::dvec3 lo = glm::dvec3(od.inverse * glm::dvec4(ray.origin, 1.0));
        const glm::dvec3 ld = glm::dmat3(od.inverse) * ray.direction;
        glm::dvec3 n = glm::cross(v1 - v0, v2 - v0);
        const double nl = glm::length(n);
        n = nl > 0.0 ? n / nl : -glm::normalize(ld);

        // Embree's distance, in units of the caller's direction; replaced by the plane intersection
        // in double unless the ray runs nearly along the plane.
        double t = (p.start + double(embreeT)) / p.length;
        const double denom = glm::dot(ld, n);
        if (std::fabs(denom) >= 1e-4 * glm::length(ld)) {
            const double tr = glm::dot(v0 - lo, n) / denom;
            if (std::isfinite(tr)) t = std::clamp(tr, ray.tnear, ray.tfar);
        }

        Hit h;
        h.object = object;
        h.primitive = rh.hit.primID;
        h.t = t;
        h.position = ray.origin + t * ray.direction;
        h.localPosition = lo + t * ld;
        const glm::dmat3 normalMatrix = glm::transpose(glm::dmat3(od.inverse));
        glm::dvec3 wn = glm::normalize(normalMatrix * n);
        h.frontFace = glm::dot(wn, ray.direction) < 0.0;
        if (!h.frontFace) {
            wn = -wn;
            n = -n;
        }
        h.normal = wn;
        h.localNormal = n;
        return h;
    }
};

CollisionWorld::CollisionWorld(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CollisionWorld::CollisionWorld(CollisionWorld&&) noexcept = default;
CollisionWorld& CollisionWorld::operator=(CollisionWorld&&) noexcept = default;
CollisionWorld::~CollisionWorld() = default;

Result<CollisionWorld> CollisionWorld::build(const Scene& scene,
                                             const std::vector<std::optional<Proxy>>& proxies,
                                             const WorldSettings& settings) {
    const std::string where = "collision world (" + scene.source + ")";
    if (Status s = validateScene(scene); !s) return fail(where + ": " + s.error());
    if (!proxies.empty() && proxies.size() != scene.objects.size())
        return fail(where + ": " + std::to_string(proxies.size()) + " proxies for " +
                    std::to_string(scene.objects.size()) + " objects");
    for (size_t i = 0; i < proxies.size(); ++i) {
        if (!proxies[i]) continue;
        const std::string name = "object '" + scene.objects[i].name + "'";
        if (Status s = validateMesh(proxies[i]->mesh); !s)
            return fail(where + ": proxy of " + name + ": " + s.error());
        if (!std::isfinite(proxies[i]->errorBound) || proxies[i]->errorBound < 0.0)
            return fail(where + ": proxy of " + name + " has an error bound that is not finite and >= 0");
    }
    if (scene.objects.size() >= size_t(std::numeric_limits<uint32_t>::max()))
        return fail(where + ": too many objects");

    auto impl = std::make_unique<Impl>();
    impl->device = rtcNewDevice(settings.deviceConfig.empty() ? nullptr : settings.deviceConfig.c_str());
    if (!impl->device)
        return fail(where + ": cannot create the Embree device with configuration \"" +
                    settings.deviceConfig + "\": " + errorName(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(impl->device, &Impl::onError, impl.get());

    // Collision meshes, error bounds and the origin of the float frame.
    impl->objects.resize(scene.objects.size());
    DBounds staticBounds, allBounds;
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& so = scene.objects[i];
        ObjectData& od = impl->objects[i];
        od.info.name = so.name;
        od.info.dynamic = so.dynamic;
        od.info.transform = so.transform;
        od.inverse = glm::inverse(so.transform);
        if (!affine(so.transform)) return fail(where + ": object '" + so.name + "': transform is not affine");
        if (!so.receivesDecals) {
            od.info.localBounds = so.mesh.bounds();
            continue;
        }
        const Mesh* mesh = &so.mesh;
        double h = 0.0;
        if (!proxies.empty() && proxies[i]) {
            mesh = &proxies[i]->mesh;
            h = proxies[i]->errorBound;
        } else if (settings.useColliders && so.collider) {
            // Certified, and at most 1% of the render mesh's diagonal above the measured distance.
            ProxySettings measure;
            measure.tolerance = 0.05f;
            measure.toleranceRelative = true;
            measure.marginFraction = 0.2f;
            measure.maxSamples = 200'000;
            measure.randomSamples = 1024;
            Result<Proxy> measured = buildProxy(so.mesh, measure, &*so.collider);
            if (!measured) return fail(where + ": collider of object '" + so.name + "': " + measured.error());
            mesh = &*so.collider;
            h = measured->errorBound;
        }
        od.info.inWorld = true;
        od.info.errorBound = h;
        od.positions = mesh->positions;
        od.indices.assign(mesh->indices.begin(), mesh->indices.begin() + mesh->triangleCount() * 3);
        od.info.triangles = mesh->triangleCount();
        od.info.localBounds = meshBounds(od.positions, od.indices);
        const DBounds wb = transformBounds(od.info.localBounds, so.transform);
        allBounds.extend(wb);
        if (!so.dynamic) staticBounds.extend(wb);
    }
    if (!staticBounds.empty())
        impl->origin = staticBounds.center();
    else if (!allBounds.empty())
        impl->origin = allBounds.center();
    // Box growth for ray starts anywhere in the world, with room to spare (regrowBoxes).
    if (!allBounds.empty()) {
        DBounds frame;
        frame.extend(allBounds.min - impl->origin);
        frame.extend(allBounds.max - impl->origin);
        for (ObjectData& od : impl->objects)
            od.reach = 2.0 * impl->reachOf(od, frame);
    }

    impl->top = impl->newScene();
    rtcSetSceneFlags(impl->top, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(impl->top, RTC_BUILD_QUALITY_LOW);
    impl->statics = impl->newScene();
    bool anyStatic = false;
    for (size_t i = 0; i < impl->objects.size(); ++i) {
        ObjectData& od = impl->objects[i];
        if (!od.info.inWorld || od.info.triangles == 0) continue;
        impl->triangles += od.info.triangles;
        if (!od.info.dynamic) {
            RTCGeometry g = impl->triangleGeometry(od, &od.info.transform);
            od.geomId = rtcAttachGeometry(impl->statics, g);
            rtcReleaseGeometry(g);
            if (impl->staticGeomToObject.size() <= od.geomId)
                impl->staticGeomToObject.resize(od.geomId + 1, 0);
            impl->staticGeomToObject[od.geomId] = uint32_t(i);
            anyStatic = true;
        } else {
            od.scene = impl->newScene();
            RTCGeometry g = impl->triangleGeometry(od, nullptr);
            rtcAttachGeometry(od.scene, g);
            rtcReleaseGeometry(g);
            rtcCommitScene(od.scene);
            RTCGeometry inst = rtcNewGeometry(impl->device, RTC_GEOMETRY_TYPE_INSTANCE);
            rtcSetGeometryInstancedScene(inst, od.scene);
            float xfm[12];
            toEmbreeTransform(od.info.transform, impl->origin, xfm);
            rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
            rtcCommitGeometry(inst);
            od.geomId = rtcAttachGeometry(impl->top, inst);
            rtcReleaseGeometry(inst);
            if (impl->instanceToObject.size() <= od.geomId) impl->instanceToObject.resize(od.geomId + 1, 0);
            impl->instanceToObject[od.geomId] = uint32_t(i);
        }
    }
    rtcCommitScene(impl->statics);
    if (anyStatic) {
        RTCGeometry inst = rtcNewGeometry(impl->device, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(inst, impl->statics);
        const float identity[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
        rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, identity);
        rtcCommitGeometry(inst);
        impl->staticInstance = rtcAttachGeometry(impl->top, inst);
        rtcReleaseGeometry(inst);
    }
    rtcCommitScene(impl->top);
    if (!impl->deviceError.empty()) return fail(where + ": " + impl->deviceError);
    impl->updateTraceBounds();
    return CollisionWorld(std::move(impl));
}

std::optional<Hit> CollisionWorld::intersect(const Ray& ray) const {
    if (rayProblem(ray)) return std::nullopt;
    RTCRayHit rh;
    Prepared p;
    if (!impl_->prepare(ray, 0, rh, p)) return std::nullopt;
    float best = rh.ray.tfar;
    TraceContext ctx;
    rtcInitIntersectContext(&ctx.embree);
    ctx.bestT = &best;
    ctx.slack = impl_->slack;
    rtcIntersect1(impl_->top, &ctx.embree, &rh);
    return impl_->finish(ray, p, rh, best);
}

std::vector<std::optional<Hit>> CollisionWorld::intersectBatch(const std::vector<Ray>& rays) const {
    // Ray by ray with rtcIntersect1: on these user-geometry triangles Embree's stream and packet paths
    // (rtcIntersect1M, rtcIntersect16) took 1.3 to 3.5 times as long per ray, coherent rays included
    // (spatter-bench placement, docs/BENCHMARKS.md).
    std::vector<std::optional<Hit>> hits;
    hits.reserve(rays.size());
    for (const Ray& ray : rays)
        hits.push_back(intersect(ray));
    return hits;
}

Status CollisionWorld::setTransform(uint32_t object, const glm::dmat4& transform) {
    if (object >= impl_->objects.size())
        return fail("setTransform: object " + std::to_string(object) + " out of range");
    ObjectData& od = impl_->objects[object];
    if (!od.info.dynamic) return fail("setTransform: object '" + od.info.name + "' is static");
    if (!od.info.inWorld)
        return fail("setTransform: object '" + od.info.name + "' is not in the collision world");
    const double det = glm::determinant(glm::dmat3(transform));
    if (!finiteMatrix(transform) || !std::isfinite(det) || !(std::fabs(det) > 1e-30) || !affine(transform))
        return fail("setTransform: transform of object '" + od.info.name +
                    "' is not a finite invertible affine matrix");
    const glm::dmat4 inverse = glm::inverse(transform);
    if (!finiteMatrix(inverse))
        return fail("setTransform: transform of object '" + od.info.name +
                    "' is not invertible in double precision");
    od.info.transform = transform;
    od.inverse = inverse;
    if (od.geomId != kInvalidId) {
        float xfm[12];
        toEmbreeTransform(transform, impl_->origin, xfm);
        RTCGeometry inst = rtcGetGeometry(impl_->top, od.geomId);
        rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
        rtcCommitGeometry(inst);
        rtcCommitScene(impl_->top);
        impl_->updateTraceBounds();
    }
    return {};
}

Status CollisionWorld::removeObject(uint32_t object) {
    if (object >= impl_->objects.size())
        return fail("removeObject: object " + std::to_string(object) + " out of range");
    ObjectData& od = impl_->objects[object];
    if (!od.info.inWorld)
        return fail("removeObject: object '" + od.info.name + "' is not in the collision world");
    od.info.inWorld = false;
    if (od.geomId != kInvalidId) {
        impl_->triangles -= od.info.triangles;
        if (od.info.dynamic) {
            rtcDetachGeometry(impl_->top, od.geomId);
            rtcReleaseScene(od.scene);
            od.scene = nullptr;
        } else {
            rtcDetachGeometry(impl_->statics, od.geomId);
            rtcCommitScene(impl_->statics);
        }
        od.geomId = kInvalidId;
        rtcCommitScene(impl_->top);
        impl_->updateTraceBounds();
    }
    return {};
}

size_t CollisionWorld::objectCount() const {
    return impl_->objects.size();
}

const CollisionObject* CollisionWorld::object(uint32_t index) const {
    return index < impl_->objects.size() ? &impl_->objects[index].info : nullptr;
}

DBounds CollisionWorld::worldBounds(uint32_t index) const {
    if (index >= impl_->objects.size()) return {};
    const CollisionObject& o = impl_->objects[index].info;
    return transformBounds(o.localBounds, o.transform);
}

double CollisionWorld::worldErrorBound(uint32_t index) const {
    if (index >= impl_->objects.size()) return 0.0;
    const CollisionObject& o = impl_->objects[index].info;
    const glm::dmat3 m(o.transform);
    return o.errorBound * std::max({glm::length(m[0]), glm::length(m[1]), glm::length(m[2])});
}

glm::dvec3 CollisionWorld::origin() const {
    return impl_->origin;
}

size_t CollisionWorld::triangleCount() const {
    return impl_->triangles;
}

} // namespace spatter
