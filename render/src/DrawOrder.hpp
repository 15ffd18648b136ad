#pragma once
// DrawOrder: the order the decal boxes are drawn in, kept as the decals change without sorting them
// again. Decals draw by their type's priority (DecalType::priority), then by spawn time, then by
// index: one region of entries per priority, lowest first, each in spawn order with room to grow.
// A decal added later (DecalChanges) is newer than every decal there and goes to the end of its
// priority's region; a removed one leaves an empty entry, and the decal moved into its index takes
// over its entry. Entries are decal indices or kEmpty; the GPU culling walks them as they are.
// The CPU keeps the entries only while it may cull (setMirrored): otherwise each decal's entry (which
// it keeps) says all the entries do, a change is kept as a write for the GPU's copy, and a new
// layout's entries live until they are uploaded.

#include "spatter/core/Decal.hpp"

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
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

    // Whether the CPU keeps the entries (DecalBatch's mirror, while the projector may cull on the CPU).
    // Keeping them again rebuilds them from each decal's entry; letting them go asks for a whole
    // upload, after which they are freed.
    void setMirrored(bool mirrored);
    // The entries, while mirrored or until a new layout's are uploaded (uploaded()); empty otherwise.
    const std::vector<uint32_t>& entries() const { return entries_; }
    size_t size() const { return size_; } // entries in the layout
    // Bytes of its own allocations.
    size_t cpuBytes() const {
        return (entries_.capacity() + pos_.capacity() + pending_.capacity() + changed_.capacity()) *
                   sizeof(uint32_t) +
               writes_.capacity() * sizeof(glm::uvec2) + regions_.capacity() * sizeof(Region);
    }
    size_t decalCount() const { return pos_.size(); }
    // Whether the layout is new since the last takeChanged (every entry changed).
    bool relaid() const { return relaid_; }
    // Decal `index`'s entry; kEmpty for one not placed yet or past the decals.
    uint32_t entryOf(size_t index) const {
        return index < pos_.size() && !(pos_[index] & kPending) ? pos_[index] : kEmpty;
    }
    // What the GPU's copy needs since the last call: every entry (entries()) after a new layout or when
    // `all`, else the changed entries as runs of entries() (SparseRuns.hpp) while mirrored, or as
    // writes (entry, value), the last of each entry, while not.
    struct Changes {
        bool all = false;
        std::vector<std::pair<size_t, size_t>> runs;
        std::vector<glm::uvec2> writes;
    };
    Changes takeChanged(bool all = false);
    // The GPU's copy has taken the last changes: entries the CPU does not keep are freed.
    void uploaded();

private:
    struct Region {
        size_t start = 0, size = 0, used = 0, empty = 0;
    };
    static constexpr uint32_t kPending = 0x80000000u; // pos_ of an added decal not yet placed

    void layout(const std::vector<std::vector<uint32_t>>& byRank);
    void set(size_t entry, uint32_t value);
    size_t regionOf(size_t entry) const;
    // The entries rebuilt from each placed decal's entry.
    std::vector<uint32_t> rebuiltEntries() const;

    std::vector<uint32_t> entries_; // while held_
    size_t size_ = 0;               // entries in the layout
    std::vector<uint32_t> pos_;     // per decal: its entry, or kPending | its place in pending_
    std::vector<uint32_t> pending_; // added decals (their current indices), kEmpty when removed again
    std::vector<Region> regions_;
    std::vector<uint32_t> changed_;  // mirrored: entries changed since takeChanged
    std::vector<glm::uvec2> writes_; // not mirrored: (entry, value) since takeChanged
    bool relaid_ = false;            // a new layout since takeChanged: everything changed
    bool mirrored_ = true;
    bool held_ = true; // entries_ holds the entries: mirrored, or a layout not yet uploaded
};

} // namespace spatter::render_detail
