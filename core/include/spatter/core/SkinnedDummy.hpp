#pragma once
// A skinned training dummy generated in code, for the gallery: legs, a torso and a head that turn
// together at the hips, and two arms that swing from the shoulders and bend at the elbows, the skin
// blending shoulder and elbow around each elbow as a character's does. About 1.75 m tall, facing +Z
// at rest. Its channels loop over `period` seconds: the hips turn 20 degrees each
// way, the arms swing 40 degrees forward and back in opposite phase, the elbows bend up to 60
// degrees. Needs no files.

#include "spatter/core/Scene.hpp"

namespace spatter {

// Appends the dummy to `scene` as one dynamic skinned object named "dummy", placed by `transform`
// (its root node's rest transform), with its own nodes and skin; its channels join the scene's first
// animation (made, named "dummy_swing", when the scene has none), so that one evaluation poses every
// dummy. Returns the new object's index. The scene still passes validateScene.
uint32_t addSkinnedDummy(Scene& scene, const glm::dmat4& transform, double period = 3.0);

} // namespace spatter
