#pragma once
// Ray: a shot in world space, in double precision, and the check that decides whether it can be
// traced at all.

#include <glm/glm.hpp>
#include <limits>

namespace spatter {

struct Ray {
    glm::dvec3 origin{0.0};
    glm::dvec3 direction{0.0, 0.0, -1.0}; // need not be unit length; t is measured in its units
    double tnear = 0.0;                   // hits with t in [tnear, tfar] count
    double tfar = std::numeric_limits<double>::infinity();
};

// Why `ray` cannot be traced, or nullptr when it can. A ray is rejected when
// - a coordinate of its origin or direction is NaN or infinite,
// - its direction is zero, or so short (squared length below the smallest normal double, which
//   takes in every denormal direction) or so long (squared length overflows) that it cannot be
//   normalised reliably,
// - tnear is NaN, infinite or negative,
// - tfar is NaN or not greater than tnear (tfar = +infinity is allowed).
// The returned text is a static string.
const char* rayProblem(const Ray& ray);

} // namespace spatter
