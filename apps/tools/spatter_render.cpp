// spatter-render SCENE: renders a scene with its decals headlessly (EGL) and writes a PNG of one
// view, and optionally the frame stats.

#include "spatter/core/Decal.hpp"
#include "spatter/core/DecalType.hpp"
#include "spatter/core/SceneLoader.hpp"
#include "spatter/core/TextFields.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/placement/RayParser.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/GlContext.hpp"
#include "spatter/render/Renderer.hpp"
#include "spatter/render/View.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace {

const char* kUsage = R"(usage: spatter-render SCENE [--decals FILE.jsonl | --rays FILE]
                      [--camera "eye=x,y,z;target=x,y,z;up=x,y,z;fov=DEG"] [--size WxH]
                      [--view final|albedo|normal|depth|ids|coverage] [--out FILE.png]
                      [--stats FILE.json] [--translate X,Y,Z] [--texture NAME]
                      [--texture-space OBJECT[:SIZE]]... [--volumetric]
                      [--decal-size W[,H]] [--max-angle DEG] [--seed N]

Renders SCENE (builtin:gallery or a .gltf, .glb, .obj, .ply, .off or .stl file) with the deferred
renderer and its decal projector, headless (EGL: a GPU where there is one, else Mesa's llvmpipe),
and writes one view as a PNG.

Decals:
  --decals FILE   spatter-place output (JSON Lines): every "placed" record becomes a decal on the
                  object it names ("object"), with its world-space centre ("position"), frame
                  ("normal", "tangent", "bitangent"), "size", "half_depth", "max_angle_deg" and
                  "object_id" (the object's 8-bit decal ID). Other records are ignored.
  --rays FILE     one ray per line, "ox oy oz dx dy dz" ('#' starts a comment), placed here through
                  the decal system on the render meshes, with --decal-size (default 0.3),
                  --max-angle (default 80) and --seed (default 1).
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
                  max angle), black elsewhere
  --volumetric    the decals are volumetric bullet holes: a crater drawn behind a hole cut into
                  the surface (stencil), instead of a flat texture
  --texture-space OBJECT[:SIZE]
                  draw the decals of the named object in texture space (rendered once into its own
                  SIZE x SIZE decal texture through its UVs, default 512) instead of projecting
                  them; repeatable. The object's UVs must not overlap and must lie in [0, 1]: a
                  mesh that breaks this is reported (first overlapping triangles) and the tool
                  exits with 1.
  --translate X,Y,Z  move the scene by this offset first; decals, rays and camera are given in the
                  moved world
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

bool jsonVec3(const nlohmann::json& j, const char* key, glm::dvec3& out) {
    if (!j.contains(key) || !j[key].is_array() || j[key].size() != 3) return false;
    for (int k = 0; k < 3; ++k) {
        if (!j[key][size_t(k)].is_number()) return false;
        out[k] = j[key][size_t(k)].get<double>();
        if (!std::isfinite(out[k])) return false;
    }
    return true;
}

bool jsonNumber(const nlohmann::json& j, const char* key, double& out) {
    if (!j.contains(key) || !j[key].is_number()) return false;
    out = j[key].get<double>();
    return std::isfinite(out);
}

// The object a record names: among objects of that name, the one whose world bounds lie nearest
// to the decal centre (names need not be unique in glTF files).
int findObject(const spatter::Scene& scene, const std::string& name, const glm::dvec3& position) {
    int best = -1;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const spatter::SceneObject& o = scene.objects[i];
        if (o.name != name) continue;
        spatter::DBounds b;
        for (const glm::vec3& p : o.mesh.positions)
            b.extend(glm::dvec3(o.transform * glm::dvec4(glm::dvec3(p), 1.0)));
        const double d = b.empty() ? 0.0 : glm::length(glm::clamp(position, b.min, b.max) - position);
        if (d < bestDistance) {
            bestDistance = d;
            best = int(i);
        }
    }
    return best;
}

// The built-in looks, in DecalTexture order.
const char* const kTextureNames[] = {"bullet_hole", "blood", "paint", "scorch"};

// `base` with the look of built-in decal texture `texture`.
spatter::DecalType withLook(spatter::DecalType base, int texture) {
    base.texture = texture;
    base.tint = glm::vec4(1.0f);
    base.roughness = -1.0f;
    if (texture == int(spatter::DecalTexture::Blood)) base.roughness = 0.25f;
    if (texture == int(spatter::DecalTexture::Paint)) base.tint = glm::vec4(0.9f, 0.75f, 0.1f, 1.0f);
    if (texture == int(spatter::DecalTexture::Scorch)) base.roughness = 0.95f;
    return base;
}

// Texture of the k-th decal: `texture`, or the built-ins in turn when it is -1 (mixed).
int lookOf(int texture, size_t k) {
    return texture >= 0 ? texture : int(k % size_t(spatter::DecalTexture::Count));
}

struct LoadedDecals {
    std::vector<spatter::Decal> decals;
    std::vector<spatter::DecalType> types;
    std::vector<uint8_t> objectIds;
    size_t records = 0;
    size_t placed = 0;
};

// A world-space decal box (centre, unit axes, size, half-depth) as a Decal on `object`, in its space:
// each box axis vector is carried by the inverse of the object's transform.
spatter::Decal toObjectSpace(const spatter::SceneObject& obj, uint32_t object, const glm::dvec3& position,
                             const glm::dvec3 axes[3], const glm::dvec2& size, double halfDepth) {
    const glm::dmat4 inv = glm::inverse(obj.transform);
    const glm::dmat3 invLinear(inv);
    const glm::dvec3 a = invLinear * (axes[0] * (0.5 * size.x));
    const glm::dvec3 b = invLinear * (axes[1] * (0.5 * size.y));
    const glm::dvec3 c = invLinear * (axes[2] * halfDepth);
    spatter::Decal d;
    d.object = object;
    d.center = glm::vec3(glm::dvec3(inv * glm::dvec4(position, 1.0)));
    d.frame.tangent = glm::vec3(glm::normalize(a));
    d.frame.bitangent = glm::vec3(glm::normalize(b));
    d.frame.normal = glm::vec3(glm::normalize(c));
    d.size = glm::vec2(float(2.0 * glm::length(a)), float(2.0 * glm::length(b)));
    d.halfDepth = float(glm::length(c));
    return d;
}

bool loadPlacedRecords(const std::string& path, const spatter::Scene& scene, const spatter::DecalType& base,
                       int texture, LoadedDecals& out, std::string& error) {
    std::ifstream in(path);
    if (!in) {
        error = "cannot read " + path;
        return false;
    }
    out.objectIds.assign(scene.objects.size(), 0);
    std::map<std::pair<double, int>, uint16_t> typeByAngleAndLook;
    size_t lineNumber = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNumber;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        ++out.records;
        const std::string where = path + ":" + std::to_string(lineNumber) + ": ";
        const nlohmann::json rec = nlohmann::json::parse(line, nullptr, false);
        if (rec.is_discarded() || !rec.is_object()) {
            error = where + "not a JSON object";
            return false;
        }
        if (!rec.contains("status") || rec["status"] != "placed") continue;
        glm::dvec3 position, axes[3];
        double halfDepth = 0.0, maxAngle = 80.0, objectId = 0.0;
        const bool ok = rec.contains("object") && rec["object"].is_string() &&
                        jsonVec3(rec, "position", position) && jsonVec3(rec, "tangent", axes[0]) &&
                        jsonVec3(rec, "bitangent", axes[1]) && jsonVec3(rec, "normal", axes[2]) &&
                        jsonNumber(rec, "half_depth", halfDepth) && rec.contains("size") &&
                        rec["size"].is_array() && rec["size"].size() == 2 && rec["size"][0].is_number() &&
                        rec["size"][1].is_number();
        if (!ok) {
            error = where +
                    "a placed record needs object, position, tangent, bitangent, normal, size and half_depth";
            return false;
        }
        const glm::dvec2 size(rec["size"][0].get<double>(), rec["size"][1].get<double>());
        if (!std::isfinite(size.x) || !std::isfinite(size.y) || !(size.x > 0.0) || !(size.y > 0.0) ||
            !(halfDepth > 0.0)) {
            error = where + "size and half_depth must be finite and positive";
            return false;
        }
        jsonNumber(rec, "max_angle_deg", maxAngle);
        jsonNumber(rec, "object_id", objectId);
        if (objectId < 0.0 || objectId > 255.0) {
            error = where + "object_id must be in 0..255";
            return false;
        }
        const std::string name = rec["object"].get<std::string>();
        const int object = findObject(scene, name, position);
        if (object < 0) {
            error = where + "the scene has no object named '" + name + "'";
            return false;
        }
        const int look = lookOf(texture, out.decals.size());
        auto it = typeByAngleAndLook.find({maxAngle, look});
        if (it == typeByAngleAndLook.end()) {
            spatter::DecalType t = withLook(base, look);
            t.maxAngleDeg = float(maxAngle);
            it = typeByAngleAndLook.emplace(std::make_pair(maxAngle, look), uint16_t(out.types.size())).first;
            out.types.push_back(t);
        }
        spatter::Decal d =
            toObjectSpace(scene.objects[size_t(object)], uint32_t(object), position, axes, size, halfDepth);
        d.type = it->second;
        d.objectId = uint8_t(objectId);
        if (rec.contains("decal_id") && rec["decal_id"].is_number_unsigned())
            d.id = rec["decal_id"].get<uint32_t>();
        out.objectIds[size_t(object)] = d.objectId;
        out.decals.push_back(d);
        ++out.placed;
    }
    // Dynamic objects that carry no decal still need an ID no decal has, so that no decal shows on
    // them: the smallest one the records do not use.
    std::vector<bool> used(256, false);
    std::vector<bool> named(scene.objects.size(), false);
    for (const spatter::Decal& d : out.decals) {
        used[d.objectId] = true;
        named[d.object] = true;
    }
    int spare = 1;
    while (spare < 256 && used[size_t(spare)])
        ++spare;
    for (size_t i = 0; i < scene.objects.size(); ++i)
        if (scene.objects[i].dynamic && !named[i]) out.objectIds[i] = uint8_t(spare < 256 ? spare : 255);
    return true;
}

bool placeRays(const std::string& path, const spatter::Scene& scene, const spatter::DecalType& type,
               int texture, uint64_t seed, LoadedDecals& out, std::string& error) {
    std::ifstream in(path);
    if (!in) {
        error = "cannot read " + path;
        return false;
    }
    std::vector<spatter::Ray> rays;
    size_t lineNumber = 0;
    for (std::string raw; std::getline(in, raw);) {
        const spatter::RayLine line = spatter::parseRayLine(raw, ++lineNumber);
        if (!line.isRay) continue;
        ++out.records;
        // An unparseable ray places nothing, as in spatter-place; one with values that are not finite
        // is rejected by the decal system (rayProblem) and places nothing either.
        if (line.ok) rays.push_back(line.ray);
    }
    spatter::DecalSettings settings;
    settings.seed = seed;
    settings.maxPerCell = std::numeric_limits<uint32_t>::max();
    settings.budget = std::numeric_limits<uint32_t>::max();
    settings.maxPerObject = std::numeric_limits<uint32_t>::max();
    spatter::Result<spatter::DecalSystem> sys = spatter::DecalSystem::create(scene, settings);
    if (!sys) {
        error = sys.error();
        return false;
    }
    for (const std::string& warning : sys->world().warnings())
        std::cerr << "spatter-render: warning: " << warning << "\n";
    spatter::Result<uint16_t> index = sys->registerType(type);
    if (!index) {
        error = index.error();
        return false;
    }
    std::vector<spatter::SpawnResult> results;
    sys->spawnBatch(rays, index.value(), results);
    for (const spatter::SpawnResult& r : results)
        out.placed += r.placed() ? 1 : 0;
    out.decals = sys->decals();
    for (int k = 0; k < int(spatter::DecalTexture::Count); ++k)
        out.types.push_back(withLook(type, k));
    for (size_t k = 0; k < out.decals.size(); ++k)
        out.decals[k].type = uint16_t(lookOf(texture, k));
    for (uint32_t o = 0; o < scene.objects.size(); ++o)
        out.objectIds.push_back(sys->objectId(o));
    return true;
}

spatter::Camera defaultCamera(const spatter::Scene& scene) {
    spatter::Camera cam;
    const spatter::DBounds b = scene.worldBounds();
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
    double decalW = 0.3, decalH = 0.3, maxAngle = 80.0;
    uint64_t seed = 1;
    std::vector<std::pair<std::string, int>> textureSpace; // object name, texture size
    bool volumetric = false;
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
        } else if (a == "--volumetric") {
            volumetric = true;
        } else if (a == "--texture-space") {
            if (!value() || v.empty()) return usageError("--texture-space needs OBJECT[:SIZE]");
            const size_t colon = v.rfind(':');
            double size = 512.0;
            if (colon != std::string::npos &&
                (!parseFinite(v.substr(colon + 1), size) || size != std::floor(size) || size < 1.0))
                return usageError("--texture-space needs OBJECT[:SIZE] with a whole SIZE");
            textureSpace.push_back({v.substr(0, colon), int(size)});
        } else if (a == "--texture") {
            if (!value()) return usageError("--texture needs bullet_hole, blood, paint, scorch or mixed");
            textureName = v;
        } else if (a == "--decal-size") {
            const std::vector<std::string> p =
                value() ? spatter::splitFields(v, ',') : std::vector<std::string>();
            if (p.empty() || p.size() > 2 || !parseFinite(p[0], decalW) ||
                (p.size() == 2 && !parseFinite(p[1], decalH)))
                return usageError("--decal-size needs W or W,H");
            if (p.size() == 1) decalH = decalW;
        } else if (a == "--max-angle") {
            if (!value() || !parseFinite(v, maxAngle))
                return usageError("--max-angle needs a number of degrees");
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
    int texture = -2;
    for (int k = 0; k < int(spatter::DecalTexture::Count); ++k)
        if (textureName == kTextureNames[k]) texture = k;
    if (textureName == "mixed") texture = -1;
    if (texture == -2) return usageError("--texture needs bullet_hole, blood, paint, scorch or mixed");

    spatter::Result<spatter::Scene> scene = spatter::loadScene(scenePath);
    if (!scene) return failure(scene.error());
    scene->translate(translate);

    spatter::Camera camera = defaultCamera(scene.value());
    if (!cameraText.empty()) {
        spatter::Result<spatter::Camera> parsed = spatter::parseCamera(cameraText);
        if (!parsed) return usageError(parsed.error());
        parsed->nearPlane = camera.nearPlane;
        camera = parsed.value();
    }

    spatter::DecalType type;
    type.name = "spatter-render";
    type.size = glm::vec2(float(decalW), float(decalH));
    type.maxAngleDeg = float(maxAngle);
    type.volumetric = volumetric;

    LoadedDecals loaded;
    std::string error;
    if (!decalsPath.empty() && !loadPlacedRecords(decalsPath, scene.value(), type, texture, loaded, error))
        return failure(error);
    if (!raysPath.empty() && !placeRays(raysPath, scene.value(), type, texture, seed, loaded, error))
        return failure(error);

    spatter::Result<spatter::GlContext> gl = spatter::GlContext::createHeadless();
    if (!gl) return failure(gl.error());
    spatter::RendererSettings settings;
    settings.width = width;
    settings.height = height;
    settings.waitForTimers = true;
    spatter::Result<spatter::Renderer> renderer = spatter::Renderer::create(gl.value(), settings);
    if (!renderer) return failure(renderer.error());
    if (spatter::Status s = renderer->setScene(scene.value()); !s) return failure(s.error());
    if (!loaded.objectIds.empty())
        if (spatter::Status s = renderer->setObjectIds(loaded.objectIds); !s) return failure(s.error());
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
    renderer->setDecalTypes(loaded.types);
    renderer->setDecals(loaded.decals);
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
        j["input_records"] = loaded.records;
        j["input_placed"] = loaded.placed;
        std::ofstream f(statsPath);
        if (!f) return failure("cannot write " + statsPath);
        f << j.dump(2) << "\n";
    }
    return 0;
}
