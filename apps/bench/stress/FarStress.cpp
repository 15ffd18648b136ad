// Far from the origin: the builtin gallery and the same rays translated by 1e3, 1e4, 1e5 and 1e6
// units. Decal centres relative to the scene must move by at most 1e-6 of their object's size (through
// the API and through `spatter-place --translate`), and the rendered coverage must keep IoU >= 0.97
// against the untranslated render up to 1e5.

#include "StressCase.hpp"
#include "StressSupport.hpp"

#include "spatter/core/GalleryScene.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/Renderer.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>

namespace spatter::stress {

namespace {

const double kOffsets[] = {1e3, 1e4, 1e5, 1e6};

// The direction the scene is moved along: not along an axis, so that every coordinate grows.
glm::dvec3 offsetVector(double magnitude) {
    return magnitude * glm::dvec3(1.0, -0.37, 0.81);
}

// Shots from the open floor of the gallery at random interior points of random triangles of its
// receivers (world space, untranslated).
std::vector<Ray> galleryShots(const Scene& scene, size_t count, uint64_t seed) {
    Rng rng(seed + 11);
    std::vector<Ray> rays;
    while (rays.size() < count) {
        const SceneObject& o = scene.objects[rng.below(uint32_t(scene.objects.size()))];
        if (!o.receivesDecals || o.mesh->triangleCount() == 0) continue;
        const size_t t = rng.below(uint32_t(o.mesh->triangleCount()));
        double u = uniform(rng, 0.05, 0.9), v = uniform(rng, 0.05, 0.9);
        if (u + v > 0.95) {
            u = 0.95 - u;
            v = 0.95 - v;
        }
        const glm::dvec3 p0(o.mesh->positions[o.mesh->indices[3 * t]]),
            p1(o.mesh->positions[o.mesh->indices[3 * t + 1]]),
            p2(o.mesh->positions[o.mesh->indices[3 * t + 2]]);
        const glm::dvec3 aim(o.transform * glm::dvec4(p0 + u * (p1 - p0) + v * (p2 - p0), 1.0));
        Ray ray;
        ray.origin = glm::dvec3(uniform(rng, -6.0, 6.0), uniform(rng, 0.5, 2.5), uniform(rng, 1.5, 7.5));
        ray.direction = aim - ray.origin;
        rays.push_back(ray);
    }
    return rays;
}

// One placed decal in world space, as the API or the tool reports it.
struct Placed {
    bool placed = false;
    std::string object;
    glm::dvec3 centre{0.0}, normal{0.0}, tangent{0.0};
    glm::dvec2 size{0.0};
    double halfDepth = 0.0;
};

std::map<std::string, double> objectSizes(const Scene& scene) {
    std::map<std::string, double> sizes;
    for (const SceneObject& o : scene.objects) {
        DBounds b;
        for (const glm::vec3& p : o.mesh->positions)
            b.extend(glm::dvec3(o.transform * glm::dvec4(glm::dvec3(p), 1.0)));
        sizes[o.name] = b.diagonal();
    }
    return sizes;
}

// Compares a translated run with the untranslated one: the largest centre shift relative to the
// object's size, and the largest change of the frame and box. Status or object mismatches are failures.
struct Comparison {
    double centre = 0.0, frame = 0.0, box = 0.0;
    size_t mismatches = 0, compared = 0;
};

void compare(const std::vector<Placed>& base, const std::vector<Placed>& moved, const glm::dvec3& offset,
             const std::map<std::string, double>& sizes, const std::string& what, Comparison& c,
             StressResult& r) {
    for (size_t i = 0; i < base.size() && i < moved.size(); ++i) {
        const Placed& a = base[i];
        const Placed& b = moved[i];
        if (a.placed != b.placed || a.object != b.object) {
            c.mismatches++;
            r.failure(what + ": ray " + std::to_string(i) + " gave " + (a.placed ? a.object : "nothing") +
                      " untranslated and " + (b.placed ? b.object : "nothing") + " translated");
            continue;
        }
        if (!a.placed) continue;
        c.compared++;
        const auto size = sizes.find(a.object);
        const double s = size == sizes.end() ? 1.0 : size->second;
        const double shift = glm::length((b.centre - offset) - a.centre) / s;
        const double frame = std::max(glm::length(b.normal - a.normal), glm::length(b.tangent - a.tangent));
        const double box =
            std::max({std::fabs(b.size.x / a.size.x - 1.0), std::fabs(b.size.y / a.size.y - 1.0),
                      std::fabs(b.halfDepth / a.halfDepth - 1.0)});
        c.centre = worse(c.centre, shift);
        c.frame = worse(c.frame, frame);
        c.box = worse(c.box, box);
        if (!(shift <= 1e-6))
            r.failure(what + ": ray " + std::to_string(i) + " on " + a.object + ": centre moved by " +
                      num(shift) + " of the object's size");
    }
    if (base.size() != moved.size()) {
        c.mismatches++;
        r.failure(what + ": " + std::to_string(moved.size()) + " records for " + std::to_string(base.size()) +
                  " rays");
    }
}

const DecalType& farType() {
    static const DecalType t = makeType("far", 0.3f, 80.0f);
    return t;
}

// Places every ray through the API in the scene translated by `offset`.
Result<std::vector<Placed>> placeThroughApi(Scene scene, const std::vector<Ray>& rays,
                                            const glm::dvec3& offset, uint64_t seed,
                                            std::vector<Decal>* decals, std::vector<uint8_t>* ids) {
    scene.translate(offset);
    Result<DecalSystem> sys = DecalSystem::create(scene, unlimitedSettings(seed));
    if (!sys) return fail(sys.error());
    const uint16_t ti = sys->registerType(farType()).value();
    std::vector<Placed> out;
    for (Ray ray : rays) {
        ray.origin += offset;
        const SpawnResult res = sys->spawn(ray, ti);
        Placed p;
        if (res.placed()) {
            const Decal& d = *sys->get(res.handle);
            const WorldDecal w = sys->worldBox(d);
            p.placed = true;
            p.object = scene.objects[d.object].name;
            p.centre = w.center;
            p.normal = glm::dvec3(w.frame.normal);
            p.tangent = glm::dvec3(w.frame.tangent);
            p.size = glm::dvec2(w.size);
            p.halfDepth = w.halfDepth;
        }
        out.push_back(p);
    }
    if (decals) *decals = sys->decals();
    if (ids) *ids = sys->objectIds();
    return out;
}

GallerySettings gallerySettings(const StressConfig& cfg) {
    GallerySettings gs;
    gs.seed = cfg.seed;
    gs.detail = cfg.full ? 2 : 0;
    return gs;
}

glm::dvec3 jsonVec(const nlohmann::json& j) {
    return glm::dvec3(j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>());
}

// Runs spatter-place on builtin:gallery with --translate and reads its records.
Result<std::vector<Placed>> placeThroughTool(const StressConfig& cfg, const std::vector<Ray>& rays,
                                             const glm::dvec3& offset, const std::string& tag) {
    const std::string raysPath = cfg.scratchDir + "/far-rays-" + tag + ".txt";
    const std::string outPath = cfg.scratchDir + "/far-decals-" + tag + ".jsonl";
    {
        std::ofstream f(raysPath);
        char line[256];
        for (const Ray& ray : rays) {
            const glm::dvec3 o = ray.origin + offset;
            std::snprintf(line, sizeof line, "%.17g %.17g %.17g %.17g %.17g %.17g\n", o.x, o.y, o.z,
                          ray.direction.x, ray.direction.y, ray.direction.z);
            f << line;
        }
        if (!f) return fail("cannot write " + raysPath);
    }
    char translate[160];
    std::snprintf(translate, sizeof translate, "%.17g,%.17g,%.17g", offset.x, offset.y, offset.z);
    const std::string command = "'" + cfg.placeTool + "' builtin:gallery --seed " + std::to_string(cfg.seed) +
                                " --size 0.3 --rays '" + raysPath + "' --translate " + translate +
                                " --out '" + outPath + "'";
    const int rc = std::system(command.c_str());
    if (rc != 0) return fail("'" + command + "' exited with " + std::to_string(rc));
    std::ifstream in(outPath);
    std::vector<Placed> out;
    for (std::string line; std::getline(in, line);) {
        const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
        if (j.is_discarded() || !j.is_object()) return fail(outPath + ": a line is not JSON: " + line);
        Placed p;
        if (j.value("status", "") == "placed") {
            p.placed = true;
            p.object = j.at("object").get<std::string>();
            p.centre = jsonVec(j.at("position"));
            p.normal = jsonVec(j.at("normal"));
            p.tangent = jsonVec(j.at("tangent"));
            p.size = glm::dvec2(j.at("size").at(0).get<double>(), j.at("size").at(1).get<double>());
            p.halfDepth = j.at("half_depth").get<double>();
        }
        out.push_back(p);
    }
    return out;
}

void addComparisonRows(StressResult& r, const std::string& prefix, double magnitude, const Comparison& c) {
    char label[64];
    std::snprintf(label, sizeof label, "%g", magnitude);
    r.row(prefix + " translated by " + label + ": |centre shift| / object size", c.centre, 1e-6, c.compared);
    r.row(prefix + " translated by " + label + ": frame change, |size or half-depth ratio - 1|",
          std::max(c.frame, c.box), 1e-5, c.compared);
    r.row(prefix + " translated by " + label + ": rays placed differently (count)", double(c.mismatches), 0.0,
          c.compared);
}

// The coverage view of `decals` on `scene` (with object IDs `ids`) seen by `camera`.
Result<Image> coverageOf(Renderer& renderer, const Scene& scene, const std::vector<uint8_t>& ids,
                         const std::vector<Decal>& decals, const Camera& camera) {
    if (Status st = renderer.setScene(scene); !st) return fail(st.error());
    if (Status st = renderer.setObjectIds(ids); !st) return fail(st.error());
    renderer.setDecalTypes({farType()});
    renderer.setDecals(decals);
    Result<FrameStats> frame = renderer.render(camera, View::Coverage);
    if (!frame) return fail(frame.error());
    return renderer.readback();
}

} // namespace

StressResult runFarPlacement(const StressConfig& cfg) {
    StressResult r;
    r.technique = "double-precision origin rebasing: static geometry stored in float around the centre "
                  "of the static bounds, rays moved into that frame in double, hits refined in double "
                  "in object space; decals stored in object space";
    const Scene scene = makeGalleryScene(gallerySettings(cfg));
    const std::vector<Ray> rays = galleryShots(scene, cfg.full ? 20'000 : 1'500, cfg.seed);
    const auto sizes = objectSizes(scene);
    Result<std::vector<Placed>> base =
        placeThroughApi(scene, rays, glm::dvec3(0.0), cfg.seed, nullptr, nullptr);
    if (!base) {
        r.failure(base.error());
        r.row("untranslated placement", INFINITY, 0.0, 0);
        return r;
    }
    for (double magnitude : kOffsets) {
        const glm::dvec3 offset = offsetVector(magnitude);
        Result<std::vector<Placed>> moved = placeThroughApi(scene, rays, offset, cfg.seed, nullptr, nullptr);
        Comparison c;
        if (!moved) {
            c.mismatches = rays.size();
            r.failure(moved.error());
        } else {
            compare(base.value(), moved.value(), offset, sizes, "API " + num(magnitude), c, r);
        }
        addComparisonRows(r, "API", magnitude, c);
    }
    return r;
}

StressResult runFarTool(const StressConfig& cfg) {
    StressResult r;
    r.technique = "as far-placement, through spatter-place --translate (JSON records in double)";
    if (cfg.placeTool.empty()) {
        r.skipped = "the spatter-place binary is not known";
        return r;
    }
    GallerySettings gs; // builtin:gallery, as the tool loads it
    gs.seed = 1;
    const Scene scene = makeGalleryScene(gs);
    const std::vector<Ray> rays = galleryShots(scene, cfg.full ? 5'000 : 400, cfg.seed);
    const auto sizes = objectSizes(scene);
    Result<std::vector<Placed>> base = placeThroughTool(cfg, rays, glm::dvec3(0.0), "0");
    if (!base) {
        r.failure(base.error());
        r.row("spatter-place untranslated", INFINITY, 0.0, 0);
        return r;
    }
    size_t placed = 0;
    for (const Placed& p : base.value())
        placed += p.placed ? 1 : 0;
    r.row("spatter-place: rays not placed untranslated (fraction)",
          1.0 - double(placed) / double(rays.size()), 0.2, rays.size());
    const std::vector<double> offsets = cfg.full
                                            ? std::vector<double>(std::begin(kOffsets), std::end(kOffsets))
                                            : std::vector<double>{1e3, 1e6};
    for (double magnitude : offsets) {
        const glm::dvec3 offset = offsetVector(magnitude);
        Result<std::vector<Placed>> moved = placeThroughTool(cfg, rays, offset, num(magnitude));
        Comparison c;
        if (!moved) {
            c.mismatches = rays.size();
            r.failure(moved.error());
        } else {
            compare(base.value(), moved.value(), offset, sizes, "spatter-place " + num(magnitude), c, r);
        }
        addComparisonRows(r, "spatter-place", magnitude, c);
    }
    return r;
}

StressResult runFarRender(const StressConfig& cfg) {
    StressResult r;
    r.technique = "camera-relative rendering: transforms stay double on the CPU and have the eye subtracted "
                  "before they become float; decals in object space; reversed-Z float depth";
    const int width = cfg.full ? 320 : 128, height = cfg.full ? 240 : 96;
    Result<Renderer> renderer = caseRenderer(cfg, width, height, r);
    if (!renderer) return r;
    Result<Renderer> gpuCulled = caseRenderer(cfg, width, height, r, 0); // the same, culled on the GPU
    if (!gpuCulled) return r;
    GallerySettings gs = gallerySettings(cfg);
    gs.detail = 0;
    const Scene scene = makeGalleryScene(gs);
    Camera cam;
    cam.eye = {0.5, 1.8, 5.0};
    cam.target = {0.0, 1.2, -3.0};
    // Shots from the eye through a grid of pixels: what the player sees gets decals.
    std::vector<Ray> rays;
    const int shots = cfg.full ? 400 : 150;
    for (int s = 0; s < shots; ++s)
        rays.push_back(Ray{cam.eye, pixelDirection(cam, width, height, (s * 37) % width, (s * 53) % height)});

    std::vector<uint8_t> reference;
    for (double magnitude : {0.0, 1e3, 1e4, 1e5, 1e6}) {
        const glm::dvec3 offset = offsetVector(magnitude);
        std::vector<Decal> decals;
        std::vector<uint8_t> ids;
        Result<std::vector<Placed>> placed = placeThroughApi(scene, rays, offset, cfg.seed, &decals, &ids);
        Scene moved = scene;
        moved.translate(offset);
        Camera c = cam;
        c.eye += offset;
        c.target += offset;
        Result<Image> image = coverageOf(renderer.value(), moved, ids, decals, c);
        Result<Image> gpuImage = coverageOf(gpuCulled.value(), moved, ids, decals, c);
        if (!placed || !image) {
            r.failure(!placed ? placed.error() : image.error());
            r.row("render at " + num(magnitude), INFINITY, 0.0, 0);
            continue;
        }
        std::vector<uint8_t> mask(size_t(width) * size_t(height));
        for (size_t i = 0; i < mask.size(); ++i)
            mask[i] = image->rgba[4 * i] > 127 ? 1 : 0;
        size_t unlike = gpuImage ? 0 : mask.size();
        for (size_t i = 0; gpuImage && i < mask.size(); ++i)
            unlike += (gpuImage->rgba[4 * i] > 127 ? 1 : 0) != mask[i] ? 1 : 0;
        r.row("coverage culled on the GPU at " + num(magnitude) + ": pixels unlike the CPU culling's",
              double(unlike), 0.0, mask.size(), gpuImage ? "" : gpuImage.error());
        if (magnitude == 0.0) {
            reference = mask;
            size_t covered = 0;
            for (uint8_t m : mask)
                covered += m;
            // The reference must show a good part of the decals, or the comparison means nothing.
            r.row("untranslated: covered pixels below 5% of the image (fraction missing)",
                  std::max(0.0, 0.05 - double(covered) / double(mask.size())), 0.0, mask.size(),
                  std::to_string(covered) + " pixels covered");
            continue;
        }
        size_t inter = 0, uni = 0;
        for (size_t i = 0; i < mask.size(); ++i) {
            inter += (mask[i] && reference[i]) ? 1 : 0;
            uni += (mask[i] || reference[i]) ? 1 : 0;
        }
        const double iou = uni == 0 ? 1.0 : double(inter) / double(uni);
        char label[96];
        std::snprintf(label, sizeof label, "coverage translated by %g: 1 - IoU vs untranslated", magnitude);
        StressRow& row =
            r.row(label, 1.0 - iou, 0.03, mask.size(), std::to_string(width) + "x" + std::to_string(height));
        row.informational = magnitude > 1e5; // the bound applies up to 1e5
    }
    return r;
}

} // namespace spatter::stress
