#include "spatter/core/Frame.hpp"

#include <algorithm>
#include <cmath>

namespace spatter {

Frame basisFromNormal(const glm::vec3& n) {
    // Duff et al. 2017, Listing 3: copysign avoids the branch and the singularity at n.z = -1.
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    Frame f;
    f.tangent = glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    f.bitangent = glm::vec3(b, sign + n.y * n.y * a, -n.y);
    f.normal = n;
    return f;
}

static bool usableTangent(const glm::vec3& n, const glm::vec3& hint, glm::vec3& out) {
    if (!std::isfinite(hint.x) || !std::isfinite(hint.y) || !std::isfinite(hint.z)) return false;
    const float len = glm::length(hint);
    if (!(len > 1e-30f) || !std::isfinite(len)) return false;
    const glm::vec3 h = hint / len;
    const glm::vec3 t = h - n * glm::dot(n, h);
    const float tl = glm::length(t);
    // Below ~0.01 (the hint within 0.6 degrees of the normal) the projected direction is dominated
    // by rounding in the hint and the normal; fall back rather than amplify it.
    if (!(tl > 1e-2f)) return false;
    out = t / tl;
    return true;
}

Frame frameFromNormalAndHint(const glm::vec3& n, const glm::vec3& hint) {
    glm::vec3 t;
    if (!usableTangent(n, hint, t) && !usableTangent(n, glm::vec3(1, 0, 0), t)) return basisFromNormal(n);
    // Re-orthogonalise once more against n so the frame is orthonormal to float precision.
    t = glm::normalize(t - n * glm::dot(n, t));
    Frame f;
    f.normal = n;
    f.tangent = t;
    f.bitangent = glm::cross(n, t);
    return f;
}

Frame rotateAboutNormal(const Frame& f, float angle) {
    const float c = std::cos(angle), s = std::sin(angle);
    Frame r;
    r.normal = f.normal;
    r.tangent = c * f.tangent + s * f.bitangent;
    r.bitangent = -s * f.tangent + c * f.bitangent;
    return r;
}

float frameError(const Frame& f) {
    const float terms[] = {
        std::fabs(glm::length(f.tangent) - 1.0f),
        std::fabs(glm::length(f.bitangent) - 1.0f),
        std::fabs(glm::length(f.normal) - 1.0f),
        std::fabs(glm::dot(f.tangent, f.bitangent)),
        std::fabs(glm::dot(f.tangent, f.normal)),
        std::fabs(glm::dot(f.bitangent, f.normal)),
        glm::length(glm::cross(f.tangent, f.bitangent) - f.normal),
    };
    float e = 0.0f;
    for (float t : terms) {
        if (!std::isfinite(t)) return INFINITY; // NaN must not hide behind a max
        e = std::max(e, t);
    }
    return e;
}

} // namespace spatter
