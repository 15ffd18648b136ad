#pragma once
// SurfaceLaying: the gallery's decals laid on the drawn surface a frame after their shots. After a
// frame, the axis lines of the decals placed since the frame before are searched in its depth
// (Renderer::findSurface); once the GPU has answered, each decal whose line meets the drawn surface
// is laid there (DecalSystem::layOnDrawnSurface; removed where the shot meets it too steeply for its
// type), carried from where that frame drew its object to where the object is now. The shots that the
// collision surface refused (met none, or met it too steeply: SpawnResult::refusedByCollisionSurface)
// are searched along their rays, and where one meets the drawn surface its decal is placed there
// (DecalSystem::spawnOnDrawnSurface), carried with the object whose ID the frame shows there. Craters, decals
// on skinned targets and decals splatted into a texture-space object's texture are left as they are. Searches
// made before the decal system was replaced (new proxies, a load) are dropped: their handles name decals of
// the system before.

#include "GallerySim.hpp"

#include "spatter/core/Result.hpp"
#include "spatter/render/Renderer.hpp"

#include <cstdint>
#include <deque>
#include <vector>

namespace spatter::gallery {

class SurfaceLaying {
public:
    // A shot fired in `sim`: its decal, or the shot itself where the collision surface refused it, is
    // searched for after the next frame.
    void shot(const GallerySim::Shot& shot, const GallerySim& sim);
    // After a frame that `renderer` drew of `sim` as it stands: searches the new decals' lines.
    Status search(Renderer& renderer, const GallerySim& sim);
    // Lays the decals of the searches the GPU has answered (all of them, waiting, with `wait`).
    void lay(Renderer& renderer, GallerySim& sim, bool wait);
    uint64_t laid() const { return laid_; } // decals laid on the drawn surface so far
    // Decals removed so far because their shot meets the drawn surface too steeply for their type.
    uint64_t removed() const { return removed_; }
    // Decals of shots the collision surface refused, placed where they meet the drawn surface so far.
    uint64_t spawned() const { return spawned_; }

private:
    struct Search {
        uint64_t request = 0;
        uint64_t system = 0;                   // GallerySim::systemNumber() when it was made
        std::vector<DecalHandle> handles;      // the first lines: these decals' axis lines
        std::vector<GallerySim::Shot> refused; // the lines after them: these shots
        std::vector<glm::dmat4> transforms;    // every object as the frame drew it
    };
    void layDecal(const Search& s, size_t i, const SurfacePoint& p, GallerySim& sim);
    void spawnRefused(const Search& s, size_t i, const SurfacePoint& p, GallerySim& sim);

    std::vector<DecalHandle> fresh_;
    std::vector<GallerySim::Shot> freshRefused_;
    uint64_t freshSystem_ = 0; // the system fresh_'s handles belong to
    std::deque<Search> searches_;
    uint64_t laid_ = 0, removed_ = 0, spawned_ = 0;
};

} // namespace spatter::gallery
