#include "GltfReference.hpp"

#include <cstring>
#include <fstream>
#include <iterator>

namespace spatter::test {

namespace {

using json = nlohmann::json;

uint32_t u32(const std::vector<uint8_t>& b, size_t at) {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i)
        v |= uint32_t(b[at + size_t(i)]) << (8 * i);
    return v;
}

int components(const std::string& type) {
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    if (type == "VEC4") return 4;
    return 16; // MAT4, the only matrix type the tests use
}

double component(const uint8_t* p, int type, bool normalized) {
    switch (type) {
    case 5120: {
        int8_t v;
        std::memcpy(&v, p, 1);
        return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case 5121:
        return normalized ? p[0] / 255.0 : p[0];
    case 5122: {
        int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case 5123: {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? v / 65535.0 : v;
    }
    case 5125: {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
    default: {
        float v;
        std::memcpy(&v, p, 4);
        return v;
    }
    }
}

size_t componentBytes(int type) {
    return type == 5120 || type == 5121 ? 1 : type == 5122 || type == 5123 ? 2 : 4;
}

glm::dmat4 trsMatrix(const glm::dvec3& t, const glm::dquat& r, const glm::dvec3& s) {
    const glm::dmat3 rot = glm::mat3_cast(r);
    glm::dmat4 m(1.0);
    for (int c = 0; c < 3; ++c)
        m[c] = glm::dvec4(rot[c] * s[c], 0.0);
    m[3] = glm::dvec4(t, 1.0);
    return m;
}

glm::dquat asQuat(const double* xyzw) {
    return glm::dquat(xyzw[3], xyzw[0], xyzw[1], xyzw[2]);
}

} // namespace

GltfReference::GltfReference(const std::string& glbPath) {
    std::ifstream in(glbPath, std::ios::binary);
    const std::vector<uint8_t> b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (b.size() < 28 || std::memcmp(b.data(), "glTF", 4) != 0) return;
    const size_t jsonLength = u32(b, 12);
    const size_t binAt = 20 + jsonLength;
    if (binAt + 8 > b.size()) return;
    const size_t binLength = u32(b, binAt);
    if (binAt + 8 + binLength > b.size()) return;
    bin_.assign(b.begin() + long(binAt + 8), b.begin() + long(binAt + 8 + binLength));
    doc_ = json::parse(b.begin() + 20, b.begin() + long(binAt));
}

std::vector<double> GltfReference::read(int accessor) const {
    const json& a = doc_["accessors"][size_t(accessor)];
    const int type = a["componentType"];
    const int n = components(a["type"]);
    const bool normalized = a.value("normalized", false);
    const size_t count = a["count"];
    std::vector<double> out(count * size_t(n), 0.0); // an accessor without a buffer view is zeros
    if (a.contains("bufferView")) {
        const json& view = doc_["bufferViews"][a["bufferView"].get<size_t>()];
        const size_t elementSize = componentBytes(type) * size_t(n);
        const size_t stride =
            view.value("byteStride", size_t(0)) ? view["byteStride"].get<size_t>() : elementSize;
        const size_t start = view.value("byteOffset", size_t(0)) + a.value("byteOffset", size_t(0));
        for (size_t i = 0; i < count; ++i)
            for (int c = 0; c < n; ++c)
                out[i * size_t(n) + size_t(c)] =
                    component(&bin_[start + i * stride + size_t(c) * componentBytes(type)], type, normalized);
    }
    if (!a.contains("sparse")) return out;
    const json& sparse = a["sparse"];
    const json& indices = sparse["indices"];
    const json& values = sparse["values"];
    const int indexType = indices["componentType"];
    const size_t indexAt =
        doc_["bufferViews"][indices["bufferView"].get<size_t>()].value("byteOffset", size_t(0)) +
        indices.value("byteOffset", size_t(0));
    const size_t valueAt =
        doc_["bufferViews"][values["bufferView"].get<size_t>()].value("byteOffset", size_t(0)) +
        values.value("byteOffset", size_t(0));
    for (size_t k = 0; k < sparse["count"].get<size_t>(); ++k) {
        const size_t target =
            size_t(component(&bin_[indexAt + k * componentBytes(indexType)], indexType, false));
        for (int c = 0; c < n; ++c)
            out[target * size_t(n) + size_t(c)] = component(
                &bin_[valueAt + (k * size_t(n) + size_t(c)) * componentBytes(type)], type, normalized);
    }
    return out;
}

int GltfReference::parentOf(int node) const {
    const json& nodes = doc_["nodes"];
    for (size_t p = 0; p < nodes.size(); ++p)
        for (const json& c : nodes[p].value("children", json::array()))
            if (c.get<int>() == node) return int(p);
    return -1;
}

std::vector<double> GltfReference::sampleChannel(const json& sampler, int width, double t,
                                                 bool rotation) const {
    const std::vector<double> times = read(sampler["input"]);
    const std::vector<double> values = read(sampler["output"]);
    const std::string mode = sampler.value("interpolation", std::string("LINEAR"));
    const bool cubic = mode == "CUBICSPLINE";
    auto element = [&](size_t key, int part) { // part: 0 in-tangent, 1 value, 2 out-tangent
        const size_t at = (cubic ? 3 * key + size_t(part) : key) * size_t(width);
        return std::vector<double>(values.begin() + long(at), values.begin() + long(at) + width);
    };
    size_t k = 0;
    while (k + 1 < times.size() && times[k + 1] <= t)
        ++k;
    if (t <= times.front() || k + 1 == times.size() || mode == "STEP") return element(k, 1);
    const double s = (t - times[k]) / (times[k + 1] - times[k]);
    const std::vector<double> a = element(k, 1), b = element(k + 1, 1);
    std::vector<double> out(static_cast<size_t>(width));
    if (!cubic && rotation) {
        const glm::dquat q =
            glm::normalize(glm::slerp(glm::normalize(asQuat(a.data())), glm::normalize(asQuat(b.data())), s));
        return {q.x, q.y, q.z, q.w};
    }
    const double td = times[k + 1] - times[k];
    const std::vector<double> outTangent = element(k, 2), inTangent = element(k + 1, 0);
    for (size_t c = 0; c < out.size(); ++c)
        out[c] = cubic ? (2 * s * s * s - 3 * s * s + 1) * a[c] +
                             td * (s * s * s - 2 * s * s + s) * outTangent[c] +
                             (-2 * s * s * s + 3 * s * s) * b[c] + td * (s * s * s - s * s) * inTangent[c]
                       : a[c] + s * (b[c] - a[c]);
    if (rotation) {
        const glm::dquat q = glm::normalize(asQuat(out.data()));
        return {q.x, q.y, q.z, q.w};
    }
    return out;
}

void GltfReference::localTrs(int node, int animation, double t, glm::dvec3& tr, glm::dquat& r,
                             glm::dvec3& s) const {
    const json& n = doc_["nodes"][size_t(node)];
    const std::vector<double> T = n.value("translation", std::vector<double>{0, 0, 0});
    const std::vector<double> R = n.value("rotation", std::vector<double>{0, 0, 0, 1});
    const std::vector<double> S = n.value("scale", std::vector<double>{1, 1, 1});
    tr = glm::dvec3(T[0], T[1], T[2]);
    r = glm::normalize(asQuat(R.data()));
    s = glm::dvec3(S[0], S[1], S[2]);
    if (animation < 0) return;
    const json& anim = doc_["animations"][size_t(animation)];
    for (const json& ch : anim["channels"]) {
        if (ch["target"].value("node", -1) != node) continue;
        const std::string path = ch["target"]["path"];
        const json& sampler = anim["samplers"][ch["sampler"].get<size_t>()];
        if (path == "translation") {
            const std::vector<double> v = sampleChannel(sampler, 3, t, false);
            tr = glm::dvec3(v[0], v[1], v[2]);
        } else if (path == "rotation") {
            r = glm::normalize(asQuat(sampleChannel(sampler, 4, t, true).data()));
        } else if (path == "scale") {
            const std::vector<double> v = sampleChannel(sampler, 3, t, false);
            s = glm::dvec3(v[0], v[1], v[2]);
        }
    }
}

glm::dmat4 GltfReference::nodeWorld(int node, int animation, double t) const {
    const json& n = doc_["nodes"][size_t(node)];
    glm::dmat4 local(1.0);
    if (n.contains("matrix")) {
        const std::vector<double> m = n["matrix"];
        for (int i = 0; i < 16; ++i)
            local[i / 4][i % 4] = m[size_t(i)];
    } else {
        glm::dvec3 tr, s;
        glm::dquat r;
        localTrs(node, animation, t, tr, r, s);
        local = trsMatrix(tr, r, s);
    }
    const int parent = parentOf(node);
    return parent == -1 ? local : nodeWorld(parent, animation, t) * local;
}

std::vector<double> GltfReference::morphWeights(int node, int animation, double t) const {
    const json& n = doc_["nodes"][size_t(node)];
    const json& mesh = doc_["meshes"][n["mesh"].get<size_t>()];
    const size_t targets = mesh["primitives"][0].value("targets", json::array()).size();
    std::vector<double> w = n.value("weights", mesh.value("weights", std::vector<double>(targets, 0.0)));
    if (animation < 0) return w;
    const json& anim = doc_["animations"][size_t(animation)];
    for (const json& ch : anim["channels"])
        if (ch["target"].value("node", -1) == node && ch["target"]["path"] == "weights")
            w = sampleChannel(anim["samplers"][ch["sampler"].get<size_t>()], int(targets), t, false);
    return w;
}

std::vector<glm::dvec3> GltfReference::worldPositions(int node, int animation, double t) const {
    const json& n = doc_["nodes"][size_t(node)];
    const std::vector<double> weights = morphWeights(node, animation, t);
    std::vector<glm::dmat4> joints;
    if (n.contains("skin")) {
        const json& skin = doc_["skins"][n["skin"].get<size_t>()];
        const std::vector<double> ibm =
            skin.contains("inverseBindMatrices") ? read(skin["inverseBindMatrices"]) : std::vector<double>();
        for (size_t j = 0; j < skin["joints"].size(); ++j) {
            glm::dmat4 inverseBind(1.0);
            for (size_t i = 0; !ibm.empty() && i < 16; ++i)
                inverseBind[int(i / 4)][int(i % 4)] = ibm[j * 16 + i];
            joints.push_back(nodeWorld(skin["joints"][j], animation, t) * inverseBind);
        }
    }
    const glm::dmat4 world = nodeWorld(node, animation, t);
    std::vector<glm::dvec3> out;
    for (const json& prim : doc_["meshes"][n["mesh"].get<size_t>()]["primitives"]) {
        const json& attributes = prim["attributes"];
        std::vector<double> p = read(attributes["POSITION"]);
        const json targets = prim.value("targets", json::array());
        for (size_t k = 0; k < targets.size(); ++k)
            if (targets[k].contains("POSITION")) {
                const std::vector<double> d = read(targets[k]["POSITION"]);
                for (size_t i = 0; i < p.size(); ++i)
                    p[i] += weights[k] * d[i];
            }
        std::vector<std::vector<double>> jointSets, weightSets;
        for (int set = 0; joints.size() && attributes.contains("JOINTS_" + std::to_string(set)); ++set) {
            jointSets.push_back(read(attributes["JOINTS_" + std::to_string(set)]));
            weightSets.push_back(read(attributes["WEIGHTS_" + std::to_string(set)]));
        }
        for (size_t v = 0; v < p.size() / 3; ++v) {
            const glm::dvec4 rest(p[3 * v], p[3 * v + 1], p[3 * v + 2], 1.0);
            if (jointSets.empty()) {
                out.push_back(glm::dvec3(world * rest));
                continue;
            }
            glm::dvec3 sum(0.0);
            double total = 0.0;
            for (size_t set = 0; set < jointSets.size(); ++set)
                for (size_t c = 0; c < 4; ++c) {
                    const double w = weightSets[set][4 * v + c];
                    sum += w * glm::dvec3(joints[size_t(jointSets[set][4 * v + c])] * rest);
                    total += w;
                }
            out.push_back(sum / total);
        }
    }
    return out;
}

} // namespace spatter::test
