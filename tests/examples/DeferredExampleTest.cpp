// spatter-example-deferred, a foreign host of the projector, run as a separate process on both of
// its paths (G-buffer blend, and DBuffer with --dbuffer): its coverage view against the CPU
// reference, its albedo under the decals against spatter-render's on the same decals, and its
// command-line contract.

#include "ExampleTestSupport.hpp"

#include <fstream>

using namespace spatter;

namespace {

const test::ExampleHost kBlend{SPATTER_EXAMPLE_DEFERRED, {}, "deferred"};
const test::ExampleHost kDBuffer{SPATTER_EXAMPLE_DEFERRED, {"--dbuffer"}, "deferred-dbuffer"};

} // namespace

TEST(DeferredExample, CoverageMatchesTheCpuReferenceOnTheGallery) {
    SPATTER_REQUIRE_TOOL_GL();
    test::expectCoverageOnTheGallery(kBlend);
}

TEST(DeferredExample, CoverageMatchesTheCpuReferenceOnSharedScenes) {
    SPATTER_REQUIRE_TOOL_GL();
    test::expectCoverageOnSharedScenes(kBlend);
}

TEST(DeferredExample, CoverageMatchesTheCpuReferenceWithTheCameraInsideADecalBox) {
    SPATTER_REQUIRE_TOOL_GL();
    test::expectCoverageWithTheCameraInsideADecalBox(kBlend);
}

TEST(DeferredExample, CoverageLeavesOutAnObjectThatTakesNoDecalsInsideTheBoxes) {
    SPATTER_REQUIRE_TOOL_GL();
    test::expectCoverageWithAnObjectThatTakesNoDecals(kBlend);
}

TEST(DeferredExample, DBufferCoverageMatchesTheCpuReferenceOnTheGallery) {
    SPATTER_REQUIRE_TOOL_GL();
    test::expectCoverageOnTheGallery(kDBuffer);
}

TEST(DeferredExample, DBufferCoverageMatchesTheCpuReferenceOnSharedScenes) {
    SPATTER_REQUIRE_TOOL_GL();
    test::expectCoverageOnSharedScenes(kDBuffer);
}

TEST(DeferredExample, DBufferCoverageMatchesTheCpuReferenceWithTheCameraInsideADecalBox) {
    SPATTER_REQUIRE_TOOL_GL();
    test::expectCoverageWithTheCameraInsideADecalBox(kDBuffer);
}

TEST(DeferredExample, DBufferCoverageLeavesOutAnObjectThatTakesNoDecalsInsideTheBoxes) {
    SPATTER_REQUIRE_TOOL_GL();
    test::expectCoverageWithAnObjectThatTakesNoDecals(kDBuffer);
}

// The same decals in the example (linear RGBA8 albedo, standard Z, RGB10A2 normals) and in
// spatter-render (sRGB albedo, reversed Z, octahedral normals): where both show a decal, the albedo
// agrees in linear terms within 2/255 on average and 8/255 at most, the quantisation of the two
// 8-bit encodings.
TEST(DeferredExample, AlbedoUnderTheDecalsAgreesWithSpatterRender) {
    SPATTER_REQUIRE_TOOL_GL();
    const test::AlbedoAgreement a = test::albedoAgainstSpatterRender(kBlend);
    EXPECT_LE(a.mean, 2.0);
    EXPECT_LE(a.largest, 8.0);
}

// The DBuffer path: the decals gathered in the projector's buffers (sRGB albedo) and applied once in
// the lighting pass round differently from a blend into the G-buffer, within the same tolerance.
TEST(DeferredExample, DBufferAlbedoUnderTheDecalsAgreesWithSpatterRender) {
    SPATTER_REQUIRE_TOOL_GL();
    const test::AlbedoAgreement a = test::albedoAgainstSpatterRender(kDBuffer);
    EXPECT_LE(a.mean, 2.0);
    EXPECT_LE(a.largest, 8.0);
}

TEST(DeferredExample, ReportsBadInputThroughItsExitCode) {
    const std::string dir = test::exampleScratch();
    const char* tool = SPATTER_EXAMPLE_DEFERRED;
    EXPECT_EQ(test::runTool(tool, {"--help"}), 0);
    EXPECT_EQ(test::runTool(tool, {}), 2);                                           // no scene
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--size", "10"}), 2);          // not WxH
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--view", "normal"}), 2);      // not one of its views
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--camera", "eye=0,0,1"}), 2); // no target
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--decals", "a", "--rays", "b"}), 2); // both
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--out"}), 2);                        // no value
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--frobnicate"}), 2);                 // unknown option
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--dbuffer=1"}), 2); // a switch takes no value
    EXPECT_EQ(test::runTool(tool, {"a.obj", "b.obj"}), 2);                 // two scenes
    EXPECT_EQ(test::runTool(tool, {dir + "/missing.obj", "--out", dir + "/x.png"}), 1); // no such scene
    std::ofstream(dir + "/deferred-bad.jsonl") << "{\"status\":\"placed\",\"object\":\"floor\"}\n";
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--decals", dir + "/deferred-bad.jsonl", "--out",
                                   dir + "/x.png"}),
              1);
}

TEST(DeferredExample, RefusesARepeatedOptionAFollowingOptionAsAValueAndPaddedSizes) {
    const char* tool = SPATTER_EXAMPLE_DEFERRED;
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--view", "final", "--view", "albedo"}), 2);
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--dbuffer", "--dbuffer"}), 2);
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--out", "--dbuffer"}), 2);
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--size", " 64x36"}), 2);
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--size", "0x40x36"}), 2);
    EXPECT_EQ(test::runTool(tool, {"builtin:gallery", "--size", "64x36.0"}), 2);
}
