#pragma once
// largestStretch: an upper bound of how far a linear map stretches a vector (its spectral norm), for
// bounds that a transform carries into the world (an error bound, a bounding sphere). The longest
// column of the matrix is that norm only where the columns are orthogonal (rotations and scales); a
// shear, which the world matrix of a rotated child under a non-uniformly scaled parent has, stretches
// farther. The square of the norm is the largest eigenvalue of the columns' Gram matrix, which
// Gershgorin's theorem bounds by its largest row sum of absolute values: for orthogonal columns the
// longest column again.

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

namespace spatter {

inline double largestStretch(const glm::dmat3& m) {
    double largest = 0.0;
    for (int i = 0; i < 3; ++i)
        largest = std::max(largest, glm::dot(m[i], m[i]) + std::abs(glm::dot(m[i], m[(i + 1) % 3])) +
                                        std::abs(glm::dot(m[i], m[(i + 2) % 3])));
    return std::sqrt(largest);
}

} // namespace spatter
