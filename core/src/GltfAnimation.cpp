// glTF animation data: joint influences and morph targets of meshes, then the nodes, skins and
// animations of a scene. Every index, count and value is checked before it is used; any problem
// rejects the whole file with a message naming the glTF part.
//
// Conventions:
// - Joint influences come from every JOINTS_n / WEIGHTS_n pair (n = 0, 1, ...), joints as unsigned
//   bytes or shorts, weights as floats or normalised unsigned bytes or shorts; each vertex's weights
//   are normalised to sum to 1. They are kept only for objects whose node has a skin.
// - Morph targets keep POSITION, NORMAL and TANGENT deltas, dense, zero-filled or sparse; other target
//   attributes are ignored.
// - Channels without a target node (left to extensions) are ignored.
// - An object is dynamic when an animation moves its node or an ancestor, moves a joint of its skin
//   (or an ancestor of one), or animates its morph weights.

#include "GltfAnimation.hpp"

#include "GltfAccessor.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace spatter::gltf {

namespace {

// Upper bound on the morph target deltas of one mesh (targets x vertices).
constexpr size_t kMaxMorphDeltas = size_t(1) << 24;
// Upper bound on the joint influences and morph target deltas of all objects of a scene; instancing
// a mesh copies its deformation.
constexpr size_t kMaxDeformationElements = size_t(1) << 26;

constexpr unsigned kJointTypes = componentBit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) |
                                 componentBit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
constexpr unsigned kUnitTypes = componentBit(TINYGLTF_COMPONENT_TYPE_FLOAT) |
                                componentBit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) |
                                componentBit(TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
constexpr unsigned kSignedUnitTypes =
    kUnitTypes | componentBit(TINYGLTF_COMPONENT_TYPE_BYTE) | componentBit(TINYGLTF_COMPONENT_TYPE_SHORT);
constexpr unsigned kFloatOnly = componentBit(TINYGLTF_COMPONENT_TYPE_FLOAT);

// An attribute accessor of `prim` with exactly `count` elements; integer data must be normalised
// when `normalizedIntegers`.
Result<AccessorView> attribute(const tinygltf::Model& model, int accessor, const std::string& role, int type,
                               unsigned types, size_t count, bool normalizedIntegers) {
    Result<AccessorView> v = viewAccessor(model, accessor, role.c_str(), type, types);
    if (!v) return v;
    const std::string what = "accessor " + std::to_string(accessor) + " (" + role + ")";
    if (v->count != count)
        return fail(what + " has " + num(v->count) + " elements, the primitive has " + num(count) +
                    " vertices");
    if (normalizedIntegers && v->componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !v->normalized)
        return fail(what + " has integer components that are not normalized");
    return v;
}

// --- joint influences ---------------------------------------------------------------------------

// Re-lays `w` out with `influences` per vertex (more than before), new slots zero.
void widen(SkinWeights& w, int influences) {
    const size_t vertices = w.influences == 0 ? 0 : w.joints.size() / size_t(w.influences);
    SkinWeights out;
    out.influences = influences;
    out.joints.assign(vertices * size_t(influences), 0);
    out.weights.assign(vertices * size_t(influences), 0.0);
    for (size_t v = 0; v < vertices; ++v)
        for (int k = 0; k < w.influences; ++k) {
            out.joints[v * size_t(influences) + size_t(k)] = w.joints[v * size_t(w.influences) + size_t(k)];
            out.weights[v * size_t(influences) + size_t(k)] = w.weights[v * size_t(w.influences) + size_t(k)];
        }
    w = std::move(out);
}

// Reads set `set` (JOINTS_set and WEIGHTS_set) into slots 4 set .. 4 set + 3 of the vertices from `base`.
Status readInfluenceSet(const tinygltf::Model& model, const tinygltf::Primitive& prim, int set, size_t base,
                        size_t count, SkinWeights& w) {
    const std::string jointsName = "JOINTS_" + std::to_string(set),
                      weightsName = "WEIGHTS_" + std::to_string(set);
    const auto weightsIt = prim.attributes.find(weightsName);
    if (weightsIt == prim.attributes.end()) return fail("has " + jointsName + " but no " + weightsName);
    Result<AccessorView> joints = attribute(model, prim.attributes.at(jointsName), jointsName,
                                            TINYGLTF_TYPE_VEC4, kJointTypes, count, false);
    if (!joints) return fail(joints.error());
    Result<AccessorView> weights =
        attribute(model, weightsIt->second, weightsName, TINYGLTF_TYPE_VEC4, kUnitTypes, count, true);
    if (!weights) return fail(weights.error());
    // Normalised integers are scaled here in double rather than by the float reader.
    weights->normalized = false;
    const double scale = weights->componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1.0 / 255.0
                         : weights->componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 1.0 / 65535.0
                                                                                            : 1.0;
    for (size_t i = 0; i < count; ++i)
        for (int c = 0; c < 4; ++c) {
            const size_t slot = (base + i) * size_t(w.influences) + size_t(4 * set + c);
            const double weight = weights->component(i, c) * scale;
            if (!(weight >= 0.0) || !std::isfinite(weight))
                return fail("accessor " + std::to_string(weightsIt->second) + " (" + weightsName +
                            ") element " + num(i) + " has a negative or non-finite weight");
            w.joints[slot] = uint16_t(joints->component(i, c));
            w.weights[slot] = weight;
        }
    return {};
}

Status appendInfluences(const tinygltf::Model& model, const tinygltf::Primitive& prim, size_t base,
                        size_t count, SkinWeights& w) {
    int sets = 0;
    while (prim.attributes.count("JOINTS_" + std::to_string(sets)))
        ++sets;
    if (sets == 0 && w.influences == 0) return {};
    if (4 * sets > w.influences) widen(w, 4 * sets);
    const size_t stride = size_t(w.influences);
    w.joints.resize((base + count) * stride, 0);
    w.weights.resize((base + count) * stride, 0.0);
    for (int set = 0; set < sets; ++set)
        if (Status s = readInfluenceSet(model, prim, set, base, count, w); !s) return s;
    for (size_t v = base; v < base + count; ++v) {
        double sum = 0.0;
        for (size_t k = 0; k < stride; ++k)
            sum += w.weights[v * stride + k];
        if (sum > 0.0)
            for (size_t k = 0; k < stride; ++k)
                w.weights[v * stride + k] = w.weights[v * stride + k] / sum;
    }
    return {};
}

// --- morph targets ------------------------------------------------------------------------------

// Appends the deltas of `name` in target `t` after padding `deltas` to `base` vertices.
Status appendDeltas(const tinygltf::Model& model, const tinygltf::Primitive& prim, size_t t, const char* name,
                    size_t base, size_t count, std::vector<glm::vec3>& deltas) {
    const auto it = prim.targets[t].find(name);
    if (it == prim.targets[t].end()) return {};
    const std::string role = "morph target " + num(t) + " " + name;
    Result<std::vector<glm::vec3>> v = readVec3(model, it->second, role.c_str(), kVertexTypes, count);
    if (!v) return fail(v.error());
    deltas.resize(base, glm::vec3(0.0f));
    deltas.insert(deltas.end(), v->begin(), v->end());
    return {};
}

Status appendTargets(const tinygltf::Model& model, const tinygltf::Primitive& prim, size_t base, size_t count,
                     std::vector<MorphTarget>& targets) {
    if (base == 0)
        targets.resize(prim.targets.size());
    else if (prim.targets.size() != targets.size())
        return fail("has " + num(prim.targets.size()) + " morph targets, an earlier primitive has " +
                    num(targets.size()));
    if (!targets.empty() && base + count > kMaxMorphDeltas / targets.size())
        return fail("has more morph target deltas than the limit of " + num(kMaxMorphDeltas));
    for (size_t t = 0; t < targets.size(); ++t) {
        MorphTarget& target = targets[t];
        if (Status s = appendDeltas(model, prim, t, "POSITION", base, count, target.positions); !s) return s;
        if (Status s = appendDeltas(model, prim, t, "NORMAL", base, count, target.normals); !s) return s;
        if (Status s = appendDeltas(model, prim, t, "TANGENT", base, count, target.tangents); !s) return s;
    }
    return {};
}

// --- nodes --------------------------------------------------------------------------------------

// The morph target count of glTF mesh `mesh`, the same for all its primitives.
Result<size_t> targetCount(const tinygltf::Model& model, int mesh) {
    if (mesh == -1) return size_t(0);
    if (!validIndex(mesh, model.meshes.size()))
        return fail("refers to mesh " + std::to_string(mesh) + ", which does not exist");
    const tinygltf::Mesh& m = model.meshes[size_t(mesh)];
    const size_t count = m.primitives.empty() ? 0 : m.primitives[0].targets.size();
    for (size_t p = 1; p < m.primitives.size(); ++p)
        if (m.primitives[p].targets.size() != count)
            return fail("has mesh " + std::to_string(mesh) +
                        ", whose primitives have different morph target counts");
    return count;
}

Result<std::vector<double>> restWeights(const tinygltf::Model& model, const tinygltf::Node& node) {
    Result<size_t> count = targetCount(model, node.mesh);
    if (!count) return fail(count.error());
    const std::vector<double>& meshWeights =
        count.value() ? model.meshes[size_t(node.mesh)].weights : std::vector<double>();
    const std::vector<double>& weights = !node.weights.empty() ? node.weights : meshWeights;
    if (weights.empty()) return std::vector<double>(count.value(), 0.0);
    if (weights.size() != count.value())
        return fail("has " + num(weights.size()) + " morph weights for " + num(count.value()) +
                    " morph targets");
    return weights;
}

Result<std::vector<SceneNode>> convertNodes(const tinygltf::Model& model) {
    std::vector<SceneNode> nodes(model.nodes.size());
    for (size_t i = 0; i < model.nodes.size(); ++i) {
        const tinygltf::Node& node = model.nodes[i];
        nodes[i].name = node.name;
        for (int c : node.children) // the hierarchy was checked to be a forest
            if (validIndex(c, nodes.size())) nodes[size_t(c)].parent = int(i);
        if (Status s = readTrs(node, nodes[i]); !s)
            return fail(named("node", i, node.name) + " " + s.error());
        Result<std::vector<double>> weights = restWeights(model, node);
        if (!weights) return fail(named("node", i, node.name) + " " + weights.error());
        nodes[i].weights = std::move(weights.value());
    }
    return nodes;
}

// --- skins --------------------------------------------------------------------------------------

Result<Skin> convertSkin(const tinygltf::Model& model, size_t index) {
    const tinygltf::Skin& source = model.skins[index];
    const std::string what = named("skin", index, source.name);
    if (source.joints.empty()) return fail(what + " has no joints");
    Skin skin;
    skin.name = source.name;
    std::vector<bool> seen(model.nodes.size(), false);
    for (int j : source.joints) {
        if (!validIndex(j, model.nodes.size()))
            return fail(what + " has joint node " + std::to_string(j) + ", which does not exist");
        if (seen[size_t(j)]) return fail(what + " lists joint node " + std::to_string(j) + " twice");
        seen[size_t(j)] = true;
        skin.joints.push_back(j);
    }
    skin.inverseBindMatrices.assign(skin.joints.size(), glm::dmat4(1.0));
    if (source.inverseBindMatrices == -1) return skin;
    Result<AccessorView> m = viewAccessor(model, source.inverseBindMatrices, "inverseBindMatrices",
                                          TINYGLTF_TYPE_MAT4, kFloatOnly);
    if (!m) return fail(what + ": " + m.error());
    if (m->count < skin.joints.size())
        return fail(what + " has " + num(skin.joints.size()) + " joints but " + num(m->count) +
                    " inverse bind matrices");
    for (size_t j = 0; j < skin.joints.size(); ++j)
        for (int c = 0; c < 16; ++c) {
            const float v = m->component(j, c);
            if (!std::isfinite(v)) return fail(what + ": inverse bind matrix " + num(j) + " is not finite");
            skin.inverseBindMatrices[j][c / 4][c % 4] = v;
        }
    return skin;
}

// --- animations ---------------------------------------------------------------------------------

Result<AnimationPath> channelPath(const std::string& path) {
    if (path == "translation") return AnimationPath::Translation;
    if (path == "rotation") return AnimationPath::Rotation;
    if (path == "scale") return AnimationPath::Scale;
    if (path == "weights") return AnimationPath::Weights;
    return fail("has target path \"" + path + "\", which is not a glTF animation path");
}

Result<Interpolation> samplerInterpolation(const std::string& name) {
    if (name.empty() || name == "LINEAR") return Interpolation::Linear;
    if (name == "STEP") return Interpolation::Step;
    if (name == "CUBICSPLINE") return Interpolation::CubicSpline;
    return fail("has interpolation \"" + name + "\", which is not STEP, LINEAR or CUBICSPLINE");
}

Status readTimes(const tinygltf::Model& model, int accessor, std::vector<double>& times) {
    Result<AccessorView> input =
        viewAccessor(model, accessor, "sampler input", TINYGLTF_TYPE_SCALAR, kFloatOnly);
    if (!input) return fail(input.error());
    if (input->count == 0) return fail("has no keyframes");
    for (size_t i = 0; i < input->count; ++i) {
        const double t = input->component(i, 0);
        if (!std::isfinite(t)) return fail("has key time " + num(i) + " that is not finite (NaN or Inf)");
        if (i == 0 && t < 0.0) // the glTF schema: "time[0] >= 0.0"
            return fail("has key time 0 at " + std::to_string(t) +
                        " s, before 0 (glTF key times start at 0 or later)");
        if (i > 0 && !(t > times.back()))
            return fail("has key times that do not increase (key " + num(i) + " at " + std::to_string(t) +
                        " s, key " + num(i - 1) + " at " + std::to_string(times.back()) + " s)");
        times.push_back(t);
    }
    return {};
}

Status readValues(const tinygltf::Model& model, int accessor, AnimationChannel& ch) {
    const bool vec3 = ch.path == AnimationPath::Translation || ch.path == AnimationPath::Scale;
    const int type = vec3                                 ? TINYGLTF_TYPE_VEC3
                     : ch.path == AnimationPath::Rotation ? TINYGLTF_TYPE_VEC4
                                                          : TINYGLTF_TYPE_SCALAR;
    Result<AccessorView> output =
        viewAccessor(model, accessor, "sampler output", type, vec3 ? kFloatOnly : kSignedUnitTypes);
    if (!output) return fail(output.error());
    if (output->componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !output->normalized)
        return fail("has integer output values that are not normalized");
    const int elementWidth = ch.path == AnimationPath::Weights ? 1 : ch.width;
    const size_t perKey = (ch.interpolation == Interpolation::CubicSpline ? 3 : 1) *
                          size_t(ch.path == AnimationPath::Weights ? ch.width : 1);
    if (output->count != ch.times.size() * perKey)
        return fail("has " + num(output->count) + " output values for " + num(ch.times.size()) +
                    " keys, expected " + num(ch.times.size() * perKey));
    for (size_t i = 0; i < output->count; ++i)
        for (int c = 0; c < elementWidth; ++c) {
            const double v = output->component(i, c);
            if (!std::isfinite(v))
                return fail("has output value " + num(i) + " that is not finite (NaN or Inf)");
            ch.values.push_back(v);
        }
    return {};
}

// Rotation keys (not tangents) must be quaternions that can be normalised.
Status checkRotationKeys(const AnimationChannel& ch) {
    const size_t stride = ch.interpolation == Interpolation::CubicSpline ? 3 : 1;
    const size_t offset = ch.interpolation == Interpolation::CubicSpline ? 1 : 0;
    for (size_t k = 0; k < ch.times.size(); ++k) {
        const double* q = &ch.values[((k * stride) + offset) * 4];
        if (!(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] > 1e-24))
            return fail("has a zero rotation quaternion at key " + num(k));
    }
    return {};
}

// The channel, or one with node -1 for a channel without a target node.
Result<AnimationChannel> convertChannel(const tinygltf::Model& model, const tinygltf::Animation& anim,
                                        size_t index, const std::vector<SceneNode>& nodes) {
    const tinygltf::AnimationChannel& source = anim.channels[index];
    AnimationChannel ch;
    if (source.target_path.empty()) return fail("has no target (or a target without a path)");
    if (source.target_node == -1) return ch;
    if (!validIndex(source.target_node, nodes.size()))
        return fail("targets node " + std::to_string(source.target_node) + ", which does not exist");
    if (!validIndex(source.sampler, anim.samplers.size()))
        return fail("refers to sampler " + std::to_string(source.sampler) + ", which does not exist");
    const SceneNode& node = nodes[size_t(source.target_node)];
    const std::string nodeName = named("node", size_t(source.target_node), node.name);
    Result<AnimationPath> path = channelPath(source.target_path);
    if (!path) return fail(path.error());
    ch.path = path.value();
    if (node.hasMatrix)
        return fail("animates " + nodeName + ", which has a matrix instead of TRS properties");
    ch.width = ch.path == AnimationPath::Translation || ch.path == AnimationPath::Scale ? 3
               : ch.path == AnimationPath::Rotation                                     ? 4
                                                    : int(node.weights.size());
    if (ch.width == 0)
        return fail("animates the morph weights of " + nodeName + ", which has no morph targets");
    const tinygltf::AnimationSampler& sampler = anim.samplers[size_t(source.sampler)];
    Result<Interpolation> interpolation = samplerInterpolation(sampler.interpolation);
    if (!interpolation)
        return fail("sampler " + std::to_string(source.sampler) + " " + interpolation.error());
    ch.interpolation = interpolation.value();
    ch.node = source.target_node;
    if (Status s = readTimes(model, sampler.input, ch.times); !s)
        return fail("sampler " + std::to_string(source.sampler) + " " + s.error());
    if (Status s = readValues(model, sampler.output, ch); !s)
        return fail("sampler " + std::to_string(source.sampler) + " " + s.error());
    if (ch.path == AnimationPath::Rotation)
        if (Status s = checkRotationKeys(ch); !s)
            return fail("sampler " + std::to_string(source.sampler) + " " + s.error());
    return ch;
}

Result<Animation> convertAnimation(const tinygltf::Model& model, size_t index,
                                   const std::vector<SceneNode>& nodes) {
    const tinygltf::Animation& source = model.animations[index];
    Animation anim;
    anim.name = source.name;
    std::map<std::pair<int, AnimationPath>, size_t> targeted;
    for (size_t c = 0; c < source.channels.size(); ++c) {
        const std::string what = named("animation", index, source.name) + " channel " + num(c);
        Result<AnimationChannel> ch = convertChannel(model, source, c, nodes);
        if (!ch) return fail(what + " " + ch.error());
        if (ch->node == -1) continue;
        const auto [it, inserted] = targeted.emplace(std::make_pair(ch->node, ch->path), c);
        if (!inserted)
            return fail(what + " animates the same property of node " + std::to_string(ch->node) +
                        " as channel " + num(it->second));
        anim.duration = std::max(anim.duration, ch->times.back());
        anim.channels.push_back(std::move(ch.value()));
    }
    return anim;
}

// --- objects ------------------------------------------------------------------------------------

// Per node: true when some animation moves it (a translation, rotation or scale channel on it or on
// an ancestor). Parents may come after their children in the node list.
std::vector<bool> movingNodes(const SceneAnimation& a) {
    std::vector<bool> moved(a.nodes.size(), false);
    for (const Animation& anim : a.animations)
        for (const AnimationChannel& ch : anim.channels)
            if (ch.path != AnimationPath::Weights) moved[size_t(ch.node)] = true;
    std::vector<bool> out(a.nodes.size(), false);
    for (size_t n = 0; n < a.nodes.size(); ++n)
        for (int p = int(n); p != -1 && !out[n]; p = a.nodes[size_t(p)].parent)
            out[n] = moved[size_t(p)];
    return out;
}

bool animatesWeights(const SceneAnimation& a, int node) {
    for (const Animation& anim : a.animations)
        for (const AnimationChannel& ch : anim.channels)
            if (ch.path == AnimationPath::Weights && ch.node == node) return true;
    return false;
}

// The joint influences (when the node is skinned) and morph target deltas the object of `node`
// takes from its mesh.
size_t deformationElements(const tinygltf::Node& node, const MeshDeformation& d) {
    size_t n = node.skin == -1 ? 0 : d.skinWeights.joints.size();
    for (const MorphTarget& t : d.morphTargets)
        n += t.positions.size() + t.normals.size() + t.tangents.size();
    return n;
}

Status checkDeformationSize(const tinygltf::Model& model, const std::vector<MeshDeformation>& deformations,
                            const Scene& scene) {
    size_t total = 0;
    for (const SceneObject& o : scene.objects) {
        if (o.node == -1) continue; // an instance (EXT_mesh_gpu_instancing): not animated
        const tinygltf::Node& node = model.nodes[size_t(o.node)];
        total += deformationElements(node, deformations[size_t(node.mesh)]);
        if (total > kMaxDeformationElements)
            return fail("the default scene has more joint influences and morph target deltas in all than the "
                        "limit of " +
                        num(kMaxDeformationElements));
    }
    return {};
}

Status bindObject(const tinygltf::Model& model, const MeshDeformation& deformation,
                  const std::vector<bool>& moving, const SceneAnimation& a, SceneObject& o) {
    const tinygltf::Node& node = model.nodes[size_t(o.node)];
    o.skin = node.skin;
    o.morphTargets = deformation.morphTargets;
    if (o.skin != -1) {
        if (!validIndex(o.skin, a.skins.size()))
            return fail("refers to skin " + std::to_string(o.skin) + ", which does not exist");
        if (deformation.skinWeights.influences == 0) return fail("has a skin, but its mesh has no JOINTS_0");
        o.skinWeights = deformation.skinWeights;
    }
    bool dynamic = moving[size_t(o.node)] || animatesWeights(a, o.node);
    if (o.skin != -1)
        for (int j : a.skins[size_t(o.skin)].joints)
            dynamic = dynamic || moving[size_t(j)];
    o.dynamic = o.dynamic || dynamic;
    return validateObjectAnimation(o, a);
}

bool hasAnimationData(const tinygltf::Model& model) {
    if (!model.animations.empty() || !model.skins.empty()) return true;
    for (const tinygltf::Mesh& m : model.meshes)
        for (const tinygltf::Primitive& p : m.primitives)
            if (!p.targets.empty()) return true;
    return false;
}

} // namespace

Status readTrs(const tinygltf::Node& node, SceneNode& out) {
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16)
            return fail("has a matrix of " + num(node.matrix.size()) + " numbers, not 16");
        out.hasMatrix = true;
        for (int i = 0; i < 16; ++i)
            out.matrix[i / 4][i % 4] = node.matrix[size_t(i)];
        return {};
    }
    if (!node.translation.empty() && node.translation.size() != 3)
        return fail("has a translation of " + num(node.translation.size()) + " numbers, not 3");
    if (!node.rotation.empty() && node.rotation.size() != 4)
        return fail("has a rotation of " + num(node.rotation.size()) + " numbers, not 4");
    if (!node.scale.empty() && node.scale.size() != 3)
        return fail("has a scale of " + num(node.scale.size()) + " numbers, not 3");
    if (!node.translation.empty())
        out.translation = glm::dvec3(node.translation[0], node.translation[1], node.translation[2]);
    if (!node.rotation.empty()) {
        const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        const double len = glm::length(q);
        if (!(len > 1e-12)) return fail("has a zero rotation quaternion");
        out.rotation = q / len;
    }
    if (!node.scale.empty()) out.scale = glm::dvec3(node.scale[0], node.scale[1], node.scale[2]);
    return {};
}

Status appendDeformation(const tinygltf::Model& model, const tinygltf::Primitive& prim, size_t vertexBase,
                         size_t vertexCount, MeshDeformation& out) {
    if (Status s = appendInfluences(model, prim, vertexBase, vertexCount, out.skinWeights); !s) return s;
    return appendTargets(model, prim, vertexBase, vertexCount, out.morphTargets);
}

void finishDeformation(size_t vertexCount, MeshDeformation& out) {
    const size_t slots = vertexCount * size_t(out.skinWeights.influences);
    out.skinWeights.joints.resize(slots, 0);
    out.skinWeights.weights.resize(slots, 0.0);
    for (MorphTarget& t : out.morphTargets) {
        t.positions.resize(vertexCount, glm::vec3(0.0f));
        if (!t.normals.empty()) t.normals.resize(vertexCount, glm::vec3(0.0f));
        if (!t.tangents.empty()) t.tangents.resize(vertexCount, glm::vec3(0.0f));
    }
}

Status addAnimation(const tinygltf::Model& model, const std::vector<MeshDeformation>& deformations,
                    Scene& scene) {
    if (!hasAnimationData(model)) {
        for (SceneObject& o : scene.objects)
            o.node = -1;
        return {};
    }
    if (Status s = checkDeformationSize(model, deformations, scene); !s) return s;
    SceneAnimation& a = scene.animation;
    Result<std::vector<SceneNode>> nodes = convertNodes(model);
    if (!nodes) return fail(nodes.error());
    a.nodes = std::move(nodes.value());
    for (size_t i = 0; i < model.skins.size(); ++i) {
        Result<Skin> skin = convertSkin(model, i);
        if (!skin) return fail(skin.error());
        a.skins.push_back(std::move(skin.value()));
    }
    for (size_t i = 0; i < model.animations.size(); ++i) {
        Result<Animation> anim = convertAnimation(model, i, a.nodes);
        if (!anim) return fail(anim.error());
        a.animations.push_back(std::move(anim.value()));
    }
    const std::vector<bool> moving = movingNodes(a);
    for (SceneObject& o : scene.objects)
        if (Status s =
                o.node == -1
                    ? Status{}
                    : bindObject(model, deformations[size_t(model.nodes[size_t(o.node)].mesh)], moving, a, o);
            !s)
            return fail(named("node", size_t(o.node), model.nodes[size_t(o.node)].name) + " " + s.error());
    return {};
}

} // namespace spatter::gltf
