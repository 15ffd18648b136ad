// spatter-place SCENE: casts rays at a scene through the decal system and prints one JSON record
// per ray (JSON Lines), in input order.

#include "spatter/core/DecalType.hpp"
#include "spatter/core/DeformingProxy.hpp"
#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/ProxyInstances.hpp"
#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SceneLoader.hpp"
#include "spatter/core/VertexDeformation.hpp"
#include "spatter/placement/DecalPersistence.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/placement/RayParser.hpp"
#include "spatter/placement/ScenePosing.hpp"

#include "cli/Arguments.hpp"
#include "cli/DistinctFiles.hpp"
#include "cli/Numbers.hpp"
#include "cli/OutputCleanup.hpp"
#include "cli/PathChecks.hpp"
#include "cli/Tolerance.hpp"
#include "spatter/core/TextFields.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

const char* kUsage = R"(usage: spatter-place SCENE [--rays FILE|-] [--seed N] [--size W[,H]] [--max-angle DEG]
                     [--proxy render|auto|TOL] [--cache DIR] [--translate X,Y,Z] [--time T]
                     [--out FILE] [--save FILE] [--summary]

Casts rays at SCENE (builtin:gallery or a .gltf, .glb, .obj, .ply, .off or .stl file) through the
decal system and prints one JSON object per input ray, in input order (JSON Lines), on stdout or
into --out FILE.

Rays (--rays FILE, or standard input when FILE is - or the option is absent): one per line,
"ox oy oz dx dy dz" in world space; the direction need not be unit length. '#' starts a comment;
lines with nothing but blanks and comments are not rays. Rays are numbered from 0.

Records:
  {"ray":0,"status":"placed","reason":"","object":"name","object_id":0,"decal_id":123,
   "position":[x,y,z],"normal":[x,y,z],"tangent":[x,y,z],"bitangent":[x,y,z],"size":[w,h],
   "half_depth":d,"projection":[x,y,z],"max_angle_deg":a,"proxy_error_bound":h}
  with --time, a decal on a skinned or morphed object also carries "time":T and
   "anchor":{"triangle":i,"bary":[b0,b1,b2]}: the triangle of the object's render mesh it lies on and
   the point's barycentric coordinates there, with which spatter-render --time draws it at another
   pose
  {"ray":1,"status":"missed","reason":"..."}
  {"ray":2,"status":"rejected","reason":"..."}
status is placed, missed (the ray hits no decal receiver) or rejected (a line that cannot be
parsed, an invalid ray, a grazing hit, ...); non-placed records carry only ray, status and reason.
position is the decal centre in world space (the hit on the collision mesh; on a skinned or morphed
object the drawn surface under it); normal, tangent and
bitangent are the unit axes of its right-handed frame; the decal box is |x| <= w/2, |y| <= h/2,
|z| <= half_depth in that frame, its depth lines along projection (the unit axis the texture is
projected along: the reversed ray, turned to 85 degrees from the normal at most, so the decal lands
where the ray meets the drawn surface; the normal for a type projected along it). object_id is the object's 8-bit decal ID (0 for static
geometry), decal_id the decal's 32-bit random ID. proxy_error_bound is the collision mesh's error
bound h in world units (the render surface lies within h of the collision surface);
half_depth = s * h + 0.25 * max(w, h), where s is 1, or up to 2 for a decal turned to face the
drawn surface under the hit (its box reaches farther along that normal); on a skinned or morphed
object, where the decal lies on the drawn surface, half_depth = 0.25 * max(w, h).

Options:
  --seed N          seed of the decal IDs, rotations and objects' decal IDs, a whole number in
                    0..18446744073709551615 (default 1)
  --size W[,H]      decal width and height in world units (H defaults to W; default 2% of the
                    scene's bounding diagonal, so that decals fit a model of centimetres and one
                    of a hundred metres alike)
  --max-angle DEG   largest angle between the reversed ray and the surface normal, in (0, 90]
                    (default 80); steeper hits are rejected
  --proxy MODE      collision meshes: render (the render meshes as they are, h = 0; the
                    default), auto (the proxy builder's defaults: h target 0.5% of each object's
                    bounding diagonal), or a tolerance TOL for h, absolute (0.01) or relative to
                    each object's bounding diagonal (1%). With auto and TOL an object's authored
                    collider, where it has one, is its proxy (not on a skinned or morphed object,
                    whose proxy holds its bound over the poses); h is certified by the proxy
                    builder.
                    On a terminal, stderr shows the progress of the builds; the builder's
                    notes (a cache entry that could not be stored, a tolerance not met) go to
                    stderr as "spatter-place: note: ..." lines
  --cache DIR       with auto and TOL: reuse proxies stored in DIR and store new ones there, keyed
                    by a hash of the object's mesh, its collider and the proxy settings, and for
                    a skinned or morphed object of its skin and its sampled poses (a second run
                    simplifies and measures nothing; a corrupt entry is rebuilt). DIR is a
                    directory, or one that can be created. Without it nothing is cached
  --translate X,Y,Z move the whole scene by this offset before building the collision world (the
                    rays are given in the moved world)
  --time T          trace the scene posed at T seconds of its first animation: animated objects at
                    their transforms then, skinned and morphed ones deformed (their proxies hold
                    their bound over the animation); rays are given in the posed world. A scene
                    without animations stays in its rest pose, with a warning
  --out FILE        write the records to FILE instead of stdout
  --save FILE       write the decal system's final state to FILE (spatter/placement/
                    DecalPersistence.hpp): loadDecals gives it back to a decal system of the same
                    scene and proxies with a type named "spatter-place"
  --summary         print one JSON object on stderr: rays, placed, missed, rejected by reason,
                    render_triangles, proxy_triangles, proxies_built, proxies_cached,
                    proxies_shared (objects that took the proxy of an earlier object with the
                    same mesh and collider), proxy_seconds, trace_seconds, seconds
  --help            this text

An object whose transform single-precision ray tracing cannot use (singular or nearly so in float,
scaled beyond 2^+-25, more than 2^32 from the world's centre, or smaller than a few float steps at
its place) is left out (rays pass through it)
with a warning on stderr that names it and says why; the rest of the scene is traced as usual.

Numbers are decimal ("2", "-0.5", "1e-3"; no hexadecimal, no blanks). Each option is given at most
once. --out and --save name neither an input nor each other's file.

No area limits apply: every ray gets its own decal. Exit code 0 when the scene loads (whatever
happens to the rays), 1 when it cannot be loaded or a proxy, the collision world or the decal system
cannot be built, 2 on bad options (an option given twice or without its value, an output that is an
input) or on files that cannot be read or written; the files that are named are checked before the
work. A run that fails leaves no --out file of its own: one it began is removed.
)";

// The double nearest to the shortest decimal that reads back as `f`, so that floats print briefly.
double shortFloat(float f) {
    char buf[32];
    for (int precision = 6; precision <= 9; ++precision) {
        std::snprintf(buf, sizeof buf, "%.*g", precision, double(f));
        if (std::strtof(buf, nullptr) == f) break;
    }
    return std::strtod(buf, nullptr);
}

nlohmann::ordered_json vec3(const glm::vec3& v) {
    return {shortFloat(v.x), shortFloat(v.y), shortFloat(v.z)};
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in(s);
    while (std::getline(in, part, sep))
        parts.push_back(part);
    if (!s.empty() && s.back() == sep) parts.push_back("");
    return parts;
}

int usageError(const std::string& message) {
    std::cerr << "spatter-place: " << message << "\n(see spatter-place --help)\n";
    return 2;
}

// The command line.
struct Options {
    std::string scenePath, raysPath = "-", outPath, savePath, proxyMode = "render";
    uint64_t seed = 1;
    std::optional<glm::dvec2> decalSize; // default: decalSizeForScene
    float maxAngle = 80.0f;
    glm::dvec3 translate{0.0};
    std::optional<double> time;
    bool summary = false;
    spatter::ProxySettings proxySettings; // --proxy TOL and --cache
};

// Reads the option `a` (and its value from `args`) into `o`; an error message, or "" when it is one.
std::string parseOption(const std::string& a, spatter::cli::Arguments& args, Options& o) {
    auto value = [&](std::string& out) {
        const std::optional<std::string> v = args.value();
        if (v) out = *v;
        return v.has_value();
    };
    std::string v;
    if (a == "--summary") {
        o.summary = true;
    } else if (a == "--rays") {
        if (!value(o.raysPath) || o.raysPath.empty()) return "--rays needs a file";
    } else if (a == "--out") {
        if (!value(o.outPath) || o.outPath.empty()) return "--out needs a file";
    } else if (a == "--save") {
        if (!value(o.savePath) || o.savePath.empty()) return "--save needs a file";
    } else if (a == "--proxy") {
        if (!value(o.proxyMode) || (o.proxyMode != "render" && o.proxyMode != "auto" &&
                                    !spatter::cli::parseTolerance(o.proxyMode, o.proxySettings)))
            return "--proxy needs render, auto or a tolerance (0.01 or 1%)";
    } else if (a == "--cache") {
        if (!value(o.proxySettings.cacheDirectory) || o.proxySettings.cacheDirectory.empty())
            return "--cache needs a directory";
    } else if (a == "--seed") {
        if (!value(v) || !spatter::cli::parseWhole(v, UINT64_MAX, o.seed))
            return "--seed needs a whole number in 0.." + std::to_string(UINT64_MAX);
    } else if (a == "--size") {
        const std::vector<std::string> parts = value(v) ? split(v, ',') : std::vector<std::string>();
        double w = 0.0, h = 0.0;
        if (parts.empty() || parts.size() > 2 || !spatter::parseDecimal(parts[0], w) ||
            (parts.size() == 2 && !spatter::parseDecimal(parts[1], h)))
            return "--size needs W or W,H";
        o.decalSize = glm::dvec2(w, parts.size() == 1 ? w : h);
    } else if (a == "--max-angle") {
        double d = 0.0;
        if (!value(v) || !spatter::parseDecimal(v, d)) return "--max-angle needs a number of degrees";
        o.maxAngle = float(d);
    } else if (a == "--translate") {
        const std::vector<std::string> parts = value(v) ? split(v, ',') : std::vector<std::string>();
        if (parts.size() != 3 || !spatter::parseDecimal(parts[0], o.translate.x) ||
            !spatter::parseDecimal(parts[1], o.translate.y) ||
            !spatter::parseDecimal(parts[2], o.translate.z))
            return "--translate needs three finite numbers X,Y,Z";
    } else if (a == "--time") {
        double t = 0.0;
        if (!value(v) || !spatter::parseDecimal(v, t)) return "--time needs a finite number of seconds";
        o.time = t;
    } else {
        return "unknown option " + a;
    }
    return "";
}

// Reads argv into `o`. Returns -1 to go on, or the exit code: 0 after --help, 2 after a usage error.
int parseOptions(int argc, char** argv, Options& o) {
    spatter::cli::Arguments args(argc, argv);
    while (args.more()) {
        const spatter::Result<std::string> a = args.next();
        if (!a) return usageError(a.error());
        if (*a == "--help" || *a == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        }
        if (a->size() > 1 && (*a)[0] == '-') {
            if (const std::string error = parseOption(*a, args, o); !error.empty()) return usageError(error);
        } else if (o.scenePath.empty()) {
            o.scenePath = *a;
        } else {
            return usageError("more than one scene given");
        }
    }
    if (o.scenePath.empty()) return usageError("no scene given");
    if (!o.proxySettings.cacheDirectory.empty() && o.proxyMode == "render")
        return usageError("--cache needs --proxy auto or TOL");
    return -1;
}

// The files the options name, before any work: the rays can be read, the outputs can be written and
// are neither an input nor each other, the cache is a usable directory.
spatter::Status checkFiles(const Options& o) {
    using spatter::cli::NamedPath;
    const NamedPath scene{"SCENE", o.scenePath}, rays{"--rays", o.raysPath}, out{"--out", o.outPath},
        save{"--save", o.savePath}, cache{"--cache", o.proxySettings.cacheDirectory};
    if (spatter::Status s = spatter::cli::distinctFiles({out, save}, {scene, rays}); !s) return s;
    if (rays.path != "-")
        if (spatter::Status s = spatter::cli::readableFile(rays); !s) return s;
    for (const NamedPath& output : {out, save})
        if (!output.path.empty())
            if (spatter::Status s = spatter::cli::creatableFile(output); !s) return s;
    if (!cache.path.empty()) return spatter::cli::usableDirectory(cache);
    return {};
}

// The render triangle a decal on a deforming object lies on at time t, and its barycentric
// coordinates there, as spatter-render --time reads them ("anchor").
class Anchors {
public:
    Anchors(const spatter::Scene& scene, double t) : scene_(scene), evaluator_(scene) {
        evaluator_.evaluate(0, t);
    }

    nlohmann::ordered_json of(const spatter::Decal& d) {
        auto it = posed_.find(d.object);
        if (it == posed_.end()) it = posed_.emplace(d.object, posedMesh(d.object)).first;
        const auto& [mesh, query] = it->second;
        const std::optional<spatter::ClosestPoint> c = query->closest(glm::dvec3(d.center));
        if (!c) return nullptr;
        const uint32_t* k = &mesh.indices[3 * size_t(c->triangle)];
        const glm::dvec3 b =
            spatter::barycentric(c->point, glm::dvec3(mesh.positions[k[0]]), glm::dvec3(mesh.positions[k[1]]),
                                 glm::dvec3(mesh.positions[k[2]]));
        return {{"triangle", c->triangle}, {"bary", {b.x, b.y, b.z}}};
    }

private:
    using Posed = std::pair<spatter::Mesh, std::shared_ptr<spatter::ClosestPointQuery>>;
    Posed posedMesh(uint32_t object) {
        spatter::Mesh m = spatter::withPositions(*scene_.objects[object].mesh,
                                                 spatter::posedPositions(scene_, object, evaluator_));
        auto query =
            std::make_shared<spatter::ClosestPointQuery>(spatter::ClosestPointQuery::create(m).value());
        return {std::move(m), std::move(query)};
    }

    const spatter::Scene& scene_;
    spatter::SceneEvaluator evaluator_;
    std::map<uint32_t, Posed> posed_;
};

} // namespace

int main(int argc, char** argv) {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();

    Options options;
    if (const int exitCode = parseOptions(argc, argv, options); exitCode >= 0) return exitCode;
    if (spatter::Status s = checkFiles(options); !s) return usageError(s.error());
    const std::string &scenePath = options.scenePath, &raysPath = options.raysPath,
                      &outPath = options.outPath, &savePath = options.savePath,
                      &proxyMode = options.proxyMode;
    const uint64_t seed = options.seed;
    const std::optional<glm::dvec2> decalSize = options.decalSize;
    const float maxAngle = options.maxAngle;
    const glm::dvec3 translate = options.translate;
    const std::optional<double> time = options.time;
    const bool summary = options.summary;
    const spatter::ProxySettings& proxySettings = options.proxySettings;
    spatter::cli::OutputCleanup cleanup; // the outputs of a run that fails

    spatter::Result<spatter::Scene> scene = spatter::loadScene(scenePath);
    if (!scene) {
        std::cerr << "spatter-place: " << scene.error() << "\n";
        return 1;
    }
    for (const std::string& w : scene->warnings)
        std::cerr << "spatter-place: warning: " << w << "\n";
    scene->translate(translate);

    std::vector<std::shared_ptr<const spatter::Proxy>> proxies;
    size_t proxiesBuilt = 0, proxiesCached = 0, proxiesShared = 0;
    const Clock::time_point proxyStart = Clock::now();
    if (proxyMode != "render") {
        proxies.resize(scene->objects.size());
        const bool terminal = isatty(fileno(stderr)) != 0;
        // One build for the objects that share a mesh; progress: the fraction of the triangles of
        // the meshes built.
        const std::vector<size_t> sources = spatter::proxySources(scene.value());
        double totalTriangles = 0.0, doneTriangles = 0.0;
        for (size_t i = 0; i < scene->objects.size(); ++i)
            if (scene->objects[i].receivesDecals && sources[i] == i)
                totalTriangles += double(scene->objects[i].mesh->triangleCount());
        for (size_t i = 0; i < scene->objects.size(); ++i) {
            const spatter::SceneObject& o = scene->objects[i];
            if (!o.receivesDecals) continue;
            if (sources[i] != i) {
                proxies[i] = proxies[sources[i]];
                ++proxiesShared;
                continue;
            }
            // On a terminal: one line, rewritten in place, cleared when the builds are done.
            spatter::ProgressCallback progress;
            if (terminal)
                progress = [&](float fraction, const char* stage) {
                    const double whole =
                        (doneTriangles + double(fraction) * double(o.mesh->triangleCount())) / totalTriangles;
                    std::fprintf(stderr, "\rspatter-place: proxies %3d%% (%zu/%zu '%.40s': %s)\033[K",
                                 int(100.0 * whole), i + 1, scene->objects.size(), o.name.c_str(), stage);
                    return true;
                };
            spatter::Result<spatter::Proxy> proxy =
                spatter::buildObjectProxy(scene.value(), i, proxySettings, progress);
            if (!proxy) {
                if (terminal) std::fputs("\r\033[K", stderr);
                std::cerr << "spatter-place: proxy of object '" << o.name << "': " << proxy.error() << "\n";
                return 1;
            }
            doneTriangles += double(o.mesh->triangleCount());
            if (terminal && !proxy->notes.empty()) std::fputs("\r\033[K", stderr);
            for (const std::string& note : proxy->notes) // a cache that could not be written, among others
                std::cerr << "spatter-place: note: proxy of object '" << o.name << "': " << note << "\n";
            proxiesBuilt += proxy->cached ? 0 : 1;
            proxiesCached += proxy->cached ? 1 : 0;
            proxies[i] = spatter::shareProxy(std::move(proxy).value());
        }
        if (terminal) std::fputs("\r\033[K", stderr);
    }
    const double proxySeconds = std::chrono::duration<double>(Clock::now() - proxyStart).count();
    spatter::WorldSettings worldSettings;
    worldSettings.useColliders = false; // --proxy render: the render meshes as they are
    spatter::Result<spatter::CollisionWorld> world =
        spatter::CollisionWorld::build(scene.value(), proxies, worldSettings);
    if (!world) {
        std::cerr << "spatter-place: " << world.error() << "\n";
        return 1;
    }
    for (const std::string& warning : world->warnings())
        std::cerr << "spatter-place: warning: " << warning << "\n";
    spatter::DecalSettings settings;
    settings.seed = seed;
    settings.maxPerCell = std::numeric_limits<uint32_t>::max();
    settings.budget = std::numeric_limits<uint32_t>::max();
    settings.maxPerObject = std::numeric_limits<uint32_t>::max();
    spatter::Result<spatter::DecalSystem> system =
        spatter::DecalSystem::create(std::move(world).value(), settings);
    if (!system) {
        std::cerr << "spatter-place: " << system.error() << "\n";
        return 1;
    }
    if (time) {
        if (scene->animation.animations.empty())
            std::cerr
                << "spatter-place: warning: --time: the scene has no animation; traced in its rest pose\n";
        else
            for (const std::string& refused :
                 spatter::poseDecalSystem(system.value(), scene.value(), {*time, translate}))
                std::cerr << "spatter-place: warning: " << refused << "\n";
    }
    std::optional<Anchors> anchors;
    if (time && !scene->animation.animations.empty()) anchors.emplace(scene.value(), *time);

    spatter::DecalType type;
    type.name = "spatter-place";
    type.size = decalSize ? glm::vec2(*decalSize)
                          : spatter::decalSizeForScene(glm::length(scene->worldBounds().extent()));
    type.maxAngleDeg = maxAngle;
    spatter::Result<uint16_t> typeIndex = system->registerType(type);
    if (!typeIndex) return usageError(typeIndex.error());

    // Read every ray line.
    std::ifstream file;
    std::istream* in = &std::cin;
    if (raysPath != "-") {
        file.open(raysPath);
        if (!file) return usageError("cannot read " + raysPath);
        in = &file;
    }
    std::vector<spatter::RayLine> lines;
    std::vector<spatter::Ray> rays;
    size_t lineNumber = 0;
    for (std::string raw; std::getline(*in, raw);) {
        spatter::RayLine p = spatter::parseRayLine(raw, ++lineNumber);
        if (!p.isRay) continue;
        if (p.ok) rays.push_back(p.ray);
        lines.push_back(std::move(p));
    }

    std::ofstream outFile;
    std::ostream* out = &std::cout;
    if (!outPath.empty()) {
        cleanup.writing(outPath);
        outFile.open(outPath);
        if (!outFile) return usageError("cannot write " + outPath);
        out = &outFile;
    }

    const Clock::time_point traceStart = Clock::now();
    std::vector<spatter::SpawnResult> results;
    system->spawnBatch(rays, typeIndex.value(), results);
    const double traceSeconds = std::chrono::duration<double>(Clock::now() - traceStart).count();

    size_t placed = 0, missed = 0, unparseable = 0;
    size_t rejectedBy[spatter::kSpawnStatusCount] = {};
    size_t next = 0;
    for (size_t r = 0; r < lines.size(); ++r) {
        nlohmann::ordered_json rec;
        rec["ray"] = r;
        if (!lines[r].ok) {
            unparseable++;
            rec["status"] = "rejected";
            rec["reason"] = "cannot parse the ray: " + lines[r].error;
        } else {
            const spatter::SpawnResult& res = results[next++];
            if (res.placed()) {
                placed++;
                const spatter::Decal& d = *system->get(res.handle);
                const spatter::WorldDecal w = system->worldBox(d);
                rec["status"] = "placed";
                rec["reason"] = "";
                rec["object"] = system->world().object(d.object)->name;
                rec["object_id"] = d.objectId;
                rec["decal_id"] = d.id;
                rec["position"] = {w.center.x, w.center.y, w.center.z};
                rec["normal"] = vec3(w.frame.normal);
                rec["tangent"] = vec3(w.frame.tangent);
                rec["bitangent"] = vec3(w.frame.bitangent);
                rec["size"] = {shortFloat(w.size.x), shortFloat(w.size.y)};
                rec["half_depth"] = shortFloat(w.halfDepth);
                rec["projection"] = vec3(w.projection);
                rec["max_angle_deg"] = shortFloat(maxAngle);
                rec["proxy_error_bound"] = system->world().worldErrorBound(d.object);
                if (anchors && system->world().deforms(d.object)) {
                    rec["time"] = *time;
                    rec["anchor"] = anchors->of(d);
                }
            } else if (res.status == spatter::SpawnStatus::Missed) {
                missed++;
                rec["status"] = "missed";
                rec["reason"] = res.reason;
            } else {
                rejectedBy[size_t(res.status)]++;
                rec["status"] = "rejected";
                rec["reason"] = std::string(spatter::toString(res.status)) + ": " + res.reason;
            }
        }
        *out << rec.dump() << '\n';
    }
    out->flush();
    if (!*out) return usageError("cannot write " + (outPath.empty() ? std::string("stdout") : outPath));
    if (!savePath.empty()) // written whole or not at all (saveDecalsToFile)
        if (spatter::Status s = spatter::saveDecalsToFile(system.value(), savePath); !s)
            return usageError(s.error());

    if (summary) {
        nlohmann::ordered_json s;
        s["rays"] = lines.size();
        s["placed"] = placed;
        s["missed"] = missed;
        nlohmann::ordered_json rejected;
        rejected["unparseable"] = unparseable;
        for (size_t k = 0; k < spatter::kSpawnStatusCount; ++k) {
            const auto status = spatter::SpawnStatus(k);
            if (status == spatter::SpawnStatus::Placed || status == spatter::SpawnStatus::Missed) continue;
            rejected[spatter::toString(status)] = rejectedBy[k];
        }
        s["rejected"] = std::move(rejected);
        s["render_triangles"] = scene->triangleCount();
        s["proxy_triangles"] = system->world().triangleCount();
        s["proxies_built"] = proxiesBuilt;
        s["proxies_cached"] = proxiesCached;
        s["proxies_shared"] = proxiesShared;
        s["proxy_seconds"] = proxySeconds;
        s["trace_seconds"] = traceSeconds;
        s["seconds"] = std::chrono::duration<double>(Clock::now() - start).count();
        std::cerr << s.dump() << "\n";
    }
    cleanup.keep();
    return 0;
}
