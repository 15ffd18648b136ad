// spatter-render SCENE: renders a scene with its decals headlessly (EGL) and writes a PNG of one
// view, and optionally the frame stats.

#include "spatter/core/DecalType.hpp"
#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SceneLoader.hpp"
#include "spatter/core/TextFields.hpp"
#include "spatter/placement/DecalLooks.hpp"
#include "spatter/placement/DecalRecords.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/GlContext.hpp"
#include "spatter/render/Renderer.hpp"
#include "spatter/render/View.hpp"

#include "cli/Arguments.hpp"
#include "cli/DistinctFiles.hpp"
#include "cli/Numbers.hpp"
#include "cli/OutputCleanup.hpp"
#include "cli/PathChecks.hpp"

#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace {

const char* kUsage = R"(usage: spatter-render SCENE [--decals FILE.jsonl | --rays FILE]
                      [--camera "eye=x,y,z;target=x,y,z;up=x,y,z;fov=DEG"] [--size WxH]
                      [--view final|albedo|normal|depth|ids|coverage] [--out FILE.png]
                      [--stats FILE.json] [--translate X,Y,Z] [--texture NAME]
                      [--texture-space OBJECT[:SIZE]]... [--volumetric]
                      [--decal-size W[,H]] [--max-angle DEG] [--seed N] [--time T]

Renders SCENE (builtin:gallery or a .gltf, .glb, .obj, .ply, .off or .stl file) with the deferred
renderer and its decal projector, headless (EGL: a GPU where there is one, else Mesa's llvmpipe),
and writes one view as a PNG.

Decals:
  --decals FILE   spatter-place output (JSON Lines): every "placed" record becomes a decal on the
                  object it names ("object"), with its world-space centre ("position"), frame
                  ("normal", "tangent", "bitangent"), "size", "half_depth", "max_angle_deg",
                  "object_id" (the object's 8-bit decal ID), "decal_id" and "projection" (the axis
                  its texture is projected along; the normal where it is absent). Other records
                  are ignored.
  --rays FILE     one ray per line, "ox oy oz dx dy dz" ('#' starts a comment), placed here through
                  the decal system on the render meshes (an object's authored collider where it
                  has one), with --decal-size W[,H] in world units (default 2% of the scene's
                  bounding diagonal, so that decals fit a model of centimetres and one of a
                  hundred metres alike), --max-angle in (0, 90] (default 80) and --seed (the seed
                  of the decal IDs, rotations and objects' decal IDs; default 1).
  --texture NAME  look of the decals: bullet_hole (default), blood, paint, scorch, or mixed (the
                  four in turn, decal by decal).

View:
  --camera "eye=x,y,z;target=x,y,z;up=x,y,z;fov=DEG"
                  perspective camera; up defaults to 0,1,0 and fov (vertical, degrees) to 60.
                  Default: looking at the centre of the scene's bounds from the front, above.
                  Pixel (i, j) of the image, j counted from the top row, shows the ray from the
                  eye through the centre of that pixel.
  --size WxH      image size (default 960x540)
  --view V        final (lit, default), albedo, normal, depth, ids, or coverage: white where at
                  least one decal writes the pixel (inside its box, object ID matching, within its
                  max angle; a texture-space decal where its texture shows), black elsewhere
  --volumetric    the decals are volumetric bullet holes: a crater drawn behind a hole cut into
                  the surface (stencil), instead of a flat texture
  --texture-space OBJECT[:SIZE]
                  draw the decals of the named object in texture space (rendered once into its own
                  SIZE x SIZE decal texture through its UVs, SIZE a power of two in [16, 4096],
                  default 512, in the pose drawn)
                  instead of projecting them; repeatable. The object's UVs must not overlap and
                  must lie in [0, 1]: a mesh that breaks this is reported (first overlapping
                  triangles) and the tool exits with 1.
  --translate X,Y,Z  move the scene by this offset first; decals, rays and camera are given in the
                  moved world
  --time T        pose the scene at T seconds of its first animation (glTF animations: animated
                  nodes move their objects, skins and morph targets deform the meshes on the GPU)
                  before rendering; before the first key a channel holds its first value, after
                  the last its last. A scene without animations is drawn in its rest pose (skins
                  and morph weights as the file sets them) with a warning. Decals, rays and camera
                  are given in the posed world; rays meet the scene as it is drawn (skinned and
                  morphed objects deformed, and their decals placed on the drawn skin). A --decals
                  record that spatter-place --time placed on a skinned or morphed object at another
                  time ("time" and "anchor") is moved to this pose with the render triangle it lies
                  on; other decals on such objects follow the object's transform only, not the
                  deformation.
Output:
  --out FILE.png  the image (default render.png)
  --stats FILE    frame stats as JSON: decals drawn, culled, invalid, per-pass GPU milliseconds,
                  the GL renderer, and what was loaded
  --help          this text

With --rays, an object whose transform single-precision ray tracing cannot use (singular or nearly
so in float, scaled beyond 2^+-25, more than 2^32 from the world's centre, or smaller than a few
float steps at its place) is left out of the
trace (rays pass through it; it is still drawn) with a warning on stderr that names it and says why.

Numbers are decimal ("2", "-0.5", "1e-3"; no hexadecimal, no blanks), sizes and --seed (0 to
18446744073709551615) whole numbers. Each option but --texture-space is given at most once, with its
value (a following "--..." is not one). Before the work the files named are checked: --out and
--stats must be files that can be written, neither an input nor each other; --decals or --rays a
file that can be read. A run that fails leaves no --out or --stats file of its own: one it began is
removed.

Exit code 0 on success, 1 when the scene, the decals or the GL context fail, 2 on bad options (the
output checks above included).
)";

int usageError(const std::string& message) {
    std::cerr << "spatter-render: " << message << "\n(see spatter-render --help)\n";
    return 2;
}

int failure(const std::string& message) {
    std::cerr << "spatter-render: " << message << "\n";
    return 1;
}

bool parseVec3(const std::string& s, glm::dvec3& out) {
    const std::vector<std::string> p = spatter::splitFields(s, ',');
    return p.size() == 3 && spatter::parseDecimal(p[0], out.x) && spatter::parseDecimal(p[1], out.y) &&
           spatter::parseDecimal(p[2], out.z);
}

// The scene posed at time `t` of its first animation (the rest pose without one), moved by `offset`.
struct PosedScene {
    spatter::ScenePose pose;
    spatter::DBounds bounds; // of every posed vertex, world space
};

PosedScene poseAt(const spatter::Scene& scene, double t, const glm::dvec3& offset) {
    spatter::SceneEvaluator evaluator(scene);
    evaluator.evaluate(scene.animation.animations.empty() ? -1 : 0, t);
    const glm::dmat4 move = glm::translate(glm::dmat4(1.0), offset);
    PosedScene out;
    for (size_t o = 0; o < scene.objects.size(); ++o) {
        const glm::dmat4 transform = move * evaluator.objectTransform(o);
        out.pose.objectTransforms.push_back(transform);
        out.pose.morphWeights.push_back(evaluator.morphWeights(o));
        for (const glm::dvec3& p : spatter::posedPositions(scene, o, evaluator))
            out.bounds.extend(glm::dvec3(transform * glm::dvec4(p, 1.0)));
    }
    for (size_t s = 0; s < scene.animation.skins.size(); ++s) {
        out.pose.jointMatrices.push_back(evaluator.jointMatrices(s));
        for (glm::dmat4& j : out.pose.jointMatrices.back())
            j = move * j;
    }
    return out;
}

spatter::Camera defaultCamera(const spatter::DBounds& b) {
    spatter::Camera cam;
    if (b.empty()) return cam;
    const double diag = std::max(b.diagonal(), 1e-6);
    cam.target = b.center();
    cam.eye = b.center() + glm::normalize(glm::dvec3(0.15, 0.35, 1.0)) * (0.75 * diag);
    cam.nearPlane = std::max(diag * 1e-4, 1e-4);
    return cam;
}

// The command line.
struct Options {
    std::string scenePath, decalsPath, raysPath, cameraText, outPath = "render.png", statsPath,
                                                             textureName = "bullet_hole";
    int width = 960, height = 540;
    spatter::View view = spatter::View::Final;
    glm::dvec3 translate{0.0};
    std::optional<glm::dvec2> decalSize; // default: decalSizeForScene
    double maxAngle = 80.0;
    uint64_t seed = 1;
    std::vector<std::pair<std::string, int>> textureSpace; // object name, texture size
    bool volumetric = false;
    std::optional<double> time;
};

// "WxH", whole numbers in 1..16384.
bool parseSize(const std::string& v, Options& o) {
    const size_t x = v.find('x');
    uint64_t w = 0, h = 0;
    if (x == std::string::npos || !spatter::cli::parseWhole(v.substr(0, x), 16384, w) ||
        !spatter::cli::parseWhole(v.substr(x + 1), 16384, h) || w < 1 || h < 1)
        return false;
    o.width = int(w);
    o.height = int(h);
    return true;
}

// "OBJECT[:SIZE]"; an error message, or "" when it is one.
std::string parseTextureSpace(const std::string& v, Options& o) {
    const size_t colon = v.rfind(':');
    uint64_t size = 512;
    if (v.empty()) return "--texture-space needs OBJECT[:SIZE]";
    if (colon != std::string::npos && !spatter::cli::parseWhole(v.substr(colon + 1), UINT64_MAX, size))
        return "--texture-space needs OBJECT[:SIZE] with a whole SIZE";
    if (size < 16 || size > 4096 || (size & (size - 1)) != 0)
        return "--texture-space needs a SIZE that is a power of two in [16, 4096]";
    o.textureSpace.push_back({v.substr(0, colon), int(size)});
    return "";
}

// "W[,H]", both above 0; an error message, or "" when it is one.
std::string parseDecalSize(const std::string& v, Options& o) {
    const std::vector<std::string> p = spatter::splitFields(v, ',');
    double w = 0.0, h = 0.0;
    if (p.size() > 2 || !spatter::parseDecimal(p[0], w) || (p.size() == 2 && !spatter::parseDecimal(p[1], h)))
        return "--decal-size needs W or W,H";
    o.decalSize = glm::dvec2(w, p.size() == 1 ? w : h);
    if (!(o.decalSize->x > 0.0 && o.decalSize->y > 0.0)) return "--decal-size needs W and H above 0";
    return "";
}

// Reads the value `v` of the option `a` into `o`; an error message, or "" when it is one.
std::string parseValue(const std::string& a, const std::string& v, Options& o) {
    if (a == "--decals" || a == "--rays" || a == "--out" || a == "--stats") {
        if (v.empty()) return a + " needs a file";
        (a == "--decals" ? o.decalsPath
         : a == "--rays" ? o.raysPath
         : a == "--out"  ? o.outPath
                         : o.statsPath) = v;
    } else if (a == "--camera") {
        o.cameraText = v;
    } else if (a == "--size") {
        if (!parseSize(v, o)) return "--size needs WxH, whole numbers in 1..16384";
    } else if (a == "--view") {
        spatter::Result<spatter::View> parsed = spatter::parseView(v);
        if (!parsed) return parsed.error();
        o.view = parsed.value();
    } else if (a == "--translate") {
        if (!parseVec3(v, o.translate)) return "--translate needs three finite numbers X,Y,Z";
    } else if (a == "--time") {
        double t = 0.0;
        if (!spatter::parseDecimal(v, t)) return "--time needs a finite number of seconds";
        o.time = t;
    } else if (a == "--texture-space") {
        return parseTextureSpace(v, o);
    } else if (a == "--texture") {
        o.textureName = v;
    } else if (a == "--decal-size") {
        return parseDecalSize(v, o);
    } else if (a == "--max-angle") {
        if (!spatter::parseDecimal(v, o.maxAngle) || !(o.maxAngle > 0.0 && o.maxAngle <= 90.0))
            return "--max-angle needs a number of degrees in (0, 90]";
    } else if (a == "--seed") {
        if (!spatter::cli::parseWhole(v, UINT64_MAX, o.seed))
            return "--seed needs a whole number in 0.." + std::to_string(UINT64_MAX);
    }
    return "";
}

// Reads argv into `o`. Returns -1 to go on, or the exit code: 0 after --help, 2 after a usage error.
int parseOptions(int argc, char** argv, Options& o) {
    static const std::set<std::string> kValued = {
        "--decals",    "--rays", "--camera",        "--size",    "--view",       "--out",       "--stats",
        "--translate", "--time", "--texture-space", "--texture", "--decal-size", "--max-angle", "--seed"};
    spatter::cli::Arguments args(argc, argv, 1, {"--texture-space"});
    while (args.more()) {
        const spatter::Result<std::string> a = args.next();
        if (!a) return usageError(a.error());
        if (*a == "--help" || *a == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        }
        if (*a == "--volumetric") {
            o.volumetric = true;
        } else if (kValued.count(*a)) {
            const std::optional<std::string> v = args.value();
            if (!v) return usageError(*a + " needs a value");
            if (const std::string error = parseValue(*a, *v, o); !error.empty()) return usageError(error);
        } else if (!a->empty() && (*a)[0] == '-') {
            return usageError("unknown option " + *a);
        } else if (o.scenePath.empty()) {
            o.scenePath = *a;
        } else {
            return usageError("more than one scene given");
        }
    }
    if (o.scenePath.empty()) return usageError("no scene given");
    if (!o.decalsPath.empty() && !o.raysPath.empty())
        return usageError("--decals and --rays exclude each other");
    return -1;
}

// The files the options name, before any work: the outputs can be written and are neither an input
// nor each other (exit code 2), the decals or rays can be read (1).
int checkFiles(const Options& o) {
    using spatter::cli::NamedPath;
    const NamedPath decals{"--decals", o.decalsPath}, rays{"--rays", o.raysPath}, out{"--out", o.outPath},
        stats{"--stats", o.statsPath};
    if (spatter::Status s = spatter::cli::distinctFiles({out, stats}, {{"SCENE", o.scenePath}, decals, rays});
        !s)
        return usageError(s.error());
    for (const NamedPath& output : {out, stats})
        if (!output.path.empty())
            if (spatter::Status s = spatter::cli::creatableFile(output); !s) return usageError(s.error());
    for (const NamedPath& input : {decals, rays})
        if (!input.path.empty())
            if (spatter::Status s = spatter::cli::readableFile(input); !s) return failure(s.error());
    return -1;
}

// The frame stats with what was drawn, as --stats writes them.
nlohmann::ordered_json statsJson(const spatter::FrameStats& stats, const Options& o,
                                 const spatter::Camera& camera, const spatter::GlContext& gl,
                                 const spatter::LoadedDecals& loaded) {
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(spatter::toJson(stats));
    j["scene"] = o.scenePath;
    j["camera"] = spatter::formatCamera(camera);
    j["gl_platform"] = gl.info().platform;
    j["input_records"] = loaded.records;
    j["input_placed"] = loaded.placed;
    if (o.time) j["time"] = *o.time;
    return j;
}

} // namespace

int main(int argc, char** argv) {
    Options options;
    if (const int exitCode = parseOptions(argc, argv, options); exitCode >= 0) return exitCode;
    if (const int exitCode = checkFiles(options); exitCode >= 0) return exitCode;
    const std::string &scenePath = options.scenePath, &decalsPath = options.decalsPath,
                      &raysPath = options.raysPath, &cameraText = options.cameraText,
                      &outPath = options.outPath, &statsPath = options.statsPath,
                      &textureName = options.textureName;
    const int width = options.width, height = options.height;
    const spatter::View view = options.view;
    const glm::dvec3 translate = options.translate;
    const std::optional<glm::dvec2> decalSize = options.decalSize;
    const double maxAngle = options.maxAngle;
    const uint64_t seed = options.seed;
    const std::vector<std::pair<std::string, int>>& textureSpace = options.textureSpace;
    const bool volumetric = options.volumetric;
    const std::optional<double> time = options.time;
    const spatter::Result<int> look = spatter::parseDecalLook(textureName);
    if (!look) return usageError("--texture needs bullet_hole, blood, paint, scorch or mixed");

    spatter::Result<spatter::Scene> scene = spatter::loadScene(scenePath);
    if (!scene) return failure(scene.error());
    for (const std::string& w : scene->warnings)
        std::cerr << "spatter-render: warning: " << w << "\n";
    std::optional<PosedScene> posed;
    if (time) {
        if (scene->animation.animations.empty())
            std::cerr
                << "spatter-render: warning: --time: the scene has no animation; drawn in its rest pose\n";
        posed = poseAt(scene.value(), *time, translate);
    }
    scene->translate(translate);
    if (posed)
        for (size_t o = 0; o < scene->objects.size(); ++o)
            scene->objects[o].transform = posed->pose.objectTransforms[o];

    spatter::Camera camera = defaultCamera(posed ? posed->bounds : scene->worldBounds());
    if (!cameraText.empty()) {
        spatter::Result<spatter::Camera> parsed = spatter::parseCamera(cameraText);
        if (!parsed) return usageError(parsed.error());
        parsed->nearPlane = camera.nearPlane;
        camera = parsed.value();
    }

    spatter::DecalType type;
    type.name = "spatter-render";
    type.size = decalSize ? glm::vec2(*decalSize)
                          : spatter::decalSizeForScene(glm::length(scene->worldBounds().extent()));
    type.maxAngleDeg = float(maxAngle);
    type.volumetric = volumetric;

    spatter::Result<spatter::LoadedDecals> loaded = spatter::LoadedDecals{};
    const std::optional<spatter::DrawPose> drawn =
        time ? std::optional<spatter::DrawPose>({*time, translate}) : std::nullopt;
    if (!decalsPath.empty())
        loaded = spatter::loadPlacedRecords(decalsPath, scene.value(), type, look.value(), drawn);
    if (!raysPath.empty())
        loaded = spatter::placeRays(raysPath, scene.value(), type, look.value(), seed, drawn);
    if (!loaded) return failure(loaded.error());
    for (const std::string& warning : loaded->warnings)
        std::cerr << "spatter-render: warning: " << warning << "\n";

    spatter::Result<spatter::GlContext> gl = spatter::GlContext::createHeadless();
    if (!gl) return failure(gl.error());
    spatter::RendererSettings settings;
    settings.width = width;
    settings.height = height;
    settings.waitForTimers = true;
    spatter::Result<spatter::Renderer> renderer = spatter::Renderer::create(gl.value(), settings);
    if (!renderer) return failure(renderer.error());
    if (spatter::Status s = renderer->setScene(scene.value()); !s) return failure(s.error());
    if (posed)
        if (spatter::Status s = renderer->setPose(posed->pose); !s) return failure(s.error());
    if (!loaded->objectIds.empty())
        if (spatter::Status s = renderer->setObjectIds(loaded->objectIds); !s) return failure(s.error());
    for (const auto& [name, size] : textureSpace) {
        uint32_t object = 0;
        while (object < scene->objects.size() && scene->objects[object].name != name)
            ++object;
        if (object == scene->objects.size())
            return failure("--texture-space: no object named '" + name + "'");
        if (spatter::Status s = renderer->setObjectDecalMode(object, spatter::DecalMode::TextureSpace, size);
            !s)
            return failure(s.error());
    }
    renderer->setDecalTypes(loaded->types);
    renderer->setDecals(loaded->decals, spatter::craterClipsOf(loaded->clips));
    spatter::Result<spatter::FrameStats> stats = renderer->render(camera, view);
    if (!stats) return failure(stats.error());
    spatter::Result<spatter::Image> image = renderer->readback();
    if (!image) return failure(image.error());
    spatter::cli::OutputCleanup cleanup; // the outputs of a run that fails
    cleanup.writing(outPath);
    if (spatter::Status s = spatter::writePng(outPath, image.value()); !s) return failure(s.error());
    if (!statsPath.empty()) {
        cleanup.writing(statsPath);
        std::ofstream f(statsPath);
        f << statsJson(stats.value(), options, camera, gl.value(), loaded.value()).dump(2) << "\n";
        f.close();
        if (!f) return failure("cannot write " + statsPath);
    }
    cleanup.keep();
    return 0;
}
