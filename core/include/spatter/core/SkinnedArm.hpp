#pragma once
// builtin:skinned-arm, a skinned and animated arm generated in code: a round bar along +Y from the
// shoulder (y = 0) to the hand (y = length), bent at the elbow (y = length / 2) by two joints. The
// vertices near the elbow blend both joints (over 30% of the length), so that the bend deforms the
// surface as a character's skin does, not as two rigid pieces. One animation, "swing", loops over
// `period` seconds: the shoulder swings up to `swingDeg` about X and back, the elbow bends up to
// `bendDeg` about Z and back (both at their largest at half the period). Needs no files; tests,
// benchmarks and the gallery use it as a skinned target whose drawn pose can be computed exactly.

#include "spatter/core/Scene.hpp"

namespace spatter {

struct SkinnedArmSettings {
    float radius = 0.1f;
    float length = 1.0f;
    int rings = 32;    // rings of vertices along the bar, clamped to [4, 1024]
    int segments = 24; // vertices around a ring, clamped to [3, 1024]
    double bendDeg = 90.0;
    double swingDeg = 30.0;
    double period = 2.0; // seconds, > 0
};

// Object 0 is the arm (dynamic, skinned by skin 0 with joints "shoulder" and "elbow", two influences
// per vertex); animation 0 is "swing". Passes validateScene.
Scene makeSkinnedArm(const SkinnedArmSettings& settings = {});

// The elbow's weight at height `y` of an arm of `length` (the shoulder has the rest): 0 below the
// blend zone, 1 above it, smooth between. What makeSkinnedArm gives each vertex, for a mesh that is
// to bend as the arm does.
double skinnedArmElbowWeight(double y, double length);

} // namespace spatter
