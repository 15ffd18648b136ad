// loadGltf on the third-party glTF files in ../shared/data/gltf (see its SOURCES.md).
//
// Expected numbers were computed once, independently of this project, by a Python script that reads
// each file's JSON and binary chunk, walks the default scene composing node matrices / TRS, and
// transforms every POSITION of every drawn mesh to world space:
//   file                         triangles  world min                        world max
//   Box/Box.gltf                        12  (-0.5, -0.5, 1.5)                (0.5, 0.5, 2.5)   root matrix
//   translates z by 2 Box/Box.glb                         12  (-0.5, -0.5, -0.5)               (0.5, 0.5,
//   0.5)   root matrix turns -90 deg about x Duck/Duck.gltf, .glb              4212  (-0.692985, 0.099294,
//   -0.613282) (0.961799, 1.639700, 0.539252)
//                                           raw positions (-69.2985, 9.9294, -61.3282)..(96.1799,
//                                           163.97, 53.9252)
//   DamagedHelmet/DamagedHelmet.glb  15452  (-0.947459, -0.900974, -1.187155) (0.942495, 0.900995, 0.812845)
//   KenneyFPS/models/*.glb: see kKenney below (identity root nodes).

#include "spatter/core/SceneLoader.hpp"

#include "TestData.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

using namespace spatter;

namespace {

constexpr double kTolerance = 1e-5;

void expectBounds(const Scene& scene, const glm::dvec3& min, const glm::dvec3& max) {
    const DBounds b = scene.worldBounds();
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(b.min[i], min[i], kTolerance) << "min axis " << i;
        EXPECT_NEAR(b.max[i], max[i], kTolerance) << "max axis " << i;
    }
}

Scene loadShared(const std::string& path) {
    Result<Scene> scene = loadGltf(path);
    EXPECT_TRUE(scene.ok()) << scene.error();
    return scene.ok() ? std::move(scene.value()) : Scene{};
}

void expectDecoded(const Image& image, int width, int height) {
    EXPECT_EQ(image.width, width) << image.name;
    EXPECT_EQ(image.height, height) << image.name;
    EXPECT_EQ(image.rgba.size(), size_t(width) * size_t(height) * 4) << image.name;
}

} // namespace

TEST(SharedGltf, BoxGltfAppliesRootMatrix) {
    SPATTER_REQUIRE_SHARED(path, "gltf/Box/Box.gltf");
    Scene scene = loadShared(path);
    EXPECT_EQ(scene.triangleCount(), 12u);
    ASSERT_EQ(scene.objects.size(), 1u);
    expectBounds(scene, {-0.5, -0.5, 1.5}, {0.5, 0.5, 2.5});
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].name, "Red");
    EXPECT_NEAR(scene.materials[0].baseColorFactor.x, 0.8, 1e-6);
    EXPECT_EQ(scene.materials[0].metallic, 0.0f);
}

TEST(SharedGltf, BoxGlbAppliesRootMatrix) {
    SPATTER_REQUIRE_SHARED(path, "gltf/Box/Box.glb");
    Scene scene = loadShared(path);
    EXPECT_EQ(scene.triangleCount(), 12u);
    ASSERT_EQ(scene.objects.size(), 1u);
    expectBounds(scene, {-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5});
    // The -90 degree turn about x maps object +y to world -z.
    const glm::dvec4 up = scene.objects[0].transform * glm::dvec4(0, 1, 0, 0);
    EXPECT_NEAR(up.z, -1.0, 1e-12);
}

TEST(SharedGltf, DuckIsScaledDownByItsRootMatrix) {
    for (const char* file : {"gltf/Duck/Duck.gltf", "gltf/Duck/Duck.glb"}) {
        SCOPED_TRACE(file);
        SPATTER_REQUIRE_SHARED(path, file);
        Scene scene = loadShared(path);
        EXPECT_EQ(scene.triangleCount(), 4212u);
        ASSERT_EQ(scene.objects.size(), 1u); // the camera node draws nothing
        expectBounds(scene, {-0.692985, 0.099294, -0.613282}, {0.961799, 1.639700, 0.539252});
        EXPECT_NEAR(scene.worldBounds().diagonal(), 2.537616, kTolerance);
        const Bounds raw = scene.objects[0].mesh->bounds();
        EXPECT_NEAR(raw.max.y, 163.97, 1e-3);
        ASSERT_EQ(scene.images.size(), 1u);
        expectDecoded(scene.images[0], 512, 512);
        ASSERT_EQ(scene.materials.size(), 1u);
        EXPECT_EQ(scene.materials[0].baseColorTexture, 0);
        EXPECT_EQ(scene.objects[0].mesh->uvs.size(), scene.objects[0].mesh->positions.size());
    }
}

TEST(SharedGltf, DamagedHelmetDecodesItsEmbeddedJpegs) {
    SPATTER_REQUIRE_SHARED(path, "gltf/DamagedHelmet/DamagedHelmet.glb");
    Scene scene = loadShared(path);
    EXPECT_EQ(scene.triangleCount(), 15452u);
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].mesh->vertexCount(), 14556u);
    expectBounds(scene, {-0.947459, -0.900974, -1.187155}, {0.942495, 0.900995, 0.812845});
    ASSERT_EQ(scene.images.size(), 5u);
    for (const Image& image : scene.images)
        expectDecoded(image, 2048, 2048);
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].baseColorTexture, 0);
    EXPECT_EQ(scene.materials[0].normalTexture, 4);
}

TEST(SharedGltf, KenneyModelsLoadWithTheirExternalTexture) {
    struct Expected {
        const char* file;
        size_t triangles;
        glm::dvec3 min, max;
    };
    const Expected kKenney[] = {
        {"grass-small.glb", 72, {-0.123833, 0, -0.156461}, {0.123833, 0.258092, 0.156461}},
        {"grass.glb", 72, {-0.255491, 0, -0.267781}, {0.255491, 0.309261, 0.267781}},
        {"platform-large-grass.glb", 180, {-2.6, 0, -2.6}, {2.6, 0.5, 2.6}},
        {"platform.glb", 180, {-1.1, 0, -1.1}, {1.1, 0.5, 1.1}},
        {"wall-high.glb", 208, {-0.75, 0, -0.35}, {0.75, 1.7, 0.35}},
        {"wall-low.glb", 178, {-1.1, 0, -0.349768}, {1.1, 0.8, 0.350232}},
    };
    for (const Expected& e : kKenney) {
        SCOPED_TRACE(e.file);
        SPATTER_REQUIRE_SHARED(path, std::string("gltf/KenneyFPS/models/") + e.file);
        Scene scene = loadShared(path);
        EXPECT_EQ(scene.triangleCount(), e.triangles);
        expectBounds(scene, e.min, e.max);
        ASSERT_EQ(scene.images.size(), 1u);
        expectDecoded(scene.images[0], 512, 512);
        EXPECT_EQ(scene.images[0].name, "Textures/colormap.png");
        ASSERT_EQ(scene.materials.size(), 1u);
        EXPECT_EQ(scene.materials[0].baseColorTexture, 0);
        ASSERT_EQ(scene.objects.size(), 1u);
        const Mesh& mesh = *scene.objects[0].mesh;
        EXPECT_EQ(mesh.uvs.size(), mesh.vertexCount());
        EXPECT_EQ(mesh.tangents.size(), mesh.vertexCount());
    }
}
