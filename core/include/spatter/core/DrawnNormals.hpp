#pragma once
// DrawnNormals: which way the drawn surface faces under a proxy or collider. For each piece of each
// collision triangle (TrianglePieces.hpp), the face normal of the render triangle nearest the piece's
// centre. A decal shot through the proxy is laid facing it, so that its footprint lies in the plane of
// the surface that is drawn rather than the proxy facet's (docs/ACCURACY.md, "Facing the drawn
// surface"). buildProxy makes the table with the proxy (the render mesh's nearest-point structure is
// built there already) and the cache keeps it, so that a collision world built from cached proxies
// does not search the render meshes again.

#include "spatter/core/HausdorffBound.hpp"
#include "spatter/core/Mesh.hpp"
#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/Result.hpp"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace spatter {

class DrawnNormals {
public:
    // Each normal as three signed 16-bit fractions of 32767 (its direction to about 3e-5 radians);
    // zero where there is none.
    using Packed = std::array<int16_t, 3>;

    // An empty table: no piece has a drawn normal.
    DrawnNormals() = default;
    // A table as stored (kPiecesPerTriangle entries per collision triangle, in piece order).
    explicit DrawnNormals(std::vector<Packed> packed) : normals_(std::move(packed)) {}

    // The table for collision mesh `collision` standing for `render` (both in the same space), `surface`
    // prepared from `render` (its nearest-point query searches, and a collision triangle it shares
    // corner for corner takes that render triangle's normal without a search); `reach` bounds how far
    // `render` lies from `collision` (the proxy's h; infinity when unknown), which only makes the search
    // quicker. `threads`: as for nearestTrianglePerPiece.
    static DrawnNormals build(const Mesh& render, const HausdorffSurface& surface, const Mesh& collision,
                              double reach, unsigned threads = 0);
    // The same with a nearest-point structure over `render` built for it. Fails when it cannot be.
    static Result<DrawnNormals> build(const Mesh& render, const Mesh& collision, double reach);

    // The unit normal of the drawn surface at the point of collision triangle `triangle` with
    // barycentric coordinates `bary`; nothing for a triangle out of range or where the nearest render
    // triangle has no area.
    std::optional<glm::dvec3> at(uint32_t triangle, const glm::dvec3& bary) const;

    bool empty() const { return normals_.empty(); }
    // Whether the table holds one entry per piece of `triangles` collision triangles.
    bool fits(size_t triangles) const;
    const std::vector<Packed>& packed() const { return normals_; }

private:
    std::vector<Packed> normals_;
};

} // namespace spatter
