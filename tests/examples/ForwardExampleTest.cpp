// spatter-example-forward, a forward renderer hosting the projector's forward path, run as a separate
// process: its coverage view (the pixels where spatterApplyForwardDecals changed the surface) against
// the CPU reference, its albedo under the decals against spatter-render's on the same decals, and its
// command-line contract, spatter-render's.

#include "ExampleTestSupport.hpp"

#include <fstream>

using namespace spatter;

namespace {

const test::ExampleHost kForward{SPATTER_EXAMPLE_FORWARD, {}, "forward"};

} // namespace

TEST(ForwardExample, CoverageMatchesTheCpuReferenceOnTheGallery) {
    SPATTER_REQUIRE_TOOL_GL();
    test::expectCoverageOnTheGallery(kForward);
}

TEST(ForwardExample, CoverageMatchesTheCpuReferenceOnSharedScenes) {
    SPATTER_REQUIRE_TOOL_GL();
    test::expectCoverageOnSharedScenes(kForward);
}

TEST(ForwardExample, CoverageMatchesTheCpuReferenceWithTheCameraInsideADecalBox) {
    SPATTER_REQUIRE_TOOL_GL();
    test::expectCoverageWithTheCameraInsideADecalBox(kForward);
}

TEST(ForwardExample, CoverageLeavesOutAnObjectThatTakesNoDecalsInsideTheBoxes) {
    SPATTER_REQUIRE_TOOL_GL();
    test::expectCoverageWithAnObjectThatTakesNoDecals(kForward);
}

// The same decals applied in the example's fragment shader (blended in float, written once to RGBA8)
// and blended into spatter-render's sRGB G-buffer: where both show a decal, the albedo agrees in
// linear terms within 2/255 on average, and 99% of the pixels within 8/255. The rest lie along
// silhouettes and grazing surfaces, where the two paths pick different mip levels of the decal
// texture: the forward path takes its texture derivatives from the triangle it shades, the deferred
// paths from the depth buffer, whose 2x2 pixel quads there reach the surface behind.
TEST(ForwardExample, AlbedoUnderTheDecalsAgreesWithSpatterRender) {
    SPATTER_REQUIRE_TOOL_GL();
    const test::AlbedoAgreement a = test::albedoAgainstSpatterRender(kForward);
    EXPECT_LE(a.mean, 2.0);
    EXPECT_LE(a.percentile99, 8.0);
}

TEST(ForwardExample, ReportsBadInputThroughItsExitCode) {
    const std::string dir = test::exampleScratch();
    const char* tool = SPATTER_EXAMPLE_FORWARD;
    EXPECT_EQ(test::runTool(tool, {"--help"}), 0);
    EXPECT_EQ(test::runTool(tool, {}), 2);                                           // no scene
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--size", "10"}), 2);          // not WxH
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--view", "normal"}), 2);      // not one of its views
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--camera", "eye=0,0,1"}), 2); // no target
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--decals", "a", "--rays", "b"}), 2); // both
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--out"}), 2);                        // no value
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--dbuffer"}),
              2);                                          // the deferred example's, not its own
    EXPECT_EQ(test::runTool(tool, {"a.obj", "b.obj"}), 2); // two scenes
    EXPECT_EQ(test::runTool(tool, {dir + "/missing.obj", "--out", dir + "/x.png"}), 1); // no such scene
    std::ofstream(dir + "/forward-bad.jsonl") << "{\"status\":\"placed\",\"object\":\"floor\"}\n";
    EXPECT_EQ(test::runTool(
                  tool, {"builtin:gallery", "--decals", dir + "/forward-bad.jsonl", "--out", dir + "/x.png"}),
              1);
}
