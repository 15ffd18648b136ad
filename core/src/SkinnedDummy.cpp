#include "spatter/core/SkinnedDummy.hpp"

#include "spatter/core/MeshBuilder.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>

namespace spatter {

namespace {

// Joints of the dummy's skin, in skin order.
enum Joint : uint16_t { Hips, ShoulderL, ElbowL, ShoulderR, ElbowR, JointCount };

constexpr double kShoulderHeight = 1.42, kShoulderSide = 0.25, kUpperArm = 0.3, kArm = 0.62;

// Appends `part` placed by `xf` and gives each of its vertices the weights `weigh(position in the
// part's own space)` returns: (joint, weight) for two influences.
template <class Weigh>
void appendPart(Mesh& mesh, SkinWeights& weights, const Mesh& part, const glm::mat4& xf, Weigh weigh) {
    appendMesh(mesh, part, xf);
    for (const glm::vec3& p : part.positions) {
        const std::array<std::pair<uint16_t, double>, 2> w = weigh(p);
        for (const auto& [joint, weight] : w) {
            weights.joints.push_back(joint);
            weights.weights.push_back(weight);
        }
    }
}

// A round bar of `length` along +Y from its origin, `rings` rings of vertices.
Mesh bar(float radius, float length, int rings, int segments) {
    std::vector<glm::vec2> profile{{0.0f, 0.0f}};
    for (int i = 0; i < rings; ++i)
        profile.emplace_back(radius, length * float(i) / float(rings - 1));
    profile.emplace_back(0.0f, length);
    return makeLathe(profile, segments);
}

// An arm hanging from its shoulder: its bar turned upside down, the elbow's share blending in around
// the elbow.
void appendArm(Mesh& mesh, SkinWeights& weights, double side, uint16_t shoulder, uint16_t elbow) {
    const glm::mat4 xf =
        glm::translate(glm::mat4(1.0f), glm::vec3(float(side), float(kShoulderHeight), 0.0f)) *
        glm::rotate(glm::mat4(1.0f), float(glm::pi<double>()), glm::vec3(0.0f, 0.0f, 1.0f));
    appendPart(mesh, weights, bar(0.05f, float(kArm), 24, 12), xf, [&](const glm::vec3& p) {
        const double t = std::clamp((double(p.y) - (kUpperArm - 0.08)) / 0.16, 0.0, 1.0);
        const double w = t * t * (3.0 - 2.0 * t);
        return std::array<std::pair<uint16_t, double>, 2>{{{shoulder, 1.0 - w}, {elbow, w}}};
    });
}

// Legs, torso and head ride the hips; the arms hang from the shoulders.
void buildBody(SceneObject& o) {
    Mesh mesh;
    SkinWeights& weights = o.skinWeights;
    const auto rigid = [](const glm::vec3&) {
        return std::array<std::pair<uint16_t, double>, 2>{{{Hips, 1.0}, {Hips, 0.0}}};
    };
    appendPart(mesh, weights, bar(0.07f, 0.86f, 6, 12),
               glm::translate(glm::mat4(1.0f), glm::vec3(0.1f, 0.0f, 0.0f)), rigid);
    appendPart(mesh, weights, bar(0.07f, 0.86f, 6, 12),
               glm::translate(glm::mat4(1.0f), glm::vec3(-0.1f, 0.0f, 0.0f)), rigid);
    appendPart(mesh, weights, bar(0.18f, 0.62f, 10, 20),
               glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.84f, 0.0f)), rigid);
    appendPart(mesh, weights, makeSphere(0.11f, 8, 16),
               glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.6f, 0.0f)), rigid);
    appendArm(mesh, weights, kShoulderSide, ShoulderL, ElbowL);
    appendArm(mesh, weights, -kShoulderSide, ShoulderR, ElbowR);
    o.mesh = shareMesh(std::move(mesh));
}

AnimationChannel turn(int node, const glm::dvec3& axis, const std::array<double, 5>& degrees, double period) {
    AnimationChannel c;
    c.node = node;
    c.path = AnimationPath::Rotation;
    c.interpolation = Interpolation::Linear;
    c.width = 4;
    for (size_t k = 0; k < degrees.size(); ++k) {
        c.times.push_back(period * double(k) / double(degrees.size() - 1));
        const glm::dquat q = glm::angleAxis(glm::radians(degrees[k]), axis);
        c.values.insert(c.values.end(), {q.x, q.y, q.z, q.w});
    }
    return c;
}

} // namespace

uint32_t addSkinnedDummy(Scene& scene, const glm::dmat4& transform, double period) {
    SceneAnimation& a = scene.animation;
    const int root = int(a.nodes.size());
    // Nodes: the dummy (placed by `transform`), its hips, and per arm a shoulder and an elbow.
    const std::array<std::pair<const char*, glm::dvec3>, 6> nodes = {
        {{"dummy", glm::dvec3(0.0)},
         {"dummy_hips", glm::dvec3(0.0)},
         {"dummy_shoulder_l", {kShoulderSide, kShoulderHeight, 0.0}},
         {"dummy_elbow_l", {0.0, -kUpperArm, 0.0}},
         {"dummy_shoulder_r", {-kShoulderSide, kShoulderHeight, 0.0}},
         {"dummy_elbow_r", {0.0, -kUpperArm, 0.0}}}};
    const std::array<int, 6> parent = {-1, root, root + 1, root + 2, root + 1, root + 4};
    for (size_t i = 0; i < nodes.size(); ++i) {
        SceneNode n;
        n.name = nodes[i].first;
        n.parent = parent[i];
        n.translation = nodes[i].second;
        if (i == 0) {
            n.hasMatrix = true;
            n.matrix = transform;
        }
        a.nodes.push_back(n);
    }
    // A joint's rest transform below the dummy's node, whose inverse takes the dummy's mesh to it.
    Skin skin;
    skin.name = "dummy";
    for (int j = 0; j < JointCount; ++j) {
        const int node = root + 1 + j;
        skin.joints.push_back(node);
        glm::dmat4 rest(1.0);
        for (int k = node; k != root; k = a.nodes[size_t(k)].parent)
            rest = glm::translate(glm::dmat4(1.0), a.nodes[size_t(k)].translation) * rest;
        skin.inverseBindMatrices.push_back(glm::inverse(rest));
    }
    const int skinIndex = int(a.skins.size());
    a.skins.push_back(skin);

    if (a.animations.empty()) a.animations.push_back(Animation{"dummy_swing", {}, 0.0});
    Animation& swing = a.animations[0];
    swing.channels.insert(swing.channels.end(),
                          {turn(root + 1, {0.0, 1.0, 0.0}, {0.0, 20.0, 0.0, -20.0, 0.0}, period),
                           turn(root + 2, {1.0, 0.0, 0.0}, {0.0, -40.0, 0.0, 40.0, 0.0}, period),
                           turn(root + 3, {1.0, 0.0, 0.0}, {0.0, -60.0, 0.0, -60.0, 0.0}, period),
                           turn(root + 4, {1.0, 0.0, 0.0}, {0.0, 40.0, 0.0, -40.0, 0.0}, period),
                           turn(root + 5, {1.0, 0.0, 0.0}, {0.0, -60.0, 0.0, -60.0, 0.0}, period)});
    swing.duration = std::max(swing.duration, period);

    SceneObject dummy = makeSceneObject("dummy", Mesh(), transform, true);
    dummy.node = root;
    dummy.skin = skinIndex;
    dummy.skinWeights.influences = 2;
    buildBody(dummy);
    scene.objects.push_back(std::move(dummy));
    return uint32_t(scene.objects.size() - 1);
}

} // namespace spatter
