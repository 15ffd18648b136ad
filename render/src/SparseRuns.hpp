#pragma once
// Runs of changed elements to upload: the sorted, distinct positions joined into [begin, end) ranges
// where the gap between them is at most `maxGap` elements (sending a few unchanged elements costs
// less than another upload call).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace spatter::render_detail {

inline std::vector<std::pair<size_t, size_t>> sparseRuns(std::vector<uint32_t> positions, size_t maxGap) {
    std::sort(positions.begin(), positions.end());
    std::vector<std::pair<size_t, size_t>> runs;
    for (const uint32_t p : positions) {
        if (!runs.empty() && p < runs.back().second + maxGap + 1) {
            runs.back().second = std::max(runs.back().second, size_t(p) + 1);
            continue;
        }
        runs.emplace_back(p, size_t(p) + 1);
    }
    return runs;
}

} // namespace spatter::render_detail
