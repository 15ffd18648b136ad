#include "spatter/core/DrawnNormals.hpp"

#include "spatter/core/TrianglePieces.hpp"

#include <cmath>

namespace spatter {

namespace {

// `n` as three signed fractions of 32767 of its unit vector; zero for a vector without direction.
DrawnNormals::Packed packNormal(const glm::dvec3& n) {
    const double length = glm::length(n);
    if (!(length > 0.0) || !std::isfinite(length)) return {0, 0, 0};
    const glm::dvec3 u = n / length;
    return {int16_t(std::lround(u.x * 32767.0)), int16_t(std::lround(u.y * 32767.0)),
            int16_t(std::lround(u.z * 32767.0))};
}

// The face normal of triangle `t` of `mesh` (not normalised; zero for one without area).
glm::dvec3 faceNormal(const Mesh& mesh, uint32_t t) {
    const uint32_t* c = &mesh.indices[3 * size_t(t)];
    const glm::dvec3 p0(mesh.positions[c[0]]);
    return glm::cross(glm::dvec3(mesh.positions[c[1]]) - p0, glm::dvec3(mesh.positions[c[2]]) - p0);
}

constexpr uint32_t kNone = UINT32_MAX;

// The table from each piece's nearest render triangle (kNone where there is none; a triangle `render`
// lacks, from a query or surface of another mesh, gives none either).
std::vector<DrawnNormals::Packed> packedNormals(const Mesh& render, const std::vector<uint32_t>& nearest) {
    std::vector<DrawnNormals::Packed> normals;
    normals.reserve(nearest.size());
    for (uint32_t t : nearest)
        normals.push_back(packNormal(t < render.triangleCount() ? faceNormal(render, t) : glm::dvec3(0.0)));
    return normals;
}

} // namespace

DrawnNormals DrawnNormals::build(const Mesh& render, const HausdorffSurface& surface, const Mesh& collision,
                                 double reach, unsigned threads) {
    return DrawnNormals(
        packedNormals(render, nearestTrianglePerPiece(surface.query(), collision, kNone, reach, threads,
                                                      surface.sameTriangles(collision))));
}

Result<DrawnNormals> DrawnNormals::build(const Mesh& render, const Mesh& collision, double reach) {
    Result<ClosestPointQuery> query = ClosestPointQuery::create(render);
    if (!query) return fail(query.error());
    return DrawnNormals(
        packedNormals(render, nearestTrianglePerPiece(query.value(), collision, kNone, reach)));
}

std::optional<glm::dvec3> DrawnNormals::at(uint32_t triangle, const glm::dvec3& bary) const {
    const size_t k = size_t(triangle) * kPiecesPerTriangle + pieceOf(bary);
    if (k >= normals_.size()) return std::nullopt;
    const Packed& p = normals_[k];
    const glm::dvec3 n(p[0], p[1], p[2]);
    if (n == glm::dvec3(0.0)) return std::nullopt;
    return glm::normalize(n);
}

bool DrawnNormals::fits(size_t triangles) const {
    return normals_.size() == triangles * kPiecesPerTriangle;
}

} // namespace spatter
