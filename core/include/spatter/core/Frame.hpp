#pragma once
// Orthonormal frames for decals.

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace spatter {

// A right-handed orthonormal frame: cross(tangent, bitangent) == normal.
struct Frame {
    glm::vec3 tangent{1, 0, 0};
    glm::vec3 bitangent{0, 1, 0};
    glm::vec3 normal{0, 0, 1};
};

// Two unit vectors completing unit `n` to a right-handed orthonormal basis (b1, b2, n), without
// branches on the axis and without precision loss near the poles (Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited"). `n` must be unit length.
Frame basisFromNormal(const glm::vec3& n);

// Frame with unit normal `n` and its tangent along `hint` projected into the tangent plane. When the
// projection is too short to be trusted (hint nearly parallel to n, zero or non-finite), falls back
// to the world X axis, and then to basisFromNormal. `n` must be unit length.
Frame frameFromNormalAndHint(const glm::vec3& n, const glm::vec3& hint);

// The frame rotated by `angle` radians about its normal.
Frame rotateAboutNormal(const Frame& f, float angle);

// Largest deviation from orthonormality and right-handedness (0 for a perfect frame).
float frameError(const Frame& f);

} // namespace spatter
