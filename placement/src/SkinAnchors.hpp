#pragma once
// SkinAnchors: the decals that stay on a deforming object's drawn surface. A decal placed by a shot on
// a skinned or morphed object keeps the point of the render surface it was placed on
// (CollisionWorld::anchorAt: a render triangle and barycentric coordinates) and its centre and frame
// relative to that triangle's frame at the pose of the shot. Each new pose (DecalSystem::setPose)
// puts them back relative to the triangle's frame at that pose, so the decal moves, turns and bends
// with the surface it lies on instead of riding the object's transform alone. Only decals on
// deforming objects are kept here, so the other decals pay nothing for it.

#include "spatter/core/Decal.hpp"
#include "spatter/placement/CollisionWorld.hpp"

#include <cstdint>
#include <glm/glm.hpp>
#include <unordered_map>
#include <vector>

namespace spatter {

// An anchored decal as a save keeps it (its object is its decal's).
struct SavedAnchor {
    uint32_t slot = 0;
    SurfaceAnchor surface;
    glm::dvec3 center{0.0}, tangent{0.0}, normal{0.0}; // in the anchor's frame
};

class SkinAnchors {
public:
    // Anchors the decal of handle slot `slot`, `decal` (which has none yet), whose frame in object
    // space is `frame` (tangent, bitangent, normal), at `location` (CollisionWorld::anchorAt).
    void add(uint32_t slot, const Decal& decal, const glm::dmat3& frame, const SurfaceLocation& location);
    // Forgets the anchor of the decal of slot `slot` on `object`, if it has one.
    void erase(uint32_t slot, uint32_t object);

    // Bytes of its anchor lists and slot index (capacities; the hash table's nodes, one per object
    // with anchors, left out).
    size_t bytes() const {
        size_t b = indexOf_.capacity() * sizeof(uint32_t);
        for (const auto& [object, list] : byObject_)
            b += list.capacity() * sizeof(Entry);
        return b;
    }

    // Every anchor, by ascending slot (a save's order does not depend on the hash table's).
    std::vector<SavedAnchor> saved() const;
    // Replaces the anchors with `saved`, each on the object of the decal objectOf(slot) names.
    template <class ObjectOf> void restore(const std::vector<SavedAnchor>& saved, ObjectOf objectOf) {
        byObject_.clear();
        indexOf_.clear();
        for (const SavedAnchor& a : saved)
            insert(objectOf(a.slot), a.slot, Anchor{a.surface, a.center, a.tangent, a.normal});
    }

    // Poses the decals anchored on `object` as the world's pose of it now stands: each one's centre
    // and frame in `decals` (at denseOf(slot)); changed(dense) is called for each.
    template <class DenseOf, class Changed>
    void repose(uint32_t object, const CollisionWorld& world, std::vector<Decal>& decals, DenseOf denseOf,
                Changed changed) const {
        const auto on = byObject_.find(object);
        if (on == byObject_.end()) return;
        for (const Entry& e : on->second) {
            const std::optional<glm::dmat4> frame = world.anchorFrame(object, e.anchor.surface);
            if (!frame) continue; // a collapsed triangle: the decal stays where it was
            const uint32_t dense = denseOf(e.slot);
            place(e.anchor, *frame, decals[dense]);
            changed(dense);
        }
    }

private:
    struct Anchor {
        SurfaceAnchor surface;
        glm::dvec3 center{0.0}, tangent{0.0}, normal{0.0}; // in the anchor's frame
    };
    // The decal's centre and frame from the anchor's, under the anchor's frame `frame`.
    static void place(const Anchor& anchor, const glm::dmat4& frame, Decal& decal);

    struct Entry {
        uint32_t slot = 0;
        Anchor anchor;
    };
    static constexpr uint32_t kNone = UINT32_MAX;
    // Appends the anchor of slot `slot` to `object`'s.
    void insert(uint32_t object, uint32_t slot, const Anchor& anchor);

    // By object, its anchors in no particular order: a pose moves its object's decals without a look
    // at the others. By handle slot, where its anchor stands in its object's list (kNone: it has
    // none), so that adding and forgetting one is a push and a swap, with no allocation of its own.
    std::unordered_map<uint32_t, std::vector<Entry>> byObject_;
    std::vector<uint32_t> indexOf_;
};

} // namespace spatter
