#pragma once
// SurfaceLaying: the gallery's decals laid on the drawn surface a frame after their shots. After a
// frame, the axis lines of the decals placed since the frame before are searched in its depth
// (Renderer::findSurface); once the GPU has answered, each decal whose line meets the drawn surface
// is laid there (DecalSystem::layOnDrawnSurface; removed where the shot meets it too steeply for its
// type), carried from where that frame drew its object to
// where the object is now. Craters, decals on skinned targets and decals splatted into a texture-space
// object's texture are left as they are. Searches made before the decal system was replaced (new proxies, a
// load) are dropped: their handles name decals of the system before.

#include "GallerySim.hpp"

#include "spatter/core/Result.hpp"
#include "spatter/render/Renderer.hpp"

#include <cstdint>
#include <deque>
#include <vector>

namespace spatter::gallery {

class SurfaceLaying {
public:
    // A shot's result in `sim`: a decal placed is searched for after the next frame.
    void placed(const SpawnResult& result, const GallerySim& sim);
    // After a frame that `renderer` drew of `sim` as it stands: searches the new decals' lines.
    Status search(Renderer& renderer, const GallerySim& sim);
    // Lays the decals of the searches the GPU has answered (all of them, waiting, with `wait`).
    void lay(Renderer& renderer, GallerySim& sim, bool wait);
    uint64_t laid() const { return laid_; } // decals laid on the drawn surface so far
    // Decals removed so far because their shot meets the drawn surface too steeply for their type.
    uint64_t removed() const { return removed_; }

private:
    struct Search {
        uint64_t request = 0;
        uint64_t system = 0; // GallerySim::systemNumber() when it was made
        std::vector<DecalHandle> handles;
        std::vector<glm::dmat4> transforms; // each decal's object as the frame drew it
    };
    std::vector<DecalHandle> fresh_;
    uint64_t freshSystem_ = 0; // the system fresh_'s handles belong to
    std::deque<Search> searches_;
    uint64_t laid_ = 0, removed_ = 0;
};

} // namespace spatter::gallery
