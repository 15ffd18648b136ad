#pragma once
// ScenePosing: a decal system posed as its scene stands at a time of the scene's first animation, as
// spatter-place --time traces it and spatter-render --time --rays draws and places it.
//
//   std::vector<std::string> refused = poseDecalSystem(system, scene, DrawPose{1.2, offset});

#include "spatter/core/Scene.hpp"
#include "spatter/placement/DecalRecords.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <string>
#include <vector>

namespace spatter {

// Poses the animated dynamic receivers of `system` (built on `scene`, moved by pose.offset) at
// pose.time of the scene's first animation: skinned and morphed ones with setPose (transform, joint
// matrices and morph weights), the others with setTransform. A scene without animations changes
// nothing. Returns the message of every object the system refuses to pose (each names it); the
// others are posed.
std::vector<std::string> poseDecalSystem(DecalSystem& system, const Scene& scene, const DrawPose& pose);

} // namespace spatter
