#pragma once
// ImageDrift: how far the drawn centre of a decal on a skinned object lies from the surface point it
// was placed on, in the image, over an animation. Each decal is drawn alone, with a centre marker for
// texture (an opaque red disc a fifth of the decal's width across at the texture's centre, clear
// elsewhere), in the albedo view; the drawn centre is the centroid of the pixels the marker changes
// (weighted by how much), so that a curved surface that clips the decal's edges does not move it. The
// point is the render-surface point nearest the decal's centre at its spawn, posed with the mesh and
// projected. Drift is their distance over the decal's size in pixels at the point's depth. Three ways
// to keep a decal on a character are drawn with the same decals:
//   skin anchors, projected   the decal system moves the decal with the skin (DecalSystem::setPose)
//                             and the decal pass projects it
//   texture-space splat       splatted into the object's decal texture in the spawn pose
//                             (DecalMode::TextureSpace; needs a UV layout without overlaps)
//   nearest joint             the spawn-time box carried by the joint of largest weight at the
//                             nearest render vertex, as engines attach decals to bones

#include "spatter/core/Result.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/placement/Ray.hpp"
#include "spatter/render/Camera.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace spatter::bench {

struct ImageDriftInput {
    const Scene* scene = nullptr;
    uint32_t object = 0;            // the skinned object, posed by animation 0
    double spawnTime = 0.0;         // when the decals are shot
    std::vector<double> frameTimes; // when they are measured
    double decalSize = 0.0;         // world units
    Camera camera;                  // fixed for every frame
    int width = 960, height = 720;
    std::vector<Ray> shots; // fired in turn until `decals` decals land visibly on the object
    size_t decals = 8;
};

struct ImageDriftRow {
    std::string method;
    std::string unavailable;       // why the method was not measured; empty when it was
    size_t decals = 0;             // decals followed
    std::vector<double> drift;     // per decal and frame where its marker shows, of the decal's size
    double atSpawnMax = 0.0;       // the largest at the spawn pose itself: what the measure reads there
    double splatMs = std::nan(""); // texture space: the splat pass per decal, median (GPU timer)
};

// The three methods' rows. Fails without an OpenGL context or when the scene cannot be drawn.
Result<std::vector<ImageDriftRow>> measureImageDrift(const ImageDriftInput& in);

} // namespace spatter::bench
