#pragma once
// Container growth that stops at the decal budget: per-decal arrays double as usual, but while they
// are below the budget they never grow past it, so that a decal system at its budget (the steady
// state of a game that keeps its decals) holds no unused capacity. Past the budget (decals fading
// out under LimitPolicy::FadeOldest no longer count) they double again.

#include <algorithm>
#include <cstddef>
#include <vector>

namespace spatter {

// Capacity for `size` elements of `v`, grown as above when it has less.
template <class T> void reserveCapped(std::vector<T>& v, size_t size, size_t budget) {
    if (size <= v.capacity()) return;
    size_t next = std::max({size, size_t(16), 2 * v.capacity()});
    if (size <= budget) next = std::min(next, budget);
    v.reserve(next);
}

} // namespace spatter
