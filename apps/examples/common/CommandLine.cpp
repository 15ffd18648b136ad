#include "CommandLine.hpp"

#include <spatter/core/SceneLoader.hpp>
#include <spatter/core/TextFields.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace example {

namespace {

// A whole number in 1..16384 written as digits (the image sizes spatter-render takes).
bool parseSide(const std::string& text, int& out) {
    double v = 0.0;
    if (text.empty() || text.size() > 5 || text.find_first_not_of("0123456789") != std::string::npos ||
        !spatter::parseDecimal(text, v) || v < 1.0 || v > 16384.0)
        return false;
    out = int(v);
    return true;
}

spatter::Status parseSize(const std::string& text, Options& o) {
    const size_t x = text.find('x');
    if (x == std::string::npos || !parseSide(text.substr(0, x), o.width) ||
        !parseSide(text.substr(x + 1), o.height))
        return spatter::fail("--size needs WxH, whole numbers in 1..16384");
    return {};
}

spatter::Status parseView(const std::string& text, Options& o) {
    const char* const names[] = {"final", "albedo", "coverage"};
    for (int k = 0; k < 3; ++k)
        if (text == names[k]) {
            o.view = View(k);
            return {};
        }
    return spatter::fail("unknown view '" + text + "' (final, albedo or coverage)");
}

// Takes the option argv[i] (and its value, moving i past it) into `o`.
spatter::Status parseOption(int argc, char** argv, int& i, const std::vector<Switch>& own, Options& o) {
    const std::string a = argv[i];
    const bool hasValue = i + 1 < argc && std::string(argv[i + 1]).rfind("--", 0) != 0; // not an option
    const std::string v = hasValue ? argv[i + 1] : "";
    if (a == "--help" || a == "-h") {
        o.help = true;
        return {};
    }
    if (std::any_of(own.begin(), own.end(), [&](const Switch& s) { return s.name == a; })) {
        o.switches.insert(a);
        return {};
    }
    const char* const valued[] = {"--decals", "--rays", "--camera", "--size", "--view", "--out"};
    if (std::find(std::begin(valued), std::end(valued), a) == std::end(valued))
        return spatter::fail("unknown option " + a);
    if (!hasValue) return spatter::fail(a + " needs a value");
    ++i;
    if (a == "--decals") o.decals = v;
    if (a == "--rays") o.rays = v;
    if (a == "--out") o.out = v;
    if (a == "--size") return parseSize(v, o);
    if (a == "--view") return parseView(v, o);
    if (a == "--camera") {
        spatter::Result<spatter::Camera> camera = spatter::parseCamera(v);
        if (!camera) return spatter::fail("--camera: " + camera.error());
        o.camera = camera.value();
    }
    return {};
}

// spatter-render's default view: the centre of the scene's bounds from the front, above; the near
// plane a thousandth of the scene's diagonal.
spatter::Camera defaultCamera(const spatter::Scene& scene) {
    spatter::Camera cam;
    const spatter::DBounds b = scene.worldBounds();
    if (b.empty()) return cam;
    const double diag = std::max(b.diagonal(), 1e-6);
    cam.target = b.center();
    cam.eye = b.center() + glm::normalize(glm::dvec3(0.15, 0.35, 1.0)) * (0.75 * diag);
    cam.nearPlane = std::max(diag * 1e-3, 1e-4);
    return cam;
}

// The perspective projection of `camera` for the image, standard Z with GL's default clip depth; the
// far plane well beyond the scene.
glm::dmat4 projectionFor(const spatter::Camera& camera, const spatter::Scene& scene, double aspect) {
    const spatter::DBounds b = scene.worldBounds();
    double farthest = 0.0;
    for (int k = 0; k < 8 && !b.empty(); ++k) {
        const glm::dvec3 corner((k & 1) ? b.max.x : b.min.x, (k & 2) ? b.max.y : b.min.y,
                                (k & 4) ? b.max.z : b.min.z);
        farthest = std::max(farthest, glm::length(corner - camera.eye));
    }
    const double farPlane = std::max(2.0 * farthest, 2.0 * camera.nearPlane);
    return glm::perspective(glm::radians(camera.fovYDeg), aspect, camera.nearPlane, farPlane);
}

} // namespace

spatter::Result<Options> parseCommandLine(int argc, char** argv, const std::vector<Switch>& own) {
    Options o;
    std::set<std::string> given; // the options so far: each is given once
    for (int i = 1; i < argc && !o.help; ++i) {
        const std::string a = argv[i];
        if (a.size() > 1 && a[0] == '-') {
            if (!given.insert(a).second) return spatter::fail(a + " given twice");
            if (spatter::Status s = parseOption(argc, argv, i, own, o); !s) return spatter::fail(s.error());
        } else if (o.scene.empty()) {
            o.scene = a;
        } else {
            return spatter::fail("more than one scene given");
        }
    }
    if (o.help) return o;
    if (o.scene.empty()) return spatter::fail("no scene given");
    if (!o.decals.empty() && !o.rays.empty()) return spatter::fail("--decals and --rays exclude each other");
    return o;
}

std::string usage(const std::string& program, const std::string& description,
                  const std::vector<Switch>& own) {
    std::string synopsis, ownHelp = own.empty() ? "" : "Its own options:\n";
    for (const Switch& s : own) {
        synopsis += " [" + s.name + "]";
        std::string help = s.help; // continued lines under the first
        for (size_t at = help.find('\n'); at != std::string::npos; at = help.find('\n', at + 1))
            help.insert(at + 1, 18, ' ');
        ownHelp +=
            "  " + s.name + std::string(s.name.size() < 16 ? 16 - s.name.size() : 1, ' ') + help + "\n";
    }
    return "usage: " + program + R"( SCENE [--decals FILE.jsonl | --rays FILE]
        [--camera "eye=x,y,z;target=x,y,z;up=x,y,z;fov=DEG"] [--size WxH]
        [--view final|albedo|coverage] [--out FILE.png])" +
           synopsis + "\n\n" + description + "\n\n" + ownHelp + (own.empty() ? "" : "\n") +
           R"(spatter-render's options, with the same meanings:
  SCENE           builtin:gallery or a .gltf, .glb, .obj, .ply, .off or .stl file
  --decals FILE   spatter-place output (JSON Lines): every "placed" record becomes a decal on the
                  object it names
  --rays FILE     one ray per line, "ox oy oz dx dy dz" ('#' starts a comment), placed here through
                  the decal system on the render meshes, or an object's authored collider where
                  it has one (decals of 2% of the scene's bounding diagonal within 80 degrees,
                  seed 1)
  --camera "eye=x,y,z;target=x,y,z;up=x,y,z;fov=DEG"
                  perspective camera; up defaults to 0,1,0 and fov (vertical, degrees) to 60.
                  Default: looking at the centre of the scene's bounds from the front, above.
                  Pixel (i, j) of the image, j counted from the top row, shows the ray from the
                  eye through the centre of that pixel.
  --size WxH      image size (default 960x540)
  --view V        final (lit, default), albedo (after the decals, sRGB), or coverage: white where
                  at least one decal changes the pixel (inside its box, object ID matching, within
                  its max angle), black elsewhere
  --out FILE.png  the image (default render.png)
  --help          this text

Each option is given once, with its value (a following "--..." is not one); W and H are digits.
Exit code 0 on success, 1 when the scene, the decals or the GL context fail, 2 on bad options.
)";
}

spatter::Result<Inputs> loadInputs(const Options& options) {
    spatter::Result<spatter::Scene> scene = spatter::loadScene(options.scene);
    if (!scene) return spatter::fail(scene.error());
    Inputs in;
    in.scene = std::move(scene.value());
    in.camera = defaultCamera(in.scene);
    if (options.camera) {
        const double nearPlane = in.camera.nearPlane;
        in.camera = *options.camera;
        in.camera.nearPlane = nearPlane;
    }
    in.view = spatter::viewRotation(in.camera) * glm::translate(glm::dmat4(1.0), -in.camera.eye);
    in.projection = projectionFor(in.camera, in.scene, double(options.width) / double(options.height));
    spatter::DecalType type; // spatter-render's defaults
    type.name = "spatter-render";
    type.size = spatter::decalSizeForScene(glm::length(in.scene.worldBounds().extent()));
    type.maxAngleDeg = 80.0f;
    const int look = int(spatter::DecalTexture::BulletHole);
    spatter::Result<spatter::LoadedDecals> decals = spatter::LoadedDecals{};
    if (!options.decals.empty()) decals = spatter::loadPlacedRecords(options.decals, in.scene, type, look);
    if (!options.rays.empty()) decals = spatter::placeRays(options.rays, in.scene, type, look, 1);
    if (!decals) return spatter::fail(decals.error());
    in.decals = std::move(decals.value());
    return in;
}

int usageError(const std::string& program, const std::string& message) {
    std::fprintf(stderr, "%s: %s\n(see %s --help)\n", program.c_str(), message.c_str(), program.c_str());
    return 2;
}

int failure(const std::string& program, const std::string& message) {
    std::fprintf(stderr, "%s: %s\n", program.c_str(), message.c_str());
    return 1;
}

} // namespace example
