#include "DecalRecord.hpp"

#include "DecalCutout.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace spatter::render_detail {

namespace {

constexpr double kPi = 3.14159265358979323846;

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Whether the decal's numbers make a box the shaders can invert in float: finite, half extents of
// normal floats (a GPU flushes denormals to zero), and a centre that the inverse's translation,
// up to |centre| / (smallest half extent), keeps finite.
bool soundNumbers(const Decal& d) {
    const glm::vec3 h(0.5f * d.size, d.halfDepth);
    const float smallest = glm::min(h.x, glm::min(h.y, h.z));
    if (!finite(d.center) || !finite(h) || !validSlant(d.slant) ||
        !(smallest >= std::numeric_limits<float>::min()))
        return false;
    const double reach =
        std::fabs(double(d.center.x)) + std::fabs(double(d.center.y)) + std::fabs(double(d.center.z));
    return reach / double(smallest) < 0.5 * double(std::numeric_limits<float>::max());
}

} // namespace

bool buildDecalRecord(const Decal& d, DecalRecordGpu& out) {
    out = DecalRecordGpu{};
    out.info = glm::uvec4(d.object, uint32_t(d.type) | uint32_t(d.opacity.bits()) << 24, d.slant, 0u);
    if (!soundNumbers(d) || !hasOrientation(d.packedFrame)) return false;
    out.centerDepth = glm::vec4(d.center, d.halfDepth);
    out.frame = glm::uvec2(uint32_t(d.packedFrame), uint32_t(d.packedFrame >> 32));
    out.halfSize = 0.5f * d.size;
    return true;
}

DecalTypeGpu buildDecalType(const DecalType& type, float wrapMaxAngleDeg,
                            const std::vector<glm::vec4>& cutouts) {
    DecalTypeGpu g{};
    const bool drawable = type.texture >= 0 && size_t(type.texture) < cutouts.size() &&
                          finite(glm::vec3(type.tint)) && std::isfinite(type.tint.w) &&
                          std::isfinite(type.maxAngleDeg) && std::isfinite(type.roughness);
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
    g.info = glm::uvec4(uint32_t(type.texture), flags, 1u, packCutout(cutouts[size_t(type.texture)]));
    g.params =
        glm::vec4(float(std::cos(angle * kPi / 180.0)), std::clamp(type.roughness, 0.0f, 1.0f), 0.0f, 0.0f);
    return g;
}

glm::dmat4 recordBoxToObject(const DecalRecordGpu& r) {
    const glm::dmat3 m = glm::mat3_cast(unpackOrientation(uint64_t(r.frame.y) << 32 | r.frame.x));
    const glm::dvec3 h(r.halfSize.x, r.halfSize.y, r.centerDepth.w);
    const glm::dvec3 b = recordFlags(r) & kDecalMirrored ? -m[1] : m[1];
    const glm::dvec2 s(unpackSlant(r.info.z));
    return glm::dmat4(glm::dvec4(m[0] * h.x, 0.0), glm::dvec4(b * h.y, 0.0),
                      glm::dvec4((m[2] + s.x * m[0] + s.y * b) * h.z, 0.0),
                      glm::dvec4(glm::dvec3(glm::vec3(r.centerDepth)), 1.0));
}

} // namespace spatter::render_detail
