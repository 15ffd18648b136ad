#pragma once
// SceneEvaluator: a scene's pose at a time t of one of its animations, in double precision. It gives
// every node's world transform, every object's transform, every skin's joint matrices and every
// object's morph weights, computed once per (animation, t) and kept until the next time.
//
// Sampling follows glTF 2.0: STEP holds a key until the next, LINEAR interpolates linearly (rotations
// by spherical interpolation along the shorter arc), CUBICSPLINE is a cubic Hermite spline through
// the keys with the file's tangents scaled by the key interval; rotations are normalised after
// sampling. Before the first key a channel holds its first value, after the last its last value; a
// caller that loops passes the time modulo the animation's duration.

#include "spatter/core/Scene.hpp"

#include <vector>

namespace spatter {

class SceneEvaluator {
public:
    // Keeps a reference to `scene`, which must outlive the evaluator, must not change while it is
    // used, and must have passed validateScene. Starts in the rest pose.
    explicit SceneEvaluator(const Scene& scene);

    // Poses the scene at time `t` (seconds) of animation `animation`. An index outside
    // scene.animation.animations, or a non-finite `t`, gives the rest pose. Returns at once when
    // (animation, t) is the pose already held.
    void evaluate(int animation, double t);

    // World transform of every node of scene.animation.nodes at the current pose.
    const std::vector<glm::dmat4>& nodeWorld() const { return world_; }

    // Object-to-world transform of object `object` at the current pose: its node's world transform,
    // or its fixed transform when it has no node. Precondition: object < scene.objects.size().
    const glm::dmat4& objectTransform(size_t object) const;

    // Joint matrices of skin `skin` at the current pose, one per joint: the joint's world transform
    // times its inverse bind matrix (they take the skinned mesh from bind space to world space).
    // Precondition: skin < scene.animation.skins.size().
    const std::vector<glm::dmat4>& jointMatrices(size_t skin) const { return joints_[skin]; }

    // Morph weights of object `object` at the current pose, one per morph target (its node's
    // weights); empty for an object without morph targets. Precondition: object < scene.objects.size().
    const std::vector<double>& morphWeights(size_t object) const;

private:
    void poseLocals(int animation, double t);
    void composeWorld();

    const Scene& scene_;
    std::vector<size_t> order_;                   // nodes, parents first
    std::vector<glm::dvec3> translation_, scale_; // local TRS of the current pose
    std::vector<glm::dquat> rotation_;
    std::vector<std::vector<double>> weights_;
    std::vector<glm::dmat4> world_;
    std::vector<std::vector<glm::dmat4>> joints_;
    bool posed_ = false;
    int animation_ = -1;
    double time_ = 0.0;
};

// Positions of object `object`'s mesh at the evaluator's current pose, in double, in the object's
// space at that pose (map them to world with evaluator.objectTransform(object)): morph targets
// added with the object's weights, then the vertices skinned by its skin's joint matrices and brought
// back through the inverse of the object's transform. An object that neither morphs nor is skinned
// gives its rest positions. A skinned object whose transform at the pose is singular gives non-finite
// positions. Precondition: object < scene.objects.size(), the scene the evaluator was made for.
std::vector<glm::dvec3> posedPositions(const Scene& scene, size_t object, const SceneEvaluator& evaluator);

} // namespace spatter
