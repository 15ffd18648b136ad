#pragma once
// AreaLimits: the bookkeeping behind the per-area limits of the decal system. Each counted decal
// (by slot) sits in three lists in spawn order: its cell of the spatial hash, its object, and the
// global list, so counting and finding the oldest are O(1).

#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
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

    explicit AreaLimits(size_t objectCount = 0) : objects_(objectCount) {}

    // Adds `slot` as the newest decal of its cell, its object and the world. `slot` must not be linked.
    void link(uint32_t slot, const CellKey& key, uint32_t object);
    // Takes `slot` out of its lists; does nothing when it is not linked.
    void unlink(uint32_t slot);
    bool linked(uint32_t slot) const { return slot < linked_.size() && linked_[slot]; }

    uint32_t cellCount(const CellKey& key) const;
    uint32_t objectCount(uint32_t object) const {
        return object < objects_.size() ? objects_[object].count : 0;
    }
    uint32_t total() const { return global_.count; }

    // Oldest linked slot, or kNone.
    uint32_t oldestInCell(const CellKey& key) const;
    uint32_t oldestOfObject(uint32_t object) const {
        return object < objects_.size() ? objects_[object].head : kNone;
    }
    uint32_t oldest() const { return global_.head; }

private:
    struct Link {
        uint32_t prev = kNone, next = kNone;
    };
    struct List {
        uint32_t head = kNone, tail = kNone, count = 0;
    };
    enum Kind { kCell = 0, kObject = 1, kGlobal = 2 };

    void pushBack(List& list, Kind kind, uint32_t slot);
    void erase(List& list, Kind kind, uint32_t slot);

    std::vector<std::array<Link, 3>> links_; // by slot
    std::vector<CellKey> keys_;              // by slot
    std::vector<uint32_t> objectOf_;         // by slot
    std::vector<bool> linked_;               // by slot
    std::unordered_map<CellKey, List, CellKeyHash> cells_;
    std::vector<List> objects_;
    List global_;
};

} // namespace spatter
