#pragma once
// DrawnNormals: which way the drawn surface faces under a proxy or collider. For each piece of each
// collision triangle (TrianglePieces.hpp), the face normal of the render triangle nearest the piece's
// centre, found once when the world is built. A decal shot through the proxy is laid facing it, so
// that its footprint lies in the plane of the surface that is drawn rather than the proxy facet's
// (docs/ACCURACY.md, "Facing the drawn surface").

#include "spatter/core/Mesh.hpp"
#include "spatter/core/Result.hpp"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace spatter {

class DrawnNormals {
public:
    // The table for collision mesh `collision` standing for `render` (both in object space). Fails
    // when the nearest-point structure over `render` cannot be built.
    static Result<DrawnNormals> build(const Mesh& render, const Mesh& collision);

    // The unit object-space normal of the drawn surface at the point of collision triangle
    // `triangle` with barycentric coordinates `bary`; nothing for a triangle out of range or where the
    // nearest render triangle has no area.
    std::optional<glm::dvec3> at(uint32_t triangle, const glm::dvec3& bary) const;

private:
    // Each normal as three signed 16-bit fractions of 32767 (its direction to about 3e-5 radians);
    // zero where there is none.
    std::vector<std::array<int16_t, 3>> normals_;
};

} // namespace spatter
