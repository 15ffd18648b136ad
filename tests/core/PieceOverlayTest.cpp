// The certifier's overlay (core's internal PieceOverlay): the bound it gives for a piece laid over a
// mesh is never below the piece's largest distance to the mesh, measured densely and exactly, is that
// distance above a flat mesh, and is the caller's cap where the piece reaches past the mesh's border.

#include "PieceOverlay.hpp"
#include "ReferenceGeometry.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/Random.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <functional>
#include <limits>
#include <numeric>
#include <vector>

using namespace spatter;
using namespace spatter::detail;

namespace {

constexpr double kCap = 1.0e3;
constexpr double kEps = 1.0e-9;

// A height field over [0, n]^2 of the x-z plane (makeGrid's, unit cells), y from `height` at the
// grid's points.
struct Grid {
    std::vector<glm::dvec3> positions;
    std::vector<uint32_t> indices;
    EdgeNeighbours neighbours;

    Grid(int n, const std::function<double(int, int)>& height) {
        std::vector<float> lines(size_t(n) + 1);
        for (int i = 0; i <= n; ++i)
            lines[size_t(i)] = float(i);
        const Mesh mesh = makeGrid(lines, lines);
        for (const glm::vec3& p : mesh.positions)
            positions.push_back({p.x, height(int(p.x), int(p.z)), p.z});
        indices = mesh.indices;
        std::vector<uint32_t> all(indices.size() / 3);
        std::iota(all.begin(), all.end(), 0u);
        neighbours = edgeNeighbours(positions, indices, all);
    }

    glm::dvec3 corner(size_t t, int k) const { return positions[indices[3 * t + size_t(k)]]; }

    // The distance from `p` to the grid and its triangle closest to `p`, by the tests' own reference
    // (not the library's closest point, which the overlay uses).
    std::pair<double, uint32_t> closest(const glm::dvec3& p) const {
        std::pair<double, uint32_t> best{std::numeric_limits<double>::infinity(), 0};
        for (uint32_t t = 0; t < indices.size() / 3; ++t) {
            const double d = test::triangleDistance(p, corner(t, 0), corner(t, 1), corner(t, 2));
            if (d < best.first) best = {d, t};
        }
        return best;
    }

    double bound(const std::array<glm::dvec3, 3>& piece) const {
        std::array<uint32_t, 3> near{};
        for (int k = 0; k < 3; ++k)
            near[size_t(k)] = closest(piece[size_t(k)]).second;
        return overlayBound(piece, near, OverlayMesh{positions, indices, neighbours}, kEps, kCap);
    }

    // The piece's largest distance to the grid over a dense barycentric lattice of its points.
    double sampledLargest(const std::array<glm::dvec3, 3>& piece, int steps) const {
        double largest = 0.0;
        for (int i = 0; i <= steps; ++i)
            for (int j = 0; i + j <= steps; ++j) {
                const double u = double(i) / steps, v = double(j) / steps;
                const glm::dvec3 p = piece[0] + u * (piece[1] - piece[0]) + v * (piece[2] - piece[0]);
                largest = std::max(largest, closest(p).first);
            }
        return largest;
    }
};

} // namespace

TEST(PieceOverlay, BoundsAPieceAboveAFlatMeshByItsHeight) {
    const Grid grid(8, [](int, int) { return 0.0; });
    const std::array<glm::dvec3, 3> piece = {glm::dvec3(1.3, 0.25, 1.1), glm::dvec3(6.7, 0.25, 2.2),
                                             glm::dvec3(3.1, 0.25, 6.9)};
    const double bound = grid.bound(piece);
    EXPECT_GE(bound, 0.25);
    EXPECT_LE(bound, 0.25 + 1e-6);
}

// A piece over a flat mesh with one dip far inside it: the triangles around the dip lie wholly under
// the piece, away from every triangle that its edges cross, and only they show the dip's depth. A bound
// that skipped their parts, or whose walk stopped at them, would give the flat mesh's 0.25.
TEST(PieceOverlay, BoundsADipWhollyUnderThePieceByItsDepth) {
    const Grid grid(12, [](int x, int z) { return x == 4 && z == 4 ? -0.5 : 0.0; });
    const std::array<glm::dvec3, 3> piece = {glm::dvec3(0.5, 0.25, 0.5), glm::dvec3(11.5, 0.25, 0.5),
                                             glm::dvec3(0.5, 0.25, 11.5)};
    const double bound = grid.bound(piece);
    const double sampled = grid.sampledLargest(piece, 110);
    EXPECT_GT(sampled, 0.5); // the dip shows: about 0.67 above its deepest point
    EXPECT_GE(bound + 10.0 * kEps, sampled);
    EXPECT_LE(bound, 0.75 + 1e-6); // at most the distance to the dip's vertex
}

// Pieces tilted at random over a field of random bumps, each across many triangles: where the overlay
// gives a bound (most pieces), it is at least every distance sampled on the piece, less the 10 eps the
// clipping's allowance may leave to the certifier's rounding allowance. The largest distance lies
// inside the piece or at any of its corners, so a bound that missed a part's corner, or a part, falls
// below it.
TEST(PieceOverlay, NeverFallsBelowTheDistanceSampledOnABumpyMesh) {
    Rng rng(7);
    std::vector<double> heights(13 * 13);
    for (double& h : heights)
        h = double(rng.uniform(-0.3f, 0.3f));
    const Grid grid(12, [&](int x, int y) { return heights[size_t(y * 13 + x)]; });
    size_t bounded = 0, pieces = 40;
    for (size_t i = 0; i < pieces; ++i) {
        std::array<glm::dvec3, 3> piece;
        for (glm::dvec3& p : piece)
            p = {rng.uniform(1.0f, 11.0f), rng.uniform(-0.2f, 0.6f), rng.uniform(1.0f, 11.0f)};
        const double bound = grid.bound(piece);
        if (bound >= kCap) continue;
        ++bounded;
        const double sampled = grid.sampledLargest(piece, 60);
        EXPECT_GE(bound + 10.0 * kEps, sampled) << "piece " << i;
        EXPECT_LE(bound, sampled + 1.0) << "piece " << i; // a bound, not the cap in disguise
    }
    std::printf("%zu of %zu pieces bounded by the overlay\n", bounded, pieces);
    EXPECT_GE(bounded, pieces / 2);
}

TEST(PieceOverlay, GivesTheCapWhereThePieceReachesPastTheBorder) {
    const Grid grid(8, [](int, int) { return 0.0; });
    const std::array<glm::dvec3, 3> piece = {glm::dvec3(1.0, 0.1, 1.0), glm::dvec3(9.5, 0.1, 2.0),
                                             glm::dvec3(3.0, 0.1, 6.0)};
    EXPECT_EQ(grid.bound(piece), kCap);
}
