#pragma once
// Proxy-versus-render mismatch: the same seeded rays cast at a scene's collision proxies and at its
// render meshes, and decals spawned on the proxies checked against the render surface.
//
// Two collision worlds are built from the scene: one with the given proxies (every receiver's
// collision mesh and error bound h) and one with the render meshes (h = 0). For every decal receiver
// the ray set holds `raysPerObject` rays from points just outside the object's world bounding
// sphere: half aimed at uniform random points of its world bounds, half at area-weighted random
// points of its render surface (so that most rays hit). For each ray:
//  - the proxy hit's distance to the render surface of the object hit, in object space, by exact
//    closest-point query (ClosestPointQuery); the proxy's certificate says it is at most h;
//  - where both worlds hit the same object: the offset along the ray between the two hits and the
//    angle between their geometric normals;
//  - where one world hits and the other misses, or they hit different objects: a disagreement;
//  - a decal spawned by the ray through a DecalSystem on the proxy world (one with the default
//    depth margin, one with a margin of tightMargin * size, so that half-depth ~ h), projected
//    along the normal: the render surface point nearest to the decal centre, expressed in the
//    decal's frame (object space, as the renderer uses it), must satisfy |x| <= w/2, |y| <= h/2,
//    |z| <= half_depth;
//  - a decal projected along the shot (default margin): the render hit of the same ray, where it is
//    on the same object, expressed in the decal's slanted box.
// Every ray is counted for the object the proxy world hit (else the render world, else the object
// it was aimed at).

#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Scene.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace spatter::test {

struct MismatchSettings {
    uint32_t raysPerObject = 2000;
    uint64_t seed = 1;
    // Decal width and height on an object: max(decalSizeFraction * its world bounding diagonal,
    // 4 * its world error bound), so that the nearest render point (within h of the centre) is well
    // inside the footprint.
    float decalSizeFraction = 0.05f;
    // DecalSettings::depthMargin of the second decal system (the first uses the default).
    float tightMargin = 1e-3f;
};

// p50, p99 (nearest rank) and maximum of a sample; all 0 for an empty one.
struct Distribution {
    size_t count = 0;
    double p50 = 0.0;
    double p99 = 0.0;
    double max = 0.0;
};
Distribution summarize(std::vector<double> values);

struct ObjectMismatch {
    std::string name;
    uint32_t object = 0;   // index into Scene::objects
    double errorBound = 0; // h, object units
    double diagonal = 0;   // bounding diagonal of the render mesh's referenced vertices, object units
    size_t renderTriangles = 0;
    size_t proxyTriangles = 0;

    size_t rays = 0;             // rays counted for this object
    size_t proxyHits = 0;        // rays whose proxy hit is on this object
    double maxHitDistance = 0.0; // largest distance of a proxy hit to the render surface, object units
    size_t hitsBeyondBound = 0;  // proxy hits farther than h (plus a 1e-6 * diagonal rounding allowance)

    // Both worlds hit this object: |t_proxy - t_render| in units of the object's world diagonal, and
    // the angle between the two hit normals in degrees.
    std::vector<double> offsets;
    std::vector<double> angles;
    // Disagreements: the proxy world hits and the render world misses, the other way round, or they
    // hit different objects.
    size_t proxyOnly = 0;
    size_t renderOnly = 0;
    size_t otherObject = 0;

    size_t decals = 0;        // placed with the default depth margin
    size_t decalsHolding = 0; // ... whose box holds the nearest render point
    size_t tightDecals = 0;   // placed with the tight margin
    size_t tightHolding = 0;  // ... whose box holds the nearest render point
    // Of the render point nearest to a decal centre, in the decal's box: the largest |z| / half_depth
    // for the default and the tight boxes, and (tight boxes) the largest max(|x| / (w/2), |y| / (h/2)).
    double defaultDepthUse = 0.0;
    double tightDepthUse = 0.0;
    double lateralUse = 0.0;
    // Decals projected along the shot (default margin) where the render world hits the same object
    // and the shot is within kMaxSlantDeg of the proxy normal: how many have that render hit within
    // the half-depth of their plane (|w| <= 1 in the unit box), its largest |w| over all of them, and
    // its largest max(|u|, |v|) over those (0 on the box's axis, but for the slope's rounding).
    size_t shotDecals = 0;
    size_t shotInSlab = 0;
    double shotDepthUse = 0.0;
    double shotLateralUse = 0.0;

    size_t disagreements() const { return proxyOnly + renderOnly + otherObject; }
};

// Measures every decal receiver of `scene` with `proxies` (empty, or one entry per object; an empty
// entry means the render mesh is the collision mesh, h = 0). Fails when a world or decal system
// cannot be built; the message names the scene.
Result<std::vector<ObjectMismatch>> measureMismatch(const Scene& scene,
                                                    const std::vector<std::shared_ptr<const Proxy>>& proxies,
                                                    const MismatchSettings& settings = {});

// Diagonal of the bounding box of the vertices referenced by `mesh.indices` (the diagonal that a
// relative proxy tolerance refers to); 0 for a mesh with no triangle.
double referencedDiagonal(const Mesh& mesh);

} // namespace spatter::test
