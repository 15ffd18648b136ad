#pragma once
// SkinAnchors: the decals that stay on a deforming object's drawn surface. A decal placed by a shot on
// a skinned or morphed object keeps the point of the render surface it was placed on
// (CollisionWorld::anchorAt: a render triangle and barycentric coordinates) and its centre and frame
// relative to that triangle's frame at the pose of the shot. Each new pose (DecalSystem::setPose)
// puts them back relative to the triangle's frame at that pose, so the decal moves, turns and bends
// with the surface it lies on instead of riding the object's transform alone. Only decals on
// deforming objects are kept here, so the other decals pay nothing for it.

#include "spatter/core/Decal.hpp"
#include "spatter/core/DecalType.hpp"
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

// Moves `decal`, just placed by a shot (`shot`: the ray's direction, world space) on an object of
// transform `objectTransform`, onto the drawn surface at `frame` (SkinAnchors::Location::frame): its
// centre onto the frame's point and its normal to the render triangle's (unless the shot grazed a
// silhouette and met that triangle from behind), so that no proxy error is left for its box to hold.
// Its half-depth becomes `depthMargin` times its size (1% at least), whatever its type asks: on a body
// a deeper box would reach the torso behind an arm. A Shot projection is slanted along `shot` again.
void moveOntoDrawnSurface(Decal& decal, const glm::dmat4& frame, const glm::dvec3& shot,
                          const DecalType& type, float depthMargin, const glm::dmat4& objectTransform);

class SkinAnchors {
public:
    // Where on the drawn surface a decal lies: the anchor and its frame at the current pose.
    struct Location {
        SurfaceAnchor surface;
        glm::dmat4 frame{1.0}; // CollisionWorld::anchorFrame
    };
    // The location of `decal`, just placed by a shot along `direction` (object space) that hit
    // collision triangle `primitive` of its object; empty when the object does not deform.
    static std::optional<Location> locate(const Decal& decal, uint32_t primitive, const glm::dvec3& direction,
                                          const CollisionWorld& world);
    // Anchors the decal of handle slot `slot`, `decal`, at `location`.
    void add(uint32_t slot, const Decal& decal, const Location& location);
    // Forgets the anchor of the decal of slot `slot` on `object`, if it has one.
    void erase(uint32_t slot, uint32_t object) {
        if (byObject_.empty()) return;
        auto on = byObject_.find(object);
        if (on == byObject_.end()) return;
        on->second.erase(slot);
        if (on->second.empty()) byObject_.erase(on);
    }

    // Every anchor, by ascending slot (a save's order does not depend on the hash table's).
    std::vector<SavedAnchor> saved() const;
    // Replaces the anchors with `saved`, each on the object of the decal objectOf(slot) names.
    template <class ObjectOf> void restore(const std::vector<SavedAnchor>& saved, ObjectOf objectOf) {
        byObject_.clear();
        for (const SavedAnchor& a : saved)
            byObject_[objectOf(a.slot)][a.slot] = Anchor{a.surface, a.center, a.tangent, a.normal};
    }

    // Poses the decals anchored on `object` as the world's pose of it now stands: each one's centre
    // and frame in `decals` (at denseOf(slot)); changed(dense) is called for each.
    template <class DenseOf, class Changed>
    void repose(uint32_t object, const CollisionWorld& world, std::vector<Decal>& decals, DenseOf denseOf,
                Changed changed) const {
        const auto on = byObject_.find(object);
        if (on == byObject_.end()) return;
        for (const auto& [slot, anchor] : on->second) {
            const std::optional<glm::dmat4> frame = world.anchorFrame(object, anchor.surface);
            if (!frame) continue; // a collapsed triangle: the decal stays where it was
            const uint32_t dense = denseOf(slot);
            place(anchor, *frame, decals[dense]);
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

    // By object, then by handle slot: a pose moves its object's decals without a look at the others.
    std::unordered_map<uint32_t, std::unordered_map<uint32_t, Anchor>> byObject_;
};

} // namespace spatter
