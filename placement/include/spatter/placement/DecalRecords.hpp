#pragma once
// DecalRecords: the decals of a Scene read from files, as spatter-render and the example hosts of the
// projector take them: the "placed" records of spatter-place's JSON Lines output, or a ray file
// placed here through a DecalSystem. The result is what a renderer or the projector takes: decals in
// their objects' space, the decal types they index, and one 8-bit decal ID per object.
//
//   Result<LoadedDecals> d = loadPlacedRecords("decals.jsonl", scene, DecalType{}, kMixedLooks);
//   if (!d) return fail(d.error());                            // "decals.jsonl:3: ..."
//   projector.setDecalTypes(d->types);                         // (kMixedLooks: DecalLooks.hpp)
//   projector.setDecals(d->decals);   // spatter's renderer: setDecals(d->decals, craterClipsOf(d->clips))
//   projector.setObjects(transforms, d->objectIds);

#include "spatter/core/CraterClip.hpp"
#include "spatter/core/Decal.hpp"
#include "spatter/core/DecalType.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Scene.hpp"

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

namespace spatter {

struct LoadedDecals {
    std::vector<Decal> decals;         // in their objects' space; Decal::type indexes `types`
    std::vector<DecalType> types;      // the looks of DecalLooks.hpp on the caller's base type
    std::vector<uint8_t> objectIds;    // one per scene object: its 8-bit decal ID
    std::vector<CraterClips> clips;    // one per decal after placeRays (DecalSystem::craterClips,
                                       // inactive for flat decals); empty after loadPlacedRecords
    std::vector<std::string> warnings; // objects the ray trace leaves out, and why (placeRays)
    size_t records = 0;                // records (non-blank lines) or rays (ray lines) read
    size_t placed = 0;                 // decals made from them
};

// A decal box in world space, as a placed record gives it.
struct WorldDecalBox {
    glm::dvec3 center{0.0};
    glm::dvec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}; // unit tangent, bitangent and normal
    glm::dvec2 size{0.0};                                   // full width and height
    double halfDepth = 0.0;
    glm::dvec3 projection{0.0}; // the axis the texture is projected along; zero: the normal
};

// The object a record names: among the objects called `name`, the one whose world bounds lie
// nearest to `position` (names need not be unique in glTF files). -1 when no object has that name.
int findObject(const Scene& scene, const std::string& name, const glm::dvec3& position);

// `box` as a Decal on `object` (its index in the scene `index`), in the object's space: each box
// axis, scaled by its half-extent, is carried by the inverse of the object's transform. The decal's
// ID, type and object ID are left 0 for the caller.
Decal toObjectSpace(const SceneObject& object, uint32_t index, const WorldDecalBox& box);

// The pose decals are drawn at: a time of the scene's first animation and the offset the scene was
// moved by (Scene::translate), for records placed at another time.
struct DrawPose {
    double time = 0.0;
    glm::dvec3 offset{0.0};
};

// Reads spatter-place's JSON Lines output: every record with "status": "placed" becomes a decal on
// the object it names ("object", found by findObject), from its world-space "position", "tangent",
// "bitangent", "normal", "size", "half_depth" and "projection" (optional: the normal when absent),
// with "object_id" (an integer in 0..255, default 0) as its object's decal ID and "decal_id" (an
// integer below 2^32) as its ID when given. Its type is `base` with "max_angle_deg" (in (0, 90],
// default 80) and the look lookOf(look, k) for the k-th decal, one type per distinct pair. Other
// records and blank lines are skipped. Dynamic objects that no record names get the smallest object
// ID no record uses, so that no decal shows on them. Fails on a look that is neither a DecalTexture
// value nor kMixedLooks, an unreadable file, a line that is not a JSON object, a placed record with a
// missing or bad field (a tangent, bitangent or normal that is zero, an axis parallel to the normal,
// an anchor's "bary" outside its triangle), a box that has no orientation or whose size, depth or
// position float does not hold in its object's space, more than 65,535 types, or an object the scene
// lacks; the error starts with "path:line: " and names the field. With `drawn`, a record that carries the
// time it was placed
// ("time") and the render triangle it lies on ("anchor": {"triangle", "bary"}, as spatter-place --time writes
// them for skinned and morphed objects) is moved from that time's pose to the drawn one with its triangle, so
// that it lies on the surface it was placed on (the triangle posed by the scene's animation in the world
// moved by drawn->offset; the objects' transforms in `scene` are those decals are drawn at, as for every
// record).
Result<LoadedDecals> loadPlacedRecords(const std::string& path, const Scene& scene, const DecalType& base,
                                       int look, const std::optional<DrawPose>& drawn = std::nullopt);

// Reads a ray file (one ray per line, "ox oy oz dx dy dz", RayParser.hpp) and places the rays in
// order through a DecalSystem on the scene's render meshes (an object's authored collider where it
// has one) with `type`, `seed` and no area limits or
// budget. Lines that do not parse and rays the system rejects place nothing. Every decal gets
// `type` with the look lookOf(look, k) (types holds the four looks, indexed by DecalTexture); the
// object IDs are the system's. With `drawn`, the rays meet the scene as it stands then: skinned and
// morphed objects deformed as the scene's first animation has them at drawn->time, in the world moved
// by drawn->offset (poseDecalSystem; the objects' transforms in `scene` are those of that pose), and
// an object the system cannot pose is left as it was with a warning. Fails on a look that is neither
// a DecalTexture value nor kMixedLooks, an unreadable file, a scene the collision world cannot take,
// or a `type` the system refuses.
Result<LoadedDecals> placeRays(const std::string& path, const Scene& scene, const DecalType& type, int look,
                               uint64_t seed, const std::optional<DrawPose>& drawn = std::nullopt);

} // namespace spatter
