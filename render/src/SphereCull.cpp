#include "SphereCull.hpp"

#include "spatter/core/DecalProjection.hpp"
#include "spatter/core/LinearStretch.hpp"

#include <algorithm>
#include <cmath>

namespace spatter::render_detail {

namespace {

// Relative rounding allowed for on the way to a corner's clip coordinates (double throughout).
constexpr double kRounding = 1e-9;

} // namespace

std::array<glm::dvec4, 4> clipSidePlanes() {
    return {glm::dvec4(1, 0, 0, 1), glm::dvec4(-1, 0, 0, 1), glm::dvec4(0, 1, 0, 1), glm::dvec4(0, -1, 0, 1)};
}

double recordRadius(const DecalRecordGpu& r) {
    const double hz = r.centerDepth.w;
    glm::dvec2 reach(r.halfSize.x, r.halfSize.y);
    if (r.info.z != 0u) reach += hz * glm::abs(glm::dvec2(unpackSlant(r.info.z)));
    return glm::length(glm::dvec3(reach, hz)) * (1.0 + kRounding);
}

SidePlanes::SidePlanes(const glm::dmat4& viewProj, const glm::dvec3& eye, const glm::dmat4& toWorld)
    : stretch_(largestStretch(glm::dmat3(toWorld)) * (1.0 + kRounding)),
      magnitude_(glm::length(glm::dvec3(toWorld[3])) + glm::length(eye)) {
    const glm::dmat3 linear(toWorld);
    const glm::dvec3 offset = glm::dvec3(toWorld[3]) - eye;
    const std::array<glm::dvec4, 4> clip = clipSidePlanes();
    for (size_t k = 0; k < 4; ++k) {
        const glm::dvec4 world = glm::transpose(viewProj) * clip[k]; // of a camera-relative point
        // dot(world.xyz, toWorld * p - eye) + world.w, as a plane of p.
        plane_[k] = glm::dvec4(glm::transpose(linear) * glm::dvec3(world),
                               glm::dot(glm::dvec3(world), offset) + world.w);
        length_[k] = glm::length(glm::dvec3(world));
    }
}

bool SidePlanes::outside(const glm::dvec3& centre, double radius) const {
    const double reach = radius * stretch_;
    const double spread = stretch_ * (std::abs(centre.x) + std::abs(centre.y) + std::abs(centre.z));
    for (int k = 0; k < 4; ++k) {
        const double slack = reach * length_[k] +
                             kRounding * (length_[k] * (spread + magnitude_ + reach) + std::abs(plane_[k].w));
        if (glm::dot(glm::dvec3(plane_[k]), centre) + plane_[k].w < -slack) return true;
    }
    return false;
}

} // namespace spatter::render_detail
