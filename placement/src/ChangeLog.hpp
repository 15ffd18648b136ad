#pragma once
// ChangeLog: the decal system's log of the changes to its dense decal array (DecalChanges.hpp),
// newest last, bounded: it keeps at most max(kMinChangeLog, decals / 4) entries and, when full, drops
// the older half (amortised O(1) per entry; its capacity grows to that bound at most).
//
// An entry keeps the change's index and kind, 5 bytes, where a DecalChange takes 12: a removal's
// `from` (the last index before it) is the array's size after it, which walking the log back from the
// array's current size gives for every entry (an addition made it one longer, a removal one shorter).

#include "spatter/core/DecalChanges.hpp"
#include "spatter/core/Result.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace spatter {

class ChangeLog {
public:
    // The entries kept at least.
    static constexpr size_t kMinEntries = 4096;

    // The number of changes logged: the version of the array they lead to.
    uint64_t version() const { return base_ + index_.size(); }
    // The version before the oldest entry kept.
    uint64_t base() const { return base_; }

    // Logs a change; `decals` is the array's size after it.
    void append(uint32_t index, DecalChangeKind kind, size_t decals);
    // The changes from `version` to version() of an array of `decals` now, in order; false, with
    // `out` empty, when `version` is older than base() or newer than version().
    bool since(uint64_t version, size_t decals, std::vector<DecalChange>& out) const;
    // Replaces the log: the version before `entries` and the entries (checkChangeLog holds).
    void assign(uint64_t base, const std::vector<DecalChange>& entries);
    // Bytes of its own allocations (capacities).
    size_t bytes() const { return index_.capacity() * sizeof(uint32_t) + kind_.capacity(); }

private:
    uint64_t base_ = 0;
    std::vector<uint32_t> index_;
    std::vector<DecalChangeKind> kind_; // parallel to index_
};

// Whether `entries`, the newest changes to an array of `decals` now, could have led to it: walked
// back from that size, each addition appended (index == size before, from == index), each removal
// moved the last decal (from == size after, index <= from), each change lay inside the array
// (from == index). The error names the first entry that does not fit.
Status checkChangeLog(const std::vector<DecalChange>& entries, size_t decals);

} // namespace spatter
