#include "spatter/core/PackedFrame.hpp"

#include <cmath>

namespace spatter {

namespace {

constexpr int kBits = 20;
constexpr uint64_t kMask = (uint64_t(1) << kBits) - 1;
constexpr double kOffset = double(1 << (kBits - 1)); // 0 packs to 2^19
constexpr double kRange = 0.70710678118654752440;    // |a smaller component| <= 1/sqrt(2)
constexpr double kScale = (kOffset - 1.0) / kRange;  // +-1/sqrt(2) packs to 1 and 2^20 - 1

// Bits 63, 62 and 60-61, and the three components other than `largest`, each of them times `scale`.
uint64_t quantize(const double c[4], int largest, double scale, bool mirrored) {
    constexpr int kOthers[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
    uint64_t bits = uint64_t(1) << 63 | uint64_t(mirrored) << 62 | uint64_t(largest) << 60;
    for (int k = 0; k < 3; ++k) {
        const double u = scale * c[kOthers[largest][k]];
        const double v = u < -kRange ? -kRange : u > kRange ? kRange : u;
        // Rounded to nearest: v * kScale + kOffset >= 1.
        bits |= uint64_t(int64_t(v * kScale + (kOffset + 0.5))) << (2 - k) * kBits;
    }
    return bits;
}

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

} // namespace

uint64_t packFrame(const glm::dvec3& t, const glm::dvec3& b, const glm::dvec3& n, bool mirrored) {
    if (!finite(t) || !finite(b) || !finite(n)) return kNoOrientation; // the trace may not see one
    // 4 w^2, 4 x^2, 4 y^2, 4 z^2 from the trace and the diagonal; row r, column c of the matrix is
    // m[c][r]: t is column 0, b column 1, n column 2.
    const double s[4] = {1.0 + t.x + b.y + n.z, 1.0 + t.x - b.y - n.z, 1.0 - t.x + b.y - n.z,
                         1.0 - t.x - b.y + n.z};
    int k = 0;
    for (int i = 1; i < 4; ++i)
        k = s[i] > s[k] ? i : k;
    const double wx = b.z - n.y, wy = n.x - t.z, wz = t.y - b.x, xy = b.x + t.y, xz = n.x + t.z,
                 yz = n.y + b.z;
    const double table[4][4] = {
        {s[0], wx, wy, wz}, {wx, s[1], xy, xz}, {wy, xy, s[2], yz}, {wz, xz, yz, s[3]}};
    if (!(s[k] > 0.0) || !std::isfinite(s[k])) return kNoOrientation;
    return quantize(table[k], k, 0.5 / std::sqrt(s[k]), mirrored); // component k: sqrt(s[k]) / 2 > 0
}

uint64_t packOrientation(const glm::dquat& unit, bool mirrored) {
    const double c[4] = {unit.w, unit.x, unit.y, unit.z};
    const double sum = c[0] * c[0] + c[1] * c[1] + c[2] * c[2] + c[3] * c[3];
    if (!std::isfinite(sum) || !(sum > 1e-24)) return kNoOrientation;
    int largest = 0; // without branches: which component is largest is random to the predictor
    double most = std::fabs(c[0]);
    for (int i = 1; i < 4; ++i) {
        const bool larger = std::fabs(c[i]) > most;
        largest = larger ? i : largest;
        most = larger ? std::fabs(c[i]) : most;
    }
    return quantize(c, largest, c[largest] < 0.0 ? -1.0 : 1.0, mirrored); // q and -q: the same rotation
}

glm::dquat unpackOrientation(uint64_t bits) {
    if (!hasOrientation(bits)) return glm::dquat(0.0, 0.0, 0.0, 0.0);
    const int largest = int(bits >> 60 & 3u);
    double c[4] = {};
    double sum = 0.0;
    int shift = 2 * kBits;
    for (int i = 0; i < 4; ++i) {
        if (i == largest) continue;
        c[i] = (double(bits >> shift & kMask) - kOffset) / kScale;
        sum += c[i] * c[i];
        shift -= kBits;
    }
    c[largest] = std::sqrt(std::fmax(0.0, 1.0 - sum));
    const glm::dquat q(c[0], c[1], c[2], c[3]);
    return q / glm::length(q);
}

} // namespace spatter
