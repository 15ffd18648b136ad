#pragma once
// IouBreakdown: where the coverage IoU of proxy-placed against render-placed decals is lost. The same
// shots are placed in a system over the proxies and in one over the render meshes; the proxy-placed
// decals are drawn again with fields taken from the decal the same shot places on the render mesh
// (where both place one): its centre; its frame; its frame and slant; centre, frame and slant; and
// all of those with its half-depth. Its centre and half-depth alone stand for a decal pass that finds
// the drawn surface along the shot in the depth buffer and holds the box as shallow there as on the
// render mesh. What is still lost with every field taken is the shots that one system places and the
// other does not (grazing silhouettes, the angle limit met on one surface and not on the other); the
// next drops the decals the render mesh does not place as well, which leaves the shots only the
// render mesh places: no correction of a placed decal can win those back. The drawn probe takes
// nothing from the render-placed decal: each proxy-placed decal is laid again where the line along its
// projection axis meets the drawn surface (relaidDecal), its box as shallow as on the render mesh, and
// dropped where the line meets none in its box: what a decal pass reading the drawn surface from the
// depth buffer would draw where the camera sees that point. Its second form leaves a decal as placed
// where the camera does not see that point (or, for a line meeting nothing, the line's middle), as
// such a pass would have to; its third also takes the normal from the pixels around the meet, as the
// pass would read it from the depth buffer at the probe's resolution. Last, placement's side: each
// proxy-placed decal keeps its centre and depth, its frame laid on the face normal of the render
// triangle nearest its centre, as a normal kept for each part of a proxy triangle could lay it.

#include "CoverageProbe.hpp"

#include "spatter/core/DecalType.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/placement/CollisionWorld.hpp"
#include "spatter/placement/Ray.hpp"
#include "spatter/render/Camera.hpp"

#include <optional>
#include <vector>

namespace spatter::bench {

// One variant of the breakdown: its column in the table, its key in the JSON, its IoU.
struct IouVariant {
    const char* column;
    const char* key;
    double iou = 0.0;
};

// The variants in the order above, the table's.
using IouBreakdown = std::vector<IouVariant>;

// The IoUs against `reference` (the render-placed decals' mask from `camera`) of the decals `shots`
// place through `proxies` with decal type `type`, each variant drawn by `probe`.
Result<IouBreakdown> iouBreakdown(CoverageProbe& probe, const Camera& camera, const Scene& scene,
                                  const std::vector<std::shared_ptr<const Proxy>>& proxies,
                                  const std::vector<Ray>& shots, const DecalType& type, double diagonal,
                                  uint64_t seed, const std::vector<uint8_t>& reference);

} // namespace spatter::bench
