#pragma once
// DecalSystem: the gameplay API that turns shots into decals (the counterpart of Unreal's
// SpawnDecalAtLocation / SpawnDecalAttached). It owns the CollisionWorld, the registered decal
// types, the live decals and the limits on them.
//
//   Result<DecalSystem> sys = DecalSystem::create(scene);          // or create(world, settings)
//   uint16_t hole = sys->registerType(holeType).value();
//   SpawnResult r = sys->spawn(Ray{eye, aim}, hole);               // r.placed() or r.status/r.reason
//   sys->update(dt);                                               // ages, fades, expires
//   renderer.setDecals(sys->decals());                             // contiguous, object space
//   DecalChanges c = sys->changesSince(seen); seen = c.version;    // or only what changed since
//
// Rules every call follows:
// - A call that places nothing returns a status and a reason and changes no state except the
//   rejection counter of its status in stats(): no decal, no limit list, no random number.
//   Random numbers are drawn only once every check has passed, in this order: the 32-bit decal ID,
//   the rotation angle (types with randomRotation), the size factor (types with sizeJitter > 0).
// - Same settings (seed), same types and same calls give bit-identical decals.
// - Decal::center and Decal::frame are in the space of the decal's object (static objects too), so
//   decals follow their object when it moves and go with it when it is removed.
// - Mutations (registerType, spawn*, update, remove, layOnDrawnSurface, setTransform, setPose,
//   removeObject, and loadDecals of DecalPersistence.hpp) may be called from any number of threads
//   at once: they take the system's lock and run one at a time, each seeing the world as the
//   previous one left it (a spawn traces against the objects where they are while it holds the
//   lock). Const calls take no lock: they may run concurrently with each other, but not with a
//   mutation (decals() and get() return references into state that mutations change).
//   version() and changesSince() are const calls like decals(): no lock, never during a mutation.
// - Every change of decals() is logged (changesSince): a placement as Added; a removal by remove, an
//   eviction, the end of a lifetime or fade in update, or removeObject as Removed, with the move that
//   fills the hole; an opacity that update() changes (bit for bit), and a decal that setPose moves or
//   layOnDrawnSurface lays again, as Changed. The version is the number of changes logged since
//   create(); a call that changes no decal logs nothing.

#include "spatter/core/CraterClip.hpp"
#include "spatter/core/Decal.hpp"
#include "spatter/core/DecalChanges.hpp"
#include "spatter/core/DecalType.hpp"
#include "spatter/core/Frame.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/placement/CollisionWorld.hpp"
#include "spatter/placement/Ray.hpp"
#include "spatter/placement/SpawnResult.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace spatter {

// What happens when a spawn would exceed a limit (cell, object cap or global budget).
enum class LimitPolicy : uint8_t {
    EvictOldest, // the oldest decal under that limit is removed at once (stats: evicted)
    FadeOldest,  // the oldest decal under that limit stops counting and fades out over its type's
                 // fadeOutTime, then update() removes it (stats: evicted, when the fade starts)
    Reject,      // the spawn fails with SpawnStatus::AreaLimit
};

// A cell limit (DecalSettings::maxPerCell) at most this keeps 4 bytes less per decal: a cell's decals
// are then few enough that taking one out of the middle of their spawn order (a removal, an expiry, an
// object's eviction) walks the cell's list instead of keeping a link back from each decal.
constexpr uint32_t kSmallCellLimit = 64;

struct DecalSettings {
    uint64_t seed = 1;        // decal IDs, rotations, size jitter and object IDs all derive from it
    float cellSize = 0.5f;    // edge of a spatial-hash cell, world units (> 0)
    uint32_t maxPerCell = 16; // decals per cell (>= 1)
    LimitPolicy policy = LimitPolicy::EvictOldest;
    uint32_t budget = 4096;       // decals in the whole world (>= 1)
    uint32_t maxPerObject = 1024; // decals per object (>= 1)
    double idSeparation = 1.0;    // dynamic objects whose bounds are closer than this (world units)
                                  // get different object IDs while 255 IDs allow it (>= 0)
    float depthMargin = 0.25f;    // half_depth = max(type.halfDepth, h + depthMargin * max(w, h)) (>= 0)
    uint32_t batchThreads = 1;    // threads spawnBatch traces with: 1 the calling thread only, 0 one per
                                  // hardware thread; each traces at least 4096 rays of the batch
};

// Every decal placed is in exactly one of: alive and not fading, evicted, expired, removed:
//   placed == alive - fading + evicted + expired + removed.
struct DecalStats {
    uint64_t placed = 0;
    std::array<uint64_t, kSpawnStatusCount> rejected{}; // calls that placed nothing, by SpawnStatus
    uint64_t evicted = 0;         // decals a limit removed or started fading (LimitPolicy)
    uint64_t expired = 0;         // decals removed at the end of their type's lifetime
    uint64_t removed = 0;         // decals removed by remove() or removeObject()
    size_t alive = 0;             // decals in decals(), fading ones included
    size_t fading = 0;            // decals in decals() fading out after an eviction (already in evicted)
    uint32_t sharedObjectIds = 0; // pairs of neighbouring dynamic objects that had to share an object ID

    uint64_t rejectedTotal() const;
    bool operator==(const DecalStats& o) const;
    bool operator!=(const DecalStats& o) const { return !(*this == o); }
};

// What a decal system holds for its decals (DecalSystem::memory), from the capacities of its own
// containers; the collision world it traces is not in it.
struct DecalSystemMemory {
    size_t records = 0;    // the Decal records (decals())
    size_t handles = 0;    // the handle slots, each decal's slot and the free slots
    size_t areaLimits = 0; // the per-area limits: the counted decals' links and cells, the area grid
    size_t changeLog = 0;  // the changes changesSince() can still give
    size_t other = 0;      // the decals update() visits, those fading out, the anchors on skinned objects
    size_t total() const { return records + handles + areaLimits + changeLog + other; }
};

// A decal's box in world space: |x| <= size.x / 2, |y| <= size.y / 2, |z| <= halfDepth in `frame`
// around `center`, its depth lines running along `projection` (a decal projected along its shot:
// the rectangle at height z above the plane is shifted along the plane with the axis). Exact for rigid
// transforms with uniform or axis-aligned scale (TRS); under shear the world box is the object-space box
// mapped by the transform, and this is its nearest orthonormal description.
struct WorldDecal {
    glm::dvec3 center{0.0};
    Frame frame;
    glm::vec2 size{0.0f};
    float halfDepth = 0.0f;
    glm::vec3 projection{0.0f}; // unit axis the texture is projected along: the normal, or slanted
                                // along the shot (DecalProjection.hpp)
};

// A decal's projection axis through its box, world space, from the face its shot came through (axisLine).
struct DecalAxisLine {
    glm::dvec3 from{0.0}, to{0.0};
    uint8_t objectId = 0;   // the decal's object decal ID: the surface it is laid on carries it
    bool alongShot = false; // the axis is the decal's shot: the shot ran from its origin to `from`
};

// What DecalSystem::layOnDrawnSurface did with a decal.
enum class DrawnSurfaceLaying : uint8_t {
    Laid,    // laid again where the renderer found the drawn surface
    Removed, // removed: its shot meets the drawn surface there more steeply than its type allows
};

class DecalSystem {
public:
    // Takes ownership of `world`. Fails on settings out of the ranges documented in DecalSettings, and
    // on denormal ones. Object IDs are assigned here, once, from the objects' bounds at this moment
    // (assignObjectIds with settings.idSeparation and settings.seed), and stay fixed when objects move.
    static Result<DecalSystem> create(CollisionWorld world, const DecalSettings& settings = {});
    // Builds the collision world of `scene` (CollisionWorld::build with no proxies) and the system.
    static Result<DecalSystem> create(const Scene& scene, const DecalSettings& settings = {});

    // Movable, not copyable. A moved-from DecalSystem holds nothing: assign to it or destroy it, and call
    // nothing else on it.
    DecalSystem(DecalSystem&&) noexcept;
    DecalSystem& operator=(DecalSystem&&) noexcept;
    ~DecalSystem();

    // Registers a type and returns its index. Fails (naming the type and field) on an empty or
    // duplicate name, a size that is not finite and positive, sizeJitter outside [0, 1),
    // maxAngleDeg outside (0, 90], a lifetime, fadeOutTime or halfDepth that is negative or not
    // finite, a denormal size, sizeJitter, maxAngleDeg, lifetime, fadeOutTime or halfDepth, a
    // negative texture, a tint that is not finite or negative or whose alpha is above 1, a roughness
    // that is not finite or above 1, a projection or depthFade that names no value of its enum, or
    // more than 65535 types.
    Result<uint16_t> registerType(const DecalType& type);
    // Index of the type named `name`, or an error naming it.
    Result<uint16_t> typeIndex(const std::string& name) const;
    // The type at `index`, or nullptr.
    const DecalType* type(uint16_t index) const;
    size_t typeCount() const;

    // Traces `ray` and places a decal of `type` where it hits. Checks, in order: type (InvalidType),
    // ray (InvalidRay), hit (Missed), object (NotReceiver for a dynamic object when the type has
    // onDynamic == false), angle between -direction and the surface normal (GrazingAngle when above
    // maxAngleDeg), the decal's box (InvalidArgument when its size or half-depth in the object's
    // space is zero, denormal or not finite), limits (AreaLimit under LimitPolicy::Reject); the last
    // two apply to spawnAt and spawnAttached as well. The decal's frame: normal = the
    // hit's geometric normal (facing the ray) or, for a type projected along the shot through a proxy
    // or collider, the drawn surface's under the hit (CollisionWorld::drawnNormalAt, where it faces
    // the shot; its box then as deep as holding the drawn surface along the shot needs); tangent =
    // the ray direction projected onto the surface (frameFromNormalAndHint: then world X, then Duff et
    // al.), turned by a random angle. A decal of
    // a volumetric type gets the clip planes of its crater from the collision proxy around it, in
    // all three spawn calls (craterClips()).
    SpawnResult spawn(const Ray& ray, uint16_t type);

    // Places a decal centred on the collision surface at `position`, facing `normal` (world space,
    // need not be unit). The surface is found by a probe ray from position + r * n to
    // position - r * n, r = max(type.size): Missed when it finds no receiver; GrazingAngle when the
    // surface normal there is more than maxAngleDeg from `normal`. InvalidArgument for a non-finite
    // position or normal or a zero normal. The tangent starts along world X.
    SpawnResult spawnAt(const glm::dvec3& position, const glm::dvec3& normal, uint16_t type);

    // Places a decal on `object` at `localPosition` facing `localNormal` (object space; no ray, no
    // angle check). InvalidArgument for an index out of range, a non-finite vector, or a normal whose
    // components are all zero or denormal or that cannot be normalised in world space;
    // NotReceiver for an object not in the world or left out of the trace (its transform breaks the
    // rule of TraceTransform.hpp), or dynamic with a type that has onDynamic == false.
    // The tangent starts along the object's X axis, so the result does not depend on where the
    // object is at the time. On a skinned or morphed object the decal lands on the drawn surface under
    // the point and follows the pose (setPose).
    SpawnResult spawnAttached(uint32_t object, const glm::vec3& localPosition, const glm::vec3& localNormal,
                              uint16_t type);

    // Spawns one decal per ray, tracing them with CollisionWorld::intersectBatch. `results` is replaced
    // by one result per ray, and everything (results, decals, IDs, random numbers, limits, stats)
    // ends exactly as if spawn had been called on each ray in order. With settings().batchThreads != 1
    // the rays are traced by several threads (CollisionWorld::intersectBatch on slices of the batch),
    // which changes nothing in the result.
    void spawnBatch(const std::vector<Ray>& rays, uint16_t type, std::vector<SpawnResult>& results);

    // Advances the clock by `dt` seconds (finite, >= 0, not denormal): a decal whose type has a
    // lifetime stays opaque until the last fadeOutTime seconds of it, fades linearly to 0, and is
    // removed (expired) when its age reaches the lifetime; a decal evicted under FadeOldest fades over
    // fadeOutTime from its eviction and is then removed. Fails, changing nothing, on a bad dt or one
    // that would take the clock past the largest finite double.
    // Visits only the decals that can change (type lifetime > 0, or fading), from the highest index in
    // decals() down: O(those decals + decals().size() / 4096); permanent decals cost nothing.
    Status update(double dt);

    // Removes a decal. False for a stale or invalid handle.
    bool remove(DecalHandle handle);
    // The decal, or nullptr for a stale or invalid handle. The pointer is valid until the next mutation.
    const Decal* get(DecalHandle handle) const;
    // The decal's box in world space under its object's current transform. On an object whose
    // transform is singular (a scale of 0: it draws nothing) the box has size and half-depth 0, its
    // frame the decal's object-space one.
    std::optional<WorldDecal> worldBox(DecalHandle handle) const;
    WorldDecal worldBox(const Decal& decal) const;
    // The line along a decal's projection axis through its box, world space: `from` on the box face the
    // shot came through (the axis's positive end, centre + reach), `to` on the opposite face. What a
    // renderer searches for the drawn surface (DecalProjector::findSurface) before layOnDrawnSurface.
    // Empty for a stale handle or a decal whose object's transform is singular.
    std::optional<DecalAxisLine> axisLine(DecalHandle handle) const;
    // Lays a decal placed through a collision proxy again on the surface that is drawn, where a renderer
    // found it: `point`, where the decal's axis line (axisLine) meets the drawn surface, and `normal`,
    // that surface's normal there (world space; need not be unit). The decal becomes the one its shot
    // would have placed on the render mesh there (relaidDecal, DecalRefit.hpp): centre on `point`, frame
    // built on `normal` as placement builds one (the shot as hint, turned about the normal by the
    // decal's own random rotation), projection axis kept (a decal along its normal stays along the new
    // one), its box as deep as on a surface with no error bound: max(type.halfDepth, depthMargin *
    // max(size)) in world units, as spawn gives a decal on a render mesh. Its ID, type, size, spawn
    // time, opacity, object and area cell are kept. Logged as Changed (changesSince); gives Laid.
    // Where the decal is projected along its shot and the shot meets the drawn surface more than the
    // type's maxAngleDeg from its normal, the shot would have placed nothing on the render mesh
    // (SpawnStatus::GrazingAngle), and a decal laid there would stretch along it: the decal is removed
    // as remove() removes it (logged as Removed, counted in stats().removed); gives Removed. A decal
    // along its normal, whose shot the record does not keep, is always laid. Fails, changing nothing
    // (no state, no random number, no log entry), naming the problem: a stale or invalid handle; a
    // point or normal that is not finite, a zero normal; a point outside the decal's box (more than
    // 1e-3 of the box's half extents outside it, in box units); a normal relaidDecal refuses (89
    // degrees or more from the decal's); a decal of a volumetric type (its crater is clipped by the
    // proxy around it) or on a skinned or morphed object (those decals are laid on the drawn surface at
    // spawn already and follow it: CollisionWorld::deforms); an object whose transform is singular; a
    // box that would not be sound (the size and half-depth checks of spawn).
    Result<DrawnSurfaceLaying> layOnDrawnSurface(DecalHandle handle, const glm::dvec3& point,
                                                 const glm::dvec3& normal);
    // Places the decal of a shot that the collision surface refused (spawn gave Missed or GrazingAngle:
    // SpawnResult::refusedByCollisionSurface) where a renderer found the shot meeting the drawn surface:
    // `point` on it and `normal`, that surface's normal there (world space; need not be unit, turned to
    // face the shot). The point need not lie on the shot: found in a later frame, a point on a moving
    // object is carried with it (as the gallery does), so only finiteness is checked. A proxy lies within its error bound h of the drawn surface, so near an object's
    // outline a shot can pass the proxy and still meet what is drawn, and a proxy facet tilted against
    // the drawn surface can graze a shot that meets the drawn surface within the type's angle. The
    // decal is the one the shot would have placed on the render mesh there: on the object
    // whose collision surface a probe along the normal meets within twice its world error bound of the
    // point (plus a hundredth of the type's size), or, where the probe meets none (beside an open edge
    // of a proxy), on the only object whose world bounds grown by as much hold the point; centred on
    // `point`, its frame built on the normal
    // with the shot as hint and turned by a random angle as spawn builds one, projected as its type
    // asks, its box as deep as on a surface with no error bound. Checked, counted and logged as spawn
    // does (InvalidType, InvalidRay, GrazingAngle from the shot and `normal`, NotReceiver, AreaLimit,
    // InvalidArgument for a point or normal that is not finite or a zero normal); Missed when no
    // object is found so; NotReceiver on a skinned or morphed object (its proxy is
    // bound over its poses: shoot it again) and InvalidArgument for a volumetric type, whose crater
    // is clipped by the proxy around a proxy hit. Any refusal changes no decal and draws no random
    // number.
    SpawnResult spawnOnDrawnSurface(const Ray& shot, const glm::dvec3& point, const glm::dvec3& normal,
                                    uint16_t type);
    // For a decal projected along its shot (DecalAxisLine::alongShot) whose shot, searched from its
    // origin to the box's face it came through, met the drawn surface before the box: a drawn feature
    // that the proxy, within its error bound of it, let the shot pass. The render mesh would have
    // placed the shot's decal there, so the decal gives way to the one spawnOnDrawnSurface places for
    // `shot` at `point`, facing `normal` (of the decal's type; counted in stats().placed and logged as
    // Added, the decal removed as remove() removes it); where the shot meets the drawn surface there
    // more than the type's maxAngleDeg from its normal, the render mesh would have placed nothing, and
    // the decal is removed (the result then says GrazingAngle). Gives spawnOnDrawnSurface's result:
    // the decal is gone when it is placed or GrazingAngle. Any other refusal changes nothing: a stale
    // or invalid handle (InvalidArgument), and the other refusals of spawnOnDrawnSurface (Missed where
    // no object can be told). No refusal counts in stats().rejected: the shot was counted when spawned.
    SpawnResult replaceOnDrawnSurface(DecalHandle handle, const Ray& shot, const glm::dvec3& point,
                                      const glm::dvec3& normal);

    // The live decals, contiguous, for the renderer. Order is deterministic but changes on removals.
    const std::vector<Decal>& decals() const;
    // The clip planes of the crater of decals()[index] (volumetric types; CraterClip.hpp): where the
    // solid it is carved into ends. None active for other decals, a crater away from any edge and an
    // index out of range. Kept beside the decals once a crater has them (8 bytes a handle slot, none
    // before), and given to a renderer so:
    //   renderer.setDecals(sys->decals(), [&](size_t i) { return sys->craterClips(i); });
    CraterClips craterClips(size_t index) const;

    // The version of decals(): the number of changes logged since create() (0: the system as created).
    uint64_t version() const;
    // The changes that turn decals() as it was at `version` into decals() now (DecalChanges.hpp), and
    // the version they lead to. The log keeps the newest max(4096, decals().size() / 4) changes at
    // most (when full it drops the older half; 5 bytes each: 20 KiB up to 16384 decals, then 1.25
    // bytes per decal); a `version` older than what it keeps, or newer than version(), gives
    // complete == false and no changes: take decals() whole. O(changes returned). The second form
    // reuses `out`'s memory.
    DecalChanges changesSince(uint64_t version) const;
    void changesSince(uint64_t version, DecalChanges& out) const;

    // Moves a dynamic object (CollisionWorld::setTransform); its decals follow. A transform the trace
    // cannot use (TraceTransform.hpp) takes the object out of the trace until a usable one, and the
    // result says so; its decals stay.
    Result<TransformUpdate> setTransform(uint32_t object, const glm::dmat4& transform);
    // Poses a skinned or morphed dynamic object as it is drawn (CollisionWorld::setPose: later shots
    // meet the posed surface). A decal that a shot (spawn, spawnBatch) places on such an object lands
    // on the drawn surface under the hit, with a half-depth of depthMargin times its size (at least a
    // hundredth of it) whatever its type asks (volumetric ones stay at the proxy's hit), and keeps that point
    // of the render surface (CollisionWorld::anchorAt): each setPose moves, turns and bends it with the
    // surface (its centre and frame change in place, logged as Changed); a save keeps that point
    // (DecalPersistence.hpp). Decals placed by spawnAt land and stay the same way, under their probe;
    // those of spawnAttached too, under a short probe along their normal through the given point (the
    // point as the object stands; twice the object's error bound either side of it, and at least a
    // hundredth of the type's size), unless that
    // probe meets another object first or nothing: then they ride the object's transform only. Fails, and
    // changes nothing, as CollisionWorld::setPose does.
    Result<TransformUpdate> setPose(uint32_t object, const glm::dmat4& transform,
                                    const std::vector<glm::dmat4>& joints,
                                    const std::vector<double>& morphWeights);
    // Removes an object from the world together with its decals (counted in stats().removed).
    Status removeObject(uint32_t object);
    // The 8-bit object decal ID of an object (0 for static objects and indices out of range).
    uint8_t objectId(uint32_t object) const;
    // The object decal IDs of every object of the world, by object index: what a renderer draws
    // the object ID target with (Renderer::setObjectIds, DecalProjector::setObjects).
    std::vector<uint8_t> objectIds() const;

    const DecalStats& stats() const;
    // The bytes it holds for its decals, by what they serve (a const call: never during a mutation).
    DecalSystemMemory memory() const;
    const DecalSettings& settings() const;
    const CollisionWorld& world() const;
    // Seconds accumulated by update().
    double time() const;

private:
    friend struct DecalSystemAccess; // saving and loading (DecalPersistence.hpp)
    struct Impl;
    explicit DecalSystem(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

} // namespace spatter
