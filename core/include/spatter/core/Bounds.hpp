#pragma once
// Axis-aligned bounding boxes in single and double precision.

#include <glm/glm.hpp>
#include <limits>

namespace spatter {

template <class Vec> struct BasicBounds {
    using Scalar = typename Vec::value_type;
    Vec min{std::numeric_limits<Scalar>::max()};
    Vec max{std::numeric_limits<Scalar>::lowest()};

    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    void extend(const Vec& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void extend(const BasicBounds& b) {
        if (b.empty()) return;
        extend(b.min);
        extend(b.max);
    }
    Vec center() const { return (min + max) * Scalar(0.5); }
    Vec extent() const { return max - min; }
    // Length of the diagonal; 0 for an empty box.
    Scalar diagonal() const { return empty() ? Scalar(0) : glm::length(max - min); }
};

using Bounds = BasicBounds<glm::vec3>;
using DBounds = BasicBounds<glm::dvec3>;

} // namespace spatter
