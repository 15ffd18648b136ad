// spatter-example-deferred, a foreign host of the projector, run as a separate process: its coverage
// view against the CPU reference (rays through every pixel centre, the projector's inclusion rule in
// double precision), held to an IoU of 0.99 like every host of the projector; its albedo under the
// decals against spatter-render's on the same decals; and its command-line contract.

#include "CommandLine.hpp"
#include "RenderTestSupport.hpp"
#include "TestData.hpp"

#include "spatter/core/Random.hpp"
#include "spatter/core/SceneLoader.hpp"
#include "spatter/render/Camera.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sys/wait.h>

using namespace spatter;

namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 120;

// Runs `tool` with `args`; returns its exit code (-1 when it did not exit normally).
int run(const char* tool, const std::vector<std::string>& args) {
    std::string cmd = tool;
    for (const std::string& a : args)
        cmd += " '" + a + "'";
    const int status = std::system((cmd + " >/dev/null 2>&1").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Why the tools cannot render here (no headless GL context), or an empty string.
std::string noGl() {
    static const std::string why = [] {
        Result<GlContext> gl = GlContext::createHeadless();
        return gl.ok() ? std::string() : gl.error();
    }();
    return why;
}

#define SPATTER_REQUIRE_TOOL_GL()                                                                            \
    if (!noGl().empty()) {                                                                                   \
        if (test::runningInCi()) FAIL() << "CI=true but no headless GL context: " << noGl();                 \
        GTEST_SKIP() << "no headless OpenGL 4.5 context (" << noGl() << ")";                                 \
    }

std::string scratch() {
    static const std::string dir = test::scratchDir("example-deferred");
    return dir;
}

Camera lookingAt(const glm::dvec3& eye, const glm::dvec3& target) {
    Camera c;
    c.eye = eye;
    c.target = target;
    return c;
}

// A camera looking at the centre of the scene's bounds from `direction`.
Camera cameraFor(const Scene& scene, const glm::dvec3& direction) {
    const DBounds b = scene.worldBounds();
    return lookingAt(b.center() + glm::normalize(direction) * (b.diagonal() * 0.8), b.center());
}

// A ray file of `count` rays from the camera's eye through random pixels of the test image.
std::string writeRays(const std::string& name, const Camera& camera, int count, uint64_t seed) {
    const std::string path = scratch() + "/" + name + ".rays";
    std::ofstream f(path);
    f.precision(17);
    Rng rng(seed);
    for (int s = 0; s < count; ++s) {
        const int i = int(rng.below(kWidth)), j = int(rng.below(kHeight));
        const glm::dvec3 d = pixelDirection(camera, kWidth, kHeight, i, j);
        f << camera.eye.x << " " << camera.eye.y << " " << camera.eye.z << " " << d.x << " " << d.y << " "
          << d.z << "\n";
    }
    return path;
}

// spatter-place's records of `rays` on `scene`, decals of `size`.
std::string placeRecords(const std::string& scene, const std::string& rays, double size) {
    const std::string out = rays + ".jsonl";
    EXPECT_EQ(run(SPATTER_PLACE_TOOL, {scene, "--rays", rays, "--size", std::to_string(size), "--out", out}),
              0);
    return out;
}

// Runs the example with `args` and the camera, size, view and output given here; returns its image
// (empty when it failed, which fails the test).
Image runExample(std::vector<std::string> args, const Camera& camera, const std::string& view,
                 const std::string& name, const char* tool = SPATTER_EXAMPLE_DEFERRED) {
    const std::string out = scratch() + "/" + name + ".png";
    args.insert(args.end(),
                {"--camera", formatCamera(camera), "--size",
                 std::to_string(kWidth) + "x" + std::to_string(kHeight), "--view", view, "--out", out});
    EXPECT_EQ(run(tool, args), 0) << name;
    Result<Image> image = loadImage(out);
    EXPECT_TRUE(image.ok()) << image.error();
    return image ? image.value() : Image{};
}

// What the example loads for `args` (its own command line and loader), for the reference.
example::Inputs inputsOf(std::vector<std::string> args, const Camera& camera) {
    args.insert(args.begin(), "spatter-example-deferred");
    args.insert(args.end(), {"--camera", formatCamera(camera)});
    std::vector<char*> argv;
    for (std::string& a : args)
        argv.push_back(a.data());
    Result<example::Options> options = example::parseCommandLine(int(argv.size()), argv.data());
    EXPECT_TRUE(options.ok()) << options.error();
    Result<example::Inputs> in = options ? example::loadInputs(options.value()) : fail(options.error());
    EXPECT_TRUE(in.ok()) << in.error();
    return in ? std::move(in.value()) : example::Inputs{};
}

// The example's coverage view against the reference computed from the decals it loads.
void expectCoverageMatches(const std::string& name, const std::vector<std::string>& args,
                           const Camera& camera) {
    const example::Inputs in = inputsOf(args, camera);
    const test::CoverageInputs ref{in.decals.decals, in.decals.types, in.decals.objectIds};
    const std::vector<uint8_t> cpu = test::referenceCoverage(in.scene, ref, in.camera, kWidth, kHeight);
    const std::vector<uint8_t> gpu = test::whiteMask(runExample(args, camera, "coverage", name));
    ASSERT_EQ(gpu.size(), cpu.size()) << name;
    test::dumpMask(name + "-cpu", cpu, kWidth, kHeight);
    // Enough covered pixels for the ratio to mean something.
    EXPECT_GT(test::countSet(cpu), size_t(kWidth * kHeight) / 20) << name;
    const double v = test::iou(gpu, cpu);
    std::printf("%s: IoU %.4f (example %zu px, cpu %zu px, %zu decals)\n", name.c_str(), v,
                test::countSet(gpu), test::countSet(cpu), in.decals.decals.size());
    EXPECT_GE(v, 0.99) << name;
}

double srgbToLinear(uint8_t v) {
    const double c = v / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

} // namespace

TEST(DeferredExample, CoverageMatchesTheCpuReferenceOnTheGallery) {
    SPATTER_REQUIRE_TOOL_GL();
    const Camera camera = lookingAt({1.5, 2.2, 4.5}, {-0.5, 1.0, -3.0});
    const std::string rays = writeRays("gallery", camera, 120, 7);
    expectCoverageMatches("gallery", {"builtin:gallery", "--rays", rays}, camera);
}

TEST(DeferredExample, CoverageMatchesTheCpuReferenceOnSharedScenes) {
    SPATTER_REQUIRE_TOOL_GL();
    for (const char* file :
         {"meshes/stanford-bunny.obj", "meshes/fandisk.obj", "gltf/DamagedHelmet/DamagedHelmet.glb"}) {
        SPATTER_REQUIRE_SHARED(path, file);
        Result<Scene> scene = loadScene(path);
        ASSERT_TRUE(scene.ok()) << scene.error();
        const Camera camera = cameraFor(scene.value(), {0.5, 0.4, 1.0});
        const std::string name = std::string(file).substr(std::string(file).rfind('/') + 1);
        const std::string rays = writeRays(name, camera, 60, 11);
        const std::string records = placeRecords(path, rays, scene->worldBounds().diagonal() * 0.12);
        expectCoverageMatches(name, {path, "--decals", records}, camera);
    }
}

// The eye 1 m in front of a decal whose box is 3 m deep, looking at it: the projector draws the
// boxes that hold the eye by their far faces, in the example's standard-Z frame too.
TEST(DeferredExample, CoverageMatchesTheCpuReferenceWithTheCameraInsideADecalBox) {
    SPATTER_REQUIRE_TOOL_GL();
    const Camera shooter = lookingAt({1.5, 2.2, 4.5}, {-0.5, 1.0, -3.0});
    const std::string placed = placeRecords("builtin:gallery", writeRays("inside", shooter, 30, 17), 2.5);
    const std::string deep = scratch() + "/inside-deep.jsonl";
    {
        std::ifstream in(placed);
        std::ofstream out(deep);
        for (std::string line; std::getline(in, line);) {
            nlohmann::json rec = nlohmann::json::parse(line);
            if (rec["status"] == "placed") rec["half_depth"] = 3.0;
            out << rec.dump() << "\n";
        }
    }
    const std::vector<std::string> args = {"builtin:gallery", "--decals", deep};
    const example::Inputs in = inputsOf(args, shooter);
    ASSERT_GT(in.decals.decals.size(), 15u);
    const Decal& d = in.decals.decals.front();
    const glm::dmat4& m = in.scene.objects[d.object].transform;
    const glm::dvec3 centre(m * glm::dvec4(glm::dvec3(d.center), 1.0));
    const glm::dvec3 normal =
        glm::normalize(glm::transpose(glm::inverse(glm::dmat3(m))) * glm::dvec3(d.frame.normal));
    const Camera inside = lookingAt(centre + normal, centre - glm::dvec3(0.3, 0.2, 0.1));
    const glm::dvec3 box(glm::inverse(m * glm::dmat4(d.boxToObject())) * glm::dvec4(inside.eye, 1.0));
    ASSERT_LE(std::max({std::fabs(box.x), std::fabs(box.y), std::fabs(box.z)}), 1.0)
        << "the eye is not in the box";
    expectCoverageMatches("inside", args, inside);
}

// The same decals in the example (linear RGBA8 albedo, standard Z, RGB10A2 normals) and in
// spatter-render (sRGB albedo, reversed Z, octahedral normals): where both show a decal, the albedo
// agrees in linear terms within 2/255 on average and 8/255 at most, the quantisation of the two
// 8-bit encodings.
TEST(DeferredExample, AlbedoUnderTheDecalsAgreesWithSpatterRender) {
    SPATTER_REQUIRE_TOOL_GL();
    const Camera camera = lookingAt({0.0, 1.8, 2.0}, {0.0, 1.4, -6.0});
    const std::vector<std::string> args = {"builtin:gallery", "--rays", writeRays("albedo", camera, 60, 5)};
    const Image example = runExample(args, camera, "albedo", "albedo-example");
    const Image spatter = runExample(args, camera, "albedo", "albedo-spatter", SPATTER_RENDER_TOOL);
    const std::vector<uint8_t> a = test::whiteMask(runExample(args, camera, "coverage", "cov-example"));
    const std::vector<uint8_t> b =
        test::whiteMask(runExample(args, camera, "coverage", "cov-spatter", SPATTER_RENDER_TOOL));
    ASSERT_EQ(example.rgba.size(), spatter.rgba.size());
    double sum = 0.0, worst = 0.0;
    size_t n = 0;
    for (size_t p = 0; p < a.size() && p < b.size(); ++p) {
        if (!a[p] || !b[p]) continue;
        for (size_t c = 0; c < 3; ++c) {
            const double d =
                std::fabs(srgbToLinear(example.rgba[p * 4 + c]) - srgbToLinear(spatter.rgba[p * 4 + c]));
            sum += d;
            worst = std::max(worst, d);
            ++n;
        }
    }
    ASSERT_GT(n / 3, size_t(kWidth * kHeight) / 20);
    std::printf("albedo under %zu decal pixels: mean difference %.2f/255, largest %.2f/255\n", n / 3,
                255.0 * sum / double(n), 255.0 * worst);
    EXPECT_LE(255.0 * sum / double(n), 2.0);
    EXPECT_LE(255.0 * worst, 8.0);
}

TEST(DeferredExample, ReportsBadInputThroughItsExitCode) {
    const std::string dir = scratch();
    const char* tool = SPATTER_EXAMPLE_DEFERRED;
    EXPECT_EQ(run(tool, {"--help"}), 0);
    EXPECT_EQ(run(tool, {}), 2);                                                  // no scene
    EXPECT_EQ(run(tool, {"builtin:gallery", "--size", "10"}), 2);                 // not WxH
    EXPECT_EQ(run(tool, {"builtin:gallery", "--view", "normal"}), 2);             // not one of its views
    EXPECT_EQ(run(tool, {"builtin:gallery", "--camera", "eye=0,0,1"}), 2);        // no target
    EXPECT_EQ(run(tool, {"builtin:gallery", "--decals", "a", "--rays", "b"}), 2); // both
    EXPECT_EQ(run(tool, {"builtin:gallery", "--out"}), 2);                        // no value
    EXPECT_EQ(run(tool, {"builtin:gallery", "--frobnicate"}), 2);                 // unknown option
    EXPECT_EQ(run(tool, {"a.obj", "b.obj"}), 2);                                  // two scenes
    EXPECT_EQ(run(tool, {dir + "/missing.obj", "--out", dir + "/x.png"}), 1);     // no such scene
    std::ofstream(dir + "/bad.jsonl") << "{\"status\":\"placed\",\"object\":\"floor\"}\n";
    EXPECT_EQ(run(tool, {"builtin:gallery", "--decals", dir + "/bad.jsonl", "--out", dir + "/x.png"}), 1);
}
