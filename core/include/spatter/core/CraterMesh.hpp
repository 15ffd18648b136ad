#pragma once
// CraterMesh: the small model behind a volumetric decal (Woodhouse, "3D Decals"): an open cup of
// unit radius whose rim is a closed boundary loop lying exactly in the z = 0 plane, with its depth
// along -z. The rim is chipped in xy only, so flattening the rim onto z = 0 gives the footprint that
// covers the whole cup seen from the front; no vertex lies above the rim plane or outside the unit
// circle. Triangles face +z (into the cavity, towards the viewer); the bottom is closed, so every
// ray entering through the rim leaves through the cup.
//
//   Result<Mesh> crater = makeCraterMesh(variant);   // variant: any value; the same one, the same mesh
//   // rim vertices: the first `shape.segments` positions, counter-clockwise seen from +z

#include "spatter/core/Mesh.hpp"
#include "spatter/core/Result.hpp"

#include <cstdint>

namespace spatter {

struct CraterShape {
    float depth = 0.45f;     // depth of the cup at its centre, in units of the radius, in (0, 4]
    float chip = 0.22f;      // largest inward chip of the rim, in units of the radius, in [0, 0.9)
    float roughness = 0.08f; // inward (downward) bumps of the inner wall, in units of the depth, [0, 0.5]
    int segments = 40;       // vertices around the rim, in [8, 1024]
    int rings = 5;           // rings of vertices from the rim to the bottom, in [1, 256]
};

// The crater of `variant` (a seed). Positions, smooth normals and indices; no UVs. Fails on a
// shape outside the ranges above.
Result<Mesh> makeCraterMesh(uint32_t variant, const CraterShape& shape = {});

// An upper bound of the depth of every crater of `shape`, in units of the radius (a shape's variants
// differ in depth by up to a quarter and by their roughness).
float craterDepthBound(const CraterShape& shape = {});

} // namespace spatter
