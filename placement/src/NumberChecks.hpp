#pragma once
// The checks of numbers the placement library makes on input before using it.

#include <cmath>
#include <glm/glm.hpp>
#include <limits>

namespace spatter {

inline bool finite3(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// A non-zero magnitude below the normal range: too small to divide by or normalise reliably.
inline bool denormal(double v) {
    return v != 0.0 && std::fabs(v) < std::numeric_limits<double>::min();
}
inline bool denormal(float v) {
    return v != 0.0f && std::fabs(v) < std::numeric_limits<float>::min();
}

} // namespace spatter
