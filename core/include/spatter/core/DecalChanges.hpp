#pragma once
// DecalChanges: what happened to a dense decal array (DecalSystem::decals()) between two versions of
// it, so that a consumer that keeps its own copy of the decals (a renderer's GPU buffer, a network
// replica, an editor view) updates only the records that changed instead of copying or diffing all of
// them every frame. Placing a decal appends one record, removing one moves the last record into its
// hole, and fading changes one record in place; a frame typically touches a handful of a large set.
//
// Use (the producer's changesSince(version) fills a DecalChanges):
//   DecalChanges c = system.changesSince(myVersion);
//   if (!c.complete) { take system.decals() whole; }
//   else for (const DecalChange& ch : c.changes) apply it to my copy (below);
//   myVersion = c.version;
//
// The changes carry no decal values: they say which records moved, appeared or changed, and the
// values are read from the producer's array as it is now. Replayed in order, keeping a "stale" flag
// per record of the copy:
//   Added:   append a record, stale;
//   Changed: mark the record at `index` stale;
//   Removed: when index != from, the record at `from` (with its stale flag) moves into `index`; then
//            drop the last record;
// after the last change the copy has the producer's size and order, and the stale records, read from
// decals()[i] at their indices, make it equal to decals(). A GPU store does the same with a copy
// from `from` to `index` on the GPU (or a re-upload when that record is stale) per removal, and one
// upload per stale record at the end.

#include <cstdint>
#include <vector>

namespace spatter {

enum class DecalChangeKind : uint8_t {
    Added,   // a new decal at `index`, which is the previous size (appended)
    Changed, // the decal at `index` changed in place (its opacity, centre, frame, size, depth or
             // slant: re-read it whole)
    Removed, // the decal at `index` is gone; the last decal (at `from` = previous size - 1) moves into
             // `index` when index != from; the size shrinks by one
};

struct DecalChange {
    uint32_t index = 0;
    uint32_t from = 0; // Removed: the previous size - 1; Added and Changed: equal to index
    DecalChangeKind kind = DecalChangeKind::Added;
};

static_assert(sizeof(DecalChange) <= 12, "a DecalChange grew past 12 bytes");

struct DecalChanges {
    uint64_t version = 0; // the version of decals() these changes lead to: pass it to the next changesSince
    bool complete = true; // false: the changes since the version asked for are no longer kept (or that
                          // version is unknown); take decals() whole; `changes` is then empty
    std::vector<DecalChange> changes; // in order: replayed on a copy of decals() as it was at the version
                                      // asked for, they give decals() as it is now
};

} // namespace spatter
