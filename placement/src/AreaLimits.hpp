#pragma once
// AreaLimits: the bookkeeping behind the per-area limits of the decal system. Each counted decal
// (by slot) sits in three lists in spawn order: its cell of the spatial hash, its object, and the
// global list, so counting and finding the oldest are O(1).
//
// Memory: a slot keeps the 32-bit index of its cell and 32-bit links in the lists it is ordered in:
// two in the global list and the object's (previous and next), one in its cell's (next) while the
// cell limit is at most kSmallCellLimit, else two (at most 28 bytes); a cell in use keeps its key
// and list (40 bytes) and a 32-bit entry in an open-addressing table at most half full. A limit at or
// above the budget keeps no order of its own (see AreaLimits()), which saves that list's links.

#include "spatter/placement/DecalSystem.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace spatter {

// A cell of the spatial hash. space 0 holds world-space cells (static objects); space 1 + i the
// object-space cells of dynamic object i.
struct CellKey {
    int64_t x = 0, y = 0, z = 0;
    uint32_t space = 0;
    bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z && space == o.space; }
};

struct CellKeyHash {
    size_t operator()(const CellKey& k) const;
};

class AreaLimits {
public:
    static constexpr uint32_t kNone = UINT32_MAX;

    // `cellLimit` and `objectLimit` are the most counted decals of a cell and of an object; their
    // lists are kept in spawn order while the limit is below the budget. The counted decals never
    // outnumber the budget, so a limit at or above it is reached only when every counted decal is
    // in that one cell (object): its oldest is then the oldest of all, and without the order
    // oldestInCell / oldestOfObject return oldest(), which is that same decal. The counts are kept
    // either way. `budget`: the decals the limits are meant to hold; the per-slot arrays grow up to
    // it without slack (CappedGrowth.hpp).
    explicit AreaLimits(size_t objectCount = 0, uint32_t budget = 4096, uint32_t cellLimit = 16,
                        uint32_t objectLimit = 1024);

    // Adds `slot` as the newest decal of its cell, its object and the world. `slot` must not be linked.
    void link(uint32_t slot, const CellKey& key, uint32_t object);
    // Takes `slot` out of its lists; `object` is the one it was linked with. Does nothing when it is
    // not linked.
    void unlink(uint32_t slot, uint32_t object);
    bool linked(uint32_t slot) const { return slot < cellOf_.size() && cellOf_[slot] != kNone; }

    uint32_t cellCount(const CellKey& key) const {
        const uint32_t c = findCell(key);
        return c == kNone ? 0 : cells_[c].list.count;
    }
    uint32_t objectCount(uint32_t object) const {
        return object < objects_.size() ? objects_[object].count : 0;
    }
    uint32_t total() const { return global_.count; }

    // Oldest linked slot, or kNone.
    uint32_t oldestInCell(const CellKey& key) const;
    uint32_t oldestOfObject(uint32_t object) const;
    uint32_t oldest() const { return global_.head; }
    // The linked slot spawned after `slot` (linked) in the world's order, or kNone: from oldest(), the
    // counted decals oldest first. A save walks them so that a load links them in the same order.
    uint32_t newer(uint32_t slot) const { return links_[size_t(slot) * stride_ + kGlobal.next]; }
    // The cell `slot` (linked) was linked with.
    CellKey cellOf(uint32_t slot) const;
    // Bytes of its own allocations (capacities).
    size_t bytes() const {
        return links_.capacity() * sizeof(uint32_t) + cellOf_.capacity() * sizeof(uint32_t) +
               cells_.capacity() * sizeof(Cell) + table_.capacity() * sizeof(uint32_t) +
               objects_.capacity() * sizeof(List);
    }

private:
    // Where a list's links lie among a slot's words; prev kNone: singly linked.
    struct Links {
        uint32_t prev = kNone, next = kNone;
    };
    static constexpr Links kGlobal{0, 1};
    struct List {
        uint32_t head = kNone, tail = kNone, count = 0;
    };
    // A cell in use (list.count > 0), or a free one whose list.head is the next free cell.
    struct Cell {
        int64_t x = 0, y = 0, z = 0;
        uint32_t space = 0;
        List list;
        bool is(const CellKey& k) const { return x == k.x && y == k.y && z == k.z && space == k.space; }
    };
    static_assert(sizeof(Cell) == 40, "a cell of the area grid grew past 40 bytes");

    static CellKey keyOf(const Cell& c);
    static size_t hashOf(const Cell& c);
    // The index of the cell of `key`, or kNone.
    uint32_t findCell(const CellKey& key) const;
    // Adds an empty cell for `key`, which has none yet, and returns its index.
    uint32_t addCell(const CellKey& key);
    // Takes an empty cell out of the table and frees its index.
    void dropCell(uint32_t cell);

    uint32_t& word(uint32_t slot, uint32_t pos) { return links_[size_t(slot) * stride_ + pos]; }
    void pushBack(List& list, Links at, uint32_t slot);
    void erase(List& list, Links at, uint32_t slot);
    // The slot before `slot` in `list`, found by walking a singly linked list from its head.
    uint32_t before(const List& list, uint32_t next, uint32_t slot) const;

    uint32_t budget_ = 0;
    unsigned stride_ = 2;          // 32-bit links per slot
    Links object_, cell_;          // where the object's and the cell's lists lie; next kNone: not ordered
    std::vector<uint32_t> links_;  // by slot, stride_ each
    std::vector<uint32_t> cellOf_; // by slot: its cell, kNone when not linked
    std::vector<Cell> cells_;      // by cell index
    uint32_t freeCells_ = kNone;   // first free cell index
    std::vector<uint32_t> table_;  // cell indices by hash (linear probing, power of two, kNone: empty)
    size_t cellsInUse_ = 0;
    std::vector<List> objects_;
    List global_;
};

} // namespace spatter
