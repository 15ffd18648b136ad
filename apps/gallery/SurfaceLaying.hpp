#pragma once
// SurfaceLaying: the gallery's decals laid on the drawn surface a frame after their shots. After a
// frame, the axis lines of the decals placed since the frame before are searched in its depth
// (Renderer::findSurface); once the GPU has answered, each decal whose line meets the drawn surface
// is laid there (DecalSystem::layOnDrawnSurface; removed where the shot meets it too steeply for its
// type), carried from where that frame drew its object to where the object is now; a decal along its
// shot whose shot, searched from its origin, met the drawn surface before the decal's box gives way
// to the shot's decal there (DecalSystem::replaceOnDrawnSurface). The shots that the
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
    // Decals replaced so far by their shot's decal where the shot met the drawn surface before their
    // box (where it met it there too steeply, they are removed, and counted in removed()).
    uint64_t replaced() const { return replaced_; }

private:
    static constexpr size_t kNoLine = SIZE_MAX;
    // A shot of a search and its lines: a placed decal's axis line through its box and, for a decal
    // along its shot, the shot from its origin to the box; or the shot itself where it was refused.
    struct Searched {
        GallerySim::Shot shot;
        size_t box = kNoLine, beforeBox = kNoLine, refused = kNoLine;
    };
    struct Search {
        uint64_t request = 0;
        uint64_t system = 0;                // GallerySim::systemNumber() when it was made
        std::vector<Searched> shots;        // the shots searched and their lines
        std::vector<glm::dmat4> transforms; // every object as the frame drew it
    };
    // Adds the lines of the decal of `shot` to `lines`, where it can be laid; false where not.
    bool addDecalLines(const GallerySim::Shot& shot, const GallerySim& sim, const Renderer& renderer,
                       std::vector<SurfaceLine>& lines, Searched& searched) const;
    void take(const Search& s, const Searched& shot, const std::vector<SurfacePoint>& points,
              GallerySim& sim);
    void layDecal(const Search& s, DecalHandle h, const SurfacePoint& p, GallerySim& sim);
    // `p` carried with the moving target whose ID the frame showed there; static surfaces (ID 0) stay.
    SurfacePoint withItsTarget(const Search& s, const SurfacePoint& p, const GallerySim& sim) const;

    std::vector<GallerySim::Shot> fresh_; // placed or refused since the last search
    uint64_t freshSystem_ = 0;            // the system fresh_'s handles belong to
    std::deque<Search> searches_;
    uint64_t laid_ = 0, removed_ = 0, spawned_ = 0, replaced_ = 0;
};

} // namespace spatter::gallery
