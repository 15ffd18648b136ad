#pragma once
// Internal to core: what HausdorffSurface prepares of a mesh (HausdorffSurface.cpp) and the certifier
// reads (HausdorffBound.cpp, SampledLowerBound.cpp): its surface triangles in a bounding-volume
// hierarchy, its closest-point query, and the tables made at their first use.

#include "spatter/core/HausdorffBound.hpp"

#include "PieceOverlay.hpp"
#include "SharedTriangles.hpp"

#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <optional>
#include <vector>

namespace spatter {

namespace detail {

// A node of the hierarchy: the box of its triangles, their range, its children.
struct HausdorffNode {
    glm::dvec3 lo{0.0}, hi{0.0};
    uint32_t first = 0, count = 0; // range of HausdorffSurface::Impl::triangles
    uint32_t child = 0;            // first of two children (child + 1 is the second); 0 for a leaf
};

// Triangles two surfaces share are looked for only where the larger has at most this many times the
// smaller's triangles. A proxy keeps fewer of the render mesh's triangles as they are the smaller it is
// (DamagedHelmet: 58% of the proxy's at 0.2%, 1.6 times smaller; 10% at 1%, 4.8 times; 6% at 2%), and
// the table of the larger's triangles costs about 85 ns a triangle (6 ms for the 69,451-triangle
// bunny): looked for up to 8 times, the builds between 4 and 8 times came out 0.97x to 1.08x of the
// time, none faster.
constexpr size_t kShareRatio = 4;

// Whether the triangles a surface of `larger` triangles shares with one of `smaller` are looked for.
inline bool looksForShared(size_t larger, size_t smaller) {
    return larger <= kShareRatio * smaller;
}

} // namespace detail

struct HausdorffSurface::Impl {
    std::vector<glm::dvec3> positions;
    std::vector<uint32_t> indices;                  // the mesh's, so that query results index them
    std::vector<std::array<uint32_t, 3>> triangles; // surface triangles' corners, in hierarchy order
    std::vector<detail::HausdorffNode> nodes;       // nodes[0] is the root
    std::vector<uint32_t> meshTriangles;            // the mesh's index of each of `triangles`
    ClosestPointQuery query;
    double scale = 0.0;        // largest absolute coordinate of a surface vertex
    double triangleArea = 0.0; // mean area of a surface triangle

    explicit Impl(ClosestPointQuery q) : query(std::move(q)) {}

    glm::dvec3 corner(uint32_t meshTriangle, int k) const {
        return positions[indices[3 * size_t(meshTriangle) + size_t(k)]];
    }

    // The triangles across each edge (the side measured to, for the overlay bound), made at the first
    // call: most bounds never lay a piece over this side.
    const detail::EdgeNeighbours& neighbours() const {
        std::call_once(neighboursMade_,
                       [this] { neighbours_ = detail::edgeNeighbours(positions, indices, meshTriangles); });
        return neighbours_;
    }

    // The surface triangles by their corners, to find those another surface shares, made at the first
    // call: a render mesh bounded against many candidates tables its triangles once.
    const detail::TriangleCorners& corners() const {
        std::call_once(cornersMade_, [this] { corners_.emplace(positions, triangles); });
        return *corners_;
    }

private:
    mutable std::once_flag neighboursMade_;
    mutable detail::EdgeNeighbours neighbours_;
    mutable std::once_flag cornersMade_;
    mutable std::optional<detail::TriangleCorners> corners_;
};

} // namespace spatter
