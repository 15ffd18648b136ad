// spatter-render --time and the gallery's --time: the scene posed at a time of its first animation,
// run as separate processes.

#include "TestData.hpp"
#include "ToolRun.hpp"

#include "spatter/core/Image.hpp"
#include "spatter/render/GlContext.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <string>
#include <sys/wait.h>

using namespace spatter;
using namespace spatter::test;

namespace {

// Pixels whose colours differ by more than 8 in some channel.
size_t differingPixels(const Image& a, const Image& b) {
    size_t n = 0;
    for (size_t i = 0; i + 3 < a.rgba.size() && i + 3 < b.rgba.size(); i += 4)
        for (size_t c = 0; c < 3; ++c)
            if (std::abs(int(a.rgba[i + c]) - int(b.rgba[i + c])) > 8) {
                ++n;
                break;
            }
    return n;
}

} // namespace

TEST(SpatterRenderTime, PosesTheSceneAtTheGivenTime) {
    SPATTER_REQUIRE_SHARED(path, "gltf/CesiumMan/CesiumMan.glb");
    SPATTER_REQUIRE_TOOL_GL();
    const std::string dir = test::scratchDir("render_time");
    const std::string common = path + " --size 128x96 --camera \"eye=0.4,1.2,3;target=0,0.8,0\" ";
    ASSERT_EQ(runTool(common + "--out " + dir + "/rest.png"), 0);
    ASSERT_EQ(runTool(common + "--time 0.5 --out " + dir + "/a.png --stats " + dir + "/a.json"), 0);
    ASSERT_EQ(runTool(common + "--time 0.5 --out " + dir + "/b.png"), 0);
    ASSERT_EQ(runTool(common + "--time 1.2 --out " + dir + "/c.png"), 0);
    Result<Image> rest = loadImage(dir + "/rest.png"), a = loadImage(dir + "/a.png"),
                  b = loadImage(dir + "/b.png"), c = loadImage(dir + "/c.png");
    ASSERT_TRUE(rest.ok() && a.ok() && b.ok() && c.ok());
    EXPECT_EQ(differingPixels(a.value(), b.value()), 0u); // a pose is a function of the time
    EXPECT_GT(differingPixels(a.value(), rest.value()), 200u);
    EXPECT_GT(differingPixels(a.value(), c.value()), 100u);
    std::ifstream stats(dir + "/a.json");
    const nlohmann::json j = nlohmann::json::parse(stats);
    EXPECT_DOUBLE_EQ(j.at("time").get<double>(), 0.5);
}

// --translate moves the pose with the scene: the same view of the moved world gives the same image.
TEST(SpatterRenderTime, PoseMovesWithTranslate) {
    SPATTER_REQUIRE_SHARED(path, "gltf/CesiumMan/CesiumMan.glb");
    SPATTER_REQUIRE_TOOL_GL();
    const std::string dir = test::scratchDir("render_time_translate");
    ASSERT_EQ(runTool(path + " --size 128x96 --time 0.7 --camera \"eye=0.4,1.2,3;target=0,0.8,0\" --out " +
                      dir + "/a.png"),
              0);
    ASSERT_EQ(runTool(path + " --size 128x96 --time 0.7 --translate 5000,0,-3000 " +
                      "--camera \"eye=5000.4,1.2,-2997;target=5000,0.8,-3000\" --out " + dir + "/b.png"),
              0);
    Result<Image> a = loadImage(dir + "/a.png"), b = loadImage(dir + "/b.png");
    ASSERT_TRUE(a.ok() && b.ok());
    EXPECT_LE(differingPixels(a.value(), b.value()), 10u);
}

TEST(SpatterRenderTime, RefusesATimeThatIsNotANumber) {
    EXPECT_EQ(runTool("builtin:gallery --time"), 2);
    EXPECT_EQ(runTool("builtin:gallery --time nan"), 2);
    EXPECT_EQ(runTool("builtin:gallery --time 1s"), 2);
}

#ifdef SPATTER_GALLERY_EXE
// The headless gallery session on an animated scene: the animation plays from --time, so the same
// time gives the same image and another time another pose.
TEST(GalleryTime, PlaysTheSceneAnimationFromTheGivenTime) {
    SPATTER_REQUIRE_SHARED(path, "gltf/CesiumMan/CesiumMan.glb");
    SPATTER_REQUIRE_TOOL_GL();
    const std::string dir = test::scratchDir("gallery_time");
    const std::string common =
        "--headless --scene " + path + " --shots 8 --size 160x90 --cache " + dir + "/cache --time ";
    ASSERT_EQ(runExe(SPATTER_GALLERY_EXE, common + "0.5 --out " + dir + "/a"), 0);
    ASSERT_EQ(runExe(SPATTER_GALLERY_EXE, common + "0.5 --out " + dir + "/b"), 0);
    ASSERT_EQ(runExe(SPATTER_GALLERY_EXE, common + "1.3 --out " + dir + "/c"), 0);
    Result<Image> a = loadImage(dir + "/a/gallery.png"), b = loadImage(dir + "/b/gallery.png"),
                  c = loadImage(dir + "/c/gallery.png");
    ASSERT_TRUE(a.ok() && b.ok() && c.ok());
    EXPECT_EQ(differingPixels(a.value(), b.value()), 0u);
    EXPECT_GT(differingPixels(a.value(), c.value()), 50u);
    EXPECT_EQ(runExe(SPATTER_GALLERY_EXE, "--headless --time later"), 2);
}
#endif
