#pragma once
// VertexDeformation: how the vertices of a mesh follow a pose, as glTF deforms a render mesh: morph
// target position deltas scaled by the pose's weights, then linear blend skinning by the pose's joint
// matrices. A render mesh carries its own (SceneObject::skinWeights and morphTargets); a collision
// proxy, which has other vertices, gets one transferred from its render mesh (transferDeformation),
// so that the proxy bends with the surface that is drawn.

#include "spatter/core/Animation.hpp"
#include "spatter/core/Mesh.hpp"
#include "spatter/core/Result.hpp"

#include <glm/glm.hpp>
#include <optional>
#include <vector>

namespace spatter {

struct SceneObject;

struct VertexDeformation {
    SkinWeights skin;                           // influences == 0: not skinned
    std::vector<std::vector<glm::vec3>> morphs; // per morph target, a position delta per vertex

    bool empty() const { return skin.influences == 0 && morphs.empty(); }
};

// Barycentric coordinates of `p`, a point of triangle (a, b, c), in double: clamped into the
// triangle, so that a point a rounding step outside still blends its corners with weights in [0, 1];
// a degenerate triangle gives its first corner (1, 0, 0).
glm::dvec3 barycentric(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

// The frame a point rides on a triangle (p0, p1, p2): columns the direction of its first edge, the
// perpendicular in its plane and its normal, and, as translation, the point with barycentric
// coordinates `bary`. Empty for a degenerate triangle.
std::optional<glm::dmat4> triangleFrame(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2,
                                        const glm::dvec3& bary);

// `mesh` with its positions replaced by `positions` (one per vertex, rounded to float), everything
// else kept: a posed copy of a mesh, as posePositions or posedPositions give its positions.
Mesh withPositions(const Mesh& mesh, const std::vector<glm::dvec3>& positions);

// The deformation of `object`'s render mesh (its skin weights and its morph targets' position deltas).
VertexDeformation deformationOf(const SceneObject& object);

// The deformation of `source` (a mesh with deformation `deformation`) carried over to the vertices of
// `target` (a mesh in the same space, for example its collision proxy): each target vertex takes the
// deformation of the nearest point of the source's surface, its triangle's corner values blended by
// the point's barycentric coordinates. Of the blended joint weights the `deformation.skin.influences`
// largest are kept (ties to the smaller joint) and renormalised. Fails when `deformation` does not
// match `source` or `source` has no surface.
Result<VertexDeformation> transferDeformation(const Mesh& source, const VertexDeformation& deformation,
                                              const Mesh& target);

// Vertex `vertex` at `p` skinned by `joints` (bind space to world, one per joint of the skin):
// the weighted sum of its joints' matrices applied to p. Precondition: the influences of `vertex`
// index `joints`.
glm::dvec3 skinVertex(const SkinWeights& skin, size_t vertex, const std::vector<glm::dmat4>& joints,
                      const glm::dvec3& p);

// Vertex `vertex` of `rest` deformed by a pose, as posePositions deforms every vertex.
glm::dvec3 posedVertex(const std::vector<glm::vec3>& rest, const VertexDeformation& deformation,
                       size_t vertex, const std::vector<glm::dmat4>& joints,
                       const std::vector<double>& weights, const glm::dmat4& toObject);

// The positions `rest` deformed by a pose, in double: morph deltas times `weights` added, then, when
// skinned, each vertex skinned by `joints` and brought into the object's space at the pose by
// `toObject` (the inverse of the object's transform there). Preconditions: `deformation` matches
// `rest`, joints cover its joint indices, weights.size() == deformation.morphs.size().
std::vector<glm::dvec3> posePositions(const std::vector<glm::vec3>& rest,
                                      const VertexDeformation& deformation,
                                      const std::vector<glm::dmat4>& joints,
                                      const std::vector<double>& weights, const glm::dmat4& toObject);

// Empty when `joints` and `weights` can pose a mesh of `deformation`: one finite affine joint matrix
// per joint index it uses (jointCount of them, the skin's joints), one finite weight per morph target;
// otherwise the problem, for example "3 joint matrices for a skin of 4 joints".
std::string poseProblem(const VertexDeformation& deformation, size_t jointCount,
                        const std::vector<glm::dmat4>& joints, const std::vector<double>& weights);

} // namespace spatter
