#include "spatter/core/VertexDeformation.hpp"

#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/Scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace spatter {

namespace {

struct Influence {
    uint16_t joint = 0;
    double weight = 0.0;
};

// The joint weights of the corners blended by `bary`, largest first (ties to the smaller joint).
std::vector<Influence> blended(const SkinWeights& from, const std::array<uint32_t, 3>& corner,
                               const glm::dvec3& bary) {
    const size_t stride = size_t(from.influences);
    std::vector<Influence> out;
    out.reserve(3 * stride);
    for (int c = 0; c < 3; ++c)
        for (size_t k = 0; k < stride; ++k) {
            const size_t at = size_t(corner[size_t(c)]) * stride + k;
            const double w = bary[c] * from.weights[at];
            if (!(w > 0.0)) continue;
            auto same = std::find_if(out.begin(), out.end(),
                                     [&](const Influence& i) { return i.joint == from.joints[at]; });
            if (same == out.end())
                out.push_back({from.joints[at], w});
            else
                same->weight += w;
        }
    std::sort(out.begin(), out.end(), [](const Influence& a, const Influence& b) {
        return a.weight != b.weight ? a.weight > b.weight : a.joint < b.joint;
    });
    return out;
}

// Writes the `count` largest of `influences`, renormalised, to `joints` and `weights`.
template <class Joints, class Weights>
void keepLargest(std::vector<Influence> influences, size_t count, Joints joints, Weights weights) {
    influences.resize(std::min(influences.size(), count));
    double sum = 0.0;
    for (const Influence& i : influences)
        sum += i.weight;
    for (size_t k = 0; k < influences.size(); ++k) {
        joints[k] = influences[k].joint;
        weights[k] = influences[k].weight / sum;
    }
}

std::string matchProblem(const Mesh& source, const VertexDeformation& d) {
    const size_t n = source.positions.size();
    const size_t stride = size_t(std::max(d.skin.influences, 0));
    if (d.skin.joints.size() != n * stride || d.skin.weights.size() != n * stride)
        return "its joint influences do not cover its " + std::to_string(n) + " vertices";
    for (const std::vector<glm::vec3>& m : d.morphs)
        if (m.size() != n) return "a morph target does not cover its " + std::to_string(n) + " vertices";
    return {};
}

bool affine(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return m[0][3] == 0.0 && m[1][3] == 0.0 && m[2][3] == 0.0 && m[3][3] == 1.0;
}

} // namespace

glm::dvec3 barycentric(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 e0 = b - a, e1 = c - a, d = p - a;
    const double d00 = glm::dot(e0, e0), d01 = glm::dot(e0, e1), d11 = glm::dot(e1, e1);
    const double d20 = glm::dot(d, e0), d21 = glm::dot(d, e1);
    const double det = d00 * d11 - d01 * d01;
    if (!(det > 0.0)) return {1.0, 0.0, 0.0};
    const double v = std::clamp((d11 * d20 - d01 * d21) / det, 0.0, 1.0);
    const double w = std::clamp((d00 * d21 - d01 * d20) / det, 0.0, 1.0 - v);
    return {1.0 - v - w, v, w};
}

std::optional<glm::dmat4> triangleFrame(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2,
                                        const glm::dvec3& bary) {
    const glm::dvec3 t = glm::normalize(p1 - p0);
    const glm::dvec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    if (!std::isfinite(t.x + t.y + t.z + n.x + n.y + n.z)) return std::nullopt;
    const glm::dvec3 at = bary.x * p0 + bary.y * p1 + bary.z * p2;
    return glm::dmat4(glm::dvec4(t, 0.0), glm::dvec4(glm::cross(n, t), 0.0), glm::dvec4(n, 0.0),
                      glm::dvec4(at, 1.0));
}

Mesh withPositions(const Mesh& mesh, const std::vector<glm::dvec3>& positions) {
    Mesh out = mesh;
    for (size_t v = 0; v < positions.size() && v < out.positions.size(); ++v)
        out.positions[v] = glm::vec3(positions[v]);
    return out;
}

VertexDeformation deformationOf(const SceneObject& object) {
    VertexDeformation d;
    d.skin = object.skinWeights;
    for (const MorphTarget& t : object.morphTargets)
        d.morphs.push_back(t.positions);
    return d;
}

Result<VertexDeformation> transferDeformation(const Mesh& source, const VertexDeformation& deformation,
                                              const Mesh& target) {
    if (const std::string problem = matchProblem(source, deformation); !problem.empty())
        return fail("deformation transfer: the source mesh's deformation does not match it: " + problem);
    Result<ClosestPointQuery> query = ClosestPointQuery::create(source);
    if (!query) return fail("deformation transfer: " + query.error());
    const size_t n = target.positions.size(), stride = size_t(deformation.skin.influences);
    VertexDeformation out;
    out.skin.influences = deformation.skin.influences;
    out.skin.joints.assign(n * stride, 0);
    out.skin.weights.assign(n * stride, 0.0);
    out.morphs.assign(deformation.morphs.size(), std::vector<glm::vec3>(n));
    for (size_t v = 0; v < n; ++v) {
        const std::optional<ClosestPoint> near = query->closest(glm::dvec3(target.positions[v]));
        if (!near) return fail("deformation transfer: the source mesh has no surface");
        const std::array<uint32_t, 3> corner = {source.indices[3 * size_t(near->triangle)],
                                                source.indices[3 * size_t(near->triangle) + 1],
                                                source.indices[3 * size_t(near->triangle) + 2]};
        const glm::dvec3 bary =
            barycentric(near->point, glm::dvec3(source.positions[corner[0]]),
                        glm::dvec3(source.positions[corner[1]]), glm::dvec3(source.positions[corner[2]]));
        if (stride > 0)
            keepLargest(blended(deformation.skin, corner, bary), stride,
                        out.skin.joints.begin() + std::ptrdiff_t(v * stride),
                        out.skin.weights.begin() + std::ptrdiff_t(v * stride));
        for (size_t t = 0; t < out.morphs.size(); ++t) {
            const std::vector<glm::vec3>& delta = deformation.morphs[t];
            out.morphs[t][v] =
                glm::vec3(bary.x * glm::dvec3(delta[corner[0]]) + bary.y * glm::dvec3(delta[corner[1]]) +
                          bary.z * glm::dvec3(delta[corner[2]]));
        }
    }
    return out;
}

glm::dvec3 skinVertex(const SkinWeights& skin, size_t vertex, const std::vector<glm::dmat4>& joints,
                      const glm::dvec3& p) {
    // The blended matrix's top three rows only (its last row never reaches the position), summed and
    // applied in the order glm's dmat4 arithmetic takes, so that the result is the same to the bit.
    const size_t stride = size_t(skin.influences);
    glm::dvec3 c0(0.0), c1(0.0), c2(0.0), c3(0.0);
    for (size_t k = 0; k < stride; ++k)
        if (const double w = skin.weights[vertex * stride + k]; w > 0.0) {
            const glm::dmat4& j = joints[skin.joints[vertex * stride + k]];
            c0 += w * glm::dvec3(j[0]);
            c1 += w * glm::dvec3(j[1]);
            c2 += w * glm::dvec3(j[2]);
            c3 += w * glm::dvec3(j[3]);
        }
    return (c0 * p.x + c1 * p.y) + (c2 * p.z + c3);
}

glm::dvec3 posedVertex(const std::vector<glm::vec3>& rest, const VertexDeformation& deformation,
                       size_t vertex, const std::vector<glm::dmat4>& joints,
                       const std::vector<double>& weights, const glm::dmat4& toObject) {
    glm::dvec3 p(rest[vertex]);
    for (size_t t = 0; t < deformation.morphs.size(); ++t)
        if (weights[t] != 0.0) p += weights[t] * glm::dvec3(deformation.morphs[t][vertex]);
    if (deformation.skin.influences == 0) return p;
    return glm::dvec3(toObject * glm::dvec4(skinVertex(deformation.skin, vertex, joints, p), 1.0));
}

std::vector<glm::dvec3> posePositions(const std::vector<glm::vec3>& rest,
                                      const VertexDeformation& deformation,
                                      const std::vector<glm::dmat4>& joints,
                                      const std::vector<double>& weights, const glm::dmat4& toObject) {
    std::vector<glm::dvec3> out(rest.size());
    for (size_t v = 0; v < rest.size(); ++v)
        out[v] = posedVertex(rest, deformation, v, joints, weights, toObject);
    return out;
}

std::string poseProblem(const VertexDeformation& deformation, size_t jointCount,
                        const std::vector<glm::dmat4>& joints, const std::vector<double>& weights) {
    if (deformation.skin.influences > 0 && joints.size() != jointCount)
        return std::to_string(joints.size()) + " joint matrices for a skin of " + std::to_string(jointCount) +
               " joints";
    if (weights.size() != deformation.morphs.size())
        return std::to_string(weights.size()) + " morph weights for " +
               std::to_string(deformation.morphs.size()) + " morph targets";
    for (size_t j = 0; j < joints.size(); ++j)
        if (!affine(joints[j])) return "joint matrix " + std::to_string(j) + " is not finite and affine";
    for (size_t t = 0; t < weights.size(); ++t)
        if (!std::isfinite(weights[t])) return "morph weight " + std::to_string(t) + " is not finite";
    return {};
}

} // namespace spatter
