#pragma once
// HausdorffBound: a certified upper bound on the Hausdorff distance between two triangle meshes, by
// branch and bound over a bounding-volume hierarchy, with an early answer to "is it at most tol?".
//
// The one-sided distance from A to B is h(A, B) = sup over points a of A of d_B(a), where d_B(a) is
// the distance from a to the surface of B (the union of its triangles of non-zero area). Two facts
// give every bound this file reports:
//  - Convexity. For one triangle t, d_t is a convex function (the distance to a convex set), so on a
//    convex region P its largest value is taken at an extreme point of P: sup over P of d_t =
//    max over the corners of P of d_t. As d_B <= d_t for every triangle t of B,
//        sup over P of d_B  <=  min over t of (max over the corners c of P of d_t(c)).
//  - Lipschitz. d_B is 1-Lipschitz, so for a triangle piece P with corners c_i and the radius e_P of
//    the smallest circle enclosing it (every point of P lies within e_P of a corner),
//        sup over P of d_B  <=  max_i d_B(c_i) + e_P.
// Every distance at a point is exact up to double rounding (Embree's BVH of B with an exact
// point-triangle distance in double, ClosestPointQuery), and every measured point lies on A, so the
// largest measured distance is a lower bound.
//
// The algorithm. A's triangles are held in a bounding-volume hierarchy of axis-aligned boxes. A node
// is bounded by convexity over the corners of its box (or, for a node of a few triangles, over the
// corners of its triangles, whose convex hull holds them), against the triangle of B closest to one of
// its vertices, and by Lipschitz from that vertex to the farthest box corner. A node whose bound is at
// most the acceptance level is done; otherwise its children are bounded in turn. At a leaf, each
// triangle is bounded by Lipschitz and by convexity against the triangles of B closest to its three
// corners, one at a time, or two sharing an edge at a time (the plane through the edge cuts the
// triangle into two convex parts, each bounded against the triangle on its side), and, where cutting
// it would likely cost more, by laying it over B's triangles along its normal (a convex part over
// each, bounded against it by convexity; PieceOverlay.hpp in the sources); a triangle above the level
// is cut by halving its longest edge (one new exact distance) and the halves bounded again. The acceptance
// level is max(L + margin, tolerance), where L is the largest distance measured so far, so pieces are refined
// only where the distance may exceed what is already known (plus the margin) and what is asked. The bound
// reported is the largest bound of an accepted node or piece: every point of A lies in one of them, so it is
// >= h(A, B). A piece whose enclosing radius is at most the margin is always accepted (its Lipschitz bound is
// at most L + margin), so the refinement ends. When a measured distance exceeds the tolerance, the answer to
// "is h <= tol?" is no, and the search stops there (`exceeded`). A triangle of A with the three corners of
// a triangle of B lies on B: it and the nodes holding only such triangles are not bounded at all (where
// one surface has at most 4 times the other's triangles; sameTriangles below).
//
// Work is split over a fixed number of subtrees of the hierarchy, walked on up to kMaxThreads threads; each
// subtree starts from the same lower bound (the distances at a fixed stride of triangle centroids), so a
// result that is not `exceeded` does not depend on the thread count or on timing: the same on every machine.
// (An `exceeded` one stops at the first distance above the tolerance that some thread measures: its `lower`
// and `farthest` may differ from run to run; the answer does not.) A relative allowance of 1e-9 (of the bound
// and of the largest coordinate) covers double rounding.

#include "spatter/core/Mesh.hpp"
#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Threads.hpp"

#include <glm/glm.hpp>
#include <limits>
#include <memory>
#include <vector>

namespace spatter {

class SampleMemory;

// One mesh prepared for certification on either side: its hierarchy (for the side measured from)
// and its closest-point query (for the side measured to). Built once and reused across any number
// of bounds, e.g. a render mesh against many candidate proxies. Copies what it needs. Move-only.
class HausdorffSurface {
public:
    // Fails like ClosestPointQuery::create (bad index, non-finite position, Embree failure). A mesh
    // with no surface is accepted.
    static Result<HausdorffSurface> create(const Mesh& mesh);

    HausdorffSurface(HausdorffSurface&&) noexcept;
    HausdorffSurface& operator=(HausdorffSurface&&) noexcept;
    ~HausdorffSurface();

    size_t surfaceTriangleCount() const;
    // The nearest-point structure over the mesh (its triangle indices are the mesh's).
    const ClosestPointQuery& query() const;
    // For each triangle of `mesh` (in the same space), the index of a surface triangle of this mesh
    // with the same three corners (bit-identical positions, in any order; the lowest where several
    // have), or UINT32_MAX where none has or the triangle names a vertex `mesh` lacks. A proxy
    // simplified from this mesh keeps many of its triangles as they are at a fine tolerance. Where
    // this surface has more than 4 times the triangles of `mesh`, few can be shared and none is looked
    // for: every entry is UINT32_MAX.
    std::vector<uint32_t> sameTriangles(const Mesh& mesh) const;

    // The prepared data, opaque outside the certifier.
    struct Impl;
    const Impl& impl() const { return *impl_; }

private:
    explicit HausdorffSurface(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

struct HausdorffSettings {
    // The bound may exceed the largest measured distance by up to this (absolute, > 0; there is no
    // default, since it depends on the meshes' scale: the 0 left here is refused): it trades the
    // sharpness of the bound for speed.
    double margin = 0.0;
    // Early answer: a bound at most this is accepted as it is, and a measured distance above it stops
    // the computation (exceeded). Infinity asks for the sharp bound only.
    double tolerance = std::numeric_limits<double>::infinity();
    // A distance already known to be attained (e.g. the other direction's lower bound); 0 if none.
    double knownLower = 0.0;
    // With a finite tolerance: where the largest distance measured comes within `margin` of it, the
    // margin shrinks to this share of the room left under the tolerance, while that room is at least
    // `minRoom` of the tolerance, so that a distance under the tolerance is certified in one walk
    // instead of bounded above it (undecided). 0 keeps the margin as given.
    double roomShare = 0.0; // in [0, 1)
    double minRoom = 0.01;  // in (0, 1]
    // Threads to walk on: 0 for the hardware's (at most kMaxThreads), else 1 to kMaxThreads. The result does
    // not depend on it (see the top of this file).
    unsigned threads = 0;
};

struct HausdorffResult {
    double lower = 0.0; // the largest distance measured: the true distance is at least this
    // The true distance is at most this (infinity when exceeded). When not exceeded,
    // upper <= max(max(lower, knownLower) + margin, tolerance) up to the rounding allowance.
    double upper = 0.0;
    bool exceeded = false; // a measured distance is above the tolerance: stopped early
    size_t queries = 0;    // points measured (exact closest-point queries, each point counted once)
    // Where `lower` was measured (the origin while it is 0): a point of A for a one-sided bound; of
    // either mesh for boundHausdorff. Where exceeded, a point farther than the tolerance.
    glm::dvec3 farthest{0.0};
    // True when the distance is certified to be at most `tolerance`.
    bool within(double tolerance) const { return !exceeded && upper <= tolerance; }
};

// The one-sided distance from `from` to `to` (see the top of this file). 0 for a `from` without
// surface. Fails when `from` has a surface and `to` has none, on a margin that is not finite and > 0,
// on a negative or NaN tolerance, a roomShare, minRoom or thread count out of its range, and on
// cancellation ("cancelled"); progress reports the stage "measure".
Result<HausdorffResult> boundOneSided(const HausdorffSurface& from, const HausdorffSurface& to,
                                      const HausdorffSettings& settings,
                                      const ProgressCallback& progress = {});

// Both one-sided bounds at once, from a to b (`ab`) and from b to a (`ba`), on one pool of threads with
// one early answer: a measured distance above the tolerance in either direction stops both, and both
// are then `exceeded` (a "no" costs about what the direction that strays needs to show it). Each
// direction starts from the larger of the two directions' starting samples (a distance attained), so
// each bound is at most max(max(lower of both, knownLower) + margin, tolerance). Fails like
// boundHausdorff.
struct HausdorffPair {
    HausdorffResult ab, ba;
};
Result<HausdorffPair> boundBothWays(const HausdorffSurface& a, const HausdorffSurface& b,
                                    const HausdorffSettings& settings, const ProgressCallback& progress = {});

// A lower bound only: the largest distance from `from` to `to` at the centroids and edge midpoints of
// at most `maxTriangles` of from's triangles (a fixed stride), stopping as soon as one is above
// `stopAbove`. No refinement and no upper bound: cheap, for steering a search whose answer is
// certified afterwards. 0 for a `from` without surface; fails like boundOneSided. `threads` as
// HausdorffSettings::threads (the result does not depend on it; above kMaxThreads, kMaxThreads are used).
Result<double> sampledLowerBound(const HausdorffSurface& from, const HausdorffSurface& to,
                                 size_t maxTriangles, double stopAbove, const ProgressCallback& progress = {},
                                 unsigned threads = 0);
// The same from a mesh not prepared for the certifier (its surface triangles in the mesh's order, where
// the prepared surface strides over its hierarchy's order: the same samples wherever all triangles
// are sampled). Fails also like checkTriangles on a bad index or a non-finite position. `memory`, where
// given: what earlier calls toward `to` (and toward no other surface) measured on the triangles they
// sampled, used and added to (SampleMemory.hpp); the answer is the same without it.
Result<double> sampledLowerBound(const Mesh& from, const HausdorffSurface& to, size_t maxTriangles,
                                 double stopAbove, const ProgressCallback& progress = {},
                                 unsigned threads = 0, SampleMemory* memory = nullptr);

// Both directions (a to b first, its lower bound then carried into b to a): lower and upper are the
// two-sided ones; `exceeded` as soon as either direction exceeds. Fails like boundOneSided, and when
// exactly one of the meshes has a surface.
Result<HausdorffResult> boundHausdorff(const HausdorffSurface& a, const HausdorffSurface& b,
                                       const HausdorffSettings& settings,
                                       const ProgressCallback& progress = {});

} // namespace spatter
