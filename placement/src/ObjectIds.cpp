#include "spatter/placement/ObjectIds.hpp"

#include "spatter/core/Random.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

namespace spatter {

double boundsDistance(const DBounds& a, const DBounds& b) {
    if (a.empty() || b.empty()) return std::numeric_limits<double>::infinity();
    const glm::dvec3 gap = glm::max(glm::dvec3(0.0), glm::max(a.min - b.max, b.min - a.max));
    return glm::length(gap);
}

ObjectIdAssignment assignObjectIds(const std::vector<DBounds>& bounds, const std::vector<bool>& dynamic,
                                   double separation, uint64_t seed) {
    ObjectIdAssignment out;
    const size_t n = bounds.size();
    out.ids.assign(n, 0);
    const double sep = std::isfinite(separation) ? std::max(separation, 0.0) : 0.0;

    // Neighbour lists by sweeping the dynamic objects sorted on their lower x bound.
    std::vector<uint32_t> order;
    for (size_t i = 0; i < n; ++i)
        if (i < dynamic.size() && dynamic[i]) order.push_back(uint32_t(i));
    std::vector<uint32_t> sweep;
    for (uint32_t i : order)
        if (!bounds[i].empty()) sweep.push_back(i);
    std::sort(sweep.begin(), sweep.end(), [&](uint32_t a, uint32_t b) {
        return bounds[a].min.x < bounds[b].min.x || (bounds[a].min.x == bounds[b].min.x && a < b);
    });
    std::vector<std::vector<uint32_t>> neighbours(n);
    for (size_t s = 0; s < sweep.size(); ++s) {
        const DBounds& a = bounds[sweep[s]];
        for (size_t r = s + 1; r < sweep.size() && bounds[sweep[r]].min.x <= a.max.x + sep; ++r) {
            if (boundsDistance(a, bounds[sweep[r]]) <= sep) {
                neighbours[sweep[s]].push_back(sweep[r]);
                neighbours[sweep[r]].push_back(sweep[s]);
            }
        }
    }

    // Greedy colouring, most constrained first.
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return neighbours[a].size() > neighbours[b].size(); });
    Rng rng(seed, 0x0b1ec7d5u);
    for (uint32_t i : order) {
        std::array<uint32_t, 256> used{};
        for (uint32_t j : neighbours[i])
            used[out.ids[j]]++;
        std::vector<uint8_t> free;
        for (int id = 1; id <= 255; ++id)
            if (used[id] == 0) free.push_back(uint8_t(id));
        if (!free.empty()) {
            out.ids[i] = free[rng.below(uint32_t(free.size()))];
        } else {
            int best = 1;
            for (int id = 2; id <= 255; ++id)
                if (used[id] < used[best]) best = id;
            out.ids[i] = uint8_t(best);
        }
    }
    for (uint32_t i : order)
        for (uint32_t j : neighbours[i])
            if (i < j && out.ids[i] == out.ids[j]) out.sharedPairs++;
    return out;
}

} // namespace spatter
