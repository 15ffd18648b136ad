#pragma once
// PoseBound: how far a deforming object's collision mesh strays from its render mesh over the poses
// of its animations. A proxy is certified at the rest pose (buildProxy); skinned and morphed with a
// deformation transferred from the render mesh (VertexDeformation.hpp) it follows the drawn surface
// only as far as its vertices allow: a proxy that kept no vertices where the skin bends cuts across
// the bend. boundOverPoses measures it.
//
// Method: every animation of the scene is sampled at `samples` + 1 evenly spaced times from 0 to
// its duration (a scene without animations: the rest pose alone). At each sampled pose both meshes
// are posed (posedPositions, posePositions) and the two-sided Hausdorff distance between them is
// certified (boundHausdorff: an upper bound, never below the true distance). Between two neighbouring
// samples a point of either surface is at most half the larger vertex displacement of the interval
// away from where it is at the nearer sample, if vertices move close to straight at even speed over
// the interval (which sampling finely enough makes true: the interval's chord then matches its
// path), so the bound over the interval is the larger of its two sampled bounds plus half of the
// render mesh's and half of the collision mesh's largest displacement.

#include "spatter/core/Mesh.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/core/VertexDeformation.hpp"

namespace spatter {

struct PoseBound {
    double bound = 0.0;      // over every animation: the largest interval bound (see above)
    double sampledMax = 0.0; // the largest certified bound at a sampled pose
    double motion = 0.0;     // the largest allowance for the motion within an interval
    size_t poses = 0;        // poses sampled
    int worstAnimation = -1; // where sampledMax was found (-1: the rest pose)
    double worstTime = 0.0;
};

// Calls `f(animation, step, t)` for every pose boundOverPoses samples, in its order: each animation
// of the scene at `samples` + 1 evenly spaced times t from 0 to its duration (step 0 to `samples`),
// or the rest pose alone (animation -1, step 0, t 0) for a scene without animations.
template <class F> void forEachSampledPose(const Scene& scene, int samples, F&& f) {
    const int animations = int(scene.animation.animations.size());
    if (animations == 0) return f(-1, 0, 0.0);
    for (int a = 0; a < animations; ++a) {
        const double duration = scene.animation.animations[size_t(a)].duration;
        for (int i = 0; i <= samples; ++i)
            f(a, i, duration * double(i) / double(samples));
    }
}

// The bound of collision mesh `collision` (object space, deformed by `deformation`, which must match
// it) against the render mesh of `scene.objects[object]` over the scene's animations, sampled
// `samples` (>= 1) times each. Each certification may exceed the distance it measures by `margin`
// (absolute, > 0). Fails on bad arguments or when a pose cannot be certified (the message says which).
Result<PoseBound> boundOverPoses(const Scene& scene, size_t object, const Mesh& collision,
                                 const VertexDeformation& deformation, int samples, double margin);

} // namespace spatter
