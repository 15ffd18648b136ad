// The spatter-render command-line contract, run as a separate process.

#include "GltfBuilder.hpp"
#include "TestData.hpp"
#include "ToolRun.hpp"

#include "spatter/core/MeshBuilder.hpp"

#include "spatter/core/Image.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/GlContext.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <sys/wait.h>

using namespace spatter;
using namespace spatter::test;

namespace {

// A wall 8 x 4 in the plane z = 0 facing +Z, as an OBJ named wall (x in [-4, 4], y in [0, 4]).
std::string writeWall(const std::string& dir) {
    const std::string path = dir + "/wall.obj";
    std::ofstream f(path);
    f << "v -4 0 0\nv 4 0 0\nv 4 4 0\nv -4 4 0\nf 1 2 3\nf 1 3 4\n";
    return path;
}

// One spatter-place record: a decal of size s on `object` at (x, y, 0), facing +Z.
std::string record(double x, double y, double s, const std::string& object = "wall") {
    std::ostringstream r;
    r << R"({"ray":0,"status":"placed","reason":"","object":")" << object
      << R"(","object_id":0,"decal_id":5,"position":[)" << x << "," << y
      << R"(,0],"normal":[0,0,1],"tangent":[1,0,0],"bitangent":[0,1,0],"size":[)" << s << "," << s
      << R"(],"half_depth":0.2,"max_angle_deg":80,"proxy_error_bound":0})";
    return r.str();
}

std::string fileText(const std::string& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The exit code of spatter-render `args`, its stderr in `errors`.
int renderWithErrors(const std::string& args, const std::string& dir, std::string& errors) {
    const std::string command =
        std::string(SPATTER_RENDER_TOOL) + " " + args + " >/dev/null 2>'" + dir + "/err.txt'";
    const int status = std::system(command.c_str());
    errors = fileText(dir + "/err.txt");
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool white(const Image& im, int x, int y) {
    return im.rgba[(size_t(y) * size_t(im.width) + size_t(x)) * 4] > 127;
}

} // namespace

TEST(SpatterRender, PixelRowsStartAtTheTopAndShowTheRayThroughTheirCentre) {
    SPATTER_REQUIRE_TOOL_GL();
    const std::string dir = test::scratchDir("tool-pixels");
    const std::string wall = writeWall(dir);
    {
        std::ofstream f(dir + "/decals.jsonl");
        f << record(-2.0, 3.0, 0.6) << "\n"
          << R"({"ray":1,"status":"missed","reason":"no hit"})"
          << "\n";
    }
    const std::string camera = "eye=0.5,2,6;target=0,2,0;fov=50";
    const int w = 160, h = 90;
    ASSERT_EQ(runTool(wall + " --decals " + dir + "/decals.jsonl --camera '" + camera +
                      "' --size 160x90 --view coverage --out " + dir + "/cov.png --stats " + dir +
                      "/stats.json"),
              0);
    Result<Image> im = loadImage(dir + "/cov.png");
    ASSERT_TRUE(im.ok()) << im.error();
    ASSERT_EQ(im->width, w);
    ASSERT_EQ(im->height, h);
    // Where the ray through each pixel centre meets the plane z = 0 decides its colour.
    const Camera cam = parseCamera(camera).value();
    size_t checked = 0;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const glm::dvec3 d = pixelDirection(cam, w, h, i, j);
            const glm::dvec3 p = cam.eye + d * (-cam.eye.z / d.z);
            const double dx = std::fabs(p.x + 2.0), dy = std::fabs(p.y - 3.0);
            if (dx < 0.28 && dy < 0.28) {
                EXPECT_TRUE(white(im.value(), i, j)) << i << "," << j;
                ++checked;
            } else if (dx > 0.32 || dy > 0.32) {
                EXPECT_FALSE(white(im.value(), i, j)) << i << "," << j;
            }
        }
    EXPECT_GT(checked, 50u);

    std::ifstream s(dir + "/stats.json");
    const nlohmann::json stats = nlohmann::json::parse(s, nullptr, false);
    ASSERT_TRUE(stats.is_object());
    EXPECT_EQ(stats["decals_drawn"], 1);
    EXPECT_EQ(stats["input_records"], 2);
    EXPECT_EQ(stats["input_placed"], 1);
    EXPECT_EQ(stats["view"], "coverage");
    EXPECT_TRUE(stats["gpu_ms"]["decals"].is_number());
    EXPECT_TRUE(stats["gl_renderer"].is_string());
}

TEST(SpatterRender, PlacesRaysAndHonoursTranslate) {
    SPATTER_REQUIRE_TOOL_GL();
    const std::string dir = test::scratchDir("tool-rays");
    const std::string wall = writeWall(dir);
    {
        std::ofstream f(dir + "/rays.txt");
        f << "# two shots at the wall\n0 2 5 0 0 -1\n1 1 5 0 0 -1\nnot a ray\n";
    }
    ASSERT_EQ(runTool(wall + " --rays " + dir +
                      "/rays.txt --decal-size 1 --camera 'eye=0,2,6;target=0,2,0' --size 96x64" +
                      " --view coverage --out " + dir + "/a.png --stats " + dir + "/a.json"),
              0);
    // The same, with scene, rays and camera 1000 units along x.
    {
        std::ofstream f(dir + "/rays-moved.txt");
        f << "1000 2 5 0 0 -1\n1001 1 5 0 0 -1\n";
    }
    ASSERT_EQ(runTool(wall + " --translate 1000,0,0 --rays " + dir + "/rays-moved.txt --decal-size 1" +
                      " --camera 'eye=1000,2,6;target=1000,2,0' --size 96x64 --view coverage --out " + dir +
                      "/b.png"),
              0);
    Result<Image> a = loadImage(dir + "/a.png");
    Result<Image> b = loadImage(dir + "/b.png");
    ASSERT_TRUE(a.ok() && b.ok());
    size_t covered = 0, same = 0;
    for (size_t i = 0; i < a->rgba.size(); i += 4) {
        covered += a->rgba[i] > 127 ? 1 : 0;
        same += (a->rgba[i] > 127) == (b->rgba[i] > 127) ? 1 : 0;
    }
    EXPECT_GT(covered, 120u);
    EXPECT_GE(double(same) / double(a->rgba.size() / 4), 0.995);
    std::ifstream s(dir + "/a.json");
    const nlohmann::json stats = nlohmann::json::parse(s, nullptr, false);
    ASSERT_TRUE(stats.is_object());
    EXPECT_EQ(stats["input_records"], 3);
    EXPECT_EQ(stats["input_placed"], 2);
    EXPECT_EQ(stats["decals_drawn"], 2);
}

TEST(SpatterRender, DrawsAndTracesAroundANodeSingularInFloat) {
    SPATTER_REQUIRE_TOOL_GL();
    const std::string dir = test::scratchDir("tool-untraced");
    const Mesh box = makeBox(glm::vec3(0.5f), 1);
    test::GltfBuilder g = test::floorAndCrate(box.positions, box.indices, test::kColumnsEqualInFloat, true);
    const std::string scene = g.writeGltf(dir, "crate");
    std::ofstream(dir + "/rays.txt") << "0 10 0 0 -1 0\n";
    ASSERT_EQ(runTool(scene + " --rays " + dir + "/rays.txt --camera 'eye=0,6,6;target=0,0,0' --size 64x48" +
                      " --out " + dir + "/a.png --stats " + dir + "/a.json"),
              0);
    std::ifstream s(dir + "/a.json");
    const nlohmann::json stats = nlohmann::json::parse(s, nullptr, false);
    ASSERT_TRUE(stats.is_object());
    EXPECT_EQ(stats["input_placed"], 1);
    EXPECT_EQ(stats["decals_drawn"], 1);
}

TEST(SpatterRender, ReportsBadInputThroughItsExitCode) {
    const std::string dir = test::scratchDir("tool-bad");
    const std::string wall = writeWall(dir);
    EXPECT_EQ(runTool("--help"), 0);
    EXPECT_EQ(runTool(""), 2);                                           // no scene
    EXPECT_EQ(runTool(wall + " --size 10"), 2);                          // not WxH
    EXPECT_EQ(runTool(wall + " --view shiny"), 2);                       // unknown view
    EXPECT_EQ(runTool(wall + " --camera 'eye=0,0,1'"), 2);               // no target
    EXPECT_EQ(runTool(wall + " --decals a --rays b"), 2);                // both
    EXPECT_EQ(runTool(wall + " --frobnicate"), 2);                       // unknown option
    EXPECT_EQ(runTool(wall + " --max-angle 95"), 2);                     // past (0, 90]
    EXPECT_EQ(runTool(wall + " --decal-size 1,0"), 2);                   // no height
    EXPECT_EQ(runTool(wall + " --texture-space wall:100"), 2);           // not a power of two
    EXPECT_EQ(runTool(dir + "/missing.obj --out " + dir + "/x.png"), 1); // no such scene
    {
        std::ofstream f(dir + "/bad.jsonl");
        f << record(0, 1, 0.5) << "\n{\"status\":\"placed\",\"object\":\"wall\"}\n";
    }
    EXPECT_EQ(runTool(wall + " --decals " + dir + "/bad.jsonl --out " + dir + "/x.png"),
              1); // incomplete record
    {
        std::ofstream f(dir + "/other.jsonl");
        f << record(0, 1, 0.5, "nothing") << "\n";
    }
    EXPECT_EQ(runTool(wall + " --decals " + dir + "/other.jsonl --out " + dir + "/x.png"),
              1); // unknown object
}

TEST(SpatterRender, TextureSpaceModeReportsOverlappingUvsAndSplatsOnUsableMeshes) {
    SPATTER_REQUIRE_TOOL_GL();
    const std::string dir = test::scratchDir("render-tool-texture-space");
    // The wall's UVs are missing: it cannot take texture-space decals.
    EXPECT_EQ(runTool(writeWall(dir) + " --texture-space wall --out " + dir + "/a.png"), 1);
    EXPECT_EQ(runTool(writeWall(dir) + " --texture-space nothing --out " + dir + "/a.png"), 1);
    EXPECT_EQ(runTool(writeWall(dir) + " --texture-space wall:0.5 --out " + dir + "/a.png"), 2);
    // A quad with UVs that fold back over themselves (two triangles on the same texels).
    const std::string folded = dir + "/folded.obj";
    std::ofstream(folded) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                             "f 1/1 2/2 3/3\nf 1/1 3/3 4/2\n";
    EXPECT_EQ(runTool(folded + " --texture-space folded --out " + dir + "/b.png"), 1);
    // The gallery's first banner has a usable layout: a shot at it is splatted into its texture.
    std::ofstream(dir + "/rays.txt") << "0 1.7 4 -6 1.0 -6.6\n";
    ASSERT_EQ(runTool("builtin:gallery --texture-space banner_0:256 --size 96x54 --rays " + dir +
                      "/rays.txt --out " + dir + "/c.png --stats " + dir + "/c.json"),
              0);
    std::ifstream in(dir + "/c.json");
    const nlohmann::json stats = nlohmann::json::parse(in, nullptr, false);
    ASSERT_TRUE(stats.is_object());
    EXPECT_EQ(stats["texture_space_objects"], 1);
    EXPECT_EQ(stats["decals_splatted"], 1);
}

TEST(SpatterRender, VolumetricOptionDrawsCratersInsteadOfFlatDecals) {
    SPATTER_REQUIRE_TOOL_GL();
    const std::string dir = test::scratchDir("render-tool-volumetric");
    std::ofstream(dir + "/rays.txt") << "0 2 5 0 0 -1\n";
    const std::string common = writeWall(dir) + " --rays " + dir + "/rays.txt --decal-size 1 --size 64x48" +
                               " --camera 'eye=0,2,5;target=0,2,0'";
    ASSERT_EQ(runTool(common + " --volumetric --out " + dir + "/v.png --stats " + dir + "/v.json"), 0);
    ASSERT_EQ(runTool(common + " --out " + dir + "/f.png --stats " + dir + "/f.json"), 0);
    std::ifstream vin(dir + "/v.json"), fin(dir + "/f.json");
    const nlohmann::json v = nlohmann::json::parse(vin, nullptr, false),
                         f = nlohmann::json::parse(fin, nullptr, false);
    ASSERT_TRUE(v.is_object() && f.is_object());
    EXPECT_EQ(v["decals_volumetric"], 1);
    EXPECT_EQ(f["decals_volumetric"], 0);
}

TEST(RenderTool, RefusesAnOutputThatIsAnInputOrTheOtherOutput) {
    const std::string dir = test::scratchDir("tool-same-file");
    const std::string wall = writeWall(dir), mesh = fileText(wall);
    std::string errors;
    EXPECT_EQ(renderWithErrors(wall + " --out " + dir + "/./wall.obj", dir, errors), 2);
    EXPECT_NE(errors.find("SCENE and --out name the same file"), std::string::npos) << errors;
    EXPECT_EQ(renderWithErrors(wall + " --out " + dir + "/x.png --stats " + wall, dir, errors), 2);
    EXPECT_EQ(fileText(wall), mesh);
    std::ofstream(dir + "/rays.txt") << "0 1 5 0 0 -1\n";
    EXPECT_EQ(renderWithErrors(wall + " --rays " + dir + "/rays.txt --out " + dir + "/rays.txt", dir, errors),
              2);
    EXPECT_NE(errors.find("--rays and --out name the same file"), std::string::npos) << errors;
    EXPECT_EQ(renderWithErrors(wall + " --out " + dir + "/x.png --stats " + dir + "/x.png", dir, errors), 2);
    EXPECT_NE(errors.find("--out and --stats name the same file"), std::string::npos) << errors;
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.png"));
}

TEST(RenderTool, ChecksItsOutputsFirstAndLeavesNoImageWhenTheStatsFail) {
    const std::string dir = test::scratchDir("tool-outputs");
    const std::string wall = writeWall(dir) + " --size 32x16 --out " + dir + "/x.png";
    std::string errors;
    EXPECT_EQ(renderWithErrors(wall + " --stats " + dir + "/no/such/folder/s.json", dir, errors), 2);
    EXPECT_NE(errors.find("does not exist"), std::string::npos) << errors;
    EXPECT_EQ(renderWithErrors(wall + " --stats " + dir, dir, errors), 2);
    EXPECT_NE(errors.find("is a directory"), std::string::npos) << errors;
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.png"));
    SPATTER_REQUIRE_TOOL_GL();
    if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full to fail a write";
    EXPECT_EQ(renderWithErrors(wall + " --stats /dev/full", dir, errors), 1); // fails as it is written
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.png")) << errors;
}

TEST(RenderTool, RefusesADirectoryGivenAsDecalsOrRays) {
    const std::string dir = test::scratchDir("tool-directories");
    const std::string wall = writeWall(dir);
    std::string errors;
    for (const char* option : {" --decals ", " --rays "}) {
        EXPECT_EQ(renderWithErrors(wall + option + dir + " --out " + dir + "/x.png", dir, errors), 1)
            << option;
        EXPECT_NE(errors.find(dir + " is a directory"), std::string::npos) << errors;
    }
}

TEST(RenderTool, RefusesARepeatedOptionASeedOutOfRangeAndPaddedNumbers) {
    const std::string dir = test::scratchDir("tool-usage");
    const std::string wall = writeWall(dir) + " --out " + dir + "/x.png ";
    std::string errors;
    EXPECT_EQ(renderWithErrors(wall + "--view final --view ids", dir, errors), 2);
    EXPECT_NE(errors.find("--view given twice"), std::string::npos) << errors;
    for (const char* bad :
         {"--seed 99999999999999999999", "--seed ' -1'", "--seed +1", "--size ' 64x36'", "--size 64x36.0",
          "--size 0x10x10", "--time 0x10", "--max-angle ' 45'", "--decal-size 1e999", "--out --volumetric"})
        EXPECT_EQ(renderWithErrors(wall + bad, dir, errors), 2) << bad;
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.png"));
}
