#include "spatter/core/CraterClip.hpp"

#include "spatter/core/Decal.hpp"

#include <algorithm>
#include <cmath>

namespace spatter {

namespace {

constexpr float kOffsetScale = 4096.0f;
constexpr float kNormalScale = 127.0f;

glm::vec3 decodeNormal(int8_t x, int8_t y) {
    glm::vec3 n(float(x) / kNormalScale, float(y) / kNormalScale, 0.0f);
    n.z = 1.0f - std::fabs(n.x) - std::fabs(n.y);
    if (n.z < 0.0f) {
        const float fx = (1.0f - std::fabs(n.y)) * (n.x >= 0.0f ? 1.0f : -1.0f);
        const float fy = (1.0f - std::fabs(n.x)) * (n.y >= 0.0f ? 1.0f : -1.0f);
        n.x = fx;
        n.y = fy;
    }
    return glm::normalize(n);
}

int8_t quantise(float v) {
    return int8_t(std::clamp(std::lround(v * kNormalScale), -127L, 127L));
}

} // namespace

glm::dmat4 craterToObject(const Decal& d) {
    const double sx = 0.5 * double(d.size.x), sy = 0.5 * double(d.size.y), sz = std::min(sx, sy);
    const Frame f = d.frame();
    return glm::dmat4(glm::dvec4(glm::dvec3(f.tangent) * sx, 0.0),
                      glm::dvec4(glm::dvec3(f.bitangent) * sy, 0.0),
                      glm::dvec4(glm::dvec3(f.normal) * sz, 0.0), glm::dvec4(glm::dvec3(d.center), 1.0));
}

CraterClip packCraterClip(const glm::vec3& normal, float offset) {
    const float length = glm::length(normal);
    if (!(length > 0.0f) || !std::isfinite(length) || !std::isfinite(offset)) return CraterClip{};
    const glm::vec3 n = normal / length;
    const float l1 = std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z);
    glm::vec2 oct(n.x / l1, n.y / l1);
    if (n.z < 0.0f)
        oct = glm::vec2((1.0f - std::fabs(oct.y)) * (oct.x >= 0.0f ? 1.0f : -1.0f),
                        (1.0f - std::fabs(oct.x)) * (oct.y >= 0.0f ? 1.0f : -1.0f));
    CraterClip c;
    c.octX = quantise(oct.x);
    c.octY = quantise(oct.y);
    // For |p| <= reach: dot(n, p) <= dot(packed, p) + |n - packed| * reach, so keeping
    // dot(packed, p) <= offset - |n - packed| * reach keeps only points with dot(n, p) <= offset.
    const float error = glm::length(n - decodeNormal(c.octX, c.octY)) * kCraterClipReach;
    const float kept = std::floor((offset - error) * kOffsetScale);
    if (kept / kOffsetScale >= kCraterClipReach) return CraterClip{}; // keeps the whole crater
    c.offset = int16_t(std::max(kept, float(INT16_MIN)));
    return c;
}

glm::vec4 unpackCraterClip(const CraterClip& c) {
    if (!c.active()) return glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    return glm::vec4(decodeNormal(c.octX, c.octY), float(c.offset) / kOffsetScale);
}

CraterClipsOf craterClipsOf(const std::vector<CraterClips>& clips) {
    return [&clips](size_t i) { return i < clips.size() ? clips[i] : CraterClips{}; };
}

} // namespace spatter
