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

#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <optional>
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

Exit code 0 on success, 1 when the scene, the decals or the GL context fail, 2 on bad options.
)";

int usageError(const std::string& message) {
    std::cerr << "spatter-render: " << message << "\n(see spatter-render --help)\n";
    return 2;
}

int failure(const std::string& message) {
    std::cerr << "spatter-render: " << message << "\n";
    return 1;
}

// A finite number (one that underflows reads as zero or a subnormal).
bool parseFinite(const std::string& s, double& out) {
    return spatter::parseNumber(s, out, spatter::OutOfRange::Accept) && std::isfinite(out);
}

bool parseVec3(const std::string& s, glm::dvec3& out) {
    const std::vector<std::string> p = spatter::splitFields(s, ',');
    return p.size() == 3 && parseFinite(p[0], out.x) && parseFinite(p[1], out.y) && parseFinite(p[2], out.z);
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

} // namespace

int main(int argc, char** argv) {
    std::string scenePath, decalsPath, raysPath, cameraText, outPath = "render.png", statsPath,
                                                             textureName = "bullet_hole";
    int width = 960, height = 540;
    spatter::View view = spatter::View::Final;
    glm::dvec3 translate(0.0);
    std::optional<glm::dvec2> decalSize; // default: decalSizeForScene
    double maxAngle = 80.0;
    uint64_t seed = 1;
    std::vector<std::pair<std::string, int>> textureSpace; // object name, texture size
    bool volumetric = false;
    std::optional<double> time;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        std::string v;
        auto value = [&]() {
            if (i + 1 >= argc) return false;
            v = argv[++i];
            return true;
        };
        if (a == "--help" || a == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        } else if (a == "--decals") {
            if (!value()) return usageError("--decals needs a file");
            decalsPath = v;
        } else if (a == "--rays") {
            if (!value()) return usageError("--rays needs a file");
            raysPath = v;
        } else if (a == "--camera") {
            if (!value()) return usageError("--camera needs \"eye=x,y,z;target=x,y,z;...\"");
            cameraText = v;
        } else if (a == "--size") {
            const size_t x = value() ? v.find('x') : std::string::npos;
            double w = 0.0, h = 0.0;
            if (x == std::string::npos || !parseFinite(v.substr(0, x), w) ||
                !parseFinite(v.substr(x + 1), h) || w < 1.0 || h < 1.0 || w > 16384.0 || h > 16384.0 ||
                w != std::floor(w) || h != std::floor(h))
                return usageError("--size needs WxH, whole numbers in 1..16384");
            width = int(w);
            height = int(h);
        } else if (a == "--view") {
            if (!value()) return usageError("--view needs a view name");
            spatter::Result<spatter::View> parsed = spatter::parseView(v);
            if (!parsed) return usageError(parsed.error());
            view = parsed.value();
        } else if (a == "--out") {
            if (!value()) return usageError("--out needs a file");
            outPath = v;
        } else if (a == "--stats") {
            if (!value()) return usageError("--stats needs a file");
            statsPath = v;
        } else if (a == "--translate") {
            if (!value() || !parseVec3(v, translate))
                return usageError("--translate needs three finite numbers X,Y,Z");
        } else if (a == "--time") {
            double t = 0.0;
            if (!value() || !parseFinite(v, t)) return usageError("--time needs a finite number of seconds");
            time = t;
        } else if (a == "--volumetric") {
            volumetric = true;
        } else if (a == "--texture-space") {
            if (!value() || v.empty()) return usageError("--texture-space needs OBJECT[:SIZE]");
            const size_t colon = v.rfind(':');
            double size = 512.0;
            if (colon != std::string::npos &&
                (!parseFinite(v.substr(colon + 1), size) || size != std::floor(size) || size < 1.0))
                return usageError("--texture-space needs OBJECT[:SIZE] with a whole SIZE");
            if (size < 16.0 || size > 4096.0 || (int(size) & (int(size) - 1)) != 0)
                return usageError("--texture-space needs a SIZE that is a power of two in [16, 4096]");
            textureSpace.push_back({v.substr(0, colon), int(size)});
        } else if (a == "--texture") {
            if (!value()) return usageError("--texture needs bullet_hole, blood, paint, scorch or mixed");
            textureName = v;
        } else if (a == "--decal-size") {
            const std::vector<std::string> p =
                value() ? spatter::splitFields(v, ',') : std::vector<std::string>();
            double w = 0.0, h = 0.0;
            if (p.empty() || p.size() > 2 || !parseFinite(p[0], w) ||
                (p.size() == 2 && !parseFinite(p[1], h)))
                return usageError("--decal-size needs W or W,H");
            decalSize = glm::dvec2(w, p.size() == 1 ? w : h);
            if (!(decalSize->x > 0.0 && decalSize->y > 0.0))
                return usageError("--decal-size needs W and H above 0");
        } else if (a == "--max-angle") {
            if (!value() || !parseFinite(v, maxAngle) || !(maxAngle > 0.0 && maxAngle <= 90.0))
                return usageError("--max-angle needs a number of degrees in (0, 90]");
        } else if (a == "--seed") {
            char* end = nullptr;
            if (!value() || v.empty() || v[0] == '-')
                return usageError("--seed needs a non-negative integer");
            seed = std::strtoull(v.c_str(), &end, 10);
            if (end != v.c_str() + v.size()) return usageError("--seed needs a non-negative integer");
        } else if (!a.empty() && a[0] == '-') {
            return usageError("unknown option " + a);
        } else if (scenePath.empty()) {
            scenePath = a;
        } else {
            return usageError("more than one scene given");
        }
    }
    if (scenePath.empty()) return usageError("no scene given");
    if (!decalsPath.empty() && !raysPath.empty()) return usageError("--decals and --rays exclude each other");
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
    if (spatter::Status s = spatter::writePng(outPath, image.value()); !s) return failure(s.error());

    if (!statsPath.empty()) {
        nlohmann::ordered_json j = nlohmann::ordered_json::parse(spatter::toJson(stats.value()));
        j["scene"] = scenePath;
        j["camera"] = spatter::formatCamera(camera);
        j["gl_platform"] = gl->info().platform;
        j["input_records"] = loaded->records;
        j["input_placed"] = loaded->placed;
        if (time) j["time"] = *time;
        std::ofstream f(statsPath);
        if (!f) return failure("cannot write " + statsPath);
        f << j.dump(2) << "\n";
    }
    return 0;
}
