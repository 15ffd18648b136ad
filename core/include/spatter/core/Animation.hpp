#pragma once
// Animation in the scene model: the node hierarchy an animated scene keeps, its skins, its
// animations (keyframed channels on node translation, rotation, scale and morph weights), and the
// per-vertex data that lets an object's mesh deform (joint influences and morph targets).
//
// The mesh of every object stays in its rest pose; SceneEvaluator (spatter/core/SceneEvaluator.hpp)
// computes the pose at a time t. Values follow glTF 2.0: rotations are unit quaternions, a node's
// local transform is T * R * S (or a fixed matrix), a skin's joint matrix is the joint's world
// transform times its inverse bind matrix.

#include "spatter/core/Result.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace spatter {

// One node of the scene's hierarchy in its rest pose.
struct SceneNode {
    std::string name;
    int parent = -1;        // index into SceneAnimation::nodes, -1 for a root
    bool hasMatrix = false; // true: `matrix` is the local transform and no channel may target it
    glm::dmat4 matrix{1.0}; // the local transform when hasMatrix
    glm::dvec3 translation{0.0};
    glm::dquat rotation{1.0, 0.0, 0.0, 0.0}; // (w, x, y, z), unit length (as glTF requires; used
                                             // as given)
    glm::dvec3 scale{1.0};
    std::vector<double> weights; // rest morph weights, one per morph target of the node's mesh
};

// Joints of a skin and the matrices that take the mesh from its bind space to each joint's space.
struct Skin {
    std::string name;
    std::vector<int> joints;                     // node indices, distinct (as glTF requires; not
                                                 // checked)
    std::vector<glm::dmat4> inverseBindMatrices; // one per joint (identity where the file has none)
};

enum class Interpolation { Step, Linear, CubicSpline };
enum class AnimationPath { Translation, Rotation, Scale, Weights };

// Keyframes of one animated property of one node.
struct AnimationChannel {
    int node = -1; // index into SceneAnimation::nodes
    AnimationPath path = AnimationPath::Translation;
    Interpolation interpolation = Interpolation::Linear;
    std::vector<double> times; // seconds, finite and strictly increasing, at least one
    // `width` numbers per element: 3 (translation, scale), 4 (rotation x, y, z, w) or the morph
    // target count (weights). One element per key, or for CubicSpline three per key (in-tangent,
    // value, out-tangent).
    std::vector<double> values;
    int width = 0;
};

struct Animation {
    std::string name;
    std::vector<AnimationChannel> channels; // at most one per node and path (as glTF requires; not
                                            // checked: of two, the later wins)
    double duration = 0.0;                  // the last key time of all channels (as the loader sets
                                            // it; not checked)
};

// Everything that animates a scene. Empty for a scene without animations, skins or morph targets.
struct SceneAnimation {
    std::vector<SceneNode> nodes; // parents before or after children, in the file's order
    std::vector<Skin> skins;
    std::vector<Animation> animations;

    bool empty() const { return nodes.empty(); }
};

// Joint influences of every vertex of a mesh: `influences` (joint, weight) pairs per vertex, weights
// non-negative and summing to 1. Joints index the object's skin's `joints`.
struct SkinWeights {
    int influences = 0; // 0: not skinned
    std::vector<uint16_t> joints;
    std::vector<double> weights; // normalised in double, so that posing loses nothing to them
};

// Displacements of one morph target, one per vertex of the mesh; NORMAL and TANGENT deltas may be
// empty (the target does not move them).
struct MorphTarget {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec3> tangents;
};

// Checks the animation data of a scene against itself, so that evaluating it never reads out of
// bounds: parent links form a forest, finite rest transforms, skin joints and their matrices, channel
// nodes, widths, value counts, finite and strictly increasing key times, finite values. The error
// names the node, skin, animation or channel and the problem.
Status validateAnimation(const SceneAnimation& animation);

struct SceneObject;

// Checks an object's animation data against the scene's: its node and skin exist, its joint
// influences cover every vertex with valid joints and weights summing to 1, and its morph targets
// match its mesh and its node's weights. The error names the problem (the caller names the object).
Status validateObjectAnimation(const SceneObject& object, const SceneAnimation& animation);

} // namespace spatter
