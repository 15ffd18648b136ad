#include "DrawOrder.hpp"

#include "SparseRuns.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace spatter::render_detail {

namespace {

uint32_t rankOf(const Decal& d, const std::vector<uint32_t>& typeRank) {
    return d.type < typeRank.size() ? typeRank[d.type] : 0u;
}

// A spawn time that is not a number sorts as 0, keeping the order strict.
double timeOf(const Decal& d) {
    return std::isfinite(d.spawnTime) ? d.spawnTime : 0.0;
}

// The order within a priority: by spawn time, then by decal ID (decals spawned at one time, in one
// frame, draw in the same order whether they arrive together or one by one), then by index.
struct Newer {
    const std::vector<Decal>& decals;
    bool operator()(uint32_t a, uint32_t b) const {
        const double ta = timeOf(decals[a]), tb = timeOf(decals[b]);
        if (ta != tb) return ta < tb;
        return decals[a].id != decals[b].id ? decals[a].id < decals[b].id : a < b;
    }
};

} // namespace

void DrawOrder::rebuild(const std::vector<Decal>& decals, const std::vector<uint32_t>& typeRank) {
    std::vector<uint32_t> order(decals.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        const uint32_t ra = rankOf(decals[a], typeRank), rb = rankOf(decals[b], typeRank);
        return ra != rb ? ra < rb : Newer{decals}(a, b);
    });
    std::vector<std::vector<uint32_t>> byRank;
    for (const uint32_t i : order) {
        const uint32_t r = rankOf(decals[i], typeRank);
        if (byRank.size() <= r) byRank.resize(r + 1);
        byRank[r].push_back(i);
    }
    pos_.assign(decals.size(), kEmpty);
    pending_.clear();
    layout(byRank);
}

void DrawOrder::add(uint32_t index) {
    pos_.push_back(kPending | uint32_t(pending_.size()));
    pending_.push_back(index);
}

void DrawOrder::remove(uint32_t index, uint32_t from) {
    const uint32_t p = pos_[index];
    if (p & kPending) {
        pending_[p & ~kPending] = kEmpty;
    } else {
        set(p, kEmpty);
        regions_[regionOf(p)].empty++;
    }
    if (index != from) {
        const uint32_t q = pos_[from];
        if (q & kPending)
            pending_[q & ~kPending] = index;
        else
            set(q, index);
        pos_[index] = q;
    }
    pos_.pop_back();
}

void DrawOrder::place(const std::vector<Decal>& decals, const std::vector<uint32_t>& typeRank) {
    // The new decals by priority, each in draw order.
    std::vector<std::vector<uint32_t>> added(regions_.size());
    for (const uint32_t i : pending_) {
        if (i == kEmpty) continue;
        const uint32_t r = rankOf(decals[i], typeRank);
        if (added.size() <= r) added.resize(r + 1);
        added[r].push_back(i);
    }
    pending_.clear();
    for (std::vector<uint32_t>& a : added)
        std::sort(a.begin(), a.end(), Newer{decals});
    bool fits = added.size() == regions_.size();
    size_t live = 0, empty = 0;
    for (size_t r = 0; r < regions_.size(); ++r) {
        live += regions_[r].used - regions_[r].empty;
        empty += regions_[r].empty;
        fits = fits && regions_[r].used + added[r].size() <= regions_[r].size;
    }
    if (fits && empty <= live + 64) { // room, and not mostly holes
        for (size_t r = 0; r < regions_.size(); ++r)
            if (!added[r].empty()) mergeIntoTail(r, added[r], decals);
        return;
    }
    // A new layout: the decals there in their order, the new ones merged in.
    std::vector<std::vector<uint32_t>> byRank(std::max(regions_.size(), added.size()));
    for (size_t r = 0; r < byRank.size(); ++r) {
        if (r < regions_.size())
            for (size_t e = regions_[r].start; e < regions_[r].start + regions_[r].used; ++e)
                if (entries_[e] != kEmpty) byRank[r].push_back(entries_[e]);
        if (r >= added.size()) continue;
        const size_t middle = byRank[r].size();
        byRank[r].insert(byRank[r].end(), added[r].begin(), added[r].end());
        std::inplace_merge(byRank[r].begin(), byRank[r].begin() + std::ptrdiff_t(middle), byRank[r].end(),
                           Newer{decals});
    }
    layout(byRank);
}

// Puts `added` (in draw order) at the end of region `r`: after the entries there that draw before
// its first, merged with those that draw after it (decals of the same spawn time with larger IDs),
// whose entries are written again without the holes among them.
void DrawOrder::mergeIntoTail(size_t r, const std::vector<uint32_t>& added,
                              const std::vector<Decal>& decals) {
    Region& g = regions_[r];
    const Newer newer{decals};
    size_t tail = g.start + g.used;
    while (tail > g.start && (entries_[tail - 1] == kEmpty || newer(added.front(), entries_[tail - 1])))
        --tail;
    std::vector<uint32_t> merged;
    for (size_t e = tail; e < g.start + g.used; ++e)
        if (entries_[e] != kEmpty)
            merged.push_back(entries_[e]);
        else
            g.empty--;
    const size_t middle = merged.size();
    merged.insert(merged.end(), added.begin(), added.end());
    std::inplace_merge(merged.begin(), merged.begin() + std::ptrdiff_t(middle), merged.end(), newer);
    const size_t end = g.start + g.used;
    for (size_t k = 0; k < merged.size(); ++k) {
        pos_[merged[k]] = uint32_t(tail + k);
        set(tail + k, merged[k]);
    }
    for (size_t e = tail + merged.size(); e < end; ++e)
        set(e, kEmpty); // the holes the tail had, now past its end
    g.used = tail + merged.size() - g.start;
}

std::vector<std::pair<size_t, size_t>> DrawOrder::takeChanged() {
    std::vector<std::pair<size_t, size_t>> runs;
    if (relaid_)
        runs.emplace_back(0, entries_.size());
    else
        runs = sparseRuns(std::move(changed_), 64);
    changed_.clear();
    relaid_ = false;
    return runs;
}

void DrawOrder::layout(const std::vector<std::vector<uint32_t>>& byRank) {
    regions_.assign(std::max<size_t>(1, byRank.size()), Region{});
    size_t start = 0;
    for (size_t r = 0; r < regions_.size(); ++r) {
        const size_t n = r < byRank.size() ? byRank[r].size() : 0;
        regions_[r] = Region{start, n + n / 4 + 64, n, 0}; // room to grow by a quarter before the next layout
        start += regions_[r].size;
    }
    entries_.assign(start, kEmpty);
    for (size_t r = 0; r < byRank.size(); ++r)
        for (size_t k = 0; k < byRank[r].size(); ++k) {
            entries_[regions_[r].start + k] = byRank[r][k];
            pos_[byRank[r][k]] = uint32_t(regions_[r].start + k);
        }
    changed_.clear();
    relaid_ = true;
}

void DrawOrder::set(size_t entry, uint32_t value) {
    entries_[entry] = value;
    if (!relaid_) changed_.push_back(uint32_t(entry));
}

size_t DrawOrder::regionOf(size_t entry) const {
    size_t r = 0;
    while (r + 1 < regions_.size() && regions_[r + 1].start <= entry)
        ++r;
    return r;
}

} // namespace spatter::render_detail
