#pragma once
// DecalSystemImpl: the state behind DecalSystem and the steps its calls share: the dense decal records
// and their handle slots, the area limits, the change log, the skin anchors, and placing a decal at a
// hit. Private to the placement library; DecalSystem.cpp (the public calls), DrawnSurfaceLaying.cpp
// (laying decals on the drawn surface) and DecalSystemAccess.cpp (saves and loads) share it.

#include "NumberChecks.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include "AreaLimits.hpp"
#include "CappedGrowth.hpp"
#include "ChangeLog.hpp"
#include "CraterClipping.hpp"
#include "DenseIndexSet.hpp"
#include "SkinAnchors.hpp"
#include "spatter/core/Random.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <unordered_map>

namespace spatter {

namespace decal_system_detail {

constexpr uint32_t kNone = UINT32_MAX;
constexpr double kPi = 3.14159265358979323846;

// Largest column length of the linear part: the largest scale factor of a TRS transform.
inline double largestScale(const glm::dmat3& m) {
    return std::max({glm::length(m[0]), glm::length(m[1]), glm::length(m[2])});
}

inline int64_t cellCoordinate(double v, double cellSize) {
    const double c = std::floor(v / cellSize);
    const double limit = 9.0e18;
    return int64_t(std::clamp(c, -limit, limit));
}

inline std::string formatNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

// A decal the renderer can use: an orientation, a finite centre, size and half-depth finite and
// at least the smallest normal float (a box of zero, denormal or infinite extent cannot be inverted).
inline bool soundBox(const Decal& d) {
    auto finite = [](const glm::vec3& v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    auto extent = [](float v) { return std::isfinite(v) && v >= std::numeric_limits<float>::min(); };
    return hasOrientation(d.packedFrame) && finite(d.center) && extent(d.size.x) && extent(d.size.y) &&
           extent(d.halfDepth);
}

// The largest world-space extent (size or half-depth) a decal may have: its box goes to object space
// and back through float, and an extent at float's limit would round past it to infinity.
constexpr float kMaxWorldExtent = std::numeric_limits<float>::max() / 4.0f;

struct Slot {
    uint32_t dense = kNone;
    uint32_t generation = 1;
};

} // namespace decal_system_detail

using namespace decal_system_detail;

struct DecalSystem::Impl {
    CollisionWorld world;
    DecalSettings settings;
    std::vector<DecalType> types;
    std::vector<uint8_t> objectIds;
    Rng rng;
    double time = 0.0;
    std::vector<Decal> decals;    // dense
    std::vector<uint32_t> slotOf; // parallel to decals: the handle slot of each
    // The decals evicted under FadeOldest, which the limits no longer count, by slot: the clock time
    // of the eviction. Few at a time, so a side table rather than 8 bytes beside every decal.
    std::unordered_map<uint32_t, double> fadingSince;
    // The clip planes of the volumetric decals, by slot (craterClips()): empty until a crater has one,
    // so that a world without clipped craters keeps nothing for them, and then 8 bytes a slot.
    std::vector<CraterClips> clipsBySlot;
    DenseIndexSet timed; // dense indices update() visits: type lifetime > 0, or fading
    ChangeLog changeLog; // the newest changes of decals
    std::vector<Slot> slots;
    std::vector<uint32_t> freeSlots;
    AreaLimits limits;
    SkinAnchors anchors; // the decals on skinned objects, which setPose moves with the skin
    DecalStats stats;
    std::mutex mutex; // held by every mutation

    Impl(CollisionWorld w, const DecalSettings& s)
        : world(std::move(w)), settings(s), rng(s.seed),
          limits(world.objectCount(), s.budget, s.maxPerCell, s.maxPerObject) {}

    // DecalSystem::spawnOnDrawnSurface with the lock held (DrawnSurfaceLaying.cpp); `caller` names the
    // call in the reasons given.
    SpawnResult spawnOnDrawnSurface(const char* caller, const Ray& shot, const glm::dvec3& point,
                                    const glm::dvec3& normal, uint16_t type);

    SpawnResult reject(SpawnStatus status, std::string reason) {
        stats.rejected[size_t(status)]++;
        SpawnResult r;
        r.status = status;
        r.reason = std::move(reason);
        return r;
    }

    std::string typeError(uint16_t type) const {
        return "no decal type with index " + std::to_string(type) + " (" + std::to_string(types.size()) +
               " registered)";
    }

    const CollisionObject& object(uint32_t index) const { return *world.object(index); }

    CellKey cellKey(uint32_t objectIndex, const glm::dvec3& local) const {
        const CollisionObject& o = object(objectIndex);
        glm::dvec3 p;
        CellKey key;
        if (o.dynamic) {
            p = local * largestScale(glm::dmat3(o.transform));
            key.space = 1 + objectIndex;
        } else {
            p = glm::dvec3(o.transform * glm::dvec4(local, 1.0));
            key.space = 0;
        }
        const double cs = settings.cellSize;
        key.x = cellCoordinate(p.x, cs);
        key.y = cellCoordinate(p.y, cs);
        key.z = cellCoordinate(p.z, cs);
        return key;
    }

    uint64_t version() const { return changeLog.version(); }

    void logChange(uint32_t index, DecalChangeKind kind) { changeLog.append(index, kind, decals.size()); }

    void setClips(uint32_t slot, const CraterClips& clips) {
        if (slot >= clipsBySlot.size()) {
            reserveCapped(clipsBySlot, slots.size(), settings.budget);
            clipsBySlot.resize(slots.size());
        }
        clipsBySlot[slot] = clips;
    }

    bool fading(uint32_t dense) const {
        return !fadingSince.empty() && fadingSince.count(slotOf[dense]) != 0;
    }

    // Removes a decal as remove() does, counted in stats.removed (a fading one is in evicted already).
    void removeCounted(uint32_t dense) {
        if (!fading(dense)) stats.removed++;
        removeDense(dense);
    }

    void removeDense(uint32_t dense) {
        const uint32_t slot = slotOf[dense];
        if (!fadingSince.empty() && fadingSince.erase(slot) != 0) stats.fading--;
        if (slot < clipsBySlot.size()) clipsBySlot[slot] = CraterClips{};
        anchors.erase(slot, decals[dense].object);
        limits.unlink(slot, decals[dense].object);
        slots[slot].dense = kNone;
        slots[slot].generation++;
        freeSlots.push_back(slot);
        const uint32_t last = uint32_t(decals.size() - 1);
        const bool lastTimed = timed.test(last);
        timed.reset(last);
        if (dense != last) {
            decals[dense] = decals[last];
            slotOf[dense] = slotOf[last];
            slots[slotOf[dense]].dense = dense;
            if (lastTimed)
                timed.set(dense);
            else
                timed.reset(dense);
        }
        decals.pop_back();
        slotOf.pop_back();
        stats.alive = decals.size();
        logChange(dense, DecalChangeKind::Removed);
    }

    void evict(uint32_t slot) {
        stats.evicted++;
        const uint32_t dense = slots[slot].dense;
        const float fade = types[decals[dense].type].fadeOutTime;
        if (settings.policy == LimitPolicy::FadeOldest && fade > 0.0f) {
            limits.unlink(slot, decals[dense].object);
            fadingSince[slot] = time;
            timed.set(dense);
            stats.fading++;
        } else {
            removeDense(dense);
        }
    }

    // Under Reject: the reason a new decal in `key` on `objectIndex` would break a limit, or empty.
    // Under the evicting policies: evicts until the new decal fits and returns empty.
    std::string makeRoom(const CellKey& key, uint32_t objectIndex) {
        if (settings.policy == LimitPolicy::Reject) {
            if (limits.cellCount(key) >= settings.maxPerCell)
                return "the cell (" + std::to_string(key.x) + ", " + std::to_string(key.y) + ", " +
                       std::to_string(key.z) + ") holds " + std::to_string(limits.cellCount(key)) +
                       " decals (maxPerCell " + std::to_string(settings.maxPerCell) + ")";
            if (limits.objectCount(objectIndex) >= settings.maxPerObject)
                return "object '" + object(objectIndex).name + "' holds " +
                       std::to_string(limits.objectCount(objectIndex)) + " decals (maxPerObject " +
                       std::to_string(settings.maxPerObject) + ")";
            if (limits.total() >= settings.budget)
                return "the world holds " + std::to_string(limits.total()) + " decals (budget " +
                       std::to_string(settings.budget) + ")";
            return {};
        }
        while (limits.cellCount(key) >= settings.maxPerCell)
            evict(limits.oldestInCell(key));
        while (limits.objectCount(objectIndex) >= settings.maxPerObject)
            evict(limits.oldestOfObject(objectIndex));
        while (limits.total() >= settings.budget)
            evict(limits.oldest());
        return {};
    }

    // Whether a decal of type `t` placed by a shot (`shot`) is projected along it.
    static bool alongShot(const DecalType& t, bool shot) {
        return shot && t.projection == Projection::Shot && !t.volumetric;
    }

    // Places a decal of `typeIndex` on `objectIndex` at `local` (object space) facing `worldNormal`
    // (unit), its tangent from `worldHint`, which is the shot's direction when `shot` is set (and then
    // the projection axis of a type projected along the shot). Every check but the box and the limits
    // has passed. The random numbers are drawn first and given back (the generator restored) when a
    // check fails. `onDrawnSurface`: `local` lies on the drawn surface, not on the collision mesh, so
    // no proxy error is left for the box to hold: its half-depth is depthMargin times its size (1% at
    // least), whatever its type asks, because on a body a deeper box would reach the torso behind an
    // arm. A placed decal's frame in object space, as packed, goes to `objectFrame` if given.
    // `boundScale`: how many times the object's error bound the drawn surface may lie from `local`
    // along `worldNormal` (DrawnFacing).
    SpawnResult place(uint32_t objectIndex, const glm::dvec3& local, const glm::dvec3& worldNormal,
                      const glm::dvec3& worldHint, uint16_t typeIndex, bool shot = false,
                      bool onDrawnSurface = false, glm::dmat3* objectFrame = nullptr,
                      double boundScale = 1.0) {
        const CollisionObject& o = object(objectIndex);
        const DecalType& t = types[typeIndex];
        const Rng unused = rng;
        const uint32_t id = rng.next();
        const float angle = t.randomRotation ? rng.uniform() * float(2.0 * kPi) : 0.0f;
        const float scale = t.sizeJitter > 0.0f ? 1.0f + rng.uniform(-t.sizeJitter, t.sizeJitter) : 1.0f;

        Frame f = frameFromNormalAndHint(glm::normalize(glm::vec3(worldNormal)), glm::vec3(worldHint));
        if (t.randomRotation) f = rotateAboutNormal(f, angle);
        const glm::vec2 size = t.size * scale;
        const glm::dmat3 m(o.transform);
        const double h = world.worldErrorBound(objectIndex) * boundScale;
        constexpr double kMinDrawnDepth = 0.01; // of the size: a box that still holds the surface under it
        const double extent = double(std::max(size.x, size.y));
        const float halfDepth = onDrawnSurface
                                    ? float(std::max(double(settings.depthMargin), kMinDrawnDepth) * extent)
                                    : std::max(t.halfDepth, float(h + double(settings.depthMargin) * extent));

        // To object space: normals by the transpose, tangents by the inverse.
        const glm::dmat3 inv = glm::inverse(m);
        const glm::dvec3 n = glm::normalize(glm::transpose(m) * glm::dvec3(f.normal));
        glm::dvec3 tan = inv * glm::dvec3(f.tangent);
        tan = glm::normalize(tan - n * glm::dot(n, tan));
        const glm::dvec3 bit = glm::cross(n, tan);

        Decal d;
        d.packedFrame = packFrame(tan, bit, n, false); // orthonormal already: packed as it is
        if (alongShot(t, shot))
            d.slant =
                slantOf(tan, bit, n, -(inv * worldHint)); // directions go to object space by the inverse
        d.center = glm::vec3(local);
        d.size = glm::vec2(float(size.x / glm::length(m * tan)), float(size.y / glm::length(m * bit)));
        d.halfDepth = float(halfDepth * glm::length(glm::transpose(inv) * n));
        d.object = objectIndex;
        d.objectId = objectIndex < objectIds.size() ? objectIds[objectIndex] : 0;
        d.id = id;
        d.type = typeIndex;
        d.spawnTime = time;
        d.opacity = 1.0f;
        const bool worldSound = std::max(size.x, size.y) <= kMaxWorldExtent && halfDepth <= kMaxWorldExtent;
        if (!soundBox(d) || !worldSound) {
            rng = unused;
            return reject(SpawnStatus::InvalidArgument,
                          "the box of a decal of type '" + t.name + "' on '" + o.name +
                              "' is degenerate in the object's or the world's space (size " +
                              formatNumber(d.size.x) + " x " + formatNumber(d.size.y) + ", half-depth " +
                              formatNumber(d.halfDepth) +
                              "): the size, depthMargin or the object's scale is too small or too large");
        }
        const CellKey key = cellKey(objectIndex, local);
        if (std::string why = makeRoom(key, objectIndex); !why.empty()) {
            rng = unused;
            return reject(SpawnStatus::AreaLimit, std::move(why));
        }

        const CraterClips clips = t.volumetric ? findCraterClips(world, o.transform, h, d) : CraterClips{};

        uint32_t slot;
        if (!freeSlots.empty()) {
            slot = freeSlots.back();
            freeSlots.pop_back();
        } else {
            slot = uint32_t(slots.size());
            reserveCapped(slots, slots.size() + 1, settings.budget);
            slots.emplace_back();
        }
        const uint32_t dense = uint32_t(decals.size());
        slots[slot].dense = dense;
        reserveCapped(decals, decals.size() + 1, settings.budget);
        reserveCapped(slotOf, slotOf.size() + 1, settings.budget);
        decals.push_back(d);
        slotOf.push_back(slot);
        if (t.lifetime > 0.0f) timed.set(dense);
        limits.link(slot, key, objectIndex);
        if (clips.any()) setClips(slot, clips);
        stats.placed++;
        stats.alive = decals.size();
        logChange(dense, DecalChangeKind::Added);

        SpawnResult r;
        r.status = SpawnStatus::Placed;
        r.handle = DecalHandle{slot, slots[slot].generation};
        if (objectFrame) *objectFrame = glm::dmat3(tan, bit, n);
        return r;
    }

    SpawnResult fromHit(const Ray& ray, const std::optional<Hit>& hit, uint16_t typeIndex) {
        if (!hit) return reject(SpawnStatus::Missed, "the ray hits no decal receiver");
        const DecalType& t = types[typeIndex];
        const CollisionObject& o = object(hit->object);
        if (o.dynamic && !t.onDynamic)
            return reject(SpawnStatus::NotReceiver,
                          "decal type '" + t.name + "' may not land on dynamic object '" + o.name + "'");
        const glm::dvec3 dir = glm::normalize(ray.direction);
        const double angle = std::acos(std::clamp(-glm::dot(dir, hit->normal), -1.0, 1.0)) * (180.0 / kPi);
        if (angle > double(t.maxAngleDeg))
            return reject(SpawnStatus::GrazingAngle, "the ray meets '" + o.name + "' at " +
                                                         formatNumber(angle) +
                                                         " degrees from its normal (type '" + t.name +
                                                         "' allows " + formatNumber(t.maxAngleDeg) + ")");
        return placeAtHit(*hit, dir, std::nullopt, dir, typeIndex, true);
    }

    // Places a decal of `typeIndex` at `hit`, made by a shot or probe along `dir` (world space, unit),
    // facing `facing` (world space, unit) or, when it is empty, the surface hit. On a skinned or
    // morphed object it lands on the drawn surface under the hit and is anchored there (SkinAnchors),
    // so that it follows the pose, and faces the render triangle when `facing` is empty; volumetric
    // decals keep the proxy's hit, where their crater is clipped. On other objects a decal projected
    // along its shot faces the drawn surface under the hit (drawnFacing). `hint` and `shot` as for
    // place().
    SpawnResult placeAtHit(const Hit& hit, const glm::dvec3& dir, const std::optional<glm::dvec3>& facing,
                           const glm::dvec3& hint, uint16_t typeIndex, bool shot) {
        if (!world.deforms(hit.object)) { // only skinned and morphed objects are anchored to the skin
            if (!facing && alongShot(types[typeIndex], shot))
                if (const std::optional<DrawnFacing> drawn = drawnFacing(hit, dir))
                    return place(hit.object, hit.localPosition, drawn->normal, hint, typeIndex, shot, false,
                                 nullptr, drawn->boundScale);
            return place(hit.object, hit.localPosition, facing ? *facing : hit.normal, hint, typeIndex, shot);
        }
        const glm::dmat3 inv = glm::inverse(glm::dmat3(object(hit.object).transform));
        const std::optional<SurfaceLocation> drawn =
            world.anchorAt(hit.object, hit.primitive, hit.localPosition, inv * dir);
        glm::dmat3 frame;
        SpawnResult placed = drawn && !types[typeIndex].volumetric
                                 ? place(hit.object, glm::dvec3(drawn->frame[3]),
                                         facing ? *facing : drawnNormal(hit, *drawn, inv, dir), hint,
                                         typeIndex, shot, true, &frame)
                                 : place(hit.object, hit.localPosition, facing ? *facing : hit.normal, hint,
                                         typeIndex, shot, false, &frame);
        if (placed.placed() && drawn) anchors.add(placed.handle.slot, decals.back(), frame, *drawn);
        return placed;
    }

    // Which way a decal shot along `dir` (world space, unit) through a proxy or collider at `hit` faces:
    // the drawn surface's normal under the hit (CollisionWorld::drawnNormalAt, world space), so that
    // its footprint lies in the plane that is drawn. Its box must then reach farther along that
    // normal: the shot meets the drawn surface within the slab of h around the hit's facet, over
    // h / |dir . n| of its length, which spans |dir . n'| / |dir . n| times h along the new normal n'.
    // Nothing (the decal faces the facet) where the object keeps no such normals, where n' does not
    // face the shot within kMaxSlantDeg, or where the box would have to hold more than twice h.
    struct DrawnFacing {
        glm::dvec3 normal;
        double boundScale;
    };
    std::optional<DrawnFacing> drawnFacing(const Hit& hit, const glm::dvec3& dir) const {
        constexpr double kMaxBoundScale = 2.0;
        const std::optional<glm::dvec3> local =
            world.drawnNormalAt(hit.object, hit.primitive, hit.localPosition);
        if (!local) return std::nullopt;
        // Normals go to world space by the cofactors of the linear part (the inverse transpose up to
        // its determinant, whose sign the turn towards the hit's normal takes up).
        const glm::dmat3 m(object(hit.object).transform);
        const glm::dmat3 cofactors(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1]));
        glm::dvec3 n = glm::normalize(cofactors * *local);
        if (glm::dot(n, hit.normal) < 0.0) n = -n; // also where the render mesh winds the other way
        const double across = -glm::dot(dir, n), facet = -glm::dot(dir, hit.normal);
        if (!(across >= std::cos(kMaxSlantDeg * kPi / 180.0)) || !(facet > 0.0)) return std::nullopt;
        const double scale = std::max(1.0, across / facet);
        if (scale > kMaxBoundScale) return std::nullopt;
        return DrawnFacing{n, scale};
    }

    // The world normal a decal on the drawn surface at `drawn` faces: its render triangle's (carried by
    // the transpose of `inv`, the inverse of the object's linear part), unless the shot along `dir`
    // grazed a silhouette and met that triangle from behind (then the proxy's, `hit.normal`).
    static glm::dvec3 drawnNormal(const Hit& hit, const SurfaceLocation& drawn, const glm::dmat3& inv,
                                  const glm::dvec3& dir) {
        const glm::dvec3 n = glm::normalize(glm::transpose(inv) * glm::dvec3(drawn.frame[2]));
        return glm::dot(n, dir) < 0.0 ? n : hit.normal;
    }

    // The hit on deforming object `objectIndex` of a probe through `local` (object space) along
    // `facing` (world space, unit), from twice the object's error bound in front of it to as far
    // behind (at least a hundredth of the type's size), so that another part of the object a little
    // farther in front is not taken for it; nothing for an object that does not deform, or when the
    // probe meets another object first or nothing.
    std::optional<Hit> probeOwnSurface(uint32_t objectIndex, const glm::dvec3& local,
                                       const glm::dvec3& facing, const DecalType& t) const {
        if (!world.deforms(objectIndex)) return std::nullopt;
        const double r =
            std::max(2.0 * world.worldErrorBound(objectIndex), 0.01 * double(std::max(t.size.x, t.size.y)));
        Ray probe;
        probe.origin = glm::dvec3(object(objectIndex).transform * glm::dvec4(local, 1.0)) + facing * r;
        probe.direction = -facing;
        probe.tnear = 0.0;
        probe.tfar = 2.0 * r;
        std::optional<Hit> hit = world.intersect(probe);
        if (!hit || hit->object != objectIndex) return std::nullopt;
        return hit;
    }

    // world.intersectBatch(rays), traced in slices by up to settings.batchThreads threads (each
    // slice's hits are exactly those of the whole batch: every ray is traced on its own).
    std::vector<std::optional<Hit>> traceBatch(const std::vector<Ray>& rays) const {
        constexpr size_t kMinRaysPerThread = 4096;
        size_t threads = settings.batchThreads != 0 ? settings.batchThreads
                                                    : std::max(1u, std::thread::hardware_concurrency());
        threads = std::min(threads, std::max<size_t>(1, rays.size() / kMinRaysPerThread));
        if (threads <= 1) return world.intersectBatch(rays);
        std::vector<std::optional<Hit>> hits(rays.size());
        auto traceSlice = [&](size_t k) {
            const size_t begin = rays.size() * k / threads, end = rays.size() * (k + 1) / threads;
            const std::vector<Ray> slice(rays.begin() + std::ptrdiff_t(begin),
                                         rays.begin() + std::ptrdiff_t(end));
            std::vector<std::optional<Hit>> sliceHits = world.intersectBatch(slice);
            std::move(sliceHits.begin(), sliceHits.end(), hits.begin() + std::ptrdiff_t(begin));
        };
        std::vector<std::thread> workers;
        size_t started = 1;
        try {
            for (; started < threads; ++started)
                workers.emplace_back(traceSlice, started);
        } catch (const std::system_error&) {
            // No more threads: the calling thread traces the slices left.
        }
        for (size_t k = started; k < threads; ++k)
            traceSlice(k);
        traceSlice(0);
        for (std::thread& w : workers)
            w.join();
        return hits;
    }

    WorldDecal toWorld(const Decal& d) const {
        const CollisionObject* o = world.object(d.object);
        const glm::dmat4 xf = o ? o->transform : glm::dmat4(1.0);
        const glm::dmat3 m(xf);
        const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(m));
        WorldDecal w;
        w.center = glm::dvec3(xf * glm::dvec4(glm::dvec3(d.center), 1.0));
        const Frame f = d.frame();
        if (!(finite3(normalMatrix[0]) && finite3(normalMatrix[1]) &&
              finite3(normalMatrix[2]))) { // a singular transform: the object, and the box, collapse
            w.frame = f;
            w.projection = f.normal;
            return w;
        }
        const glm::dvec3 nScaled = normalMatrix * glm::dvec3(f.normal);
        const glm::dvec3 n = glm::normalize(nScaled);
        const glm::dvec3 tScaled = m * glm::dvec3(f.tangent);
        glm::dvec3 t = tScaled - n * glm::dot(n, tScaled);
        t = glm::normalize(t);
        w.frame.normal = glm::vec3(n);
        w.frame.tangent = glm::vec3(t);
        w.frame.bitangent = glm::vec3(d.mirrored() ? -glm::cross(n, t) : glm::cross(n, t));
        w.size = glm::vec2(float(d.size.x * glm::length(tScaled)),
                           float(d.size.y * glm::length(m * glm::dvec3(f.bitangent))));
        w.halfDepth = float(d.halfDepth / glm::length(nScaled));
        w.projection = glm::vec3(glm::normalize(m * glm::dvec3(d.projectionAxis())));
        return w;
    }
};

} // namespace spatter
