#pragma once
// CraterClipping: where the solid a volumetric decal's crater is carved into ends around the hit,
// found in the collision proxy when the decal is placed (DecalSystem), as CraterClip planes.
//
// Rays in crater space (CraterClip.hpp) walk the proxy: one from just in front of the centre
// straight back, through the surface the decal lies on, to the crater's depth bound (the back of a
// thin wall), then eight sideways at half the depth that is still inside the solid, out to just past
// the rim (the side face at an edge or a corner). Along each ray the faces met are counted, entering
// (front) and leaving (back); where the ray leaves the solid, that face's plane is a candidate, unless
// another solid begins within twice the proxy error bound (a wall standing on a floor: the floor
// goes on under the crater). Near-parallel candidates are merged, and the two that cut the most are
// kept. The proxies of objects met are in the world as they are at that moment; a decal keeps its
// planes when other objects move later.

#include "spatter/core/CraterClip.hpp"
#include "spatter/core/Decal.hpp"
#include "spatter/placement/CollisionWorld.hpp"

#include <glm/glm.hpp>

namespace spatter {

// The clip planes of `decal` (object space, its box sound) on an object with `objectToWorld`, whose
// collision mesh stays within `errorBound` (world units) of the render surface.
CraterClips findCraterClips(const CollisionWorld& world, const glm::dmat4& objectToWorld, double errorBound,
                            const Decal& decal);

} // namespace spatter
