#include "spatter/core/Scene.hpp"

#include <cmath>
#include <unordered_set>
#include <utility>

namespace spatter {

Mesh& SceneObject::editMesh() {
    auto own = std::make_shared<Mesh>(mesh ? *mesh : Mesh());
    mesh = own;
    return *own;
}

std::shared_ptr<const Mesh> shareMesh(Mesh mesh) {
    return std::make_shared<const Mesh>(std::move(mesh));
}

SceneObject makeSceneObject(std::string name, std::shared_ptr<const Mesh> mesh, const glm::dmat4& transform,
                            bool dynamic) {
    SceneObject o;
    o.name = std::move(name);
    o.mesh = std::move(mesh);
    o.transform = transform;
    o.dynamic = dynamic;
    return o;
}

SceneObject makeSceneObject(std::string name, Mesh mesh, const glm::dmat4& transform, bool dynamic) {
    return makeSceneObject(std::move(name), shareMesh(std::move(mesh)), transform, dynamic);
}

size_t Scene::triangleCount() const {
    size_t n = 0;
    for (const SceneObject& o : objects)
        n += o.mesh ? o.mesh->triangleCount() : 0;
    return n;
}

size_t Scene::meshCount() const {
    std::unordered_set<const Mesh*> meshes;
    for (const SceneObject& o : objects)
        if (o.mesh) meshes.insert(o.mesh.get());
    return meshes.size();
}

size_t Scene::dynamicObjectCount() const {
    size_t n = 0;
    for (const SceneObject& o : objects)
        n += o.dynamic ? 1 : 0;
    return n;
}

DBounds Scene::worldBounds() const {
    DBounds b;
    for (const SceneObject& o : objects) {
        if (!o.mesh) continue;
        for (const glm::vec3& p : o.mesh->positions)
            b.extend(glm::dvec3(o.transform * glm::dvec4(glm::dvec3(p), 1.0)));
    }
    return b;
}

void Scene::translate(const glm::dvec3& offset) {
    for (SceneObject& o : objects)
        o.transform[3] += glm::dvec4(offset, 0.0);
}

std::string transformProblem(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return "transform is not finite";
    if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
        return "transform is not affine";
    return {};
}

Status validateScene(const Scene& scene) {
    if (Status s = validateAnimation(scene.animation); !s) return fail("animation data: " + s.error());
    std::unordered_set<const Mesh*> checked; // a mesh that objects share is checked once
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& o = scene.objects[i];
        const std::string what = "object " + std::to_string(i) + " (" + o.name + ")";
        if (!o.mesh) return fail(what + ": has no render mesh");
        if (checked.insert(o.mesh.get()).second)
            if (Status s = validateMesh(*o.mesh); !s) return fail(what + ": render mesh " + s.error());
        if (o.collider)
            if (Status s = validateMesh(*o.collider); !s) return fail(what + ": collider " + s.error());
        if (const std::string problem = transformProblem(o.transform); !problem.empty())
            return fail(what + ": " + problem);
        if (Status s = validateObjectAnimation(o, scene.animation); !s) return fail(what + " " + s.error());
        for (const Submesh& sm : o.mesh->submeshes)
            if (sm.material < -1 || sm.material >= int(scene.materials.size()))
                return fail(what + ": submesh material " + std::to_string(sm.material) + " does not exist");
    }
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        const int n = int(scene.images.size());
        if (m.baseColorTexture < -1 || m.baseColorTexture >= n || m.normalTexture < -1 ||
            m.normalTexture >= n)
            return fail("material " + std::to_string(i) + " (" + m.name + ") refers to a missing image");
    }
    for (size_t i = 0; i < scene.images.size(); ++i) {
        const Image& im = scene.images[i];
        if (im.empty() || im.rgba.size() != size_t(im.width) * size_t(im.height) * 4)
            return fail("image " + std::to_string(i) + " (" + im.name + ") has no valid pixels");
    }
    return {};
}

} // namespace spatter
