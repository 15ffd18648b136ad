#pragma once
// TraceTransform: which object-to-world transforms the collision world can trace.
//
// Embree works in single precision: it receives an object's transform as floats (a dynamic object's
// instance matrix; a static object's vertices moved into the world's float frame), inverts the float
// matrix itself, and maps every ray into the object's space with that inverse. A matrix that is
// invertible in double can be singular or nearly singular once rounded to float (two columns that
// differ only past float's seventh digit, a scale of 1e-20): Embree's inverse is then infinite or
// NaN, the rays it hands its own traversal are invalid, and an Embree built with assertions (as
// Debian's is) aborts the process. So the world applies one rule, to the matrix as Embree gets it.
//
// A transform is traced when its linear part A, rounded to float, satisfies all of
//   1. |A|_F <= 2^25 and |A^-1|_F <= 2^25 (Frobenius norms; A^-1 of the float matrix, so a float
//      determinant of 0 fails here): every scale between about 3e-8 and 3.4e7. Instance-space rays
//      then stay finite and inside Embree's range of +-1.8e18 for any ray through the world.
//   2. the condition number |A|_F * |A^-1|_F <= 2^16 (65,536; 3 for a rotation): float rounding of
//      an instance-space ray then moves it by at most about 2^16 * 2^-24 = 2^-8 of its distance from
//      the frame origin before the hit is refined in double on the hit triangle, so the triangle the
//      trace finds is the right one away from edges. A strongly squashed box, (100, 100, 0.01), has
//      14,142 and is traced; (1000, 1000, 0.001) has 1.4e6 and is not.
//   3. the object's collision bounds, transformed, lie within 2^32 (4.3e9) of the world's float-frame
//      origin (CollisionWorld::origin): the float frame stays within range for every ray.
//   4. those bounds are not a single point, and their largest extent is at least 2^-21 of their
//      distance from the origin (a few float steps there): Embree's float bounds of the object keep
//      a size, which its BVH builders assert. A 1 cm object is traced up to about 20 km out.
// A transform whose entries are not finite, or whose bottom row is not (0, 0, 0, 1), is refused
// outright (validateScene, setTransform). One that is finite and affine but breaks the rule is not
// an error: the object is left out of the trace (shots pass through it) with a warning that names it
// and says why; glTF exporters and animations hide a node with a scale of 0.

#include "spatter/core/Bounds.hpp"

#include <glm/glm.hpp>
#include <string>

namespace spatter {

// Limits of the rule above.
constexpr double kTraceMaxScale = 33554432.0;             // 2^25, for |A|_F and |A^-1|_F
constexpr double kTraceMaxCondition = 65536.0;            // 2^16
constexpr double kTraceMaxFrameExtent = 4294967296.0;     // 2^32
constexpr double kTraceMinRelativeSize = 1.0 / 2097152.0; // 2^-21

// The condition number |A|_F * |A^-1|_F of the linear part of `transform` rounded to float;
// infinity when the float matrix is singular or its inverse overflows.
double floatConditionNumber(const glm::dmat4& transform);

// Rules 1 and 2, on the transform alone (finite and affine, checked by the caller): empty when they
// hold, otherwise why not, e.g. "transform is singular in single precision (condition number
// 4e+09, limit 65536)".
std::string floatLinearProblem(const glm::dmat4& transform);

// Rules 3 and 4, for an object whose collision mesh has object-space bounds `local` (empty bounds:
// nothing to check) placed by `transform` in a float frame centred at `frameOrigin`.
std::string tracePlacementProblem(const glm::dmat4& transform, const Bounds& local,
                                  const glm::dvec3& frameOrigin);

// The whole rule: floatLinearProblem, then tracePlacementProblem; empty when the world can trace it.
std::string traceTransformProblem(const glm::dmat4& transform, const Bounds& local,
                                  const glm::dvec3& frameOrigin);

} // namespace spatter
