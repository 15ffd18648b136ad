#include "spatter/core/SkinnedArm.hpp"

#include "spatter/core/MeshBuilder.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace spatter {

namespace {

Mesh armMesh(const SkinnedArmSettings& s, int rings) {
    std::vector<glm::vec2> profile{{0.0f, 0.0f}};
    for (int i = 0; i < rings; ++i)
        profile.emplace_back(s.radius, s.length * float(i) / float(rings - 1));
    profile.emplace_back(0.0f, s.length);
    return makeLathe(profile, std::clamp(s.segments, 3, 1024));
}

AnimationChannel rotationChannel(int node, const glm::dvec3& axis, double degrees, double period) {
    AnimationChannel c;
    c.node = node;
    c.path = AnimationPath::Rotation;
    c.interpolation = Interpolation::Linear;
    c.times = {0.0, 0.5 * period, period};
    c.width = 4;
    for (double angle : {0.0, degrees, 0.0}) {
        const glm::dquat q = glm::angleAxis(glm::radians(angle), axis);
        c.values.insert(c.values.end(), {q.x, q.y, q.z, q.w});
    }
    return c;
}

} // namespace

double skinnedArmElbowWeight(double y, double length) {
    const double t = std::clamp((y - 0.35 * length) / (0.3 * length), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

Scene makeSkinnedArm(const SkinnedArmSettings& s) {
    Scene scene;
    scene.source = "builtin:skinned-arm";
    SceneAnimation& a = scene.animation;
    a.nodes.resize(3);
    a.nodes[0].name = "arm";
    a.nodes[1].name = "shoulder";
    a.nodes[2].name = "elbow";
    a.nodes[2].parent = 1;
    a.nodes[2].translation = glm::dvec3(0.0, 0.5 * s.length, 0.0);
    Skin skin;
    skin.name = "arm";
    skin.joints = {1, 2};
    skin.inverseBindMatrices = {glm::dmat4(1.0),
                                glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, -0.5 * s.length, 0.0))};
    a.skins.push_back(skin);
    const double period = s.period > 0.0 ? s.period : 2.0;
    Animation swing;
    swing.name = "swing";
    swing.channels = {rotationChannel(1, {1.0, 0.0, 0.0}, s.swingDeg, period),
                      rotationChannel(2, {0.0, 0.0, 1.0}, s.bendDeg, period)};
    swing.duration = period;
    a.animations.push_back(swing);

    SceneObject arm = makeSceneObject("arm", armMesh(s, std::clamp(s.rings, 4, 1024)), glm::dmat4(1.0), true);
    arm.node = 0;
    arm.skin = 0;
    arm.skinWeights.influences = 2;
    for (const glm::vec3& p : arm.mesh->positions) {
        const double w = skinnedArmElbowWeight(p.y, s.length);
        arm.skinWeights.joints.insert(arm.skinWeights.joints.end(), {0, 1});
        arm.skinWeights.weights.insert(arm.skinWeights.weights.end(), {1.0 - w, w});
    }
    scene.objects.push_back(std::move(arm));
    return scene;
}

} // namespace spatter
