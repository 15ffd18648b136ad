#include "spatter/core/ProxyInstances.hpp"
#include "spatter/core/DeformingProxy.hpp"
#include "spatter/core/GalleryScene.hpp"
#include "spatter/core/MeshBuilder.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

using namespace spatter;

namespace {

Mesh bumpySphere(float bumps) {
    Mesh m = makeSphere(1.0f, 24, 48);
    displace(m, [bumps](const glm::vec3& p, const glm::vec3&) { return 0.05f * std::sin(bumps * p.x); });
    return m;
}

SceneObject placed(const std::string& name, const Mesh& mesh, double x, bool dynamic = false) {
    return makeSceneObject(name, mesh, glm::translate(glm::dmat4(1.0), glm::dvec3(x, 0.0, 0.0)), dynamic);
}

} // namespace

TEST(ProxySources, ObjectsWithTheSameMeshAndColliderTakeTheFirstOnesProxy) {
    const Mesh a = bumpySphere(4.0f), b = bumpySphere(5.0f);
    Mesh aOtherNormals = a; // normals, UVs and submeshes do not change a proxy
    for (glm::vec3& n : aOtherNormals.normals)
        n = -n;
    Scene scene;
    scene.objects = {placed("a", a, 0.0), placed("b", b, 3.0), placed("a moving", a, 6.0, true),
                     placed("a with other normals", aOtherNormals, 9.0), placed("b again", b, 12.0)};
    SceneObject withCollider = placed("a with a collider", a, 15.0);
    withCollider.collider = b;
    scene.objects.push_back(withCollider);
    withCollider.name = "a with that collider again";
    scene.objects.push_back(withCollider);
    EXPECT_EQ(proxySources(scene), (std::vector<size_t>{0, 1, 0, 0, 1, 5, 5}));
}

TEST(ProxySources, ObjectsThatTakeNoDecalsOrDeformKeepTheirOwn) {
    const Mesh a = bumpySphere(4.0f);
    Scene scene;
    scene.objects = {placed("a, no decals", a, 0.0), placed("a", a, 3.0), placed("a skinned", a, 6.0, true),
                     placed("a morphed at rest", a, 9.0)};
    scene.objects[0].receivesDecals = false;
    scene.objects[2].skin = 0; // a dynamic object that deforms: its proxy holds over its own poses
    scene.objects[3].morphTargets.resize(1);
    EXPECT_EQ(proxySources(scene), (std::vector<size_t>{0, 1, 2, 1}));
}

TEST(ProxySources, MeshesThatDifferInOneBitOrOneIndexKeepTheirOwn) {
    const Mesh a = bumpySphere(4.0f);
    Mesh moved = a;
    moved.positions[7].y = std::nextafter(moved.positions[7].y, 2.0f);
    Mesh turned = a; // the same triangles, one of them listed from another corner
    std::rotate(turned.indices.begin(), turned.indices.begin() + 1, turned.indices.begin() + 3);
    Mesh colliderMoved = a;
    colliderMoved.positions[0].x += 1e-3f;
    Scene scene;
    scene.objects = {placed("a", a, 0.0), placed("moved", moved, 3.0), placed("turned", turned, 6.0)};
    SceneObject withCollider = placed("with a collider", a, 9.0), withOther = placed("with another", a, 12.0);
    withCollider.collider = a;
    withOther.collider = colliderMoved;
    scene.objects.push_back(withCollider);
    scene.objects.push_back(withOther);
    EXPECT_EQ(proxySources(scene), (std::vector<size_t>{0, 1, 2, 3, 4}));
}

// What makes sharing sound: a proxy depends on its object's render mesh and collider alone, so the
// proxy an object takes from its source is the one built for it.
TEST(ProxySources, ASharedProxyIsTheOneBuiltForTheObjectItself) {
    Scene scene;
    const Mesh a = bumpySphere(4.0f);
    scene.objects = {placed("a", a, 0.0), placed("a far away", a, 1e4, true)};
    ASSERT_EQ(proxySources(scene)[1], 0u);
    ProxySettings settings;
    settings.tolerance = 0.01f;
    Result<Proxy> first = buildObjectProxy(scene, 0, settings), second = buildObjectProxy(scene, 1, settings);
    ASSERT_TRUE(first && second);
    ASSERT_EQ(first->source, ProxySource::Simplified);
    EXPECT_EQ(first->errorBound, second->errorBound);
    ASSERT_EQ(first->mesh.positions.size(), second->mesh.positions.size());
    EXPECT_EQ(std::memcmp(first->mesh.positions.data(), second->mesh.positions.data(),
                          first->mesh.positions.size() * sizeof(glm::vec3)),
              0);
    EXPECT_EQ(first->mesh.indices, second->mesh.indices);
}

TEST(ProxySources, TheGallerysTargetsAndBannersShareOneProxyEach) {
    const Scene scene = makeGalleryScene();
    const std::vector<size_t> sources = proxySources(scene);
    ASSERT_EQ(sources.size(), scene.objects.size());
    size_t shared = 0;
    for (size_t i = 0; i < sources.size(); ++i) {
        const std::string& name = scene.objects[i].name;
        std::string expected = name;
        for (const std::string kind : {"target_", "banner_"})
            if (name.rfind(kind, 0) == 0) expected = kind + "0";
        EXPECT_EQ(scene.objects[sources[i]].name, expected);
        shared += sources[i] != i ? 1 : 0;
    }
    EXPECT_EQ(shared, 3u);
}
