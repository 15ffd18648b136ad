#pragma once
// DecalType: what a kind of decal looks like and how it is placed. Registered by name with the
// decal system; the renderer reads the appearance half.

#include "spatter/core/DecalProjection.hpp"

#include <glm/glm.hpp>
#include <string>

namespace spatter {

// Built-in procedural decal textures (layers of the renderer's decal texture array).
enum class DecalTexture : int { BulletHole = 0, Blood = 1, Paint = 2, Scorch = 3, Count = 4 };

// How a decal fades with the distance of a pixel to its plane, as a fraction of the half-depth.
enum class DepthFade : int { None = 0, Linear = 1, Smooth = 2 };

struct DecalType {
    std::string name;

    // Placement.
    glm::vec2 size{0.1f, 0.1f}; // full width (along the tangent) and height, world units
    float sizeJitter = 0.0f;    // relative, in [0, 1): size *= 1 + uniform(-j, j)
    bool randomRotation = true; // rotate the tangent about the normal by a seeded random angle
    float maxAngleDeg = 80.0f;  // largest angle between the reversed ray and the surface normal;
                                // the renderer also rejects pixels whose normal is farther than
                                // this from the decal's normal or from the axis it is projected
                                // along (the reversed shot, for a decal along its shot)
    float lifetime = 0.0f;      // seconds; 0 = permanent
    float fadeOutTime = 1.0f;   // seconds of fading before a decal is removed (lifetime, eviction)
    float halfDepth = 0.0f;     // least half-depth (world units): the automatic one (h plus
                                // depthMargin times the size) where larger; 0 = automatic; not
                                // used on skinned or morphed objects (laid on the drawn surface)
    bool onDynamic = true;      // may land on dynamic objects
    // The axis the texture is projected along (DecalProjection.hpp). Shot: a decal placed by spawn or
    // spawnBatch lands where its ray meets the drawn surface, even where that lies off the collision
    // proxy, and faces the drawn surface under the proxy (CollisionWorld::drawnNormalAt); spawnAt and
    // spawnAttached have no shot and project along the normal, as do volumetric
    // types (a crater is carved along the normal).
    Projection projection = Projection::Shot;

    // Appearance.
    int texture = int(DecalTexture::BulletHole); // layer in the decal texture array
    glm::vec4 tint{1.0f};
    bool wrapAround = false; // follow corners and curvature by the surface normal
    DepthFade depthFade = DepthFade::Smooth;
    bool normalMap = true;   // blend the texture's normal map into the G-buffer normal
    float roughness = -1.0f; // roughness written under the decal; < 0 keeps the surface's
    // Draw order (Unreal's SortOrder, Unity's draw order): decals of a higher priority draw over those
    // of a lower one whatever their spawn order; within a priority, newer decals (Decal::spawnTime)
    // draw over older ones, and decals of the same instant in the order they are given.
    int priority = 0;
    // Volumetric: instead of the projected texture, a crater model is drawn behind a stencil hole in
    // the surface (Renderer.hpp), with the surface's material continued into it; the decal system
    // clips it where the solid ends around the hit (DecalSystem::craterClips).
    bool volumetric = false;
};

// The decal size the tools take when none is given: 2% of the scene's bounding diagonal, so that
// decals fit a model of a few centimetres and a level of a hundred metres alike.
inline glm::vec2 decalSizeForScene(double sceneDiagonal) {
    return glm::vec2(float(0.02 * sceneDiagonal));
}

} // namespace spatter
