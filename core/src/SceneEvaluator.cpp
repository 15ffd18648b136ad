#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/VertexDeformation.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace spatter {

namespace {

// Where time `t` falls among `times`: key `k` and the fraction `s` towards key k + 1 (0 at or outside
// the ends, where k is the first or last key).
struct KeySpan {
    size_t k = 0;
    double s = 0.0;
};

KeySpan findSpan(const std::vector<double>& times, double t) {
    const size_t next = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin());
    if (next == 0) return {0, 0.0};
    if (next == times.size()) return {times.size() - 1, 0.0};
    return {next - 1, (t - times[next - 1]) / (times[next] - times[next - 1])};
}

// Component `c` of element `element` of key `k`: CUBICSPLINE keys hold (in-tangent, value,
// out-tangent), the others only the value (element 1 below stands for it).
double keyValue(const AnimationChannel& ch, size_t k, int element, int c) {
    const size_t w = size_t(ch.width);
    if (ch.interpolation != Interpolation::CubicSpline) return ch.values[k * w + size_t(c)];
    return ch.values[(3 * k + size_t(element)) * w + size_t(c)];
}

// Samples `ch` at `t` into out[0 .. width).
void sample(const AnimationChannel& ch, double t, double* out) {
    const KeySpan span = findSpan(ch.times, t);
    const bool between = span.k + 1 < ch.times.size() && span.s > 0.0;
    for (int c = 0; c < ch.width; ++c) {
        const double a = keyValue(ch, span.k, 1, c);
        if (!between || ch.interpolation == Interpolation::Step) {
            out[c] = a;
            continue;
        }
        const double b = keyValue(ch, span.k + 1, 1, c), s = span.s;
        if (ch.interpolation == Interpolation::Linear) {
            out[c] = (1.0 - s) * a + s * b;
            continue;
        }
        const double td = ch.times[span.k + 1] - ch.times[span.k];
        const double s2 = s * s, s3 = s2 * s;
        out[c] = (2 * s3 - 3 * s2 + 1) * a + td * (s3 - 2 * s2 + s) * keyValue(ch, span.k, 2, c) +
                 (-2 * s3 + 3 * s2) * b + td * (s3 - s2) * keyValue(ch, span.k + 1, 0, c);
    }
}

glm::dquat quat(const double* xyzw) {
    return glm::dquat(xyzw[3], xyzw[0], xyzw[1], xyzw[2]);
}

// Spherical interpolation from `a` to `b` (unit) along the shorter arc.
glm::dquat slerp(const glm::dquat& a, glm::dquat b, double s) {
    double d = glm::dot(a, b);
    if (d < 0.0) {
        b = -b;
        d = -d;
    }
    const double theta = std::acos(std::min(d, 1.0));
    const double sinTheta = std::sin(theta);
    if (sinTheta < 1e-12) return glm::normalize(a * (1.0 - s) + b * s);
    return a * (std::sin((1.0 - s) * theta) / sinTheta) + b * (std::sin(s * theta) / sinTheta);
}

glm::dquat sampleRotation(const AnimationChannel& ch, double t) {
    const KeySpan span = findSpan(ch.times, t);
    const bool between = span.k + 1 < ch.times.size() && span.s > 0.0;
    if (ch.interpolation == Interpolation::Linear && between) {
        const glm::dquat a = glm::normalize(quat(&ch.values[span.k * 4]));
        const glm::dquat b = glm::normalize(quat(&ch.values[(span.k + 1) * 4]));
        return glm::normalize(slerp(a, b, span.s));
    }
    double q[4];
    sample(ch, t, q);
    return glm::normalize(quat(q));
}

glm::dmat4 localMatrix(const glm::dvec3& t, const glm::dquat& r, const glm::dvec3& s) {
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), t);
    m *= glm::mat4_cast(r);
    return glm::scale(m, s);
}

} // namespace

SceneEvaluator::SceneEvaluator(const Scene& scene) : scene_(scene) {
    const std::vector<SceneNode>& nodes = scene.animation.nodes;
    std::vector<std::vector<size_t>> children(nodes.size());
    for (size_t n = 0; n < nodes.size(); ++n)
        if (nodes[n].parent == -1)
            order_.push_back(n);
        else
            children[size_t(nodes[n].parent)].push_back(n);
    for (size_t i = 0; i < order_.size(); ++i)
        for (size_t c : children[order_[i]])
            order_.push_back(c);
    world_.assign(nodes.size(), glm::dmat4(1.0));
    joints_.resize(scene.animation.skins.size());
    for (size_t s = 0; s < joints_.size(); ++s)
        joints_[s].assign(scene.animation.skins[s].joints.size(), glm::dmat4(1.0));
    evaluate(-1, 0.0);
}

void SceneEvaluator::evaluate(int animation, double t) {
    const bool valid =
        animation >= 0 && size_t(animation) < scene_.animation.animations.size() && std::isfinite(t);
    if (!valid) {
        animation = -1;
        t = 0.0;
    }
    if (posed_ && animation == animation_ && t == time_) return;
    poseLocals(animation, t);
    composeWorld();
    posed_ = true;
    animation_ = animation;
    time_ = t;
}

void SceneEvaluator::poseLocals(int animation, double t) {
    const std::vector<SceneNode>& nodes = scene_.animation.nodes;
    translation_.resize(nodes.size());
    rotation_.resize(nodes.size());
    scale_.resize(nodes.size());
    weights_.resize(nodes.size());
    for (size_t n = 0; n < nodes.size(); ++n) {
        translation_[n] = nodes[n].translation;
        rotation_[n] = nodes[n].rotation;
        scale_[n] = nodes[n].scale;
        weights_[n].assign(nodes[n].weights.begin(), nodes[n].weights.end());
    }
    if (animation == -1) return;
    double v[3];
    for (const AnimationChannel& ch : scene_.animation.animations[size_t(animation)].channels) {
        const size_t n = size_t(ch.node);
        switch (ch.path) {
        case AnimationPath::Translation:
            sample(ch, t, v);
            translation_[n] = glm::dvec3(v[0], v[1], v[2]);
            break;
        case AnimationPath::Rotation:
            rotation_[n] = sampleRotation(ch, t);
            break;
        case AnimationPath::Scale:
            sample(ch, t, v);
            scale_[n] = glm::dvec3(v[0], v[1], v[2]);
            break;
        case AnimationPath::Weights:
            sample(ch, t, weights_[n].data());
            break;
        }
    }
}

void SceneEvaluator::composeWorld() {
    const std::vector<SceneNode>& nodes = scene_.animation.nodes;
    for (size_t n : order_) {
        const glm::dmat4 local =
            nodes[n].hasMatrix ? nodes[n].matrix : localMatrix(translation_[n], rotation_[n], scale_[n]);
        world_[n] = nodes[n].parent == -1 ? local : world_[size_t(nodes[n].parent)] * local;
    }
    for (size_t s = 0; s < joints_.size(); ++s) {
        const Skin& skin = scene_.animation.skins[s];
        for (size_t j = 0; j < skin.joints.size(); ++j)
            joints_[s][j] = world_[size_t(skin.joints[j])] * skin.inverseBindMatrices[j];
    }
}

const glm::dmat4& SceneEvaluator::objectTransform(size_t object) const {
    const SceneObject& o = scene_.objects[object];
    return o.node == -1 ? o.transform : world_[size_t(o.node)];
}

const std::vector<double>& SceneEvaluator::morphWeights(size_t object) const {
    static const std::vector<double> none;
    const SceneObject& o = scene_.objects[object];
    return o.morphTargets.empty() ? none : weights_[size_t(o.node)];
}

std::vector<glm::dvec3> posedPositions(const Scene& scene, size_t object, const SceneEvaluator& evaluator) {
    const SceneObject& o = scene.objects[object];
    std::vector<glm::dvec3> out(o.mesh->positions.begin(), o.mesh->positions.end());
    const std::vector<double>& weights = evaluator.morphWeights(object);
    for (size_t t = 0; t < o.morphTargets.size(); ++t)
        for (size_t v = 0; v < out.size(); ++v)
            out[v] += weights[t] * glm::dvec3(o.morphTargets[t].positions[v]);
    if (o.skin == -1) return out;
    const std::vector<glm::dmat4>& joints = evaluator.jointMatrices(size_t(o.skin));
    const glm::dmat4 toObject = glm::inverse(evaluator.objectTransform(object));
    for (size_t v = 0; v < out.size(); ++v)
        out[v] = glm::dvec3(toObject * glm::dvec4(skinVertex(o.skinWeights, v, joints, out[v]), 1.0));
    return out;
}

} // namespace spatter
