#pragma once
// Internal to core: the triangles two surfaces share corner for corner (the same three positions, in
// any order). meshoptimizer keeps the render mesh's vertices where it simplifies, and at a fine
// tolerance many of its triangles as they are (DamagedHelmet at 0.2%: most of the proxy's). A shared
// triangle lies on both surfaces, so every distance from it to the other surface is 0: the certificate
// (HausdorffBound.cpp) bounds none of it, and its drawn normals are its own render triangle's.

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace spatter::detail {

// A surface's triangles in an open-addressing table keyed by their corners, to look up another
// surface's triangles in it. Holds no reference to the surface: each lookup is handed it again.
class TriangleCorners {
public:
    using Triangles = std::vector<std::array<uint32_t, 3>>;

    TriangleCorners(const std::vector<glm::dvec3>& positions, const Triangles& triangles);

    // Calls found(i) for each triangle i of the surface (the one it was built from: `positions`,
    // `triangles`) whose corners are p's, in any order.
    template <class Found>
    void forEachSame(const std::vector<glm::dvec3>& positions, const Triangles& triangles,
                     const std::array<glm::dvec3, 3>& p, Found&& found) const {
        if (slots_.empty()) return;
        const std::array<glm::dvec3, 3> key = sortedCorners(p);
        const uint64_t h = hashCorners(key);
        for (size_t i = h & mask_; slots_[i].triangle != kEmpty; i = (i + 1) & mask_) {
            if (slots_[i].hash != h) continue;
            const std::array<uint32_t, 3>& t = triangles[slots_[i].triangle];
            if (sortedCorners({positions[t[0]], positions[t[1]], positions[t[2]]}) == key)
                found(slots_[i].triangle);
        }
    }

    // The corners in lexicographic order (x, then y, then z), so that a triangle's key does not
    // depend on where its corners start or which way they turn.
    static std::array<glm::dvec3, 3> sortedCorners(std::array<glm::dvec3, 3> p);
    // A hash of sorted corners, the same for -0 and +0 (which compare equal).
    static uint64_t hashCorners(const std::array<glm::dvec3, 3>& sorted);

private:
    static constexpr uint32_t kEmpty = UINT32_MAX;
    struct Slot {
        uint64_t hash = 0;
        uint32_t triangle = kEmpty;
    };
    std::vector<Slot> slots_; // a power of two, at least twice the triangles
    size_t mask_ = 0;
};

} // namespace spatter::detail
