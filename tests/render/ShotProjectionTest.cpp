// Decals projected along the shot, drawn: no bleeding through a thin slab onto its back face or the
// wall behind it, whatever the angle of the shot, no paint on a face the shot could not reach, and
// the GPU's slanted boxes cover what the CPU reference's do.

#include "RenderTestSupport.hpp"
#include "ShotDecals.hpp"

#include "TestData.hpp"

#include "spatter/core/MeshBuilder.hpp"

#include <gtest/gtest.h>

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
    DecalType t = test::paintType();
    t.maxAngleDeg = 85.0f;
    return test::shotFromTheRight(scene, t, glm::dvec3(0.0, 0.1, 0.01), degrees);
}

// Covered pixels of `cam` whose surface is not the slab's face facing `side` (+1 front, -1 back).
size_t coveredOffTheSlab(const Scene& scene, const std::vector<uint8_t>& coverage, const Camera& cam,
                         double side) {
    return coveredWhere(scene, coverage, cam, [side](const std::optional<Hit>& hit) {
        return !(hit && hit->object == 0 && hit->normal.z * side > 0.99);
    });
}

// Covered pixels of `cam` whose surface is the ridge's falling face (normal x below -0.1).
size_t coveredOnTheFallingFace(const Scene& scene, const std::vector<uint8_t>& coverage, const Camera& cam) {
    return coveredWhere(scene, coverage, cam,
                        [](const std::optional<Hit>& hit) { return hit && hit->normal.x < -0.1; });
}

} // namespace

TEST(ShotProjection, AFaceTurnedAwayFromTheShotTakesNoPaintThoughItFacesTheDecalNormal) {
    SPATTER_REQUIRE_GL(gl);
    // The falling face is 50 degrees from the flat face's normal, within the type's 80, but 110 from
    // the reversed shot, which comes from the right 60 degrees off the normal: the shot cannot reach it.
    const test::RidgeShot ridge = test::ridgeShot(50.0, 60.0);
    ASSERT_EQ(ridge.inputs.decals.size(), 1u);
    const Scene& scene = ridge.scene;
    const test::CoverageInputs& in = ridge.inputs;

    Result<Renderer> r = test::makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r->setScene(scene).ok());
    r->setDecals(in.decals);
    const Camera cam = test::lookAt({-0.5, -0.2, 0.9}, {0.0, 0.0, -0.05});
    r->setDecalTypes(in.types);
    const std::vector<uint8_t> seen = test::whiteMask(test::renderView(r.value(), cam, View::Coverage));
    EXPECT_GT(test::countSet(seen), 100u);
    EXPECT_EQ(coveredOnTheFallingFace(scene, seen, cam), 0u);
    EXPECT_GE(test::iou(seen, test::referenceCoverage(scene, in, cam, kW, kH)), 0.97);

    // Without the angle test the box does reach the falling face: the test can see it.
    test::CoverageInputs anyAngle = in;
    anyAngle.types[0].maxAngleDeg = 180.0f;
    r->setDecalTypes(anyAngle.types);
    const std::vector<uint8_t> all = test::whiteMask(test::renderView(r.value(), cam, View::Coverage));
    EXPECT_GT(coveredOnTheFallingFace(scene, all, cam), 20u);
}

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
