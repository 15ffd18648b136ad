#include "spatter/core/GalleryScene.hpp"
#include "spatter/core/UvOverlap.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <utility>

using namespace spatter;

namespace {

GallerySettings coarse(uint64_t seed = 1) {
    GallerySettings s;
    s.seed = seed;
    s.detail = 0;
    return s;
}

const Scene& defaultScene() {
    static const Scene scene = makeGalleryScene();
    return scene;
}

const Scene& coarseScene() {
    static const Scene scene = makeGalleryScene(coarse());
    return scene;
}

const SceneObject* find(const Scene& scene, const std::string& name) {
    for (const SceneObject& o : scene.objects)
        if (o.name == name) return &o;
    return nullptr;
}

template <class T> bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool identical(const Scene& a, const Scene& b) {
    if (a.objects.size() != b.objects.size() || a.materials.size() != b.materials.size()) return false;
    for (size_t i = 0; i < a.objects.size(); ++i) {
        const SceneObject &x = a.objects[i], &y = b.objects[i];
        if (x.name != y.name || x.dynamic != y.dynamic ||
            std::memcmp(&x.transform, &y.transform, sizeof(x.transform)) != 0)
            return false;
        if (!sameBytes(x.mesh->positions, y.mesh->positions) ||
            !sameBytes(x.mesh->normals, y.mesh->normals) || !sameBytes(x.mesh->uvs, y.mesh->uvs) ||
            !sameBytes(x.mesh->tangents, y.mesh->tangents) || !sameBytes(x.mesh->indices, y.mesh->indices) ||
            x.mesh->submeshes.size() != y.mesh->submeshes.size())
            return false;
    }
    return true;
}

DBounds worldBounds(const SceneObject& o) {
    DBounds b;
    for (const glm::vec3& p : o.mesh->positions)
        b.extend(glm::dvec3(o.transform * glm::dvec4(glm::dvec3(p), 1.0)));
    return b;
}

// Every undirected edge used by exactly two triangles.
bool closed(const Mesh& mesh) {
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = mesh.indices[t + k], b = mesh.indices[t + (k + 1) % 3];
            ++edges[{std::min(a, b), std::max(a, b)}];
        }
    for (const auto& e : edges)
        if (e.second != 2) return false;
    return !edges.empty();
}

// Nearest hit of a world-space ray against every triangle of the scene (Moller-Trumbore).
struct Hit {
    double t = INFINITY;
    const SceneObject* object = nullptr;
};

Hit castRay(const Scene& scene, const glm::dvec3& origin, const glm::dvec3& dir) {
    Hit hit;
    for (const SceneObject& o : scene.objects) {
        std::vector<glm::dvec3> world(o.mesh->positions.size());
        for (size_t i = 0; i < world.size(); ++i)
            world[i] = glm::dvec3(o.transform * glm::dvec4(glm::dvec3(o.mesh->positions[i]), 1.0));
        for (size_t t = 0; t + 2 < o.mesh->indices.size(); t += 3) {
            const glm::dvec3 a = world[o.mesh->indices[t]], b = world[o.mesh->indices[t + 1]],
                             c = world[o.mesh->indices[t + 2]];
            const glm::dvec3 e1 = b - a, e2 = c - a, pv = glm::cross(dir, e2);
            const double det = glm::dot(e1, pv);
            if (std::fabs(det) < 1e-14) continue;
            const glm::dvec3 tv = origin - a;
            const double u = glm::dot(tv, pv) / det;
            if (u < 0.0 || u > 1.0) continue;
            const glm::dvec3 qv = glm::cross(tv, e1);
            const double v = glm::dot(dir, qv) / det;
            if (v < 0.0 || u + v > 1.0) continue;
            const double d = glm::dot(e2, qv) / det;
            if (d > 1e-9 && d < hit.t) hit = {d, &o};
        }
    }
    return hit;
}

} // namespace

TEST(GalleryScene, SameSeedGivesBitIdenticalScene) {
    EXPECT_TRUE(identical(makeGalleryScene(coarse(42)), makeGalleryScene(coarse(42))));
}

TEST(GalleryScene, DifferentSeedGivesDifferentScene) {
    EXPECT_FALSE(identical(makeGalleryScene(coarse(42)), makeGalleryScene(coarse(43))));
}

TEST(GalleryScene, HasNamedStaticObjectsAndDynamicTargets) {
    const Scene& scene = coarseScene();
    EXPECT_EQ(scene.source, "builtin:gallery");
    for (const char* name : {"floor", "wall_back", "wall_left", "wall_right", "pillar_0", "pillar_3",
                             "crate_0", "crate_5", "arch", "target_0", "target_2", "banner_0", "banner_1"}) {
        const SceneObject* o = find(scene, name);
        ASSERT_NE(o, nullptr) << name;
        EXPECT_EQ(o->dynamic,
                  std::string(name).rfind("target_", 0) == 0 || std::string(name).rfind("banner_", 0) == 0)
            << name;
        EXPECT_GT(o->mesh->triangleCount(), 0u) << name;
        EXPECT_TRUE(o->receivesDecals) << name;
    }
    EXPECT_EQ(scene.dynamicObjectCount(), 5u);
    std::set<std::string> names;
    for (const SceneObject& o : scene.objects)
        EXPECT_TRUE(names.insert(o.name).second) << "duplicate " << o.name;
}

TEST(GalleryScene, TargetCountFollowsSettingsWithinLimits) {
    GallerySettings s = coarse();
    s.bannerCount = 0;
    s.targetCount = 5;
    EXPECT_EQ(makeGalleryScene(s).dynamicObjectCount(), 5u);
    s.targetCount = -3;
    EXPECT_EQ(makeGalleryScene(s).dynamicObjectCount(), 0u);
    s.targetCount = 1000;
    EXPECT_EQ(makeGalleryScene(s).dynamicObjectCount(), 8u);
}

TEST(GalleryScene, DetailIsClampedToSupportedLevels) {
    GallerySettings below = coarse();
    below.detail = -4;
    EXPECT_TRUE(identical(makeGalleryScene(below), coarseScene()));
}

TEST(GalleryScene, CoarseDetailIsSmallAndValid) {
    const Scene& scene = coarseScene();
    EXPECT_LT(scene.triangleCount(), 8000u);
    EXPECT_GT(scene.triangleCount(), 1000u);
    EXPECT_TRUE(validateScene(scene).ok()) << validateScene(scene).error();
}

TEST(GalleryScene, DefaultDetailIsDenseValidAndWellFormed) {
    const Scene& scene = defaultScene();
    EXPECT_GE(scene.triangleCount(), 40000u);
    EXPECT_LE(scene.triangleCount(), 150000u);
    ASSERT_TRUE(validateScene(scene).ok()) << validateScene(scene).error();
    for (const SceneObject& o : scene.objects) {
        const Mesh& m = *o.mesh;
        ASSERT_EQ(m.uvs.size(), m.vertexCount()) << o.name;
        ASSERT_EQ(m.tangents.size(), m.vertexCount()) << o.name;
        size_t badNormals = 0, badTangents = 0, zeroArea = 0;
        for (size_t i = 0; i < m.vertexCount(); ++i) {
            badNormals += std::fabs(glm::length(m.normals[i]) - 1.0f) > 1e-5f;
            badTangents += std::fabs(glm::length(glm::vec3(m.tangents[i])) - 1.0f) > 1e-5f ||
                           std::fabs(m.tangents[i].w) != 1.0f;
        }
        for (size_t t = 0; t < m.triangleCount(); ++t) {
            const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                            c = m.positions[m.indices[3 * t + 2]];
            zeroArea += glm::length(glm::cross(b - a, c - a)) < 1e-10f;
        }
        EXPECT_EQ(badNormals, 0u) << o.name;
        EXPECT_EQ(badTangents, 0u) << o.name;
        EXPECT_EQ(zeroArea, 0u) << o.name;
        ASSERT_FALSE(m.submeshes.empty()) << o.name;
        uint32_t covered = 0;
        for (const Submesh& s : m.submeshes)
            covered += s.indexCount;
        EXPECT_EQ(covered, m.indices.size()) << o.name;
    }
}

TEST(GalleryScene, ClosedObjectsAreClosedAtEveryDetail) {
    for (const Scene* scene : {&coarseScene(), &defaultScene()})
        for (const SceneObject& o : scene->objects) {
            if (o.name == "floor" || o.name.rfind("banner_", 0) == 0) continue;
            EXPECT_TRUE(closed(*o.mesh)) << o.name;
        }
}

TEST(GalleryScene, BoundsAsDocumented) {
    const DBounds b = defaultScene().worldBounds();
    EXPECT_GE(b.min.x, -10.0 - 1e-4);
    EXPECT_LE(b.max.x, 10.0 + 1e-4);
    EXPECT_GE(b.min.y, -0.1 - 1e-4);
    EXPECT_LE(b.max.y, 4.25);
    EXPECT_GE(b.min.z, -4.0 - 1e-4);
    EXPECT_LE(b.max.z, 8.0 + 1e-4);
    EXPECT_GT(b.extent().x, 19.9);
    EXPECT_GT(b.extent().z, 11.9);
    EXPECT_GT(b.max.y, 3.9);
    const DBounds floor = worldBounds(*find(defaultScene(), "floor"));
    EXPECT_NEAR(floor.min.y, 0.0, 0.02);
    EXPECT_NEAR(floor.max.y, 0.0, 0.02);
    const DBounds back = worldBounds(*find(defaultScene(), "wall_back"));
    EXPECT_LE(back.max.z, -3.6 + 1e-4); // brick relief only moves the front face inward
    EXPECT_GE(back.max.z, -3.62);
    EXPECT_NEAR(back.max.y, 4.0, 1e-4);
}

TEST(GalleryScene, TargetsStandInFrontOfBackWallWithGap) {
    const Scene& scene = defaultScene();
    const double wallFront = worldBounds(*find(scene, "wall_back")).max.z;
    const DBounds wall = worldBounds(*find(scene, "wall_back"));
    int targets = 0;
    for (const SceneObject& o : scene.objects) {
        if (o.name.rfind("target_", 0) != 0) continue;
        ++targets;
        const DBounds b = worldBounds(o);
        EXPECT_GE(b.min.z - wallFront, 0.25) << o.name;
        EXPECT_LT(b.max.z - wallFront, 1.0) << o.name; // close enough that the wall is right behind
        EXPECT_GT(b.min.x, wall.min.x) << o.name;      // and the wall covers it from behind
        EXPECT_LT(b.max.x, wall.max.x) << o.name;
        EXPECT_LT(b.max.y, wall.max.y) << o.name;
        EXPECT_NE(o.transform[3], glm::dvec4(0.0, 0.0, 0.0, 1.0)) << o.name;
        ASSERT_EQ(o.mesh->submeshes.size(), 3u) << o.name;
        EXPECT_NE(o.mesh->submeshes[0].material, o.mesh->submeshes[1].material) << o.name;
    }
    EXPECT_GE(targets, 2);
}

TEST(GalleryScene, CratesArePlacedAndTurned) {
    const Scene& scene = coarseScene();
    int turned = 0;
    for (int i = 0; i < 6; ++i) {
        const SceneObject* crate = find(scene, "crate_" + std::to_string(i));
        ASSERT_NE(crate, nullptr);
        const glm::dvec3 center = worldBounds(*crate).center();
        EXPECT_NEAR(glm::distance(center, glm::dvec3(crate->transform[3])), 0.0, 0.05) << crate->name;
        turned += std::fabs(crate->transform[0][2]) > 1e-3; // rotated about Y
        EXPECT_NEAR(crate->transform[1][1], 1.0, 1e-9);     // but upright
        EXPECT_GE(worldBounds(*crate).min.y, -0.02) << crate->name;
    }
    EXPECT_GE(turned, 4);
}

TEST(GalleryScene, MaterialsAreDistinct) {
    const Scene& scene = coarseScene();
    ASSERT_GE(scene.materials.size(), 6u);
    std::set<int> used;
    for (const SceneObject& o : scene.objects)
        for (const Submesh& s : o.mesh->submeshes)
            used.insert(s.material);
    EXPECT_GE(used.size(), 6u);
    EXPECT_EQ(used.count(-1), 0u);
    for (size_t i = 0; i < scene.materials.size(); ++i)
        for (size_t j = i + 1; j < scene.materials.size(); ++j)
            EXPECT_NE(scene.materials[i].baseColorFactor, scene.materials[j].baseColorFactor)
                << scene.materials[i].name << " " << scene.materials[j].name;
}

TEST(GalleryScene, PlayerSeesTargetsAndBackWall) {
    const Scene& scene = coarseScene();
    const glm::dvec3 eye(0.0, 1.7, 8.0);
    for (const SceneObject& o : scene.objects) {
        if (o.name.rfind("target_", 0) != 0) continue;
        const glm::dvec3 plate = glm::dvec3(o.transform * glm::dvec4(0.0, 1.5, 0.0, 1.0));
        const Hit hit = castRay(scene, eye, glm::normalize(plate - eye));
        ASSERT_NE(hit.object, nullptr) << o.name;
        EXPECT_EQ(hit.object->name, o.name);
    }
    const Hit wall = castRay(scene, eye, glm::normalize(glm::dvec3(-1.0, 2.5, -3.6) - eye));
    ASSERT_NE(wall.object, nullptr);
    EXPECT_EQ(wall.object->name, "wall_back");
    const Hit floor = castRay(scene, eye, glm::normalize(glm::dvec3(0.0, 0.0, 5.0) - eye));
    ASSERT_NE(floor.object, nullptr);
    EXPECT_EQ(floor.object->name, "floor");
}

TEST(GalleryScene, DetailAddsRelief) {
    GallerySettings s = coarse();
    s.detail = 1;
    const Scene medium = makeGalleryScene(s);
    const SceneObject* coarseWall = find(coarseScene(), "wall_back");
    const SceneObject* mediumWall = find(medium, "wall_back");
    ASSERT_NE(coarseWall, nullptr);
    ASSERT_NE(mediumWall, nullptr);
    EXPECT_GT(mediumWall->mesh->triangleCount(), 10 * coarseWall->mesh->triangleCount());
    // Mortar grooves: front-face vertices (away from the 2 cm bevel) more than 1 cm behind the face plane.
    auto grooved = [](const Mesh& wall) {
        size_t n = 0;
        for (const glm::vec3& p : wall.positions)
            n += std::fabs(p.x) < 9.98f && std::fabs(p.y) < 2.03f && p.z < 0.19f && p.z > 0.1f;
        return n;
    };
    EXPECT_EQ(grooved(*coarseWall->mesh), 0u);
    EXPECT_GT(grooved(*mediumWall->mesh), 1000u);
    EXPECT_GT(medium.triangleCount(), coarseScene().triangleCount());
}

TEST(GalleryScene, BannersHaveUvsThatCanCarryTextureSpaceDecals) {
    for (const char* name : {"banner_0", "banner_1"}) {
        const SceneObject* banner = find(defaultScene(), name);
        ASSERT_NE(banner, nullptr) << name;
        Result<UvOverlapReport> report = findUvOverlaps(*banner->mesh);
        ASSERT_TRUE(report.ok()) << report.error();
        EXPECT_TRUE(report->usable()) << name << ": " << report->summary();
        EXPECT_EQ(report->degenerate, 0u) << name;
    }
}
