#include "DecalRecord.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace spatter::render_detail {

namespace {

constexpr double kPi = 3.14159265358979323846;

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

uint32_t floatBits(float f) {
    uint32_t u = 0;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

// Whether the decal's numbers can make a box at all: finite, extents of normal floats (its
// orientation is checked as it is unpacked: frame() is zero for a zero or non-finite one).
bool soundNumbers(const Decal& d) {
    constexpr float kMinExtent = std::numeric_limits<float>::min(); // a denormal cannot be inverted
    return finite(d.center) && std::isfinite(d.size.x) && std::isfinite(d.size.y) &&
           std::isfinite(d.halfDepth) && std::isfinite(d.opacity) && d.size.x >= kMinExtent &&
           d.size.y >= kMinExtent && d.halfDepth >= kMinExtent;
}

} // namespace

bool buildDecalRecord(const Decal& d, DecalRecordGpu& out) {
    out = DecalRecordGpu{};
    if (!soundNumbers(d)) return false;
    const Frame f = d.frame(); // orthonormal: its inverse is its transpose
    if (f.normal == glm::vec3(0.0f)) return false;
    const glm::dvec3 axes[3] = {glm::dvec3(f.tangent) / (0.5 * double(d.size.x)),
                                glm::dvec3(f.bitangent) / (0.5 * double(d.size.y)),
                                glm::dvec3(f.normal) / double(d.halfDepth)};
    const glm::dvec3 c(d.center);
    for (int r = 0; r < 3; ++r)
        out.objectToBox[r] = glm::vec4(glm::vec3(axes[r]), float(-glm::dot(axes[r], c)));
    const uint32_t mirrored = d.mirrored() ? kDecalMirrored : 0u;
    out.info = glm::uvec4(d.object, uint32_t(d.type) | uint32_t(d.objectId) << 16 | mirrored << 24,
                          floatBits(std::clamp(d.opacity, 0.0f, 1.0f)), d.id);
    return true;
}

DecalTypeGpu buildDecalType(const DecalType& type, float wrapMaxAngleDeg, int layerCount) {
    DecalTypeGpu g{};
    const bool drawable = type.texture >= 0 && type.texture < layerCount && finite(glm::vec3(type.tint)) &&
                          std::isfinite(type.tint.w) && std::isfinite(type.maxAngleDeg) &&
                          std::isfinite(type.roughness);
    if (!drawable) return g;
    uint32_t flags = 0;
    if (type.wrapAround) flags |= kDecalWrap;
    if (type.normalMap) flags |= kDecalNormalMap;
    if (type.depthFade == DepthFade::Linear) flags |= kDecalFadeLinear;
    if (type.depthFade == DepthFade::Smooth) flags |= kDecalFadeSmooth;
    if (type.roughness >= 0.0f) flags |= kDecalRoughness;
    double angle = std::clamp(double(type.maxAngleDeg), 0.0, 180.0);
    if (type.wrapAround) angle = std::max(angle, std::clamp(double(wrapMaxAngleDeg), 0.0, 180.0));
    g.tint = type.tint;
    g.info = glm::uvec4(uint32_t(type.texture), flags, 1u, 0u);
    g.params =
        glm::vec4(float(std::cos(angle * kPi / 180.0)), std::clamp(type.roughness, 0.0f, 1.0f), 0.0f, 0.0f);
    return g;
}

glm::dmat4 recordBoxToObject(const DecalRecordGpu& r) {
    glm::dmat4 toBox(1.0);
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 4; ++c)
            toBox[c][k] = double(r.objectToBox[k][c]);
    return glm::inverse(toBox);
}

} // namespace spatter::render_detail
