#include "ExampleTestSupport.hpp"

#include "CommandLine.hpp"

#include "GltfBuilder.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/core/SceneLoader.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sys/wait.h>

namespace spatter::test {

namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 120;

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

// The gallery's test view: the wall of targets, from the front.
Camera galleryCamera() {
    return lookingAt({1.5, 2.2, 4.5}, {-0.5, 1.0, -3.0});
}

// A ray file of `count` rays from the camera's eye through random pixels of the test image.
std::string writeRays(const std::string& name, const Camera& camera, int count, uint64_t seed) {
    const std::string path = exampleScratch() + "/" + name + ".rays";
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
    EXPECT_EQ(
        runTool(SPATTER_PLACE_TOOL, {scene, "--rays", rays, "--size", std::to_string(size), "--out", out}),
        0);
    return out;
}

// What the examples load for `args` (their own command line and loader), for the reference.
example::Inputs inputsOf(std::vector<std::string> args, const Camera& camera) {
    args.insert(args.begin(), "example");
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

// The host's coverage view against the reference computed from the decals it loads.
void expectCoverageMatches(const ExampleHost& host, const std::string& name,
                           const std::vector<std::string>& args, const Camera& camera) {
    const example::Inputs in = inputsOf(args, camera);
    const CoverageInputs ref{in.decals.decals, in.decals.types, in.decals.objectIds};
    const std::vector<uint8_t> cpu = referenceCoverage(in.scene, ref, in.camera, kWidth, kHeight);
    const std::vector<uint8_t> gpu = whiteMask(runExample(host, args, camera, "coverage", name));
    ASSERT_EQ(gpu.size(), cpu.size()) << name;
    dumpMask(host.name + "-" + name + "-cpu", cpu, kWidth, kHeight);
    // Enough covered pixels for the ratio to mean something.
    EXPECT_GT(countSet(cpu), size_t(kWidth * kHeight) / 20) << name;
    const double v = iou(gpu, cpu);
    std::printf("%s, %s: IoU %.4f (example %zu px, cpu %zu px, %zu decals)\n", host.name.c_str(),
                name.c_str(), v, countSet(gpu), countSet(cpu), in.decals.decals.size());
    EXPECT_GE(v, 0.99) << host.name << ", " << name;
}

// `records` (spatter-place's) with every placed box given `halfDepth`.
std::string deepened(const std::string& records, double halfDepth) {
    const std::string deep = records + ".deep.jsonl";
    std::ifstream in(records);
    std::ofstream out(deep);
    for (std::string line; std::getline(in, line);) {
        nlohmann::json rec = nlohmann::json::parse(line);
        if (rec["status"] == "placed") rec["half_depth"] = halfDepth;
        out << rec.dump() << "\n";
    }
    return deep;
}

// A wall of 6 x 4 m in the plane z = 0 and, 0.4 m in front of it, a plate of 1.2 m that takes no
// decals (its node's extras say "decals": false).
std::string wallAndPlate(const std::string& name) {
    const Mesh box = makeBox(glm::vec3(0.5f), 1);
    GltfBuilder g;
    g.addMesh(box.positions, box.indices);
    g.push("nodes", {{"name", "wall"}, {"mesh", 0}, {"scale", {6, 4, 0.2}}});
    g.push("nodes", {{"name", "plate"},
                     {"mesh", 0},
                     {"scale", {1.2, 1.2, 0.05}},
                     {"translation", {0, 0, 0.4}},
                     {"extras", {{"decals", false}}}});
    g.doc["scenes"] = {{{"nodes", {0, 1}}}};
    g.doc["scene"] = 0;
    return g.writeGltf(exampleScratch(), name);
}

double srgbToLinear(uint8_t v) {
    const double c = v / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// The albedo of `a` against `b` where `mask` is set, in linear terms and units of 1/255.
AlbedoAgreement agreement(const Image& a, const Image& b, const std::vector<uint8_t>& mask) {
    AlbedoAgreement r;
    if (a.rgba.size() != b.rgba.size() || a.rgba.size() != mask.size() * 4) return r;
    double sum = 0.0;
    std::vector<double> worst; // per pixel, its largest channel difference
    for (size_t p = 0; p < mask.size(); ++p) {
        if (!mask[p]) continue;
        worst.push_back(0.0);
        for (size_t c = p * 4; c < p * 4 + 3; ++c) {
            const double d = 255.0 * std::fabs(srgbToLinear(a.rgba[c]) - srgbToLinear(b.rgba[c]));
            sum += d;
            worst.back() = std::max(worst.back(), d);
        }
    }
    r.pixels = worst.size();
    if (worst.empty()) return r;
    std::sort(worst.begin(), worst.end());
    r.mean = sum / double(3 * r.pixels);
    r.percentile99 = worst[worst.size() * 99 / 100];
    r.largest = worst.back();
    return r;
}

} // namespace

int runTool(const char* tool, const std::vector<std::string>& args) {
    std::string cmd = tool;
    for (const std::string& a : args)
        cmd += " '" + a + "'";
    const int status = std::system((cmd + " >/dev/null 2>&1").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string exampleScratch() {
    static const std::string dir = scratchDir("examples");
    return dir;
}

Image runExample(const ExampleHost& host, const std::vector<std::string>& args, const Camera& camera,
                 const std::string& view, const std::string& name) {
    const std::string out = exampleScratch() + "/" + host.name + "-" + name + ".png";
    std::vector<std::string> all = args;
    all.insert(all.end(), host.switches.begin(), host.switches.end());
    all.insert(all.end(),
               {"--camera", formatCamera(camera), "--size",
                std::to_string(kWidth) + "x" + std::to_string(kHeight), "--view", view, "--out", out});
    EXPECT_EQ(runTool(host.tool, all), 0) << host.name << ", " << name;
    Result<Image> image = loadImage(out);
    EXPECT_TRUE(image.ok()) << image.error();
    return image ? image.value() : Image{};
}

void expectCoverageOnTheGallery(const ExampleHost& host) {
    const std::string rays = writeRays(host.name + "-gallery", galleryCamera(), 120, 7);
    expectCoverageMatches(host, "gallery", {"builtin:gallery", "--rays", rays}, galleryCamera());
}

void expectCoverageOnSharedScenes(const ExampleHost& host) {
    for (const char* file :
         {"meshes/stanford-bunny.obj", "meshes/fandisk.obj", "gltf/DamagedHelmet/DamagedHelmet.glb"}) {
        SPATTER_REQUIRE_SHARED(path, file);
        Result<Scene> scene = loadScene(path);
        ASSERT_TRUE(scene.ok()) << scene.error();
        const Camera camera = cameraFor(scene.value(), {0.5, 0.4, 1.0});
        const std::string name = std::string(file).substr(std::string(file).rfind('/') + 1);
        const std::string rays = writeRays(host.name + "-" + name, camera, 60, 11);
        const std::string records = placeRecords(path, rays, scene->worldBounds().diagonal() * 0.12);
        expectCoverageMatches(host, name, {path, "--decals", records}, camera);
    }
}

// The eye 1 m in front of a decal on its projection axis (the shot's), inside its box, looking at it:
// the projector draws the boxes that hold the eye by their far faces (the forward path tests the
// shaded point against every box).
void expectCoverageWithTheCameraInsideADecalBox(const ExampleHost& host) {
    const std::string rays = writeRays(host.name + "-inside", galleryCamera(), 30, 17);
    const std::vector<std::string> args = {"builtin:gallery", "--decals",
                                           deepened(placeRecords("builtin:gallery", rays, 2.5), 3.0)};
    const example::Inputs in = inputsOf(args, galleryCamera());
    ASSERT_GT(in.decals.decals.size(), 15u);
    const Decal& d = in.decals.decals.front();
    const glm::dmat4& m = in.scene.objects[d.object].transform;
    const glm::dvec3 centre(m * glm::dvec4(glm::dvec3(d.center), 1.0));
    const glm::dvec3 normal =
        glm::normalize(glm::transpose(glm::inverse(glm::dmat3(m))) * glm::dvec3(d.frame().normal));
    const glm::dvec3 axis = glm::normalize(glm::dmat3(m) * glm::dvec3(d.projectionAxis()));
    const Camera inside =
        lookingAt(centre + axis / glm::dot(axis, normal), centre - glm::dvec3(0.3, 0.2, 0.1));
    const glm::dvec3 box(glm::inverse(m * glm::dmat4(d.boxToObject())) * glm::dvec4(inside.eye, 1.0));
    ASSERT_LE(std::max({std::fabs(box.x), std::fabs(box.y), std::fabs(box.z)}), 1.0)
        << "the eye is not in the box";
    expectCoverageMatches(host, "inside", args, inside);
}

// Decals on the wall whose boxes (half-depth 1 m) reach through the plate in front of it.
void expectCoverageWithAnObjectThatTakesNoDecals(const ExampleHost& host) {
    const std::string scene = wallAndPlate(host.name + "-plate");
    const Camera camera = lookingAt({0.8, 0.5, 4.0}, {0.0, 0.0, 0.0});
    const std::string rays = writeRays(host.name + "-plate", camera, 60, 3);
    const std::string records = deepened(placeRecords(scene, rays, 0.8), 1.0);
    expectCoverageMatches(host, "plate", {scene, "--decals", records}, camera);
}

AlbedoAgreement albedoAgainstSpatterRender(const ExampleHost& host) {
    const Camera camera = lookingAt({0.0, 1.8, 2.0}, {0.0, 1.4, -6.0});
    const std::vector<std::string> args = {"builtin:gallery", "--rays",
                                           writeRays(host.name + "-albedo", camera, 60, 5)};
    const ExampleHost renderer{SPATTER_RENDER_TOOL, {}, host.name + "-spatter-render"};
    const Image a = runExample(host, args, camera, "albedo", "albedo");
    const Image b = runExample(renderer, args, camera, "albedo", "albedo");
    std::vector<uint8_t> both = whiteMask(runExample(host, args, camera, "coverage", "albedo-coverage"));
    const std::vector<uint8_t> coveredB =
        whiteMask(runExample(renderer, args, camera, "coverage", "albedo-coverage"));
    for (size_t p = 0; p < both.size() && p < coveredB.size(); ++p)
        both[p] = both[p] && coveredB[p];
    const AlbedoAgreement r = agreement(a, b, both);
    EXPECT_GT(r.pixels, size_t(kWidth * kHeight) / 20) << "too few pixels under decals in both to compare";
    std::printf("%s: albedo under %zu decal pixels against spatter-render: mean difference %.2f/255, 99th "
                "percentile %.2f/255, largest %.2f/255\n",
                host.name.c_str(), r.pixels, r.mean, r.percentile99, r.largest);
    return r;
}

} // namespace spatter::test
