#pragma once
// Internal to placement: the set of decals DecalSystem::update() visits, walked from the highest
// dense index down.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace spatter {

// A set of dense indices: one bit per index and one summary bit per 64 of them (set when any of the
// 64 is), so the set members are found from the highest down in O(members + size / 4096) words.
// DecalSystem::update() keeps the decals it has to visit in one.
class DenseIndexSet {
public:
    bool test(uint32_t i) const {
        const size_t w = i >> 6;
        return w < words_.size() && ((words_[w] >> (i & 63)) & 1u) != 0;
    }
    void set(uint32_t i) {
        const size_t w = i >> 6;
        if (w >= words_.size()) {
            words_.resize(w + 1, 0);
            summary_.resize((words_.size() + 63) >> 6, 0);
        }
        words_[w] |= uint64_t(1) << (i & 63);
        summary_[w >> 6] |= uint64_t(1) << (w & 63);
    }
    void reset(uint32_t i) {
        const size_t w = i >> 6;
        if (w >= words_.size()) return;
        words_[w] &= ~(uint64_t(1) << (i & 63));
        if (words_[w] == 0) summary_[w >> 6] &= ~(uint64_t(1) << (w & 63));
    }
    static constexpr uint32_t kNone = UINT32_MAX;

    // The highest member below `end`, or kNone.
    uint32_t highestBelow(uint32_t end) const {
        if (end == 0 || words_.empty()) return kNone;
        const size_t top = (end - 1) >> 6;
        size_t w = std::min(top, words_.size() - 1);
        const uint64_t word = w == top ? words_[w] & upTo((end - 1) & 63) : words_[w];
        if (word != 0) return uint32_t(w * 64 + highestBit(word));
        if (w == 0) return kNone;
        --w; // the highest non-empty word at or below w, through the summary
        size_t s = w >> 6;
        for (uint64_t bits = summary_[s] & upTo(w & 63);; bits = summary_[--s]) {
            if (bits != 0) {
                const size_t found = s * 64 + highestBit(bits);
                return uint32_t(found * 64 + highestBit(words_[found]));
            }
            if (s == 0) return kNone;
        }
    }

    size_t bytes() const { return (words_.capacity() + summary_.capacity()) * sizeof(uint64_t); }

private:
    static uint64_t upTo(unsigned bit) { return (uint64_t(2) << bit) - 1; } // bits 0..bit
    static unsigned highestBit(uint64_t v) { return 63u - unsigned(__builtin_clzll(v)); }

    std::vector<uint64_t> words_;
    std::vector<uint64_t> summary_;
};

} // namespace spatter
