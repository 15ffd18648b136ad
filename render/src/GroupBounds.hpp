#pragma once
// GroupBounds: for each group of 256 places of the draw order, up to four boxes, each in the space of
// one object the group's decals lie on, holding its decals there (shaders/cull_group_bounds.glsl),
// so that the GPU culling's first pass (cull_groups.comp) culls a group out of view whole, reading
// none of its decals: a world of a million decals with a few hundred groups in view costs its culling
// a pass over 3,907 groups, not a million places. The boxes are in their objects' spaces, so they
// hold while the objects move; they are written again on the GPU (cull_bounds.comp) only for the
// groups whose places or decals changed, which the CPU marks as the draw order and the decal records
// change. It pays where decals spawned together lie together, as a player's shots do; a group spread
// over the world, or over more than four objects, is tested by place as before.

#include "DecalBatch.hpp"
#include "DrawOrder.hpp"
#include "GlObjects.hpp"

#include "spatter/core/Result.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace spatter::render_detail {

class GroupBounds {
public:
    static constexpr uint32_t kGroupPlaces = 256; // places of a group (cull_layout.glsl)

    // Builds the compute programs on first use.
    Status prepare();

    // Marks groups whose boxes must be written again: every group; those of draw order entries
    // [begin, end) or of one entry; those holding the decals of `staged` records (by their entries in
    // `order`; decals not placed yet are marked when they are).
    void markAll() { all_ = true; }
    void markEntries(size_t begin, size_t end);
    void markEntry(size_t entry) { markEntries(entry, entry + 1); }
    void markDecals(const DrawOrder& order, const std::vector<StagedRecords>& staged);

    // Writes the marked groups' boxes from the draw order and decal records bound at their binding
    // points (`places` entries, `groups` groups) and leaves the boxes bound for the passes after it.
    void update(uint32_t places, uint32_t groups);
    // Tests each group against the view of the frame block, clearing the groups' visible counts and
    // listing those to test by place, their count as an indirect dispatch (cull_groups.comp).
    void list(uint32_t groups);

    // Bytes of the GPU buffers it holds, and of its own allocations.
    size_t gpuBytes() const { return boundsCapacity_ + listCapacity_; }
    size_t cpuBytes() const {
        return marked_.capacity() * sizeof(uint64_t) + listed_.capacity() * sizeof(uint32_t);
    }

private:
    void write(uint32_t places, uint32_t groups);

    GlProgram write_, test_;
    GlBuffer bounds_, list_;
    size_t boundsCapacity_ = 0, listCapacity_ = 0;
    std::vector<uint64_t> marked_; // a bit a group
    std::vector<uint32_t> listed_; // the marked groups, for the GPU
    bool all_ = true;
};

} // namespace spatter::render_detail
