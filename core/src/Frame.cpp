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

glm::dquat orientationOf(const glm::dvec3& t, const glm::dvec3& b, const glm::dvec3& n) {
    const double s[4] = {1.0 + t.x + b.y + n.z, 1.0 + t.x - b.y - n.z, 1.0 - t.x + b.y - n.z,
                         1.0 - t.x - b.y + n.z};
    int k = 0;
    for (int i = 1; i < 4; ++i)
        k = s[i] > s[k] ? i : k;
    // Row r, column c of the matrix is m[c][r]: t is column 0, b column 1, n column 2.
    const double wx = b.z - n.y, wy = n.x - t.z, wz = t.y - b.x, xy = b.x + t.y, xz = n.x + t.z,
                 yz = n.y + b.z;
    const double table[4][4] = {
        {s[0], wx, wy, wz}, {wx, s[1], xy, xz}, {wy, xy, s[2], yz}, {wz, xz, yz, s[3]}};
    const double scale = std::copysign(0.5 / std::sqrt(s[k]), table[k][0]); // w >= 0
    return glm::dquat(table[k][0] * scale, table[k][1] * scale, table[k][2] * scale, table[k][3] * scale);
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
