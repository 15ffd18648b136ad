#pragma once
// Object decal IDs: the 8-bit ID each object writes into the G-buffer and each of its decals
// carries, so that a decal never draws over a different object that happens to lie inside its box.
// Static geometry shares ID 0; each dynamic object gets one of 1..255, chosen so that objects whose
// bounds lie within a set distance of each other never share one while that is possible.

#include "spatter/core/Bounds.hpp"

#include <cstdint>
#include <vector>

namespace spatter {

struct ObjectIdAssignment {
    std::vector<uint8_t> ids; // one per object: 0 for static, 1..255 for dynamic
    uint32_t sharedPairs = 0; // pairs of neighbouring dynamic objects that had to share an ID
};

// Assigns IDs by greedy colouring of the neighbourhood graph of the dynamic objects (an edge joins
// two objects whose world bounds are at most `separation` apart; objects with empty bounds have no
// neighbours). Objects are coloured in order of decreasing neighbour count (then index); each takes
// an ID drawn with a generator seeded by `seed` from those its coloured neighbours do not use, so
// objects that later move next to each other are unlikely to share one. When every ID is taken
// around an object (more than 254 neighbours), it takes the one fewest of its neighbours use and
// sharedPairs counts the resulting pairs. Same inputs, same IDs. `dynamic` has one entry per
// object, like `bounds`; missing entries count as static.
ObjectIdAssignment assignObjectIds(const std::vector<DBounds>& bounds, const std::vector<bool>& dynamic,
                                   double separation, uint64_t seed);

// Distance between two boxes (0 when they touch or overlap; infinity when either is empty).
double boundsDistance(const DBounds& a, const DBounds& b);

} // namespace spatter
