#pragma once
// Distances between triangle meshes: exact closest-point queries on a mesh surface (Embree
// rtcPointQuery with an exact point-triangle distance in double precision), and the two one-sided
// Hausdorff distances between two meshes with a certified upper bound.
//
// The surface of a mesh is the union of its triangles of non-zero area: triangles with a repeated
// index or three collinear corners draw nothing and are ignored on both sides of every query.
//
// How the upper bound is derived. The distance to a fixed surface B, d_B(p) = min over q in B of
// |p - q|, is 1-Lipschitz: |d_B(p) - d_B(s)| <= |p - s|. Every triangle of A is cut into pieces: first
// into four at its edge midpoints, then by halving a piece's longest edge, again and again; the
// corners of the pieces are the samples. Let c_P be the radius of the smallest circle enclosing a
// piece P (its circumradius when no angle is obtuse, half its longest edge otherwise): every point of
// P lies within c_P of one of P's corners, so
//     sup over P of d_B  <=  (largest d_B at P's corners) + c_P.
// A piece is cut no further once c_P <= r (the sampling radius) or once its sum is at most M1 + r,
// where M1 is the largest distance at the vertices and edge midpoints of A (measured first). The
// bound reported is the largest sum over all pieces, so it is >= the true one-sided distance, and as
// every piece met one of the two rules, bound <= measuredMax + r. Flat, close regions therefore need
// few samples; pieces are cut finely only where the distance is near its maximum. Every sample lies on
// A, so the largest sampled distance is attained: measuredMax <= true distance <= bound.
// A relative allowance of 1e-9 (of the bound and of the largest coordinate) covers double rounding.
// When the pieces would need more than maxSamples samples, r is doubled and the cutting redone; the
// margin reported is bound - measuredMax, at most the r finally used (up to the rounding allowance).
//
// Thread safety: a ClosestPointQuery may be queried from several threads at once.

#include "spatter/core/Mesh.hpp"
#include "spatter/core/Result.hpp"

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <optional>

namespace spatter {

// Reports progress of a long operation: `fraction` in [0, 1] of the current `stage` (a short
// static string such as "simplify" or "measure"). Return false to cancel: the operation then stops
// soon and returns the error "cancelled". Called on the thread that started the operation.
using ProgressCallback = std::function<bool(float fraction, const char* stage)>;

struct ClosestPoint {
    glm::dvec3 point{0.0}; // nearest point of the surface
    double distance = 0.0; // |query - point|
    uint32_t triangle = 0; // index of the triangle holding `point` in the mesh (indices[3 * triangle])
};

// Nearest-point queries on one mesh's surface, and ray queries on the same structure. Copies what it
// needs: the mesh may be destroyed after create(). Move-only.
class ClosestPointQuery {
public:
    // Builds the query structure. Fails on an index count that is not a multiple of 3, an index past
    // the vertex count or a non-finite position (the message names the first one), or when Embree
    // cannot create its device. A mesh with no surface is accepted: closest() then returns nothing.
    static Result<ClosestPointQuery> create(const Mesh& mesh);

    ClosestPointQuery(ClosestPointQuery&&) noexcept;
    ClosestPointQuery& operator=(ClosestPointQuery&&) noexcept;
    ~ClosestPointQuery();

    // The nearest surface point to `p`, exact up to double rounding; of triangles at the same
    // distance, the one first in the mesh, so that the answer is the same on every processor. Empty
    // when the mesh has no surface or `p` is not finite.
    std::optional<ClosestPoint> closest(const glm::dvec3& p) const;
    // The same, searched only within `reach` of `p` (up to double rounding): empty also when no surface
    // point lies that near, or `reach` is NaN or negative. A caller that knows how far the surface can
    // be (a certified bound) saves most of the search.
    std::optional<ClosestPoint> closest(const glm::dvec3& p, double reach) const;

    // Whether some surface point lies within `radius` of `p` (exact up to double rounding): the
    // search stops at the first such point. False when the mesh has no surface or a value is not
    // finite.
    bool within(const glm::dvec3& p, double radius) const;

    // Where the ray from `origin` along unit `direction` first meets the surface within `reach`
    // (single precision): the triangle (an index of the mesh) and the distance. Empty when it meets
    // none, or for a value that is not finite.
    struct RayMeet {
        uint32_t triangle = 0;
        double t = 0.0;
    };
    std::optional<RayMeet> firstMeet(const glm::dvec3& origin, const glm::dvec3& direction,
                                     double reach) const;

    // Number of triangles with non-zero area (the ones that make up the surface).
    size_t surfaceTriangleCount() const;

private:
    struct Impl;
    explicit ClosestPointQuery(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

struct SurfaceSampling {
    // Sampling radius r (absolute units): the bound exceeds the measured maximum by at most r.
    // <= 0 samples only the vertices and edge midpoints (the margin is then at most the largest
    // enclosing radius of their pieces).
    double radius = 0.0;
    // Largest number of samples per direction for the cutting; r is doubled until it fits. Vertices
    // and edge midpoints are always measured.
    size_t maxSamples = 2'000'000;
    // Extra random samples per direction, area-weighted, from Rng(seed). They can raise the measured
    // maximum (a better lower estimate) but are not needed for the bound.
    uint32_t randomSamples = 16384;
    uint64_t seed = 1;
};

struct OneSidedDistance {
    double measuredMax = 0.0; // largest distance at a sample: the true distance is at least this
    double bound = 0.0;       // the true one-sided Hausdorff distance is at most this
    double margin = 0.0;      // bound - measuredMax
    size_t samples = 0;       // closest-point queries made
};

struct MeshDistance {
    OneSidedDistance aToB; // sup over the surface of A of the distance to B
    OneSidedDistance bToA;
    // The true two-sided Hausdorff distance lies in [lowerBound(), upperBound()].
    double lowerBound() const {
        return aToB.measuredMax > bToA.measuredMax ? aToB.measuredMax : bToA.measuredMax;
    }
    double upperBound() const { return aToB.bound > bToA.bound ? aToB.bound : bToA.bound; }
};

// The one-sided distance from the surface of `from` to the surface of `to` (given as its query).
// Both distances are 0 for a `from` with no surface. Fails when `from` is invalid (as in
// ClosestPointQuery::create), when `from` has a surface and `to` has none, and on cancellation.
Result<OneSidedDistance> measureOneSidedDistance(const Mesh& from, const ClosestPointQuery& to,
                                                 const SurfaceSampling& sampling,
                                                 const ProgressCallback& progress = {});

// Both one-sided distances between `a` and `b`. Fails like measureOneSidedDistance, and when exactly
// one of the meshes has a surface.
Result<MeshDistance> measureMeshDistance(const Mesh& a, const Mesh& b, const SurfaceSampling& sampling,
                                         const ProgressCallback& progress = {});

} // namespace spatter
