#pragma once
// TrianglePieces: a triangle cut into kPieceCuts^2 pieces by a grid of kPieceCuts steps along its
// edges from the first corner, numbered row by row (rows along the second corner's coordinate), each
// cell's lower piece before its upper one. What is kept per piece of a proxy or collider triangle
// (the drawn surface it stands for: DrawnNormals.hpp, the skinned objects' walk) is found at a
// piece's centre (nearestTrianglePerPiece) and read back at a hit by pieceOf.

#include "spatter/core/Mesh.hpp"
#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/Threads.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace spatter {

constexpr int kPieceCuts = 3;
constexpr size_t kPiecesPerTriangle = size_t(kPieceCuts) * kPieceCuts;

// Calls `f(centre)` for the centre of each piece of the triangle with corner `p0` and edges `e1`,
// `e2` (to the second and third corners), in piece order.
template <class F>
void forEachPieceCentre(const glm::dvec3& p0, const glm::dvec3& e1, const glm::dvec3& e2, F&& f) {
    constexpr int n = kPieceCuts;
    for (int i = 0; i < n; ++i)
        for (int j = 0; i + j < n; ++j)
            for (int flip = 0; flip < (i + j < n - 1 ? 2 : 1); ++flip) {
                const double third = flip ? 2.0 / 3.0 : 1.0 / 3.0;
                f(p0 + e1 * ((i + third) / n) + e2 * ((j + third) / n));
            }
}

// The piece (0 .. kPiecesPerTriangle - 1) holding the point of barycentric coordinates `bary` (of
// the first, second and third corners); a point outside the triangle goes to the nearest piece of
// its row.
inline size_t pieceOf(const glm::dvec3& bary) {
    constexpr int n = kPieceCuts;
    auto step = [](double b) { return b > 0.0 ? (b < 1.0 ? int(b * n) : n - 1) : 0; };
    const int i = step(bary.y), j = std::min(step(bary.z), n - 1 - i);
    const bool flip = i + j < n - 1 && (bary.y * n - i) + (bary.z * n - j) > 1.0;
    return size_t(i * (2 * n - i) + 2 * j + (flip ? 1 : 0)); // rows before i hold 2 (n - i') - 1 each
}

// For each piece of each triangle of `collision`, in piece order, the triangle of the mesh `query`
// answers for that is nearest the piece's centre; `none` where it finds none. `reach`: how far that
// surface may lie from `collision` (a certified bound such as a proxy's h; infinity when none is
// known): the search looks that far first, then everywhere. On `threads` threads (0: the hardware's,
// at most kMaxThreads; the result does not depend on it). `held`, empty or one entry per collision
// triangle: a triangle of that surface holding the collision triangle (the same corners;
// HausdorffSurface::sameTriangles), `none` where none is known; each piece of a held triangle lies on
// it, so it is taken without a search.
std::vector<uint32_t> nearestTrianglePerPiece(const ClosestPointQuery& query, const Mesh& collision,
                                              uint32_t none,
                                              double reach = std::numeric_limits<double>::infinity(),
                                              unsigned threads = 0, const std::vector<uint32_t>& held = {});

} // namespace spatter
