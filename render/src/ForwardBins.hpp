#pragma once
// ForwardBins: the forward path's screen tiles. From the visible decals of a frame (the projector's
// instance, object and visible-list buffers bound at their binding points) four compute passes
// write each decal's camera-relative world form, count the decals per tile, turn the counts into
// runs of an item list and fill and sort the runs into drawing order (shaders/forward_*.comp). The
// screen rectangles come from the CPU culling, so the item list's size is known before the GPU runs.
// After culling on the GPU the count is not known on the CPU: the tiles then have runs of a fixed
// length, filled as the rectangles are found. A tile with more decals than its run holds, up to a
// limit, gets a run over every decal binned instead (the items 0, 1, 2, ... that follow the tiles'
// runs, which a host's shader reads as any run): exact, and slower for that tile. The GPU reports
// the fullest tile, by which the caller sizes the runs of later binnings.

#include "DecalBatch.hpp"
#include "GlObjects.hpp"
#include "GpuReadback.hpp"
#include "ProjectorLayouts.hpp"

#include "spatter/core/Result.hpp"
#include "spatter/render/DecalProjector.hpp"

#include <cstdint>
#include <optional>
#include <vector>

namespace spatter::render_detail {

class ForwardBins {
public:
    // Whether runs of `tileCapacity` items (twice the fullest tile's decals, a power of two) are short:
    // one invocation sorts each (longer ones are sorted by a work group a tile, forward_sort.comp's
    // SORT_BY_TILE), and the compute resolve tests a pixel against the boxes before it reads more
    // (decal_resolve.comp's SPARSE_TILES).
    static bool shortRuns(uint32_t tileCapacity) { return tileCapacity <= 32; }

    // Builds the compute programs on first use.
    Status prepare();
    // Bins the visible decals of `vis` (in draw order, as the visible list holds them) into the tiles
    // of `frame`; `head` carries the frame's parameters (the grid is filled in here). Returns the
    // bytes sent to the GPU. Needs prepare() to have succeeded.
    size_t bin(const ForwardFrame& frame, const DecalVisibility& vis, int tileSize, ForwardGridGpu head);
    // The same for a visible list the GPU culled (GpuCulling; `draws` its indirect draw, whose instance
    // count is the list's length), with no count on the CPU: up to `capacity` visible decals are binned
    // (the rest are left out), each tile's run holds up to `tileCapacity` of them (a tile with more, up
    // to `mostPerTile`, gets a run over every decal binned; past that the rest are left out), and two
    // passes do it (the rectangles found and the runs filled at once, then sorted). `shownOnly`: each
    // decal goes into the tiles of the part of its box that can show (its texture's cutout: the
    // compute resolve), not of its whole box (the forward path, whose count of decals that pass a
    // pixel is its coverage). Returns the bytes sent.
    size_t binCulled(const ForwardFrame& frame, int tileSize, ForwardGridGpu head, GLuint draws,
                     size_t capacity, uint32_t tileCapacity, uint32_t mostPerTile, bool shownOnly);
    void bind(const ForwardBindings& b) const;
    // Marks the last binCulled's left-out flag and fullest tile, which its passes write into the
    // read-back buffer, as ready to read (leftOut and fullestTile read them), once a binning: at the
    // end of the pass, where the mark holds up no pass after the binning.
    void readBack();
    // Whether the latest binCulled the GPU has finished (this one's when `wait`, read back now if
    // readBack() has not been) left decals out: more
    // visible decals than the buffers held, or a tile past `mostPerTile`.
    bool leftOut(bool wait);
    // Whether it left decals out because a tile held more than `mostPerTile` (not for want of room in
    // the buffers, which the next binning sizes from the latest count).
    bool tileOverflowed(bool wait);
    // The most decals one tile held in the latest binCulled the GPU has finished (this one's when
    // `wait`); nothing before the first, or after a binning culled on the CPU.
    std::optional<uint32_t> fullestTile(bool wait);

    GLuint decals() const { return decals_.get(); }
    GLuint tiles() const { return tiles_.get(); }
    GLuint items() const { return items_.get(); }

    // Bytes of the GPU buffers it holds.
    size_t gpuBytes() const {
        return decalsCapacity_ + tilesCapacity_ + itemsCapacity_ + rectsCapacity_ + countsCapacity_;
    }

private:
    // The tile rectangles of the visible decals (x0 | y0 << 16, x1 | y1 << 16) and the item count.
    size_t tileRects(const ForwardFrame& frame, const DecalVisibility& vis, int tileSize, glm::ivec2 tiles);
    void dispatch(uint32_t visible, uint32_t tileCount) const;

    // Room in the items for `runItems` of the tiles' runs and, after them, the items 0, 1, 2, ... of
    // the runs over `everyDecal` decals (sent when the room or their place changed; the item list made
    // anew, smaller, where a quarter of it will do). Returns the bytes sent.
    size_t reserveItems(size_t runItems, size_t everyDecal);

    // The grid of `frame`'s tiles, the head's grid filled in.
    glm::ivec2 grid(const ForwardFrame& frame, int tileSize, ForwardGridGpu& head) const;

    GlProgram prepare_, scan_, fill_, sort_, prepareCulled_, prepareShown_, sortCulled_, sortCulledByTile_;
    GlBuffer decals_, tiles_, items_, rects_, counts_;
    size_t decalsCapacity_ = 0, tilesCapacity_ = 0, itemsCapacity_ = 0, rectsCapacity_ = 0,
           countsCapacity_ = 0;
    size_t everyDecalAt_ = 0, everyDecalCount_ = 0; // the identity items in items_ (0: none)
    std::vector<glm::uvec2> rectsCpu_;
    GpuReadback tileInfo_{2}; // the latest binCulled's left-out flag and most decals of a tile
    uint32_t zeroCounts_ = 0; // tiles, from the first, whose counts are zero (binCulled's sort zeroes them)
};

} // namespace spatter::render_detail
