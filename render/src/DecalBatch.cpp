#include "DecalBatch.hpp"

#include "SparseRuns.hpp"

#include <algorithm>
#include <cmath>

namespace spatter::render_detail {

void DecalBatch::configure(float wrapMaxAngleDeg, std::vector<glm::vec4> cutouts) {
    if (wrapMaxAngleDeg == wrapMaxAngleDeg_ && cutouts == cutouts_) return;
    wrapMaxAngleDeg_ = wrapMaxAngleDeg;
    cutouts_ = std::move(cutouts);
    rebuildTypes();
}

void DecalBatch::setTypes(std::vector<DecalType> types) {
    types_ = std::move(types);
    rebuildTypes();
}

void DecalBatch::setHostDrawn(std::vector<uint8_t> types, std::vector<uint8_t> objects) {
    hostTypes_ = std::move(types);
    hostObjects_ = std::move(objects);
    rebuildTypes();
}

void DecalBatch::rebuildTypes() {
    typeRecords_.clear();
    std::vector<int> priorities;
    for (size_t i = 0; i < types_.size(); ++i) {
        const DecalType& t = types_[i];
        typeRecords_.push_back(buildDecalType(t, wrapMaxAngleDeg_, cutouts_));
        if (i < hostTypes_.size() && hostTypes_[i] != 0) typeRecords_.back().info.z = 2; // the host's
        priorities.push_back(t.priority);
    }
    std::sort(priorities.begin(), priorities.end());
    priorities.erase(std::unique(priorities.begin(), priorities.end()), priorities.end());
    std::vector<uint32_t> ranks;
    for (const DecalType& t : types_)
        ranks.push_back(uint32_t(std::lower_bound(priorities.begin(), priorities.end(), t.priority) -
                                 priorities.begin()));
    if (ranks != typeRank_) ranksChanged_ = true; // the order is laid out afresh with the next decals
    typeRank_ = std::move(ranks);
}

void DecalBatch::setMirrorLimit(size_t limit) {
    mirrorLimit_ = limit;
    if (mirror_ && size() >= limit) {
        std::vector<DecalRecordGpu>().swap(records_); // frees the memory, which "= {}" keeps
        mirror_ = false;
        order_.setMirrored(false);
    }
}

void DecalBatch::setDecals(const std::vector<Decal>& decals) {
    ranksChanged_ = false;
    order_.rebuild(decals, typeRank_);
    sound_.assign(decals.size(), true);
    unsound_ = 0;
    mirror_ = decals.size() < mirrorLimit_;
    order_.setMirrored(mirror_);
    records_ = mirror_ ? std::vector<DecalRecordGpu>(decals.size()) : std::vector<DecalRecordGpu>{};
    staged_.clear();
    typeBound_ = 0;
    std::vector<uint32_t> all(decals.size());
    for (size_t i = 0; i < all.size(); ++i)
        all[i] = uint32_t(i);
    stage(decals, std::move(all));
}

void DecalBatch::applyChanges(const std::vector<Decal>& decals, const DecalChanges& changes) {
    std::vector<uint32_t> stale;
    if (!changes.complete || ranksChanged_ || !replay(decals, changes, stale)) {
        setDecals(decals);
        return;
    }
    order_.place(decals, typeRank_);
    updateMirror(decals);
    stage(decals, std::move(stale));
}

// Replays `changes` on the order, the validity bits and the CPU copy; false when they do not fit.
bool DecalBatch::replay(const std::vector<Decal>& decals, const DecalChanges& changes,
                        std::vector<uint32_t>& stale) {
    for (const DecalChange& c : changes.changes) {
        const size_t n = size();
        if (c.kind == DecalChangeKind::Added) {
            if (c.index != n) return false;
            order_.add(c.index);
            sound_.push_back(true);
            if (mirror_) records_.emplace_back();
        } else if (c.kind == DecalChangeKind::Removed) {
            if (c.index >= n || c.from != n - 1) return false;
            order_.remove(c.index, c.from);
            unsound_ -= sound_[c.index] ? 0 : 1;
            sound_[c.index] = sound_[c.from];
            sound_.pop_back();
            if (mirror_) {
                records_[c.index] = records_[c.from];
                records_.pop_back();
            }
            if (c.index == c.from) continue;
        } else if (c.index >= n) {
            return false;
        }
        stale.push_back(c.index);
    }
    return size() == decals.size();
}

// Builds the records of the decals at `stale` (those past the end are gone) and stages them.
void DecalBatch::stage(const std::vector<Decal>& decals, std::vector<uint32_t> stale) {
    stale.erase(std::remove_if(stale.begin(), stale.end(), [&](uint32_t i) { return i >= decals.size(); }),
                stale.end());
    for (const auto& [begin, end] : sparseRuns(std::move(stale), 4)) {
        StagedRecords run;
        run.begin = begin;
        run.records.resize(end - begin);
        for (size_t i = begin; i < end; ++i) {
            typeBound_ = std::max(typeBound_, size_t(decals[i].type) + 1);
            setValid(i, buildDecalRecord(decals[i], run.records[i - begin]));
            if (mirror_) records_[i] = run.records[i - begin];
        }
        staged_.push_back(std::move(run));
    }
}

void DecalBatch::setValid(size_t i, bool sound) {
    if (sound_[i] == sound) return;
    unsound_ += sound ? size_t(-1) : 1;
    sound_[i] = sound;
}

// Keeps the CPU copy below the mirror limit (taking it from `decals` when it was not kept) and drops
// it above.
void DecalBatch::updateMirror(const std::vector<Decal>& decals) {
    const bool want = decals.size() < mirrorLimit_;
    if (want == mirror_) return;
    mirror_ = want;
    order_.setMirrored(want);
    std::vector<DecalRecordGpu>().swap(records_);
    if (!want) return;
    records_.resize(decals.size());
    for (size_t i = 0; i < decals.size(); ++i)
        buildDecalRecord(decals[i], records_[i]);
}

size_t DecalBatch::invalidCount() const {
    return unsound_;
}

bool DecalBatch::typesPlain() const {
    return typeBound_ <= typeRecords_.size() &&
           std::all_of(typeRecords_.begin(), typeRecords_.end(),
                       [](const DecalTypeGpu& t) { return t.info.z == 1u; });
}

uint32_t DecalBatch::flagsUnion() const {
    uint32_t flags = kDecalMirrored;
    for (const DecalTypeGpu& t : typeRecords_)
        flags |= t.info.z == 1 ? t.info.y : 0u;
    return flags;
}

bool DecalBatch::hostDrawn(const DecalRecordGpu& r) const {
    return (recordType(r) < typeRecords_.size() && typeRecords_[recordType(r)].info.z == 2) ||
           hostDrawnObject(r.info.x);
}

bool DecalBatch::valid(size_t i) const {
    if (!mirror_ || i >= records_.size() || !sound_[i]) return false;
    const DecalRecordGpu& r = records_[i];
    return r.info.x < objectCount_ && recordType(r) < typeRecords_.size() &&
           typeRecords_[recordType(r)].info.z != 0;
}

size_t DecalBatch::cpuBytes() const {
    size_t bytes = order_.cpuBytes() + sound_.capacity() / 8 + records_.capacity() * sizeof(DecalRecordGpu) +
                   typeRecords_.capacity() * sizeof(DecalTypeGpu) +
                   staged_.capacity() * sizeof(StagedRecords);
    for (const StagedRecords& run : staged_)
        bytes += run.records.capacity() * sizeof(DecalRecordGpu);
    return bytes;
}

void DecalBatch::markUploaded() {
    std::vector<StagedRecords>().swap(staged_);
}

} // namespace spatter::render_detail
