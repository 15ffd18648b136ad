#pragma once
// Decals placed as a player would place them, for the render tests: shots from the camera through
// random pixels, traced by a DecalSystem over the scene.

#include "RenderTestSupport.hpp"

#include "spatter/core/DecalType.hpp"
#include "spatter/core/ProxyBuilder.hpp"

#include <optional>
#include <vector>

namespace spatter::test {

struct Placed {
    CoverageInputs inputs; // the decals, their types and the objects' decal IDs
    size_t placed = 0;
};

// Shoots `shots` rays from `cam` through random pixels of a 160 x 120 view, cycling through `types`.
// With `proxies`, the rays are traced against them instead of the render meshes.
Placed shootFromCamera(const Scene& scene, const Camera& cam, const std::vector<DecalType>& types, int shots,
                       uint64_t seed, const std::vector<std::shared_ptr<const Proxy>>& proxies = {});

// A decal type of `size` with the built-in texture `tex`; a half-depth of 0 takes the decal system's.
DecalType makeType(const char* name, glm::vec2 size, DecalTexture tex, bool wrap = false,
                   float halfDepth = 0.0f);

// The gallery (detail 1) from a camera over the floor towards the far wall, with 60 shots cycling
// through a bullet hole, a blood splat that wraps round corners and a deep scorch mark.
struct GalleryShots {
    Scene scene;
    Camera camera;
    Placed placed;
};
GalleryShots galleryShots();

// A paint decal type 0.3 wide, not turned, projected along its shot.
DecalType paintType();

// One decal of type `t` shot at `aim` from the right (+X), `degrees` off +Z, with `t` as the inputs'
// type 0 (the shot is expected to place).
CoverageInputs shotFromTheRight(const Scene& scene, const DecalType& t, const glm::dvec3& aim,
                                double degrees);

// A roof ridge along Y: a flat face (z = 0, normal +Z) for x in [0, 0.5] and, left of the ridge, a
// face falling away at `fallDegrees` (normal (-sin, 0, cos)) for x in [-0.5, 0], 0.6 deep along Y;
// each face a UV island of its own (u in [0.52, 0.98] and [0.02, 0.48]), with tangents.
Mesh ridgeMesh(double fallDegrees);

// The ridge as a scene, and one paintType() decal shot at its flat face 0.04 right of the ridge from
// the right, `shotDegrees` off its normal.
struct RidgeShot {
    Scene scene;
    CoverageInputs inputs;
};
RidgeShot ridgeShot(double fallDegrees, double shotDegrees);

} // namespace spatter::test
