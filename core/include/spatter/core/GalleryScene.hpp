#pragma once
// builtin:gallery, the procedural shooting gallery: floor, back walls, pillars, crates, an arch
// and dynamic targets, with real geometric detail (bevels, brick relief, noise displacement) so
// that a simplified proxy differs visibly from the render mesh. Needs no files.
//
// Layout (metres, Y up; a player at (0, 1.7, 8) looking towards -Z sees the back wall, the targets
// through and beside the arch, crates and pillars):
// - "floor": concrete grid (open mesh) over x in [-10, 10], z in [-4, 8], surface at y = 0 +- 2 cm.
// - "wall_back": red brick slab x in [-10, 10], y in [-0.1, 4], z in [-4, -3.6] (front face at
//   z = -3.6; brick relief only moves it inward). "wall_left" / "wall_right": grey block slabs
//   0.4 m thick along x = -10..-9.6 and 9.6..10, z in [-3.65, 4], rotated +-90 degrees about Y.
// - "pillar_0".."pillar_3": fluted metal pillars at (+-7.5, -2) and (+-7.5, 3.5), y in [-0.05, 4].
// - "crate_0".."crate_5": wooden crates (cubes of 0.7..1 m, two stacked) near x = +-6, each
//   turned about Y.
// - "arch": stone arch centred at (0, 0, -1), 0.6 m deep, opening 4 m wide and 3.6 m high, top at y = 4.2.
// - "target_0".."target_{n-1}" (dynamic): bullseye plates (radius 0.4 m, centre 1.5 m up) on stands,
//   origins at (x, 0, -3.1) spread over x in [-5, 5]; every target lies in z in [-3.3, -2.99], so at
//   least 0.3 m in front of the back wall. Submeshes: white plate, red rings, dark steel stand.
// - "banner_0".."banner_{n-1}" (dynamic): cloth banners 1 m wide and 1.4 m long hanging from
//   (+-6, 3.4, -2.6), facing +Z: open single-sided grids whose UVs map them once onto the unit
//   square, so they can carry texture-space decals; the demo waves them on the GPU.
// Every object's mesh is built around its own origin and placed by its transform. Closed meshes
// (every edge used by two triangles): walls, pillars, crates, arch, targets (not the floor and banners). All
// meshes have unit normals from the displaced geometry, UVs in metres and tangents. World bounds lie inside
// x in [-10, 10], y in [-0.1, 4.25], z in [-4, 8].
// Triangles in total (3 targets): detail 0 a few thousand, detail 2 (default) between 40k and 150k.

#include "spatter/core/Scene.hpp"

#include <cstdint>

namespace spatter {

struct GallerySettings {
    uint64_t seed = 1;   // same seed, bit-identical scene
    int detail = 2;      // subdivision level of relief, clamped to [0, 3]; 0 is coarse without brick,
                         // plank and joint relief (fast tests), 2 the default
    int targetCount = 3; // dynamic targets in front of the back wall, clamped to [0, 8]
    int bannerCount = 2; // dynamic cloth banners, clamped to [0, 2]
};

Scene makeGalleryScene(const GallerySettings& settings = {});

} // namespace spatter
