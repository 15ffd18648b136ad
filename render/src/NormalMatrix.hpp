#pragma once
// The matrix that carries an object's normals to world space.

#include <cmath>
#include <glm/glm.hpp>

namespace spatter::render_detail {

// The inverse transpose of `m`; for a singular m (an object flattened by a scale of 0) the cofactor
// matrix, which maps normals in the same directions wherever the inverse exists and stays finite.
inline glm::dmat3 normalMatrix(const glm::dmat3& m) {
    const glm::dmat3 inverseTranspose = glm::transpose(glm::inverse(m));
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            if (!std::isfinite(inverseTranspose[c][r]))
                return glm::dmat3(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1]));
    return inverseTranspose;
}

} // namespace spatter::render_detail
