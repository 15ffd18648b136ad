#include "spatter/core/PackedFrame.hpp"

#include <cmath>

namespace spatter {

namespace {

constexpr int kBits = 20;
constexpr uint64_t kMask = (uint64_t(1) << kBits) - 1;
constexpr double kOffset = double(1 << (kBits - 1)); // 0 packs to 2^19
constexpr double kRange = 0.70710678118654752440;    // |a smaller component| <= 1/sqrt(2)
constexpr double kScale = (kOffset - 1.0) / kRange;  // +-1/sqrt(2) packs to 1 and 2^20 - 1

} // namespace

uint64_t packOrientation(const glm::dquat& unit, bool mirrored) {
    const double c[4] = {unit.w, unit.x, unit.y, unit.z};
    const double sum = c[0] * c[0] + c[1] * c[1] + c[2] * c[2] + c[3] * c[3];
    if (!std::isfinite(sum) || !(sum > 1e-24)) return kNoOrientation;
    int largest = 0;
    for (int i = 1; i < 4; ++i)
        largest = std::fabs(c[i]) > std::fabs(c[largest]) ? i : largest;
    const double sign = c[largest] < 0.0 ? -1.0 : 1.0; // q and -q are the same rotation
    uint64_t bits = uint64_t(1) << 63 | uint64_t(mirrored) << 62 | uint64_t(largest) << 60;
    int shift = 2 * kBits;
    for (int i = 0; i < 4; ++i) {
        if (i == largest) continue;
        const double v = std::fmin(std::fmax(sign * c[i], -kRange), kRange);
        bits |= uint64_t(std::lround(v * kScale + kOffset)) << shift;
        shift -= kBits;
    }
    return bits;
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
