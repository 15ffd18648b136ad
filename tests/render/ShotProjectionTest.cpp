// Decals projected along the shot, drawn: no bleeding through a thin slab onto its back face or the
// wall behind it, whatever the angle of the shot, and the GPU's slanted boxes cover what the CPU
// reference's do.

#include "RenderTestSupport.hpp"

#include "TestData.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

using namespace spatter;
using namespace spatter::test;

namespace {

// A slab 1 x 1 x 0.02 at the origin (front face +Z at z = 0.01) and a wall 3 x 3 x 0.1 behind it,
// its front face at z = -0.25.
Scene slabScene() {
    Scene s;
    s.source = "test:slab and wall";
    s.objects.push_back(makeSceneObject("slab", makeBox(glm::vec3(0.5f, 0.5f, 0.01f), 4)));
    s.objects.push_back(makeSceneObject("wall", makeBox(glm::vec3(1.5f, 1.5f, 0.05f), 4),
                                        glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, -0.3))));
    return s;
}

// One decal shot at the slab's front face `degrees` from its normal, from the right (+X).
test::CoverageInputs shotAtSlab(const Scene& scene, double degrees) {
    DecalType t;
    t.name = "paint";
    t.texture = int(DecalTexture::Paint);
    t.size = glm::vec2(0.3f);
    t.maxAngleDeg = 85.0f;
    t.randomRotation = false;
    Result<DecalSystem> s = DecalSystem::create(scene);
    EXPECT_TRUE(s.ok()) << s.error();
    const uint16_t type = s->registerType(t).value();
    const double a = degrees * kPi / 180.0;
    const glm::dvec3 back(std::sin(a), 0.0, std::cos(a));
    Ray ray;
    ray.origin = glm::dvec3(0.0, 0.1, 0.01) + 2.0 * back;
    ray.direction = -back;
    const SpawnResult r = s->spawn(ray, type);
    EXPECT_TRUE(r.placed()) << r.reason;
    test::CoverageInputs in;
    in.decals = s->decals();
    in.types = {t};
    return in;
}

// Covered pixels of `cam` whose surface is not the slab's face facing `side` (+1 front, -1 back).
size_t coveredOffTheSlab(const Scene& scene, const std::vector<uint8_t>& coverage, const Camera& cam,
                         double side) {
    Result<CollisionWorld> world = CollisionWorld::build(scene);
    EXPECT_TRUE(world.ok()) << world.error();
    size_t off = 0;
    for (int j = 0; j < kH; ++j)
        for (int i = 0; i < kW; ++i) {
            if (!coverage[size_t(j) * kW + size_t(i)]) continue;
            Ray ray;
            ray.origin = cam.eye;
            ray.direction = pixelDirection(cam, kW, kH, i, j);
            const std::optional<Hit> hit = world->intersect(ray);
            const bool face = hit && hit->object == 0 && hit->normal.z * side > 0.99;
            if (!face) ++off;
        }
    return off;
}

} // namespace

TEST(ShotProjection, GrazingShotsMarkNeitherTheBackOfAThinSlabNorTheWallBehind) {
    SPATTER_REQUIRE_GL(gl);
    const Scene scene = slabScene();
    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r->setScene(scene).ok());
    // In front, seeing the front face and the wall around the slab; between slab and wall, seeing the
    // back face and the wall where the shots go on.
    const Camera front = test::lookAt({-0.4, 0.3, 1.6}, {0.0, 0.0, -0.1});
    const Camera gap = test::lookAt({-0.3, 0.1, -0.2}, {0.4, 0.0, 0.0});
    for (double degrees : {10.0, 45.0, 80.0}) {
        SCOPED_TRACE(std::to_string(degrees) + " degrees");
        const test::CoverageInputs in = shotAtSlab(scene, degrees);
        ASSERT_EQ(in.decals.size(), 1u);
        ASSERT_NE(in.decals[0].slant, 0u);
        r->setDecalTypes(in.types);
        r->setDecals(in.decals);
        const std::vector<uint8_t> seen = test::whiteMask(test::renderView(r.value(), front, View::Coverage));
        EXPECT_GT(test::countSet(seen), 100u);
        EXPECT_EQ(coveredOffTheSlab(scene, seen, front, 1.0), 0u);
        EXPECT_GE(test::iou(seen, test::referenceCoverage(scene, in, front, kW, kH)), 0.97);
        const std::vector<uint8_t> behind = test::whiteMask(test::renderView(r.value(), gap, View::Coverage));
        EXPECT_EQ(test::countSet(behind), 0u);

        // The box does reach the back face, shifted along the shot: the angle test keeps it clean.
        // The wall, which faces the decal, stays out of the box by its depth.
        test::CoverageInputs anyAngle = in;
        anyAngle.types[0].maxAngleDeg = 180.0f;
        r->setDecalTypes(anyAngle.types);
        const std::vector<uint8_t> through =
            test::whiteMask(test::renderView(r.value(), gap, View::Coverage));
        EXPECT_GT(test::countSet(through), 20u);
        EXPECT_EQ(coveredOffTheSlab(scene, through, gap, -1.0), 0u);
    }
}
