#include "ChangeLog.hpp"

#include <algorithm>
#include <string>

namespace spatter {

namespace {

// The array's size before a change of `kind` that left it `after` long (an addition made it one
// longer, a removal one shorter).
uint64_t sizeBefore(DecalChangeKind kind, uint64_t after) {
    if (kind == DecalChangeKind::Added) return after - 1;
    if (kind == DecalChangeKind::Removed) return after + 1;
    return after;
}

} // namespace

void ChangeLog::append(uint32_t index, DecalChangeKind kind, size_t decals) {
    const size_t bound = std::max(kMinEntries, decals / 4);
    if (index_.size() >= bound) {
        const auto drop = std::ptrdiff_t(index_.size() - bound / 2);
        index_.erase(index_.begin(), index_.begin() + drop);
        kind_.erase(kind_.begin(), kind_.begin() + drop);
        base_ += uint64_t(drop);
        if (index_.capacity() > 2 * bound) {
            index_.shrink_to_fit();
            kind_.shrink_to_fit();
        }
    }
    if (index_.size() == index_.capacity()) {
        const size_t room = std::min(bound, std::max<size_t>(256, 2 * index_.size()));
        index_.reserve(room);
        kind_.reserve(room);
    }
    index_.push_back(index);
    kind_.push_back(kind);
}

bool ChangeLog::since(uint64_t version, size_t decals, std::vector<DecalChange>& out) const {
    out.clear();
    if (version < base_ || version > this->version()) return false;
    const size_t first = size_t(version - base_);
    out.resize(index_.size() - first);
    uint64_t size = decals; // the array's size after entry k
    for (size_t k = index_.size(); k-- > first;) {
        DecalChange& c = out[k - first];
        c.index = index_[k];
        c.kind = kind_[k];
        c.from = c.kind == DecalChangeKind::Removed ? uint32_t(size) : c.index;
        size = sizeBefore(c.kind, size);
    }
    return true;
}

void ChangeLog::assign(uint64_t base, const std::vector<DecalChange>& entries) {
    base_ = base;
    index_.clear();
    kind_.clear();
    index_.reserve(entries.size());
    kind_.reserve(entries.size());
    for (const DecalChange& c : entries) {
        index_.push_back(c.index);
        kind_.push_back(c.kind);
    }
}

Status checkChangeLog(const std::vector<DecalChange>& entries, size_t decals) {
    uint64_t size = decals; // after entry k
    for (size_t k = entries.size(); k-- > 0;) {
        const DecalChange& c = entries[k];
        bool fits = c.index < size && c.from == c.index; // a change inside the array
        if (c.kind == DecalChangeKind::Added) fits = size > 0 && c.index == size - 1 && c.from == c.index;
        if (c.kind == DecalChangeKind::Removed) fits = c.from == size && c.index <= c.from;
        if (!fits)
            return fail("change " + std::to_string(k) + " of the log (index " + std::to_string(c.index) +
                        ", from " + std::to_string(c.from) + ") does not lead to the " +
                        std::to_string(decals) + " decals saved");
        size = sizeBefore(c.kind, size);
    }
    return {};
}

} // namespace spatter
