#include "SkinPoints.hpp"

#include "spatter/core/VertexDeformation.hpp"

#include <optional>

namespace spatter::bench {

const uint32_t* cornersOf(const Mesh& mesh, const SurfaceAnchor& a) {
    return &mesh.indices[3 * size_t(a.triangle)];
}

glm::dvec3 pointOf(const Mesh& mesh, const std::vector<glm::dvec3>& p, const SurfaceAnchor& a) {
    const uint32_t* c = cornersOf(mesh, a);
    return a.bary.x * p[c[0]] + a.bary.y * p[c[1]] + a.bary.z * p[c[2]];
}

SurfaceAnchor nearestPoint(const ClosestPointQuery& query, const Mesh& mesh, const std::vector<glm::dvec3>& p,
                           const glm::dvec3& centre) {
    const std::optional<ClosestPoint> c = query.closest(centre);
    if (!c) return {};
    SurfaceAnchor a{c->triangle, {}};
    const uint32_t* k = cornersOf(mesh, a);
    a.bary = barycentric(c->point, p[k[0]], p[k[1]], p[k[2]]);
    return a;
}

uint16_t carryingJoint(const SkinWeights& skin, const std::vector<glm::dvec3>& p, const glm::dvec3& centre) {
    size_t nearest = 0;
    for (size_t v = 1; v < p.size(); ++v)
        if (glm::length(p[v] - centre) < glm::length(p[nearest] - centre)) nearest = v;
    const size_t stride = size_t(skin.influences), first = nearest * stride;
    size_t best = first;
    for (size_t k = first + 1; k < first + stride; ++k)
        if (skin.weights[k] > skin.weights[best]) best = k;
    return skin.joints[best];
}

} // namespace spatter::bench
