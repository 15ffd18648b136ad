#include "AreaLimits.hpp"

namespace spatter {

size_t CellKeyHash::operator()(const CellKey& k) const {
    // splitmix64-style mixing of the four fields.
    auto mix = [](uint64_t h, uint64_t v) {
        h ^= v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
        h ^= h >> 31;
        h *= 0xbf58476d1ce4e5b9ULL;
        return h ^ (h >> 29);
    };
    uint64_t h = mix(0, uint64_t(k.x));
    h = mix(h, uint64_t(k.y));
    h = mix(h, uint64_t(k.z));
    return size_t(mix(h, k.space));
}

void AreaLimits::pushBack(List& list, Kind kind, uint32_t slot) {
    Link& l = links_[slot][kind];
    l.prev = list.tail;
    l.next = kNone;
    if (list.tail != kNone)
        links_[list.tail][kind].next = slot;
    else
        list.head = slot;
    list.tail = slot;
    list.count++;
}

void AreaLimits::erase(List& list, Kind kind, uint32_t slot) {
    Link& l = links_[slot][kind];
    if (l.prev != kNone)
        links_[l.prev][kind].next = l.next;
    else
        list.head = l.next;
    if (l.next != kNone)
        links_[l.next][kind].prev = l.prev;
    else
        list.tail = l.prev;
    l = Link();
    list.count--;
}

void AreaLimits::link(uint32_t slot, const CellKey& key, uint32_t object) {
    if (slot >= links_.size()) {
        links_.resize(slot + 1);
        keys_.resize(slot + 1);
        objectOf_.resize(slot + 1, 0);
        linked_.resize(slot + 1, false);
    }
    if (object >= objects_.size()) objects_.resize(object + 1);
    keys_[slot] = key;
    objectOf_[slot] = object;
    linked_[slot] = true;
    pushBack(cells_[key], kCell, slot);
    pushBack(objects_[object], kObject, slot);
    pushBack(global_, kGlobal, slot);
}

void AreaLimits::unlink(uint32_t slot) {
    if (!linked(slot)) return;
    auto cell = cells_.find(keys_[slot]);
    erase(cell->second, kCell, slot);
    if (cell->second.count == 0) cells_.erase(cell);
    erase(objects_[objectOf_[slot]], kObject, slot);
    erase(global_, kGlobal, slot);
    linked_[slot] = false;
}

uint32_t AreaLimits::cellCount(const CellKey& key) const {
    auto it = cells_.find(key);
    return it == cells_.end() ? 0 : it->second.count;
}

uint32_t AreaLimits::oldestInCell(const CellKey& key) const {
    auto it = cells_.find(key);
    return it == cells_.end() ? kNone : it->second.head;
}

} // namespace spatter
