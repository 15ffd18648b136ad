#pragma once
// The smallest power of two at or above a size: the screen tiles' runs (DecalProjector) are sized so.

#include <cstdint>

namespace spatter::render_detail {

// 1 for 0.
inline uint64_t nextPowerOfTwo(uint64_t v) {
    uint64_t p = 1;
    while (p < v)
        p *= 2;
    return p;
}

} // namespace spatter::render_detail
