#include "spatter/placement/CollisionWorld.hpp"

#include "CollisionObjects.hpp"

#include "spatter/core/LinearStretch.hpp"
#include "spatter/placement/TraceTransform.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

namespace spatter {

namespace {

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

// What a prepared ray needs to map Embree's answer back onto the caller's ray.
struct Prepared {
    double start = 0.0;  // distance along the unit direction where the traced ray starts
    double length = 1.0; // length of the caller's direction
};

// A ray of a batch, prepared for Embree.
struct BatchRay {
    RTCRayHit rh; // rh.ray.dir: unit
    Prepared p;
    size_t index = 0; // in the batch
};

// Consecutive rays of a batch go into one packet while they start within 1e-3 of the world's extent
// of the packet's first ray with directions within kGroupAngleDeg of its direction; the packet is
// traced as a packet when it has at least kMinPacketLanes rays, all within kPacketHalfAngleDeg of
// their mean direction, else ray by ray (rtcIntersect1 is faster for wider bundles and for few
// rays, see intersectBatch).
constexpr double kGroupAngleDeg = 15.0;
constexpr double kPacketHalfAngleDeg = 3.0;
constexpr unsigned kMinPacketLanes = 4;

// Static objects whose collision triangles the world holds this many times or more are traced as
// instances of one object-space scene rather than copied into the static scene: PLACEMENT.md gives
// the measurements.
constexpr uint32_t kInstancedCopies = 4;

// The (unit) direction of a prepared ray.
glm::dvec3 direction(const RTCRay& r) {
    return glm::dvec3(r.dir_x, r.dir_y, r.dir_z);
}

// Up to 16 batch rays in Embree's packet layout (RTCRayHitN of `width` lanes).
struct Packet {
    explicit Packet(unsigned w) : width(w) {}
    alignas(64) float soa[20 * 16] = {}; // RTCRayHitN of `width` lanes: 12 ray and 8 hit arrays
    alignas(64) int valid[16];
    float bestT[16];
    BatchRay rays[16];
    glm::dvec3 origin{0.0}; // of the first ray, the caller's
    unsigned width;
    unsigned lanes = 0;

    // The slot the next ray is prepared in.
    BatchRay& next() { return rays[lanes]; }

    // Takes the ray prepared in next() (from `from`, the caller's origin) into the packet; false, leaving
    // it there, when its origin or direction is too far from the first ray's (`spread`, `groupCos`).
    bool take(const glm::dvec3& from, double spread, double groupCos) {
        if (lanes == 0)
            origin = from;
        else if (glm::distance(from, origin) > spread ||
                 glm::dot(direction(rays[lanes].rh.ray), direction(rays[0].rh.ray)) < groupCos)
            return false;
        ++lanes;
        return true;
    }

    // Whether the rays are a narrow bundle: kMinPacketLanes or more, all within kPacketHalfAngleDeg
    // of their mean direction.
    bool narrow() const {
        if (lanes < kMinPacketLanes) return false;
        glm::dvec3 mean(0.0);
        for (unsigned i = 0; i < lanes; ++i)
            mean += direction(rays[i].rh.ray);
        mean = glm::normalize(mean);
        const double minCos = std::cos(glm::radians(kPacketHalfAngleDeg));
        for (unsigned i = 0; i < lanes; ++i)
            if (glm::dot(mean, direction(rays[i].rh.ray)) < minCos) return false;
        return true;
    }

    RTCRayHitN* rayhit() { return reinterpret_cast<RTCRayHitN*>(soa); }

    // Lays the rays out for Embree; the lanes beyond `lanes` are invalid copies of the first.
    void layOut() {
        RTCRayN* ray = RTCRayHitN_RayN(rayhit(), width);
        RTCHitN* hit = RTCRayHitN_HitN(rayhit(), width);
        for (unsigned i = 0; i < width; ++i) {
            valid[i] = i < lanes ? -1 : 0;
            const RTCRay& r = rays[i < lanes ? i : 0].rh.ray;
            RTCRayN_org_x(ray, width, i) = r.org_x;
            RTCRayN_org_y(ray, width, i) = r.org_y;
            RTCRayN_org_z(ray, width, i) = r.org_z;
            RTCRayN_tnear(ray, width, i) = r.tnear;
            RTCRayN_dir_x(ray, width, i) = r.dir_x;
            RTCRayN_dir_y(ray, width, i) = r.dir_y;
            RTCRayN_dir_z(ray, width, i) = r.dir_z;
            RTCRayN_time(ray, width, i) = r.time;
            RTCRayN_tfar(ray, width, i) = r.tfar;
            RTCRayN_mask(ray, width, i) = r.mask;
            RTCRayN_id(ray, width, i) = i;
            RTCRayN_flags(ray, width, i) = r.flags;
            RTCHitN_geomID(hit, width, i) = kInvalidId;
            RTCHitN_primID(hit, width, i) = kInvalidId;
            RTCHitN_instID(hit, width, i, 0) = kInvalidId;
            bestT[i] = r.tfar;
        }
    }
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
    DBounds traceBounds;      // frame coordinates, padded
    float slack = 0.0f;       // tfar slack of offerHit: 1e-6 of the size of traceBounds
    unsigned packetWidth = 4; // lanes of intersectBatch's packets: the widest Embree runs natively
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
        const ObjectData& shape = objects[od.shape()];
        if (&shape != &od) od.indices = shape.indices;
        od.traced.resize(shape.positions.size());
        for (size_t i = 0; i < shape.positions.size(); ++i) {
            glm::dvec3 p(shape.positions[i]);
            if (toFrame) p = glm::dvec3(*toFrame * glm::dvec4(p, 1.0)) - origin;
            od.traced[i] = glm::vec3(p);
        }
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(g, unsigned(od.indices.size() / 3));
        rtcSetGeometryUserData(g, static_cast<TracedTriangles*>(&od));
        rtcSetGeometryBoundsFunction(g, triangleBounds, nullptr);
        rtcSetGeometryIntersectFunction(g, intersectTriangle);
        // A posed mesh keeps its triangles and moves its vertices: its hierarchy is refitted.
        if (od.posable) rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_REFIT);
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
    // coordinates): the frame itself for the static scene's objects, object space for instances. With the
    // rule of TraceTransform.hpp (objects within 2^32 of the origin, inverse norms at most 2^25) it stays
    // below 2^59, inside Embree's range of +-1.844e18 (about 2^60.7) for instance-space origins.
    double reachOf(const ObjectData& od, const DBounds& frame) const {
        double r = 0.0;
        for (int i = 0; i < 8; ++i) {
            const glm::dvec3 c((i & 1) ? frame.max.x : frame.min.x, (i & 2) ? frame.max.y : frame.min.y,
                               (i & 4) ? frame.max.z : frame.min.z);
            r = std::max(
                r, glm::length(od.info.instanced ? glm::dvec3(od.inverse * glm::dvec4(c + origin, 1.0)) : c));
        }
        return r;
    }

    // Rays start inside traceBounds: the boxes of objects grown for a smaller world (see
    // triangleBounds) are grown again and their scenes rebuilt.
    void regrowBoxes() {
        bool staticsChanged = false, changed = false;
        // The instanced scenes regrown, by the object whose triangles they hold.
        std::vector<uint32_t> regrown;
        for (ObjectData& od : objects) {
            if (!od.info.traced || od.geomId == kInvalidId) continue;
            const double needed = reachOf(od, traceBounds);
            TracedTriangles& traced = objects[od.tracedBy];
            if (needed <= traced.reach) continue;
            traced.reach = 2.0 * needed;
            changed = true;
            if (od.info.instanced) {
                rtcCommitGeometry(rtcGetGeometry(od.scene, 0));
                rtcCommitScene(od.scene);
                regrown.push_back(od.tracedBy);
            } else {
                rtcCommitGeometry(rtcGetGeometry(statics, od.geomId));
                staticsChanged = true;
            }
        }
        if (!regrown.empty()) commitInstancesOf(regrown);
        if (staticsChanged) {
            rtcCommitScene(statics);
            rtcCommitGeometry(rtcGetGeometry(top, staticInstance));
        }
        if (changed) rtcCommitScene(top);
    }

    // Commits the instances of the scenes holding the triangles of objects `tracers`.
    void commitInstancesOf(const std::vector<uint32_t>& tracers) {
        for (const ObjectData& od : objects)
            if (od.info.instanced && od.geomId != kInvalidId &&
                std::find(tracers.begin(), tracers.end(), od.tracedBy) != tracers.end())
                rtcCommitGeometry(rtcGetGeometry(top, od.geomId));
    }

    // Which objects are traced as instances of object-space scenes (the dynamic ones, and the static
    // ones whose collision mesh the world holds kInstancedCopies times or more), and which of those
    // share one scene: those that read one collision mesh (shape()) and do not deform trace the first
    // one's.
    void chooseInstances() {
        std::vector<uint32_t> staticCopies(objects.size(), 0); // by shape
        for (const ObjectData& od : objects)
            if (od.info.inWorld && !od.info.dynamic && od.info.triangles > 0) ++staticCopies[od.shape()];
        std::vector<uint32_t> holder(objects.size(), kInvalidId); // by shape: the first instanced
        for (uint32_t i = 0; i < objects.size(); ++i) {
            ObjectData& od = objects[i];
            const bool copies = od.info.triangles > 0 && staticCopies[od.shape()] >= kInstancedCopies;
            od.info.instanced = od.info.inWorld && (od.info.dynamic || copies);
            if (!od.info.instanced || od.posable || od.info.triangles == 0) continue;
            if (holder[od.shape()] == kInvalidId) holder[od.shape()] = i;
            od.tracedBy = holder[od.shape()];
        }
    }

    // Every collision object into Embree: the static ones as geometries of one scene (in the float
    // frame), the instanced ones (chooseInstances) as instances of object-space scenes; then the top
    // scene committed.
    void attachObjects() {
        top = newScene();
        rtcSetSceneFlags(top, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_DYNAMIC);
        rtcSetSceneBuildQuality(top, RTC_BUILD_QUALITY_LOW);
        statics = newScene();
        bool anyStatic = false;
        for (size_t i = 0; i < objects.size(); ++i) {
            ObjectData& od = objects[i];
            if (!od.info.inWorld || od.info.triangles == 0) continue;
            triangles += od.info.triangles;
            if (od.info.instanced) {
                attachInstance(od, uint32_t(i));
            } else if (od.info.traced) {
                attachStatic(od, uint32_t(i));
                anyStatic = true;
            }
        }
        rtcCommitScene(statics);
        if (anyStatic) {
            RTCGeometry inst = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
            rtcSetGeometryInstancedScene(inst, statics);
            const float identity[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
            rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, identity);
            rtcCommitGeometry(inst);
            staticInstance = rtcAttachGeometry(top, inst);
            rtcReleaseGeometry(inst);
        }
        rtcCommitScene(top);
    }

    // A static object's triangles, in the float frame, into the static scene.
    void attachStatic(ObjectData& od, uint32_t object) {
        RTCGeometry g = triangleGeometry(od, &od.info.transform);
        od.geomId = rtcAttachGeometry(statics, g);
        rtcReleaseGeometry(g);
        if (staticGeomToObject.size() <= od.geomId) staticGeomToObject.resize(od.geomId + 1, 0);
        staticGeomToObject[od.geomId] = object;
    }

    // An instanced object's triangles into a scene of its own, or the scene of the object it traces
    // (chooseInstances), instanced in the top scene.
    void attachInstance(ObjectData& od, uint32_t object) {
        if (od.tracedBy != object) {
            od.scene = objects[od.tracedBy].scene;
            rtcRetainScene(od.scene);
        } else {
            od.scene = newScene();
            // A posed mesh's hierarchy is refitted, not rebuilt: Embree refits a geometry of build
            // quality REFIT in a two-level (LOW) scene flagged DYNAMIC, and rebuilds it otherwise.
            if (od.posable) {
                rtcSetSceneFlags(od.scene, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_DYNAMIC);
                rtcSetSceneBuildQuality(od.scene, RTC_BUILD_QUALITY_LOW);
            }
            RTCGeometry g = triangleGeometry(od, nullptr);
            rtcAttachGeometry(od.scene, g);
            rtcReleaseGeometry(g);
            rtcCommitScene(od.scene);
        }
        // An untraced object's instance holds the identity, which Embree can invert, and is
        // disabled until setTransform gives the object a usable transform.
        RTCGeometry inst = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(inst, od.scene);
        float xfm[12];
        toEmbreeTransform(od.info.traced ? od.info.transform : glm::dmat4(1.0), origin, xfm);
        rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
        if (!od.info.traced) rtcDisableGeometry(inst);
        rtcCommitGeometry(inst);
        od.geomId = rtcAttachGeometry(top, inst);
        rtcReleaseGeometry(inst);
        if (instanceToObject.size() <= od.geomId) instanceToObject.resize(od.geomId + 1, 0);
        instanceToObject[od.geomId] = object;
    }

    // Applies the rule of TraceTransform.hpp, with the frame's origin known, to every object in the
    // world, and sizes the box growth of the traced ones for ray starts anywhere in the world, with
    // room to spare (regrowBoxes).
    void decideTraced() {
        DBounds frame;
        for (ObjectData& od : objects) {
            if (!od.info.inWorld) continue;
            if (od.info.untraced.empty())
                od.info.untraced = tracePlacementProblem(od.info.transform, od.info.localBounds, origin);
            od.info.traced = od.info.untraced.empty();
            od.inverse = glm::inverse(od.info.transform);
            if (!od.info.traced) continue;
            const DBounds wb = transformBounds(od.info.localBounds, od.info.transform);
            frame.extend(wb.min - origin);
            frame.extend(wb.max - origin);
        }
        if (frame.empty()) return;
        for (ObjectData& od : objects) {
            if (!od.info.traced) continue;
            TracedTriangles& traced = objects[od.tracedBy];
            traced.reach = std::max(traced.reach, 2.0 * reachOf(od, frame));
        }
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
        // distance would not be representable either. What Embree gets is valid by construction:
        // the origin is finite and within its range (below), the direction unit, tnear 0 and tfar
        // finite (lo <= hi, both inside the finite trace bounds).
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

    // The warning line of an object in the world that is not traced.
    std::string untracedLine(uint32_t i) const {
        const CollisionObject& o = objects[i].info;
        return "object " + std::to_string(i) + " (" + o.name + "): " + o.untraced + "; not traced";
    }

    // The closest hit of one prepared ray, traced with rtcIntersect1.
    std::optional<Hit> traceSingle(const Ray& ray, RTCRayHit& rh, const Prepared& p) const {
        float best = rh.ray.tfar;
        TraceContext ctx;
        rtcInitIntersectContext(&ctx.embree);
        ctx.bestT = &best;
        ctx.slack = slack;
        rtcIntersect1(top, &ctx.embree, &rh);
        return finish(ray, p, rh, best);
    }

    // Traces the packet (rtcIntersect4, 8 or 16 by its width) and finishes each lane's hit into
    // `hits`. Not with RTC_INTERSECT_CONTEXT_FLAG_COHERENT: Embree's frustum traversal (3.13) skipped
    // the far faces of a box for bursts that start inside it, which rays traced alone hit.
    void tracePacket(Packet& packet, const std::vector<Ray>& rays,
                     std::vector<std::optional<Hit>>& hits) const {
        packet.layOut();
        TraceContext ctx;
        rtcInitIntersectContext(&ctx.embree);
        ctx.bestT = packet.bestT;
        ctx.slack = slack;
        if (packet.width == 16)
            rtcIntersect16(packet.valid, top, &ctx.embree, reinterpret_cast<RTCRayHit16*>(packet.soa));
        else if (packet.width == 8)
            rtcIntersect8(packet.valid, top, &ctx.embree, reinterpret_cast<RTCRayHit8*>(packet.soa));
        else
            rtcIntersect4(packet.valid, top, &ctx.embree, reinterpret_cast<RTCRayHit4*>(packet.soa));
        for (unsigned i = 0; i < packet.lanes; ++i) {
            const BatchRay& b = packet.rays[i];
            hits[b.index] =
                finish(rays[b.index], b.p, rtcGetRayHitFromRayHitN(packet.rayhit(), packet.width, i),
                       packet.bestT[i]);
        }
    }

    // Traces the rays gathered in `packet` (as a packet when they are a narrow bundle, else one by
    // one) and empties it.
    void flush(Packet& packet, const std::vector<Ray>& rays, std::vector<std::optional<Hit>>& hits) const {
        if (packet.narrow()) {
            tracePacket(packet, rays, hits);
        } else {
            for (unsigned i = 0; i < packet.lanes; ++i) {
                BatchRay& b = packet.rays[i];
                hits[b.index] = traceSingle(rays[b.index], b.rh, b.p);
            }
        }
        packet.lanes = 0;
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
        const ObjectData& shape = objects[od.shape()];
        if (size_t(rh.hit.primID) * 3 + 2 >= shape.indices.size()) return std::nullopt;
        const uint32_t* tri = &shape.indices[size_t(rh.hit.primID) * 3];
        const glm::dvec3 v0(shape.positions[tri[0]]), v1(shape.positions[tri[1]]),
            v2(shape.positions[tri[2]]);

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
                                             const std::vector<std::shared_ptr<const Proxy>>& proxies,
                                             const WorldSettings& settings) {
    const std::string where = "collision world (" + scene.source + ")";
    if (Status s = validateScene(scene); !s) return fail(where + ": " + s.error());
    if (!proxies.empty() && proxies.size() != scene.objects.size())
        return fail(where + ": " + std::to_string(proxies.size()) + " proxies for " +
                    std::to_string(scene.objects.size()) + " objects");
    std::unordered_set<const Proxy*> checked; // a proxy that objects share is checked once
    for (size_t i = 0; i < proxies.size(); ++i)
        if (proxies[i] && checked.insert(proxies[i].get()).second)
            if (Status s = checkProxy(*proxies[i], scene.objects[i].name); !s)
                return fail(where + ": " + s.error());
    if (scene.objects.size() >= size_t(std::numeric_limits<uint32_t>::max()))
        return fail(where + ": too many objects");

    auto impl = std::make_unique<Impl>();
    impl->device = rtcNewDevice(settings.deviceConfig.empty() ? nullptr : settings.deviceConfig.c_str());
    if (!impl->device)
        return fail(where + ": cannot create the Embree device with configuration \"" +
                    settings.deviceConfig + "\": " + errorName(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(impl->device, &Impl::onError, impl.get());
    if (rtcGetDeviceProperty(impl->device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED))
        impl->packetWidth = 16;
    else if (rtcGetDeviceProperty(impl->device, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED))
        impl->packetWidth = 8;

    // Collision meshes, error bounds and the origin of the float frame.
    if (Status s = fillObjects(scene, proxies, settings, impl->objects); !s)
        return fail(where + ": " + s.error());
    DBounds staticBounds, allBounds;
    for (ObjectData& od : impl->objects) {
        if (!od.info.inWorld) continue;
        // The frame's origin comes from the objects whose scale and condition the trace can use.
        od.info.untraced = floatLinearProblem(od.info.transform);
        if (!od.info.untraced.empty()) continue;
        const DBounds wb = transformBounds(od.info.localBounds, od.info.transform);
        allBounds.extend(wb);
        if (!od.info.dynamic) staticBounds.extend(wb);
    }
    impl->chooseInstances();
    if (!staticBounds.empty())
        impl->origin = staticBounds.center();
    else if (!allBounds.empty())
        impl->origin = allBounds.center();
    impl->decideTraced();

    impl->attachObjects();
    if (!impl->deviceError.empty()) return fail(where + ": " + impl->deviceError);
    impl->updateTraceBounds();
    return CollisionWorld(std::move(impl));
}

std::optional<Hit> CollisionWorld::intersect(const Ray& ray) const {
    if (rayProblem(ray)) return std::nullopt;
    RTCRayHit rh;
    Prepared p;
    if (!impl_->prepare(ray, 0, rh, p)) return std::nullopt;
    return impl_->traceSingle(ray, rh, p);
}

// Rays are taken in batch order and gathered while they stay coherent with the first of a group
// (Packet::take); a narrow group (Packet::narrow) is one Embree packet (tracePacket), whose leaves
// the vectorised triangle test takes on all valid lanes at once. Packets beat rtcIntersect1 only on
// narrow bundles: on the 4,111-triangle bunny proxy, 16-ray shots take 0.53x to 0.55x (1 degree
// cone), 0.66x to 0.72x (3 degrees) and 0.87x to 0.93x (5 degrees) the time per ray of intersect,
// and 1.0x from 7 degrees on, so wider groups and scattered rays go ray by ray (spatter-bench
// placement, docs/BENCHMARKS.md). Sorting a batch by origin and direction cells before grouping cost
// about 15% per ray on batches of 16 scattered rays and gained nothing on batches that list each
// burst's rays together, as games do.
std::vector<std::optional<Hit>> CollisionWorld::intersectBatch(const std::vector<Ray>& rays) const {
    std::vector<std::optional<Hit>> hits(rays.size());
    const double spread = 1e-3 * glm::length(impl_->traceBounds.max - impl_->traceBounds.min);
    const double groupCos = std::cos(glm::radians(kGroupAngleDeg));
    Packet packet(impl_->packetWidth);
    for (size_t i = 0; i < rays.size(); ++i) {
        BatchRay& b = packet.next();
        if (rayProblem(rays[i]) || !impl_->prepare(rays[i], 0, b.rh, b.p)) continue;
        b.index = i;
        if (!packet.take(rays[i].origin, spread, groupCos)) {
            // The ray starts the next packet, once the rays before it are traced.
            const unsigned at = packet.lanes;
            impl_->flush(packet, rays, hits);
            packet.rays[0] = packet.rays[at];
            packet.take(rays[i].origin, spread, groupCos);
        }
        if (packet.lanes == packet.width) impl_->flush(packet, rays, hits);
    }
    impl_->flush(packet, rays, hits);
    return hits;
}

Result<TransformUpdate> CollisionWorld::setTransform(uint32_t object, const glm::dmat4& transform) {
    if (object >= impl_->objects.size())
        return fail("setTransform: object " + std::to_string(object) + " out of range");
    ObjectData& od = impl_->objects[object];
    if (!od.info.dynamic) return fail("setTransform: object '" + od.info.name + "' is static");
    if (!od.info.inWorld)
        return fail("setTransform: object '" + od.info.name + "' is not in the collision world");
    if (const std::string problem = transformProblem(transform); !problem.empty())
        return fail("setTransform: object '" + od.info.name + "': " + problem);
    const bool wasTraced = od.info.traced;
    od.info.transform = transform;
    od.info.untraced = traceTransformProblem(transform, od.info.localBounds, impl_->origin);
    od.info.traced = od.info.untraced.empty();
    od.inverse = glm::inverse(transform);
    if (od.geomId != kInvalidId && (od.info.traced || wasTraced)) {
        RTCGeometry inst = rtcGetGeometry(impl_->top, od.geomId);
        if (od.info.traced) {
            float xfm[12];
            toEmbreeTransform(transform, impl_->origin, xfm);
            rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
            if (!wasTraced) rtcEnableGeometry(inst);
        } else {
            rtcDisableGeometry(inst);
        }
        rtcCommitGeometry(inst);
        rtcCommitScene(impl_->top);
        impl_->updateTraceBounds();
    }
    TransformUpdate update;
    update.traced = od.info.traced;
    if (!update.traced) update.warning = impl_->untracedLine(object);
    return update;
}

Result<TransformUpdate> CollisionWorld::setPose(uint32_t object, const glm::dmat4& transform,
                                                const std::vector<glm::dmat4>& joints,
                                                const std::vector<double>& morphWeights) {
    if (object >= impl_->objects.size())
        return fail("setPose: object " + std::to_string(object) + " out of range");
    ObjectData& od = impl_->objects[object];
    const std::string name = "setPose: object '" + od.info.name + "'";
    if (!od.info.dynamic) return fail(name + " is static");
    if (!od.info.inWorld) return fail(name + " is not in the collision world");
    if (!od.posable) return fail(name + " has no skin and no morph targets (move it with setTransform)");
    if (const std::string problem = transformProblem(transform); !problem.empty())
        return fail(name + ": " + problem);
    Result<std::vector<glm::vec3>> posed = poseCollisionMesh(*od.posable, transform, joints, morphWeights);
    if (!posed) return fail(name + ": " + posed.error());
    od.positions = std::move(posed).value();
    od.poseJoints = joints;
    od.poseMorphs = morphWeights;
    od.traced = od.positions; // a dynamic object is traced in its own space
    od.info.localBounds = meshBounds(od.positions, od.indices);
    if (od.scene) {
        rtcCommitGeometry(rtcGetGeometry(od.scene, 0));
        rtcCommitScene(od.scene);
    }
    return setTransform(object, transform);
}

bool CollisionWorld::deforms(uint32_t object) const {
    return object < impl_->objects.size() && impl_->objects[object].posable &&
           impl_->objects[object].info.inWorld;
}

std::optional<SurfaceLocation> CollisionWorld::anchorAt(uint32_t object, uint32_t primitive,
                                                        const glm::dvec3& localPosition,
                                                        const glm::dvec3& localDirection) const {
    if (object >= impl_->objects.size()) return std::nullopt;
    const ObjectData& od = impl_->objects[object];
    if (!od.posable || !od.info.inWorld || size_t(primitive) >= od.indices.size() / 3) return std::nullopt;
    const glm::dvec3 bary = od.barycentricOn(primitive, localPosition);
    // The drawn surface lies within h of the proxy: along a shot up to 82 degrees off its normal,
    // within 8h (and a hair more, for a proxy that is the drawn mesh itself).
    const double reach = 8.0 * od.info.errorBound + 1e-6 * double(od.info.localBounds.diagonal());
    const CollisionHit hit{od.positions, od.indices, primitive, bary, localPosition, localDirection, reach};
    return anchorOf(*od.posable, hit, Pose{od.poseJoints, od.poseMorphs, od.inverse});
}

std::optional<glm::dvec3> CollisionWorld::drawnNormalAt(uint32_t object, uint32_t primitive,
                                                        const glm::dvec3& localPosition) const {
    if (object >= impl_->objects.size()) return std::nullopt;
    const ObjectData& od = impl_->objects[object];
    const ObjectData& shape = impl_->objects[od.shape()];
    if (!shape.drawnNormals || !od.info.inWorld || size_t(primitive) >= shape.indices.size() / 3)
        return std::nullopt;
    return shape.drawnNormals->at(primitive, shape.barycentricOn(primitive, localPosition));
}

std::optional<glm::dmat4> CollisionWorld::anchorFrame(uint32_t object, const SurfaceAnchor& anchor) const {
    if (object >= impl_->objects.size()) return std::nullopt;
    const ObjectData& od = impl_->objects[object];
    if (!od.posable) return std::nullopt;
    return spatter::anchorFrame(*od.posable, od.indices, anchor,
                                Pose{od.poseJoints, od.poseMorphs, od.inverse});
}

Status CollisionWorld::removeObject(uint32_t object) {
    if (object >= impl_->objects.size())
        return fail("removeObject: object " + std::to_string(object) + " out of range");
    ObjectData& od = impl_->objects[object];
    if (!od.info.inWorld)
        return fail("removeObject: object '" + od.info.name + "' is not in the collision world");
    od.info.inWorld = false;
    od.info.traced = false;
    od.info.untraced.clear();
    if (od.geomId != kInvalidId) {
        impl_->triangles -= od.info.triangles;
        if (od.info.instanced) {
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
    return o.errorBound * largestStretch(glm::dmat3(o.transform));
}

std::vector<std::string> CollisionWorld::warnings() const {
    std::vector<std::string> lines;
    for (uint32_t i = 0; i < impl_->objects.size(); ++i)
        if (impl_->objects[i].info.inWorld && !impl_->objects[i].info.traced)
            lines.push_back(impl_->untracedLine(i));
    return lines;
}

glm::dvec3 CollisionWorld::origin() const {
    return impl_->origin;
}

size_t CollisionWorld::triangleCount() const {
    return impl_->triangles;
}

} // namespace spatter
