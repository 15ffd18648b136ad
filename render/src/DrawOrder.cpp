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

} // namespace

void DrawOrder::rebuild(const std::vector<Decal>& decals, const std::vector<uint32_t>& typeRank) {
    std::vector<uint32_t> order(decals.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        const uint32_t ra = rankOf(decals[a], typeRank), rb = rankOf(decals[b], typeRank);
        if (ra != rb) return ra < rb;
        const double ta = timeOf(decals[a]), tb = timeOf(decals[b]);
        return ta != tb ? ta < tb : a < b;
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
    std::vector<size_t> wanted(regions_.size(), 0);
    bool fits = true;
    size_t live = 0, empty = 0;
    for (const Region& g : regions_) {
        live += g.used - g.empty;
        empty += g.empty;
    }
    for (const uint32_t i : pending_) {
        if (i == kEmpty) continue;
        const uint32_t r = rankOf(decals[i], typeRank);
        if (r >= regions_.size() || regions_[r].used + ++wanted[r] > regions_[r].size) fits = false;
    }
    if (fits && empty <= live + 64) { // room, and not mostly holes
        for (const uint32_t i : pending_) {
            if (i == kEmpty) continue;
            Region& g = regions_[rankOf(decals[i], typeRank)];
            pos_[i] = uint32_t(g.start + g.used);
            set(g.start + g.used++, i);
        }
        pending_.clear();
        return;
    }
    // A new layout: the decals there in their order, then the new ones.
    std::vector<uint32_t> rebuilt;
    const std::vector<uint32_t>& entries = held_ ? entries_ : (rebuilt = rebuiltEntries());
    std::vector<std::vector<uint32_t>> byRank(regions_.size());
    for (size_t r = 0; r < regions_.size(); ++r)
        for (size_t e = regions_[r].start; e < regions_[r].start + regions_[r].used; ++e)
            if (entries[e] != kEmpty) byRank[r].push_back(entries[e]);
    for (const uint32_t i : pending_) {
        if (i == kEmpty) continue;
        const uint32_t r = rankOf(decals[i], typeRank);
        if (byRank.size() <= r) byRank.resize(r + 1);
        byRank[r].push_back(i);
    }
    pending_.clear();
    layout(byRank);
}

DrawOrder::Changes DrawOrder::takeChanged(bool all) {
    Changes c;
    c.all = relaid_ || all;
    if (c.all && !held_) {
        entries_ = rebuiltEntries();
        held_ = true;
    }
    if (!c.all && mirrored_) c.runs = sparseRuns(std::move(changed_), 64);
    if (!c.all && !mirrored_) {
        // The last write of each entry, in entry order.
        std::stable_sort(writes_.begin(), writes_.end(),
                         [](const glm::uvec2& a, const glm::uvec2& b) { return a.x < b.x; });
        for (size_t i = 0; i < writes_.size(); ++i)
            if (i + 1 == writes_.size() || writes_[i + 1].x != writes_[i].x) c.writes.push_back(writes_[i]);
    }
    changed_.clear();
    std::vector<glm::uvec2>().swap(writes_);
    relaid_ = false;
    return c;
}

void DrawOrder::uploaded() {
    if (mirrored_ || !held_) return;
    std::vector<uint32_t>().swap(entries_);
    held_ = false;
}

void DrawOrder::setMirrored(bool mirrored) {
    if (mirrored == mirrored_) return;
    mirrored_ = mirrored;
    if (mirrored) {
        if (!held_) entries_ = rebuiltEntries();
        held_ = true;
        for (const glm::uvec2& w : writes_) // not taken yet: uploaded as changed entries
            changed_.push_back(w.x);
        std::vector<glm::uvec2>().swap(writes_);
        return;
    }
    // The GPU's copy may be behind (the CPU culled): all of it goes up next, then the entries go.
    changed_.clear();
    relaid_ = true;
}

std::vector<uint32_t> DrawOrder::rebuiltEntries() const {
    std::vector<uint32_t> entries(size_, kEmpty);
    for (size_t d = 0; d < pos_.size(); ++d)
        if (!(pos_[d] & kPending)) entries[pos_[d]] = uint32_t(d);
    return entries;
}

void DrawOrder::layout(const std::vector<std::vector<uint32_t>>& byRank) {
    regions_.assign(std::max<size_t>(1, byRank.size()), Region{});
    size_t start = 0;
    for (size_t r = 0; r < regions_.size(); ++r) {
        const size_t n = r < byRank.size() ? byRank[r].size() : 0;
        regions_[r] = Region{start, n + n / 4 + 64, n, 0}; // room to grow by a quarter before the next layout
        start += regions_[r].size;
    }
    size_ = start;
    entries_.assign(start, kEmpty);
    held_ = true;
    for (size_t r = 0; r < byRank.size(); ++r)
        for (size_t k = 0; k < byRank[r].size(); ++k) {
            entries_[regions_[r].start + k] = byRank[r][k];
            pos_[byRank[r][k]] = uint32_t(regions_[r].start + k);
        }
    changed_.clear();
    std::vector<glm::uvec2>().swap(writes_);
    relaid_ = true;
}

void DrawOrder::set(size_t entry, uint32_t value) {
    if (held_) entries_[entry] = value;
    if (relaid_) return;
    if (mirrored_)
        changed_.push_back(uint32_t(entry));
    else
        writes_.push_back({uint32_t(entry), value});
}

size_t DrawOrder::regionOf(size_t entry) const {
    size_t r = 0;
    while (r + 1 < regions_.size() && regions_[r + 1].start <= entry)
        ++r;
    return r;
}

} // namespace spatter::render_detail
