#include "spatter/core/Animation.hpp"

#include "spatter/core/Scene.hpp"

#include <cmath>

namespace spatter {

namespace {

std::string num(size_t value) {
    return std::to_string(value);
}

bool validIndex(int index, size_t count) {
    return index >= 0 && size_t(index) < count;
}

bool finiteMatrix(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

bool finiteNode(const SceneNode& n) {
    const glm::dvec4 q(n.rotation.x, n.rotation.y, n.rotation.z, n.rotation.w);
    return finiteMatrix(n.matrix) && std::isfinite(glm::dot(n.translation, n.translation)) &&
           std::isfinite(glm::dot(q, q)) && std::isfinite(glm::dot(n.scale, n.scale));
}

Status checkNodes(const std::vector<SceneNode>& nodes) {
    for (size_t i = 0; i < nodes.size(); ++i) {
        const SceneNode& n = nodes[i];
        if (n.parent != -1 && !validIndex(n.parent, nodes.size()))
            return fail("node " + num(i) + " has parent " + std::to_string(n.parent) +
                        ", which does not exist");
        if (!finiteNode(n)) return fail("node " + num(i) + " has a transform that is not finite");
        // A chain longer than the node count repeats a node: a cycle.
        size_t steps = 0;
        for (int p = n.parent; p != -1; p = nodes[size_t(p)].parent)
            if (++steps > nodes.size()) return fail("the node hierarchy has a cycle through node " + num(i));
    }
    return {};
}

Status checkSkins(const SceneAnimation& a) {
    for (size_t s = 0; s < a.skins.size(); ++s) {
        const Skin& skin = a.skins[s];
        if (skin.joints.empty()) return fail("skin " + num(s) + " has no joints");
        if (skin.inverseBindMatrices.size() != skin.joints.size())
            return fail("skin " + num(s) + " has " + num(skin.joints.size()) + " joints but " +
                        num(skin.inverseBindMatrices.size()) + " inverse bind matrices");
        for (size_t j = 0; j < skin.joints.size(); ++j) {
            if (!validIndex(skin.joints[j], a.nodes.size()))
                return fail("skin " + num(s) + " joint " + num(j) + " is not a node");
            if (!finiteMatrix(skin.inverseBindMatrices[j]))
                return fail("skin " + num(s) + " inverse bind matrix " + num(j) + " is not finite");
        }
    }
    return {};
}

size_t expectedWidth(const AnimationChannel& ch, const SceneNode& node) {
    switch (ch.path) {
    case AnimationPath::Translation:
    case AnimationPath::Scale:
        return 3;
    case AnimationPath::Rotation:
        return 4;
    default:
        return node.weights.size();
    }
}

Status checkChannel(const AnimationChannel& ch, const std::vector<SceneNode>& nodes) {
    if (!validIndex(ch.node, nodes.size())) return fail("targets a node that does not exist");
    if (nodes[size_t(ch.node)].hasMatrix) return fail("targets a node with a matrix");
    const size_t width = expectedWidth(ch, nodes[size_t(ch.node)]);
    if (width == 0 || size_t(ch.width) != width)
        return fail("has width " + std::to_string(ch.width) + ", the target needs " + num(width));
    if (ch.times.empty()) return fail("has no keyframes");
    for (size_t k = 0; k < ch.times.size(); ++k)
        if (!std::isfinite(ch.times[k]) || (k > 0 && !(ch.times[k] > ch.times[k - 1])))
            return fail("has key times that are not finite and strictly increasing");
    const size_t perKey = width * (ch.interpolation == Interpolation::CubicSpline ? 3 : 1);
    if (ch.values.size() != ch.times.size() * perKey)
        return fail("has " + num(ch.values.size()) + " values for " + num(ch.times.size()) + " keys");
    for (double v : ch.values)
        if (!std::isfinite(v)) return fail("has a value that is not finite");
    return {};
}

} // namespace

Status validateAnimation(const SceneAnimation& a) {
    if (Status s = checkNodes(a.nodes); !s) return s;
    if (Status s = checkSkins(a); !s) return s;
    for (size_t i = 0; i < a.animations.size(); ++i)
        for (size_t c = 0; c < a.animations[i].channels.size(); ++c)
            if (Status s = checkChannel(a.animations[i].channels[c], a.nodes); !s)
                return fail("animation " + num(i) + " (" + a.animations[i].name + ") channel " + num(c) +
                            " " + s.error());
    return {};
}

namespace {

Status checkInfluences(const SceneObject& o, const Skin& skin) {
    const SkinWeights& w = o.skinWeights;
    const size_t stride = size_t(w.influences);
    if (w.influences <= 0) return fail("is skinned but has no joint influences");
    if (w.joints.size() != o.mesh->vertexCount() * stride || w.weights.size() != w.joints.size())
        return fail("has joint influences for " + num(w.joints.size() / stride) + " vertices, its mesh has " +
                    num(o.mesh->vertexCount()));
    for (size_t v = 0; v < o.mesh->vertexCount(); ++v) {
        double sum = 0.0;
        for (size_t k = 0; k < stride; ++k) {
            const double weight = w.weights[v * stride + k];
            if (!(weight >= 0.0) || !std::isfinite(weight))
                return fail("vertex " + num(v) + " has a negative or non-finite joint weight");
            if (weight > 0.0 && w.joints[v * stride + k] >= skin.joints.size())
                return fail("vertex " + num(v) + " uses joint " + num(w.joints[v * stride + k]) +
                            ", the skin has " + num(skin.joints.size()));
            sum += weight;
        }
        if (std::abs(sum - 1.0) > 1e-3)
            return fail("vertex " + num(v) + " has joint weights summing to " + std::to_string(sum) +
                        ", not 1");
    }
    return {};
}

Status checkTargets(const SceneObject& o, const SceneAnimation& a) {
    const size_t n = o.mesh->vertexCount();
    for (size_t t = 0; t < o.morphTargets.size(); ++t) {
        const MorphTarget& m = o.morphTargets[t];
        if (m.positions.size() != n || (!m.normals.empty() && m.normals.size() != n) ||
            (!m.tangents.empty() && m.tangents.size() != n))
            return fail("morph target " + num(t) + " does not have one delta per vertex");
        for (const std::vector<glm::vec3>* deltas : {&m.positions, &m.normals, &m.tangents})
            for (const glm::vec3& d : *deltas)
                if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z))
                    return fail("morph target " + num(t) + " has a delta that is not finite");
    }
    if (!o.morphTargets.empty() &&
        (o.node == -1 || a.nodes[size_t(o.node)].weights.size() != o.morphTargets.size()))
        return fail("has " + num(o.morphTargets.size()) +
                    " morph targets but its node has no weight for each");
    return {};
}

} // namespace

Status validateObjectAnimation(const SceneObject& o, const SceneAnimation& a) {
    if (o.node != -1 && !validIndex(o.node, a.nodes.size()))
        return fail("refers to animation node " + std::to_string(o.node) + ", which does not exist");
    if (o.skin != -1) {
        if (o.node == -1 || !validIndex(o.skin, a.skins.size()))
            return fail("refers to skin " + std::to_string(o.skin) + ", which does not exist or has no node");
        if (Status s = checkInfluences(o, a.skins[size_t(o.skin)]); !s) return s;
    } else if (o.skinWeights.influences != 0) {
        return fail("has joint influences but no skin");
    }
    return checkTargets(o, a);
}

} // namespace spatter
