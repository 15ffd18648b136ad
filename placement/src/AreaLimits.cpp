#include "AreaLimits.hpp"

#include "CappedGrowth.hpp"

#include <algorithm>

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

AreaLimits::AreaLimits(size_t objectCount, uint32_t budget, uint32_t cellLimit, uint32_t objectLimit)
    : budget_(budget), objects_(objectCount) {
    if (objectLimit < budget) {
        object_.prev = stride_++;
        object_.next = stride_++;
    }
    if (cellLimit < budget) {
        // Up to kSmallCellLimit a cell holds so few counted decals that taking one out of its middle
        // walks its list; the oldest, which evictions take, is the head.
        if (cellLimit > kSmallCellLimit) cell_.prev = stride_++;
        cell_.next = stride_++;
    }
}

CellKey AreaLimits::keyOf(const Cell& c) {
    CellKey k;
    k.x = c.x;
    k.y = c.y;
    k.z = c.z;
    k.space = c.space;
    return k;
}

size_t AreaLimits::hashOf(const Cell& c) {
    return CellKeyHash()(keyOf(c));
}

uint32_t AreaLimits::findCell(const CellKey& key) const {
    if (table_.empty()) return kNone;
    const size_t mask = table_.size() - 1;
    for (size_t i = CellKeyHash()(key) & mask;; i = (i + 1) & mask) {
        const uint32_t c = table_[i];
        if (c == kNone || cells_[c].is(key)) return c;
    }
}

uint32_t AreaLimits::addCell(const CellKey& key) {
    if (2 * (cellsInUse_ + 1) > table_.size()) { // at most half full: rehash into twice the size
        std::vector<uint32_t> old(std::max<size_t>(16, 2 * table_.size()), kNone);
        old.swap(table_);
        const size_t mask = table_.size() - 1;
        for (uint32_t c : old) {
            if (c == kNone) continue;
            size_t i = hashOf(cells_[c]) & mask;
            while (table_[i] != kNone)
                i = (i + 1) & mask;
            table_[i] = c;
        }
    }
    uint32_t c;
    if (freeCells_ != kNone) {
        c = freeCells_;
        freeCells_ = cells_[c].list.head;
    } else {
        c = uint32_t(cells_.size());
        cells_.emplace_back();
    }
    Cell& cell = cells_[c];
    cell.x = key.x;
    cell.y = key.y;
    cell.z = key.z;
    cell.space = key.space;
    cell.list = List();
    const size_t mask = table_.size() - 1;
    size_t i = CellKeyHash()(key) & mask;
    while (table_[i] != kNone)
        i = (i + 1) & mask;
    table_[i] = c;
    cellsInUse_++;
    return c;
}

void AreaLimits::dropCell(uint32_t c) {
    const size_t mask = table_.size() - 1;
    size_t i = hashOf(cells_[c]) & mask;
    while (table_[i] != c)
        i = (i + 1) & mask;
    // Backward-shift deletion: move up every later entry of the run that may not stay behind the hole.
    for (size_t j = (i + 1) & mask; table_[j] != kNone; j = (j + 1) & mask) {
        const size_t home = hashOf(cells_[table_[j]]) & mask;
        // The entry at j may stay when its home lies cyclically in (i, j].
        const bool stays = i < j ? (home > i && home <= j) : (home > i || home <= j);
        if (!stays) {
            table_[i] = table_[j];
            i = j;
        }
    }
    table_[i] = kNone;
    cells_[c].list.head = freeCells_;
    freeCells_ = c;
    cellsInUse_--;
}

void AreaLimits::pushBack(List& list, Links at, uint32_t slot) {
    list.count++;
    if (at.prev != kNone) word(slot, at.prev) = list.tail;
    word(slot, at.next) = kNone;
    if (list.tail != kNone)
        word(list.tail, at.next) = slot;
    else
        list.head = slot;
    list.tail = slot;
}

uint32_t AreaLimits::before(const List& list, uint32_t next, uint32_t slot) const {
    uint32_t prev = kNone;
    for (uint32_t s = list.head; s != slot && s != kNone; s = links_[size_t(s) * stride_ + next])
        prev = s;
    return prev;
}

void AreaLimits::erase(List& list, Links at, uint32_t slot) {
    list.count--;
    const uint32_t prev = at.prev != kNone ? word(slot, at.prev) : before(list, at.next, slot);
    const uint32_t next = word(slot, at.next);
    if (prev != kNone)
        word(prev, at.next) = next;
    else
        list.head = next;
    if (next != kNone && at.prev != kNone)
        word(next, at.prev) = prev;
    else if (next == kNone)
        list.tail = prev;
    if (at.prev != kNone) word(slot, at.prev) = kNone;
    word(slot, at.next) = kNone;
}

void AreaLimits::link(uint32_t slot, const CellKey& key, uint32_t object) {
    if (slot >= cellOf_.size()) {
        reserveCapped(cellOf_, size_t(slot) + 1, budget_);
        reserveCapped(links_, (size_t(slot) + 1) * stride_, size_t(budget_) * stride_);
        cellOf_.resize(size_t(slot) + 1, kNone);
        links_.resize(cellOf_.size() * stride_, kNone);
    }
    if (object >= objects_.size()) objects_.resize(size_t(object) + 1);
    uint32_t c = findCell(key);
    if (c == kNone) c = addCell(key);
    cellOf_[slot] = c;
    pushBack(global_, kGlobal, slot);
    if (object_.next != kNone)
        pushBack(objects_[object], object_, slot);
    else
        objects_[object].count++;
    if (cell_.next != kNone)
        pushBack(cells_[c].list, cell_, slot);
    else
        cells_[c].list.count++;
}

void AreaLimits::unlink(uint32_t slot, uint32_t object) {
    if (!linked(slot)) return;
    const uint32_t c = cellOf_[slot];
    cellOf_[slot] = kNone;
    erase(global_, kGlobal, slot);
    if (object_.next != kNone)
        erase(objects_[object], object_, slot);
    else
        objects_[object].count--;
    if (cell_.next != kNone)
        erase(cells_[c].list, cell_, slot);
    else
        cells_[c].list.count--;
    if (cells_[c].list.count == 0) dropCell(c);
}

CellKey AreaLimits::cellOf(uint32_t slot) const {
    return keyOf(cells_[cellOf_[slot]]);
}

uint32_t AreaLimits::oldestInCell(const CellKey& key) const {
    if (cell_.next == kNone) return cellCount(key) != 0 ? oldest() : kNone;
    const uint32_t c = findCell(key);
    return c == kNone ? kNone : cells_[c].list.head;
}

uint32_t AreaLimits::oldestOfObject(uint32_t object) const {
    if (object_.next == kNone) return objectCount(object) != 0 ? oldest() : kNone;
    return object < objects_.size() ? objects_[object].head : kNone;
}

} // namespace spatter
