#include "RecordPose.hpp"

#include "spatter/core/VertexDeformation.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace spatter {

std::optional<glm::dmat4> RecordPoses::frameAt(uint32_t object, const SurfaceAnchor& anchor, double t) {
    const Mesh& mesh = *scene_.objects[object].mesh;
    if (size_t(anchor.triangle) >= mesh.triangleCount()) return std::nullopt;
    std::vector<glm::dvec3>& world = posed_[{object, t}];
    if (world.empty()) {
        evaluator_.evaluate(scene_.animation.animations.empty() ? -1 : 0, t);
        const glm::dmat4 toWorld =
            glm::translate(glm::dmat4(1.0), offset_) * evaluator_.objectTransform(object);
        world = posedPositions(scene_, object, evaluator_);
        for (glm::dvec3& p : world)
            p = glm::dvec3(toWorld * glm::dvec4(p, 1.0));
    }
    const uint32_t* c = &mesh.indices[3 * size_t(anchor.triangle)];
    return triangleFrame(world[c[0]], world[c[1]], world[c[2]], anchor.bary);
}

WorldDecalBox moveBox(const WorldDecalBox& box, const glm::dmat4& from, const glm::dmat4& to) {
    const glm::dmat4 m = to * glm::inverse(from);
    const glm::dmat3 rotation(m);
    WorldDecalBox out = box;
    out.center = glm::dvec3(m * glm::dvec4(box.center, 1.0));
    for (glm::dvec3& axis : out.axes)
        axis = glm::normalize(rotation * axis);
    if (box.projection != glm::dvec3(0.0)) out.projection = glm::normalize(rotation * box.projection);
    return out;
}

} // namespace spatter
