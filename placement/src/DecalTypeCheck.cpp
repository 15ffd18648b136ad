#include "DecalTypeCheck.hpp"

#include "NumberChecks.hpp"

#include <cmath>

namespace spatter {

namespace {

bool finiteNormal(float v) {
    return std::isfinite(v) && !denormal(v);
}

std::string placementProblem(const DecalType& t) {
    if (!finiteNormal(t.size.x) || !finiteNormal(t.size.y) || !(t.size.x > 0.0f) || !(t.size.y > 0.0f))
        return "size must be finite, > 0 and not denormal";
    if (!finiteNormal(t.sizeJitter) || t.sizeJitter < 0.0f || !(t.sizeJitter < 1.0f))
        return "sizeJitter must be in [0, 1) and not denormal";
    if (!finiteNormal(t.maxAngleDeg) || !(t.maxAngleDeg > 0.0f) || t.maxAngleDeg > 90.0f)
        return "maxAngleDeg must be in (0, 90] and not denormal";
    if (!finiteNormal(t.lifetime) || t.lifetime < 0.0f)
        return "lifetime must be finite, >= 0 and not denormal";
    if (!finiteNormal(t.fadeOutTime) || t.fadeOutTime < 0.0f)
        return "fadeOutTime must be finite, >= 0 and not denormal";
    if (!finiteNormal(t.halfDepth) || t.halfDepth < 0.0f)
        return "halfDepth must be finite, >= 0 and not denormal";
    if (t.projection != Projection::Normal && t.projection != Projection::Shot)
        return "projection " + std::to_string(int(t.projection)) + " is not Normal (0) or Shot (1)";
    return {};
}

std::string appearanceProblem(const DecalType& t) {
    if (t.texture < 0) return "texture must be >= 0";
    if (!std::isfinite(t.tint.x) || !std::isfinite(t.tint.y) || !std::isfinite(t.tint.z) ||
        !std::isfinite(t.tint.w))
        return "tint must be finite";
    if (t.tint.x < 0.0f || t.tint.y < 0.0f || t.tint.z < 0.0f || !(t.tint.w >= 0.0f && t.tint.w <= 1.0f))
        return "tint must be >= 0, its alpha in [0, 1]";
    if (!std::isfinite(t.roughness)) return "roughness must be finite";
    if (t.roughness > 1.0f) return "roughness must be at most 1 (< 0 keeps the surface's)";
    if (t.depthFade != DepthFade::None && t.depthFade != DepthFade::Linear &&
        t.depthFade != DepthFade::Smooth)
        return "depthFade " + std::to_string(int(t.depthFade)) + " is not None (0), Linear (1) or Smooth (2)";
    return {};
}

} // namespace

std::string decalTypeProblem(const DecalType& t) {
    if (std::string p = placementProblem(t); !p.empty()) return p;
    return appearanceProblem(t);
}

} // namespace spatter
