#include "spatter/placement/DecalSystem.hpp"
#include "NumberChecks.hpp"

#include "AreaLimits.hpp"
#include "CappedGrowth.hpp"
#include "ChangeLog.hpp"
#include "CraterClipping.hpp"
#include "DecalSystemState.hpp"
#include "DenseIndexSet.hpp"
#include "SkinAnchors.hpp"
#include "spatter/core/DecalRefit.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/placement/ObjectIds.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <system_error>
#include <thread>
#include <unordered_map>

namespace spatter {

namespace {

constexpr uint32_t kNone = UINT32_MAX;
constexpr double kPi = 3.14159265358979323846;

// Largest column length of the linear part: the largest scale factor of a TRS transform.
double largestScale(const glm::dmat3& m) {
    return std::max({glm::length(m[0]), glm::length(m[1]), glm::length(m[2])});
}

int64_t cellCoordinate(double v, double cellSize) {
    const double c = std::floor(v / cellSize);
    const double limit = 9.0e18;
    return int64_t(std::clamp(c, -limit, limit));
}

std::string formatNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

// A decal the renderer can use: an orientation, a finite centre, size and half-depth finite and
// at least the smallest normal float (a box of zero, denormal or infinite extent cannot be inverted).
bool soundBox(const Decal& d) {
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

} // namespace

uint64_t DecalStats::rejectedTotal() const {
    uint64_t n = 0;
    for (uint64_t r : rejected)
        n += r;
    return n;
}

bool DecalStats::operator==(const DecalStats& o) const {
    return placed == o.placed && rejected == o.rejected && evicted == o.evicted && expired == o.expired &&
           removed == o.removed && alive == o.alive && fading == o.fading &&
           sharedObjectIds == o.sharedObjectIds;
}

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

DecalSystem::DecalSystem(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
DecalSystem::DecalSystem(DecalSystem&&) noexcept = default;
DecalSystem& DecalSystem::operator=(DecalSystem&&) noexcept = default;
DecalSystem::~DecalSystem() = default;

Result<DecalSystem> DecalSystem::create(CollisionWorld world, const DecalSettings& s) {
    if (std::string problem = DecalSystemAccess::settingsProblem(s); !problem.empty()) return fail(problem);
    auto impl = std::make_unique<Impl>(std::move(world), s);
    const size_t n = impl->world.objectCount();
    std::vector<DBounds> bounds(n);
    std::vector<bool> dynamic(n);
    for (uint32_t i = 0; i < n; ++i) {
        bounds[i] = impl->world.worldBounds(i);
        dynamic[i] = impl->world.object(i)->dynamic;
    }
    ObjectIdAssignment ids = assignObjectIds(bounds, dynamic, s.idSeparation, s.seed);
    impl->objectIds = std::move(ids.ids);
    impl->stats.sharedObjectIds = ids.sharedPairs;
    return DecalSystem(std::move(impl));
}

Result<DecalSystem> DecalSystem::create(const Scene& scene, const DecalSettings& settings) {
    Result<CollisionWorld> world = CollisionWorld::build(scene);
    if (!world) return fail(world.error());
    return create(std::move(world).value(), settings);
}

Result<uint16_t> DecalSystem::registerType(const DecalType& t) {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    const std::string where = "decal type '" + t.name + "': ";
    if (t.name.empty()) return fail("decal type: empty name");
    for (const DecalType& other : impl_->types)
        if (other.name == t.name) return fail(where + "a type of that name is already registered");
    if (impl_->types.size() >= 65535) return fail(where + "65535 types are registered already");
    if (!std::isfinite(t.size.x) || !std::isfinite(t.size.y) || !(t.size.x > 0.0f) || !(t.size.y > 0.0f) ||
        denormal(t.size.x) || denormal(t.size.y))
        return fail(where + "size must be finite, > 0 and not denormal");
    if (!std::isfinite(t.sizeJitter) || t.sizeJitter < 0.0f || !(t.sizeJitter < 1.0f) ||
        denormal(t.sizeJitter))
        return fail(where + "sizeJitter must be in [0, 1) and not denormal");
    if (!std::isfinite(t.maxAngleDeg) || !(t.maxAngleDeg > 0.0f) || t.maxAngleDeg > 90.0f ||
        denormal(t.maxAngleDeg))
        return fail(where + "maxAngleDeg must be in (0, 90] and not denormal");
    if (!std::isfinite(t.lifetime) || t.lifetime < 0.0f || denormal(t.lifetime))
        return fail(where + "lifetime must be finite, >= 0 and not denormal");
    if (!std::isfinite(t.fadeOutTime) || t.fadeOutTime < 0.0f || denormal(t.fadeOutTime))
        return fail(where + "fadeOutTime must be finite, >= 0 and not denormal");
    if (!std::isfinite(t.halfDepth) || t.halfDepth < 0.0f || denormal(t.halfDepth))
        return fail(where + "halfDepth must be finite, >= 0 and not denormal");
    if (t.texture < 0) return fail(where + "texture must be >= 0");
    if (!std::isfinite(t.tint.x) || !std::isfinite(t.tint.y) || !std::isfinite(t.tint.z) ||
        !std::isfinite(t.tint.w))
        return fail(where + "tint must be finite");
    if (!std::isfinite(t.roughness)) return fail(where + "roughness must be finite");
    impl_->types.push_back(t);
    return uint16_t(impl_->types.size() - 1);
}

Result<uint16_t> DecalSystem::typeIndex(const std::string& name) const {
    for (size_t i = 0; i < impl_->types.size(); ++i)
        if (impl_->types[i].name == name) return uint16_t(i);
    return fail("no decal type named '" + name + "'");
}

const DecalType* DecalSystem::type(uint16_t index) const {
    return index < impl_->types.size() ? &impl_->types[index] : nullptr;
}

size_t DecalSystem::typeCount() const {
    return impl_->types.size();
}

SpawnResult DecalSystem::spawn(const Ray& ray, uint16_t type) {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    if (type >= impl_->types.size()) return impl_->reject(SpawnStatus::InvalidType, impl_->typeError(type));
    if (const char* problem = rayProblem(ray)) return impl_->reject(SpawnStatus::InvalidRay, problem);
    return impl_->fromHit(ray, impl_->world.intersect(ray), type);
}

SpawnResult DecalSystem::spawnAt(const glm::dvec3& position, const glm::dvec3& normal, uint16_t type) {
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    if (type >= s.types.size()) return s.reject(SpawnStatus::InvalidType, s.typeError(type));
    if (!finite3(position)) return s.reject(SpawnStatus::InvalidArgument, "spawnAt: position is not finite");
    if (!finite3(normal)) return s.reject(SpawnStatus::InvalidArgument, "spawnAt: normal is not finite");
    const double len2 = glm::dot(normal, normal);
    if (!(len2 >= std::numeric_limits<double>::min()) || !std::isfinite(len2))
        return s.reject(SpawnStatus::InvalidArgument, "spawnAt: normal is zero or cannot be normalised");
    const DecalType& t = s.types[type];
    const glm::dvec3 n = normal / std::sqrt(len2);
    const double r = double(std::max(t.size.x, t.size.y));
    Ray probe;
    probe.origin = position + n * r;
    probe.direction = -n;
    probe.tnear = 0.0;
    probe.tfar = 2.0 * r;
    const std::optional<Hit> hit = s.world.intersect(probe);
    if (!hit)
        return s.reject(SpawnStatus::Missed, "spawnAt: no decal receiver within " + formatNumber(r) +
                                                 " of the position along the normal");
    const CollisionObject& o = s.object(hit->object);
    if (o.dynamic && !t.onDynamic)
        return s.reject(SpawnStatus::NotReceiver,
                        "decal type '" + t.name + "' may not land on dynamic object '" + o.name + "'");
    const double angle = std::acos(std::clamp(glm::dot(n, hit->normal), -1.0, 1.0)) * (180.0 / kPi);
    if (angle > double(t.maxAngleDeg))
        return s.reject(SpawnStatus::GrazingAngle, "spawnAt: the surface of '" + o.name + "' is " +
                                                       formatNumber(angle) +
                                                       " degrees from the normal (type '" + t.name +
                                                       "' allows " + formatNumber(t.maxAngleDeg) + ")");
    return s.placeAtHit(*hit, probe.direction, n, glm::dvec3(1.0, 0.0, 0.0), type, false);
}

SpawnResult DecalSystem::spawnAttached(uint32_t objectIndex, const glm::vec3& localPosition,
                                       const glm::vec3& localNormal, uint16_t type) {
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    if (type >= s.types.size()) return s.reject(SpawnStatus::InvalidType, s.typeError(type));
    const CollisionObject* o = s.world.object(objectIndex);
    if (!o)
        return s.reject(SpawnStatus::InvalidArgument,
                        "spawnAttached: object " + std::to_string(objectIndex) + " out of range (" +
                            std::to_string(s.world.objectCount()) + " objects)");
    const glm::dvec3 p(localPosition), ln(localNormal);
    if (!finite3(p))
        return s.reject(SpawnStatus::InvalidArgument, "spawnAttached: local position is not finite");
    if (!finite3(ln))
        return s.reject(SpawnStatus::InvalidArgument, "spawnAttached: local normal is not finite");
    if (std::max({std::fabs(localNormal.x), std::fabs(localNormal.y), std::fabs(localNormal.z)}) <
        std::numeric_limits<float>::min())
        return s.reject(SpawnStatus::InvalidArgument, "spawnAttached: local normal is zero or denormal");
    if (!o->inWorld)
        return s.reject(SpawnStatus::NotReceiver, "object '" + o->name + "' is not in the collision world");
    if (!o->traced) return s.reject(SpawnStatus::NotReceiver, "object '" + o->name + "': " + o->untraced);
    const glm::dmat3 m(o->transform);
    const glm::dvec3 wn = glm::transpose(glm::inverse(m)) * ln;
    const double len2 = glm::dot(wn, wn);
    if (!(len2 >= std::numeric_limits<double>::min()) || !std::isfinite(len2))
        return s.reject(SpawnStatus::InvalidArgument,
                        "spawnAttached: local normal is zero or cannot be normalised");
    const DecalType& t = s.types[type];
    if (o->dynamic && !t.onDynamic)
        return s.reject(SpawnStatus::NotReceiver,
                        "decal type '" + t.name + "' may not land on dynamic object '" + o->name + "'");
    const glm::dvec3 facing = wn / std::sqrt(len2), hint = m * glm::dvec3(1.0, 0.0, 0.0);
    // On a skinned or morphed object the decal lands on the drawn surface under the point, found by a
    // short probe along the normal (probeOwnSurface), and follows the pose from there.
    if (const std::optional<Hit> hit = s.probeOwnSurface(objectIndex, p, facing, t); hit)
        return s.placeAtHit(*hit, -facing, facing, hint, type, false);
    return s.place(objectIndex, p, facing, hint, type);
}

void DecalSystem::spawnBatch(const std::vector<Ray>& rays, uint16_t type, std::vector<SpawnResult>& results) {
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    results.clear();
    results.reserve(rays.size());
    if (type >= s.types.size()) {
        for (size_t i = 0; i < rays.size(); ++i)
            results.push_back(s.reject(SpawnStatus::InvalidType, s.typeError(type)));
        return;
    }
    const std::vector<std::optional<Hit>> hits = s.traceBatch(rays);
    for (size_t i = 0; i < rays.size(); ++i) {
        if (const char* problem = rayProblem(rays[i]))
            results.push_back(s.reject(SpawnStatus::InvalidRay, problem));
        else
            results.push_back(s.fromHit(rays[i], hits[i], type));
    }
}

Status DecalSystem::update(double dt) {
    if (!std::isfinite(dt) || dt < 0.0 || denormal(dt))
        return fail("update: dt must be finite, >= 0 and not denormal");
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    s.time += dt;
    // Only the timed decals can change: the others are opaque (1) from their placement on and stay.
    // They are visited from the highest dense index down, as a walk over every decal would meet them,
    // and a removal moves the last decal (visited already) into the hole: the indices below the one
    // visited, and the members of `timed` among them, do not move.
    for (uint32_t i = s.timed.highestBelow(uint32_t(s.decals.size())); i != DenseIndexSet::kNone;
         i = s.timed.highestBelow(i)) {
        Decal& d = s.decals[i];
        const auto fade = s.fadingSince.empty() ? s.fadingSince.end() : s.fadingSince.find(s.slotOf[i]);
        const bool fading = fade != s.fadingSince.end();
        const DecalType& t = s.types[d.type];
        float opacity = 1.0f;
        bool remove = false;
        if (t.lifetime > 0.0f) {
            const double age = s.time - d.spawnTime;
            if (age >= double(t.lifetime)) {
                remove = true;
                if (!fading) s.stats.expired++;
            } else {
                const double fadeStart = std::max(0.0, double(t.lifetime) - double(t.fadeOutTime));
                if (age > fadeStart)
                    opacity = float((double(t.lifetime) - age) / (double(t.lifetime) - fadeStart));
            }
        }
        if (!remove && fading) {
            const double since = s.time - fade->second;
            if (since >= double(t.fadeOutTime))
                remove = true;
            else
                opacity = std::min(opacity, float(1.0 - since / double(t.fadeOutTime)));
        }
        if (remove) {
            s.removeDense(i);
        } else if (const Opacity stored(opacity); stored.bits() != d.opacity.bits()) {
            d.opacity = stored; // a change only when the stored step does
            s.logChange(i, DecalChangeKind::Changed);
        }
    }
    return {};
}

bool DecalSystem::remove(DecalHandle handle) {
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    if (!get(handle)) return false;
    const uint32_t dense = s.slots[handle.slot].dense;
    if (!s.fading(dense)) s.stats.removed++; // a fading decal is counted in evicted already
    s.removeDense(dense);
    return true;
}

const Decal* DecalSystem::get(DecalHandle handle) const {
    const Impl& s = *impl_;
    if (handle.slot >= s.slots.size()) return nullptr;
    const Slot& slot = s.slots[handle.slot];
    if (slot.generation != handle.generation || slot.dense == kNone) return nullptr;
    return &s.decals[slot.dense];
}

std::optional<WorldDecal> DecalSystem::worldBox(DecalHandle handle) const {
    const Decal* d = get(handle);
    if (!d) return std::nullopt;
    return impl_->toWorld(*d);
}

WorldDecal DecalSystem::worldBox(const Decal& decal) const {
    return impl_->toWorld(decal);
}

std::optional<DecalAxisLine> DecalSystem::axisLine(DecalHandle handle) const {
    const Decal* d = get(handle);
    if (!d) return std::nullopt;
    const CollisionObject* o = impl_->world.object(d->object);
    if (!o) return std::nullopt;
    const glm::dmat3 inv = glm::inverse(glm::dmat3(o->transform));
    if (!(finite3(inv[0]) && finite3(inv[1]) && finite3(inv[2]))) return std::nullopt; // singular
    const glm::dvec3 center(d->center), reach(d->boxToObject()[2]);
    DecalAxisLine line;
    line.from = glm::dvec3(o->transform * glm::dvec4(center + reach, 1.0));
    line.to = glm::dvec3(o->transform * glm::dvec4(center - reach, 1.0));
    line.objectId = d->objectId;
    return line;
}

namespace {

// Why a decal of type `t` on `o` cannot be laid on the drawn surface at `point` facing `normal`
// (world space), or empty.
std::string drawnSurfaceRefusal(const DecalType& t, const CollisionObject& o, bool deforms,
                                const glm::dvec3& point, const glm::dvec3& normal) {
    if (t.volumetric)
        return "a decal of volumetric type '" + t.name +
               "' keeps the proxy's hit, where its crater is clipped";
    if (deforms)
        return "object '" + o.name + "' is skinned or morphed: its decals lie on the drawn surface already";
    if (!finite3(point)) return "point is not finite";
    if (!finite3(normal)) return "normal is not finite";
    const double len2 = glm::dot(normal, normal);
    if (!(len2 >= std::numeric_limits<double>::min()) || !std::isfinite(len2))
        return "normal is zero or cannot be normalised";
    const glm::dmat3 inv = glm::inverse(glm::dmat3(o.transform));
    if (!(finite3(inv[0]) && finite3(inv[1]) && finite3(inv[2])))
        return "the transform of object '" + o.name + "' is singular";
    return {};
}

// Where object-space `local` lies in the box of `d`, in box units, or empty when outside it by more
// than a thousandth of its half extents.
std::string outsideBox(const Decal& d, const glm::dvec3& local) {
    const glm::dvec3 inBox(glm::inverse(glm::dmat4(d.boxToObject())) * glm::dvec4(local, 1.0));
    constexpr double kBoxTolerance = 1e-3; // of the box's half extents
    const double outside = std::max({std::fabs(inBox.x), std::fabs(inBox.y), std::fabs(inBox.z)});
    if (outside <= 1.0 + kBoxTolerance) return {};
    return "the point lies outside the decal's box (at " + formatNumber(inBox.x) + ", " +
           formatNumber(inBox.y) + ", " + formatNumber(inBox.z) + " in box units)";
}

} // namespace

Result<DrawnSurfaceLaying> DecalSystem::layOnDrawnSurface(DecalHandle handle, const glm::dvec3& point,
                                                          const glm::dvec3& normal) {
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    const Decal* found = get(handle);
    if (!found) return fail("layOnDrawnSurface: stale or invalid handle");
    const Decal& d = *found;
    const DecalType& t = s.types[d.type];
    const CollisionObject& o = s.object(d.object);
    if (std::string why = drawnSurfaceRefusal(t, o, s.world.deforms(d.object), point, normal); !why.empty())
        return fail("layOnDrawnSurface: " + why);
    // To object space (normals by the transpose of the linear part).
    const glm::dmat3 m(o.transform), inv = glm::inverse(m);
    const glm::dvec3 local = inv * (point - glm::dvec3(o.transform[3]));
    const glm::dvec3 localNormal = glm::transpose(m) * glm::normalize(normal);
    if (std::string why = outsideBox(d, local); !why.empty()) return fail("layOnDrawnSurface: " + why);
    const double localLength = glm::length(localNormal);
    if (!(localLength > 0.0) || !std::isfinite(localLength))
        return fail("layOnDrawnSurface: the normal cannot be carried to the object's space");
    std::optional<Decal> laid =
        relaidDecal(d, m, glm::vec3(local), glm::vec3(localNormal / localLength), 0.0f);
    if (!laid)
        return fail("layOnDrawnSurface: the normal is 89 degrees or more from the decal's, or the decal "
                    "cannot be laid on it");
    // The half-depth of a decal on a surface with no error bound (place with h = 0), world units, then
    // in the object's space along the laid decal's normal.
    const glm::vec2 worldSize = s.toWorld(d).size;
    const double extent = double(std::max(worldSize.x, worldSize.y));
    const float halfDepth = std::max(t.halfDepth, float(double(s.settings.depthMargin) * extent));
    laid->halfDepth =
        float(double(halfDepth) * glm::length(glm::transpose(inv) * glm::dvec3(laid->frame().normal)));
    if (!soundBox(*laid) || !(extent <= double(kMaxWorldExtent) && halfDepth <= kMaxWorldExtent))
        return fail("layOnDrawnSurface: the box of the decal laid again on '" + o.name +
                    "' is degenerate in the object's or the world's space (size " +
                    formatNumber(laid->size.x) + " x " + formatNumber(laid->size.y) + ", half-depth " +
                    formatNumber(laid->halfDepth) + ")");
    const uint32_t dense = s.slots[handle.slot].dense;
    if (const std::optional<double> angle = laidShotAngleDeg(d, *laid, m); angle && *angle > t.maxAngleDeg) {
        s.stats.removed++;
        s.removeDense(dense);
        return DrawnSurfaceLaying::Removed;
    }
    s.decals[dense] = *laid;
    s.logChange(dense, DecalChangeKind::Changed);
    return DrawnSurfaceLaying::Laid;
}

const std::vector<Decal>& DecalSystem::decals() const {
    return impl_->decals;
}

CraterClips DecalSystem::craterClips(size_t index) const {
    const Impl& s = *impl_;
    if (index >= s.decals.size()) return {};
    const uint32_t slot = s.slotOf[index];
    return slot < s.clipsBySlot.size() ? s.clipsBySlot[slot] : CraterClips{};
}

uint64_t DecalSystem::version() const {
    return impl_->version();
}

void DecalSystem::changesSince(uint64_t version, DecalChanges& out) const {
    const Impl& s = *impl_;
    out.version = s.version();
    out.complete = s.changeLog.since(version, s.decals.size(), out.changes);
}

DecalChanges DecalSystem::changesSince(uint64_t version) const {
    DecalChanges out;
    changesSince(version, out);
    return out;
}

Result<TransformUpdate> DecalSystem::setTransform(uint32_t object, const glm::dmat4& transform) {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->world.setTransform(object, transform);
}

Result<TransformUpdate> DecalSystem::setPose(uint32_t object, const glm::dmat4& transform,
                                             const std::vector<glm::dmat4>& joints,
                                             const std::vector<double>& morphWeights) {
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    Result<TransformUpdate> update = s.world.setPose(object, transform, joints, morphWeights);
    if (!update) return update;
    s.anchors.repose(
        object, s.world, s.decals, [&s](uint32_t slot) { return s.slots[slot].dense; },
        [&s](uint32_t dense) { s.logChange(dense, DecalChangeKind::Changed); });
    return update;
}

Status DecalSystem::removeObject(uint32_t object) {
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    if (Status st = s.world.removeObject(object); !st) return st;
    for (size_t i = s.decals.size(); i-- > 0;) {
        if (s.decals[i].object != object) continue;
        if (!s.fading(uint32_t(i))) s.stats.removed++; // a fading decal is counted in evicted already
        s.removeDense(uint32_t(i));
    }
    return {};
}

uint8_t DecalSystem::objectId(uint32_t object) const {
    return object < impl_->objectIds.size() ? impl_->objectIds[object] : 0;
}

std::vector<uint8_t> DecalSystem::objectIds() const {
    std::vector<uint8_t> ids(impl_->world.objectCount());
    for (uint32_t o = 0; o < ids.size(); ++o)
        ids[o] = objectId(o);
    return ids;
}

const DecalStats& DecalSystem::stats() const {
    return impl_->stats;
}

DecalSystemMemory DecalSystem::memory() const {
    const Impl& s = *impl_;
    DecalSystemMemory m;
    m.records = s.decals.capacity() * sizeof(Decal);
    m.handles = s.slotOf.capacity() * sizeof(uint32_t) + s.slots.capacity() * sizeof(Slot) +
                s.freeSlots.capacity() * sizeof(uint32_t);
    m.areaLimits = s.limits.bytes();
    m.changeLog = s.changeLog.bytes();
    // A node of the fading table holds its entry and a link; the table a pointer per bucket.
    const size_t fadingNode = sizeof(std::pair<const uint32_t, double>) + sizeof(void*);
    m.other = s.timed.bytes() + s.fadingSince.size() * fadingNode +
              s.fadingSince.bucket_count() * sizeof(void*) + s.clipsBySlot.capacity() * sizeof(CraterClips) +
              s.anchors.bytes();
    return m;
}
const DecalSettings& DecalSystem::settings() const {
    return impl_->settings;
}
const CollisionWorld& DecalSystem::world() const {
    return impl_->world;
}
double DecalSystem::time() const {
    return impl_->time;
}

std::string DecalSystemAccess::settingsProblem(const DecalSettings& s) {
    if (!std::isfinite(s.cellSize) || !(s.cellSize > 0.0f) || denormal(s.cellSize))
        return "decal settings: cellSize must be finite, > 0 and not denormal";
    if (s.maxPerCell < 1) return "decal settings: maxPerCell must be >= 1";
    if (s.budget < 1) return "decal settings: budget must be >= 1";
    if (s.maxPerObject < 1) return "decal settings: maxPerObject must be >= 1";
    if (uint8_t(s.policy) > uint8_t(LimitPolicy::Reject)) return "decal settings: unknown limit policy";
    if (!std::isfinite(s.idSeparation) || s.idSeparation < 0.0 || denormal(s.idSeparation))
        return "decal settings: idSeparation must be finite, >= 0 and not denormal";
    if (!std::isfinite(s.depthMargin) || s.depthMargin < 0.0f || denormal(s.depthMargin))
        return "decal settings: depthMargin must be finite, >= 0 and not denormal";
    return {};
}

std::unique_lock<std::mutex> DecalSystemAccess::lock(DecalSystem& system) {
    return std::unique_lock<std::mutex>(system.impl_->mutex);
}

DecalSystemState DecalSystemAccess::capture(const DecalSystem& system) {
    const DecalSystem::Impl& s = *system.impl_;
    DecalSystemState st;
    st.settings = s.settings;
    for (const DecalType& t : s.types)
        st.typeNames.push_back(t.name);
    for (uint32_t i = 0; i < s.world.objectCount(); ++i) {
        const CollisionObject& o = s.object(i);
        st.objects.push_back({o.name, o.meshHash, o.dynamic, o.inWorld, s.objectIds[i], o.transform});
    }
    st.rngState = s.rng.state();
    st.rngIncrement = s.rng.increment();
    st.time = s.time;
    st.stats = s.stats;
    st.decals = s.decals;
    st.slotOf = s.slotOf;
    st.clips.reserve(s.decals.size());
    for (size_t i = 0; i < s.decals.size(); ++i)
        st.clips.push_back(system.craterClips(i));
    st.generations.reserve(s.slots.size());
    for (const Slot& slot : s.slots)
        st.generations.push_back(slot.generation);
    st.freeSlots = s.freeSlots;
    st.fading.assign(s.fadingSince.begin(), s.fadingSince.end());
    std::sort(st.fading.begin(), st.fading.end());
    st.limitOrder.reserve(s.limits.total());
    for (uint32_t slot = s.limits.oldest(); slot != AreaLimits::kNone; slot = s.limits.newer(slot)) {
        const Decal& d = s.decals[s.slots[slot].dense];
        const CellKey key = s.limits.cellOf(slot);
        if (!(key == s.cellKey(d.object, glm::dvec3(d.center))))
            st.cellExceptions.push_back({uint32_t(st.limitOrder.size()), key});
        st.limitOrder.push_back(slot);
    }
    st.changeLogBase = s.changeLog.base();
    s.changeLog.since(st.changeLogBase, s.decals.size(), st.changeLog);
    st.anchors = s.anchors.saved();
    return st;
}

void DecalSystemAccess::restore(DecalSystem& system, DecalSystemState&& st, const RestorePlan& plan) {
    DecalSystem::Impl& s = *system.impl_;
    for (const auto& [object, transform] : plan.moves)
        s.world.setTransform(object, transform);
    for (uint32_t object : plan.removals)
        s.world.removeObject(object);
    for (size_t i = 0; i < st.objects.size() && i < s.objectIds.size(); ++i)
        if (plan.keepObject[i]) s.objectIds[i] = st.objects[i].objectId;
    st.settings.batchThreads = s.settings.batchThreads;
    s.settings = st.settings;
    s.rng = Rng::fromState(st.rngState, st.rngIncrement);
    s.time = st.time;
    s.stats = st.stats;
    s.changeLog.assign(st.changeLogBase, st.changeLog);
    restoreDecals(s, st);
    relink(s, st, plan.keepObject);
    for (size_t i = s.decals.size(); i-- > 0;) { // as removeObject does
        if (plan.keepObject[s.decals[i].object]) continue;
        if (!s.fading(uint32_t(i))) s.stats.removed++;
        s.removeDense(uint32_t(i));
    }
}

void DecalSystemAccess::restoreDecals(DecalSystem::Impl& s, DecalSystemState& st) {
    s.decals = std::move(st.decals);
    s.slotOf = std::move(st.slotOf);
    s.slots.assign(st.generations.size(), Slot());
    for (size_t i = 0; i < st.generations.size(); ++i)
        s.slots[i].generation = st.generations[i];
    for (uint32_t i = 0; i < s.slotOf.size(); ++i)
        s.slots[s.slotOf[i]].dense = i;
    s.freeSlots = std::move(st.freeSlots);
    s.anchors.restore(st.anchors, [&s](uint32_t slot) { return s.decals[s.slots[slot].dense].object; });
    s.fadingSince = std::unordered_map<uint32_t, double>(st.fading.begin(), st.fading.end());
    s.clipsBySlot = {};
    for (uint32_t i = 0; i < st.clips.size(); ++i)
        if (st.clips[i].any()) s.setClips(s.slotOf[i], st.clips[i]);
    s.timed = DenseIndexSet();
    for (uint32_t i = 0; i < s.decals.size(); ++i)
        if (s.types[s.decals[i].type].lifetime > 0.0f || s.fading(i)) s.timed.set(i);
}

void DecalSystemAccess::relink(DecalSystem::Impl& s, const DecalSystemState& st,
                               const std::vector<bool>& keep) {
    const DecalSettings& set = s.settings;
    s.limits = AreaLimits(s.world.objectCount(), set.budget, set.maxPerCell, set.maxPerObject);
    size_t exception = 0;
    for (uint32_t k = 0; k < st.limitOrder.size(); ++k) {
        const uint32_t slot = st.limitOrder[k];
        const Decal& d = s.decals[s.slots[slot].dense];
        const bool given = exception < st.cellExceptions.size() && st.cellExceptions[exception].position == k;
        const CellKey key = given ? st.cellExceptions[exception++].key : CellKey();
        if (keep[d.object])
            s.limits.link(slot, given ? key : s.cellKey(d.object, glm::dvec3(d.center)), d.object);
    }
}

} // namespace spatter
