#pragma once
// DrawOrder: the order the decal boxes are drawn in, kept as the decals change without sorting them
// again. Decals draw by their type's priority (DecalType::priority), then by spawn time, then by
// index: one region of entries per priority, lowest first, each in spawn order with room to grow.
// A decal added later (DecalChanges) is newer than every decal there and goes to the end of its
// priority's region; a removed one leaves an empty entry, and the decal moved into its index takes
// over its entry. Entries are decal indices or kEmpty; the GPU culling walks them as they are.

#include "spatter/core/Decal.hpp"

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace spatter::render_detail {

class DrawOrder {
public:
    static constexpr uint32_t kEmpty = UINT32_MAX;

    // `typeRank[t]`: the rank of type t's priority among the distinct priorities (0 the lowest);
    // decals of types past its end rank 0. Lays every decal out afresh, sorted.
    void rebuild(const std::vector<Decal>& decals, const std::vector<uint32_t>& typeRank);
    // The changes of DecalChanges.hpp, replayed in order; add() waits for place().
    void add(uint32_t index);
    void remove(uint32_t index, uint32_t from);
    // Puts the decals added since the last call at the end of their priority's region, in the order
    // they were added, by the types of `decals` (the decals as they are after the changes).
    void place(const std::vector<Decal>& decals, const std::vector<uint32_t>& typeRank);

    const std::vector<uint32_t>& entries() const { return entries_; }
    // Bytes of its own allocations.
    size_t cpuBytes() const {
        return (entries_.capacity() + pos_.capacity() + pending_.capacity() + changed_.capacity()) *
                   sizeof(uint32_t) +
               regions_.capacity() * sizeof(Region);
    }
    size_t decalCount() const { return pos_.size(); }
    // The runs of entries changed since the last call (SparseRuns.hpp); all of them after a new layout.
    std::vector<std::pair<size_t, size_t>> takeChanged();

private:
    struct Region {
        size_t start = 0, size = 0, used = 0, empty = 0;
    };
    static constexpr uint32_t kPending = 0x80000000u; // pos_ of an added decal not yet placed

    void layout(const std::vector<std::vector<uint32_t>>& byRank);
    void set(size_t entry, uint32_t value);
    size_t regionOf(size_t entry) const;

    std::vector<uint32_t> entries_;
    std::vector<uint32_t> pos_;     // per decal: its entry, or kPending | its place in pending_
    std::vector<uint32_t> pending_; // added decals (their current indices), kEmpty when removed again
    std::vector<Region> regions_;
    std::vector<uint32_t> changed_; // entries changed since takeChanged
    bool relaid_ = false;           // a new layout since takeChanged: everything changed
};

} // namespace spatter::render_detail
