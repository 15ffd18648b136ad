#include "spatter/core/TrianglePieces.hpp"

#include "SurfaceGeometry.hpp"

#include <algorithm>
#include <optional>

namespace spatter {

std::vector<uint32_t> nearestTrianglePerPiece(const ClosestPointQuery& query, const Mesh& collision,
                                              uint32_t none, double reach, unsigned threads,
                                              const std::vector<uint32_t>& held) {
    std::vector<uint32_t> nearest(collision.triangleCount() * kPiecesPerTriangle, none);
    auto nearestTo = [&](const glm::dvec3& centre) {
        std::optional<ClosestPoint> near = query.closest(centre, reach);
        if (!near) near = query.closest(centre); // none within reach: rounding, or a wrong bound
        return near ? near->triangle : none;
    };
    detail::parallelChunks(
        collision.triangleCount(), 64, detail::workersFor(threads),
        [&](size_t begin, size_t end, unsigned) {
            for (size_t t = begin; t < end; ++t) {
                if (t < held.size() && held[t] != none) {
                    std::fill_n(nearest.begin() + std::ptrdiff_t(t * kPiecesPerTriangle), kPiecesPerTriangle,
                                held[t]);
                    continue;
                }
                const uint32_t* c = &collision.indices[3 * t];
                const glm::dvec3 p0(collision.positions[c[0]]);
                size_t k = t * kPiecesPerTriangle;
                forEachPieceCentre(p0, glm::dvec3(collision.positions[c[1]]) - p0,
                                   glm::dvec3(collision.positions[c[2]]) - p0,
                                   [&](const glm::dvec3& centre) { nearest[k++] = nearestTo(centre); });
            }
        },
        [](double) { return true; });
    return nearest;
}

} // namespace spatter
