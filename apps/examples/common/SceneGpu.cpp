#include "SceneGpu.hpp"

#include "GlHelpers.hpp"

#include <array>

namespace example {

const char* const kSceneVertex = R"(#version 450 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 0) uniform mat4 u_modelViewProj;
layout(location = 4) uniform mat4 u_model;
layout(location = 8) uniform mat3 u_normalMatrix;
out vec3 v_normal;
out vec3 v_position;
void main() {
    gl_Position = u_modelViewProj * vec4(a_position, 1.0);
    v_normal = u_normalMatrix * a_normal;
    v_position = (u_model * vec4(a_position, 1.0)).xyz;
}
)";

namespace {

glm::vec4 materialOf(const spatter::Scene& scene, int index) {
    const spatter::Material m = index >= 0 ? scene.materials[size_t(index)] : spatter::Material{};
    return glm::vec4(glm::vec3(m.baseColorFactor), glm::clamp(m.roughness, 0.02f, 1.0f));
}

ObjectGpu upload(const spatter::Scene& scene, const spatter::Mesh& mesh) {
    ObjectGpu g;
    if (mesh.indices.empty()) return g;
    GLuint buffers[3] = {0, 0, 0};
    g.vertexArray = meshVertexArray(mesh, buffers);
    if (mesh.submeshes.empty()) g.ranges.push_back({0, GLsizei(mesh.indices.size()), materialOf(scene, -1)});
    for (const spatter::Submesh& s : mesh.submeshes)
        g.ranges.push_back({GLsizei(s.firstIndex), GLsizei(s.indexCount), materialOf(scene, s.material)});
    return g;
}

// The smallest decal ID that no decal clips to (a decal clips to its object's ID, `objectIds`); fails
// when the decals use all 256.
spatter::Result<uint8_t> unusedDecalId(const std::vector<spatter::Decal>& decals,
                                       const std::vector<uint8_t>& objectIds) {
    std::array<bool, 256> used{};
    for (const spatter::Decal& d : decals)
        if (d.object < objectIds.size()) used[objectIds[d.object]] = true;
    for (size_t id = 0; id < used.size(); ++id)
        if (!used[id]) return uint8_t(id);
    return spatter::fail("the decals use all 256 object decal IDs: none is left for the objects that take "
                         "no decals");
}

} // namespace

spatter::Result<SceneGpu> uploadScene(const Inputs& in) {
    SceneGpu g;
    g.decalIds = in.decals.objectIds;
    g.decalIds.resize(in.scene.objects.size(), 0);
    for (size_t i = 0; i < in.scene.objects.size(); ++i) {
        const spatter::SceneObject& o = in.scene.objects[i];
        if (!o.receivesDecals) {
            spatter::Result<uint8_t> id = unusedDecalId(in.decals.decals, in.decals.objectIds);
            if (!id) return spatter::fail(id.error());
            g.decalIds[i] = id.value();
        }
        g.objects.push_back(upload(in.scene, *o.mesh));
        g.transforms.push_back(o.transform);
    }
    return g;
}

void drawScene(const SceneGpu& scene, const Inputs& in) {
    const glm::dmat4 viewProjection = in.projection * spatter::viewRotation(in.camera);
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        glm::dmat4 model = scene.transforms[i];
        model[3] -= glm::dvec4(in.camera.eye, 0.0); // relative to the eye, in double
        const glm::mat4 modelViewProj(viewProjection * model), eyeRelative(model);
        const glm::mat3 normalMatrix(glm::transpose(glm::inverse(glm::dmat3(scene.transforms[i]))));
        glUniformMatrix4fv(0, 1, GL_FALSE, &modelViewProj[0][0]);
        glUniformMatrix4fv(4, 1, GL_FALSE, &eyeRelative[0][0]);
        glUniformMatrix3fv(8, 1, GL_FALSE, &normalMatrix[0][0]);
        glUniform1ui(12, scene.decalIds[i]);
        glUniform1i(13, glm::determinant(glm::dmat3(scene.transforms[i])) < 0.0 ? 1 : 0);
        glBindVertexArray(scene.objects[i].vertexArray);
        for (const DrawRange& r : scene.objects[i].ranges) {
            glUniform4fv(11, 1, &r.material[0]);
            glDrawElements(GL_TRIANGLES, r.count, GL_UNSIGNED_INT,
                           reinterpret_cast<const void*>(size_t(r.first) * sizeof(uint32_t)));
        }
    }
}

} // namespace example
