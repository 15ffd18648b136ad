#include "TrianglePieces.hpp"

namespace spatter {

std::vector<uint32_t> nearestTrianglePerPiece(const ClosestPointQuery& query, const Mesh& collision,
                                              uint32_t none) {
    std::vector<uint32_t> nearest;
    nearest.reserve(collision.triangleCount() * kPiecesPerTriangle);
    for (size_t t = 0; t < collision.triangleCount(); ++t) {
        const uint32_t* c = &collision.indices[3 * t];
        const glm::dvec3 p0(collision.positions[c[0]]);
        forEachPieceCentre(p0, glm::dvec3(collision.positions[c[1]]) - p0,
                           glm::dvec3(collision.positions[c[2]]) - p0, [&](const glm::dvec3& centre) {
                               const std::optional<ClosestPoint> near = query.closest(centre);
                               nearest.push_back(near ? near->triangle : none);
                           });
    }
    return nearest;
}

} // namespace spatter
