#pragma once
// What a spawn call returns: a handle to the new decal, or the reason it was not placed.

#include <cstddef>
#include <cstdint>
#include <string>

namespace spatter {

enum class SpawnStatus : uint8_t {
    Placed = 0,
    Missed,          // the ray (or the probe of spawnAt) hit no decal receiver
    GrazingAngle,    // the angle between the reversed ray (spawnAt: the given normal) and the surface
                     // normal exceeds the type's maxAngleDeg
    NotReceiver,     // the object does not take this decal: not in the collision world, left out of
                     // the trace (spawnAttached), or dynamic while the type has onDynamic == false
    InvalidRay,      // rayProblem rejected the ray
    InvalidType,     // no decal type has that index
    InvalidArgument, // spawnAt / spawnAttached: non-finite or zero vector, object index out of range;
                     // any spawn: the decal's box would be degenerate in its object's space (a size or
                     // half-depth that is zero, denormal or infinite there: extreme type sizes, a zero
                     // depthMargin on an exact collision mesh, extreme object scales)
    AreaLimit,       // a limit was reached under LimitPolicy::Reject
};
constexpr size_t kSpawnStatusCount = 8;

// Lower-case snake-case name of the status ("placed", "missed", "grazing_angle", "not_receiver",
// "invalid_ray", "invalid_type", "invalid_argument", "area_limit").
const char* toString(SpawnStatus status);

// Refers to one decal. A handle goes stale when its decal is removed (expired, evicted, removed, or
// its object removed); a stale handle never refers to a later decal.
struct DecalHandle {
    uint32_t slot = UINT32_MAX;
    uint32_t generation = 0;
    bool operator==(const DecalHandle& o) const { return slot == o.slot && generation == o.generation; }
    bool operator!=(const DecalHandle& o) const { return !(*this == o); }
};

struct SpawnResult {
    SpawnStatus status = SpawnStatus::Missed;
    DecalHandle handle; // valid only when placed
    std::string reason; // empty when placed; otherwise says why, with the numbers involved

    bool placed() const { return status == SpawnStatus::Placed; }
    // Whether the collision surface refused a shot that the drawn surface may still take: it met no
    // collision surface (Missed) or met one too steeply (GrazingAngle). A proxy lies within its error
    // bound of the drawn surface, not on it: a shot can pass beside it and meet what is drawn, and a
    // proxy facet tilted against the drawn surface can take a shot as grazing that meets the drawn
    // surface within the type's angle. DecalSystem::spawnOnDrawnSurface places such a shot's decal where
    // a renderer finds the shot meeting the drawn surface.
    bool refusedByCollisionSurface() const {
        return status == SpawnStatus::Missed || status == SpawnStatus::GrazingAngle;
    }
};

} // namespace spatter
