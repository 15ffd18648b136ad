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
// samples every vertex is taken to move straight at even speed (which sampling finely enough makes
// true: the interval's chord then matches its path), so every point of either surface does too. A
// point x and its nearest point y on the other surface at one end of the interval then move apart by
// at most how far the two surfaces move against each other there: the largest difference between a
// displacement of a corner of x's triangle (of a piece of it, for a collision triangle larger than the
// render triangles) and one of y's, over pairs of triangles within that end's bound of each other.
// From either end the distance grows by at most that share of the interval, so the bound over the
// interval is the larger of its two sampled bounds plus half the larger of the two ends' relative
// motions. Two surfaces that move together (the same joints carry both) gain little over an
// interval, however far they travel.

#include "spatter/core/Mesh.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/core/VertexDeformation.hpp"

namespace spatter {

struct PoseBound {
    double bound = 0.0;      // over every animation: the largest interval bound (see above)
    double sampledMax = 0.0; // the largest certified bound at a sampled pose
    double motion = 0.0;     // the largest allowance for the surfaces' relative motion in an interval
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
// `threads` as HausdorffSettings::threads (the result does not depend on it).
Result<PoseBound> boundOverPoses(const Scene& scene, size_t object, const Mesh& collision,
                                 const VertexDeformation& deformation, int samples, double margin,
                                 unsigned threads = 0);

// The same poses sampled, not certified: at each, the largest distance sampledLowerBound finds both
// ways at up to `maxTriangles` triangles a direction, a distance the meshes attain there. `bound` and
// `sampledMax` are the largest of them (no motion allowance), so boundOverPoses is never below it;
// `motion` is 0. Much cheaper than boundOverPoses: for finding the worst pose and for ruling a
// candidate out. Fails like boundOverPoses.
Result<PoseBound> sampledOverPoses(const Scene& scene, size_t object, const Mesh& collision,
                                   const VertexDeformation& deformation, int samples, size_t maxTriangles,
                                   unsigned threads = 0);

} // namespace spatter
