// Non-finite and denormal input: NaN, +-Inf and denormal values in every argument of the placement
// API (spawn, spawnBatch, spawnAt, spawnAttached, setTransform, registerType, update, the settings of
// create, CollisionWorld::build and setTransform) and of the renderer (setObjectTransform, setScene,
// setLight, setDecals, the camera). Each must be rejected with a reason and leave the state unchanged:
// the same decals, stats (but the rejection counter), transforms and clock, and the next random number
// (the next decal equals a control system's); the renderer's next image equals the one before.
//
// Denormal means a value too small to be normalised or inverted where it is a magnitude: a direction
// or normal whose every component is zero or denormal, a size, a time, an angle, a cell size, a
// transform scale, a field of view or a near plane. A denormal coordinate of a position is a point
// next to the origin; it is accepted and must act exactly like the zero it rounds to.

#include "StressCase.hpp"
#include "StressSupport.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/Renderer.hpp"

#include <cfloat>
#include <cmath>
#include <cstring>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <map>

namespace spatter::stress {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDenormal = 4e-320;
constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();
constexpr float kInff = std::numeric_limits<float>::infinity();
constexpr float kDenormalf = 1e-40f;

// Plane, and a dynamic cube above it.
Scene targetScene() {
    Scene s = planeScene(5.0);
    s.objects.push_back(
        makeSceneObject("cube", makeUnitCube(), glm::translate(glm::dmat4(1.0), glm::dvec3(1, 1, 0)), true));
    return s;
}

const Ray kGood{{-2.0, 3.0, 2.0}, {0.3, -1.0, -0.4}};

Result<DecalSystem> makeSystem(const Scene& scene, uint64_t seed) {
    Result<DecalSystem> sys = DecalSystem::create(scene, unlimitedSettings(seed));
    if (!sys) return sys;
    DecalType t = makeType("hole", 0.2f, 80.0f, 0.2f);
    t.lifetime = 10.0f;
    sys->registerType(t);
    // Some history: decals on the plane and on the cube, and a clock.
    sys->spawn(Ray{{1.0, 3.0, 0.0}, {0.0, -1.0, 0.0}}, 0);
    sys->spawn(Ray{{-1.0, 3.0, 1.0}, {0.1, -1.0, 0.0}}, 0);
    sys->update(0.5);
    return sys;
}

bool sameDecal(const Decal& a, const Decal& b) {
    return a.packedFrame == b.packedFrame && a.center == b.center && a.size == b.size &&
           a.halfDepth == b.halfDepth && a.object == b.object && a.objectId == b.objectId && a.id == b.id &&
           a.type == b.type && a.spawnTime == b.spawnTime && a.opacity == b.opacity;
}

bool sameDecals(const std::vector<Decal>& a, const std::vector<Decal>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (!sameDecal(a[i], b[i])) return false;
    return true;
}

// What a rejected call answered.
struct Answer {
    bool rejected = false;
    std::string reason;
};

Answer answer(const SpawnResult& r) {
    return {!r.placed() && r.status != SpawnStatus::Missed && r.status != SpawnStatus::GrazingAngle,
            r.reason};
}
Answer answer(const Status& s) {
    return {!s.ok(), s.error()};
}
template <class T> Answer answer(const Result<T>& r) {
    return {!r.ok(), r.error()};
}

struct BadCall {
    std::string api;
    std::string what;
    std::function<Answer(DecalSystem&)> call;
};

struct ApiTally {
    size_t calls = 0, accepted = 0, silent = 0, changed = 0;
};

// Runs `bad` on a fresh system and checks rejection, reason and unchanged state against a control.
void check(const BadCall& bad, const Scene& scene, uint64_t seed, std::map<std::string, ApiTally>& tallies,
           StressResult& r) {
    ApiTally& t = tallies[bad.api];
    t.calls++;
    Result<DecalSystem> sys = makeSystem(scene, seed);
    Result<DecalSystem> control = makeSystem(scene, seed);
    if (!sys || !control) {
        t.changed++;
        r.failure(bad.api + ": cannot build the system");
        return;
    }
    const DecalStats before = sys->stats();
    const Answer a = bad.call(sys.value());
    if (!a.rejected) {
        t.accepted++;
        r.failure(bad.api + " accepted " + bad.what);
    } else if (a.reason.empty()) {
        t.silent++;
        r.failure(bad.api + " rejected " + bad.what + " without a reason");
    }
    DecalStats after = sys->stats();
    after.rejected = before.rejected; // the rejection counter may move
    bool same = after == before && sameDecals(sys->decals(), control->decals()) &&
                sys->time() == control->time() && sys->typeCount() == control->typeCount();
    for (uint32_t o = 0; o < scene.objects.size(); ++o)
        same = same && sys->world().object(o)->transform == control->world().object(o)->transform;
    // No random number was drawn: the next decal is the control's.
    const SpawnResult next = sys->spawn(kGood, 0), expected = control->spawn(kGood, 0);
    same = same && next.placed() && expected.placed() &&
           sameDecal(*sys->get(next.handle), *control->get(expected.handle));
    if (!same) {
        t.changed++;
        r.failure(bad.api + " changed the state on " + bad.what);
    }
}

std::vector<BadCall> placementCalls() {
    std::vector<BadCall> calls;
    const std::vector<std::pair<std::string, double>> values = {
        {"NaN", kNaN}, {"+Inf", kInf}, {"-Inf", -kInf}};
    // spawn: every component of origin and direction, tnear and tfar.
    for (const auto& [name, v] : values) {
        for (int k = 0; k < 3; ++k) {
            Ray o = kGood, d = kGood;
            o.origin[k] = v;
            d.direction[k] = v;
            calls.push_back({"spawn", "origin[" + std::to_string(k) + "] = " + name,
                             [o](DecalSystem& s) { return answer(s.spawn(o, 0)); }});
            calls.push_back({"spawn", "direction[" + std::to_string(k) + "] = " + name,
                             [d](DecalSystem& s) { return answer(s.spawn(d, 0)); }});
        }
        Ray n = kGood, f = kGood;
        n.tnear = v;
        f.tfar = v == kInf ? -kInf : v;
        calls.push_back({"spawn", "tnear = " + name, [n](DecalSystem& s) { return answer(s.spawn(n, 0)); }});
        calls.push_back({"spawn", "tfar = " + name, [f](DecalSystem& s) { return answer(s.spawn(f, 0)); }});
    }
    for (const glm::dvec3& d : {glm::dvec3(0.0), glm::dvec3(kDenormal, -kDenormal, 0.0),
                                glm::dvec3(0.0, -std::numeric_limits<double>::denorm_min(), 0.0),
                                glm::dvec3(1e300, -1e300, 1e300)}) {
        Ray ray = kGood;
        ray.direction = d;
        calls.push_back(
            {"spawn", "direction " + vec(d), [ray](DecalSystem& s) { return answer(s.spawn(ray, 0)); }});
    }
    calls.push_back(
        {"spawn", "type 7 (not registered)", [](DecalSystem& s) { return answer(s.spawn(kGood, 7)); }});

    // spawnBatch: a batch of nothing but bad rays.
    calls.push_back({"spawnBatch", "NaN, Inf and denormal rays", [](DecalSystem& s) {
                         Ray a = kGood, b = kGood, c = kGood;
                         a.origin.x = kNaN;
                         b.direction.y = kInf;
                         c.direction = glm::dvec3(kDenormal);
                         std::vector<SpawnResult> rs;
                         s.spawnBatch({a, b, c}, 0, rs);
                         Answer all{rs.size() == 3, rs.empty() ? "" : rs[0].reason};
                         for (const SpawnResult& x : rs) {
                             const Answer one = answer(x);
                             all.rejected = all.rejected && one.rejected;
                             if (one.reason.empty()) all.reason.clear();
                         }
                         return all;
                     }});

    // spawnAt: position and normal.
    const glm::dvec3 at(0.5, 0.0, 0.5), up(0.0, 1.0, 0.0);
    for (const auto& [name, v] : values)
        for (int k = 0; k < 3; ++k) {
            glm::dvec3 p = at, n = up;
            p[k] = v;
            n[k] = v;
            calls.push_back({"spawnAt", "position[" + std::to_string(k) + "] = " + name,
                             [p, up](DecalSystem& s) { return answer(s.spawnAt(p, up, 0)); }});
            calls.push_back({"spawnAt", "normal[" + std::to_string(k) + "] = " + name,
                             [at, n](DecalSystem& s) { return answer(s.spawnAt(at, n, 0)); }});
        }
    for (const glm::dvec3& n :
         {glm::dvec3(0.0), glm::dvec3(0.0, kDenormal, 0.0), glm::dvec3(kDenormal, kDenormal, -kDenormal)})
        calls.push_back(
            {"spawnAt", "normal " + vec(n), [at, n](DecalSystem& s) { return answer(s.spawnAt(at, n, 0)); }});

    // spawnAttached: object, local position and normal (float).
    const std::vector<std::pair<std::string, float>> fvalues = {
        {"NaN", kNaNf}, {"+Inf", kInff}, {"-Inf", -kInff}};
    const glm::vec3 lp(0.0f, 0.5f, 0.0f), ln(0.0f, 1.0f, 0.0f);
    for (const auto& [name, v] : fvalues)
        for (int k = 0; k < 3; ++k) {
            glm::vec3 p = lp, n = ln;
            p[k] = v;
            n[k] = v;
            calls.push_back({"spawnAttached", "position[" + std::to_string(k) + "] = " + name,
                             [p, ln](DecalSystem& s) { return answer(s.spawnAttached(1, p, ln, 0)); }});
            calls.push_back({"spawnAttached", "normal[" + std::to_string(k) + "] = " + name,
                             [lp, n](DecalSystem& s) { return answer(s.spawnAttached(1, lp, n, 0)); }});
        }
    for (const glm::vec3& n : {glm::vec3(0.0f), glm::vec3(0.0f, kDenormalf, 0.0f),
                               glm::vec3(std::numeric_limits<float>::denorm_min(), -kDenormalf, kDenormalf)})
        calls.push_back({"spawnAttached", "normal " + vec(glm::dvec3(n)),
                         [lp, n](DecalSystem& s) { return answer(s.spawnAttached(1, lp, n, 0)); }});
    calls.push_back({"spawnAttached", "object 99 (out of range)",
                     [lp, ln](DecalSystem& s) { return answer(s.spawnAttached(99, lp, ln, 0)); }});

    // setTransform of the dynamic cube (object 1).
    auto transforms = [] {
        std::vector<std::pair<std::string, glm::dmat4>> m;
        const glm::dmat4 base = glm::translate(glm::dmat4(1.0), glm::dvec3(1, 1, 0));
        for (const auto& [name, v] :
             std::vector<std::pair<std::string, double>>{{"NaN", kNaN}, {"+Inf", kInf}})
            for (int c = 0; c < 4; ++c) {
                glm::dmat4 x = base;
                x[c][c == 3 ? 0 : c] = v;
                m.push_back({name + " in column " + std::to_string(c), x});
            }
        glm::dmat4 projective = base;
        projective[0][3] = 0.5;
        m.push_back({"projective bottom row", projective});
        return m;
    }();
    for (const auto& [name, m] : transforms) {
        const glm::dmat4 x = m;
        calls.push_back({"setTransform", name, [x](DecalSystem& s) { return answer(s.setTransform(1, x)); }});
    }
    calls.push_back({"setTransform", "static object 0",
                     [](DecalSystem& s) { return answer(s.setTransform(0, glm::dmat4(1.0))); }});
    calls.push_back({"setTransform", "object 99 (out of range)",
                     [](DecalSystem& s) { return answer(s.setTransform(99, glm::dmat4(1.0))); }});

    // registerType: every numeric field.
    auto typeWith = [](const char* name, const std::function<void(DecalType&)>& change) {
        DecalType t = makeType(name, 0.2f, 80.0f);
        change(t);
        return t;
    };
    const std::vector<std::pair<std::string, float>> typeValues = {
        {"NaN", kNaNf}, {"+Inf", kInff}, {"-Inf", -kInff}, {"denormal", kDenormalf}};
    for (const auto& [name, v] : typeValues) {
        const float x = v;
        const std::vector<std::pair<std::string, DecalType>> types = {
            {"size.x = " + name, typeWith("a", [x](DecalType& t) { t.size.x = x; })},
            {"size.y = " + name, typeWith("b", [x](DecalType& t) { t.size.y = x; })},
            {"sizeJitter = " + name, typeWith("c", [x](DecalType& t) { t.sizeJitter = x; })},
            {"maxAngleDeg = " + name, typeWith("d", [x](DecalType& t) { t.maxAngleDeg = x; })},
            {"lifetime = " + name, typeWith("e", [x](DecalType& t) { t.lifetime = x; })},
            {"fadeOutTime = " + name, typeWith("f", [x](DecalType& t) { t.fadeOutTime = x; })},
            {"halfDepth = " + name, typeWith("g", [x](DecalType& t) { t.halfDepth = x; })},
        };
        for (const auto& [what, t] : types) {
            const DecalType type = t;
            calls.push_back(
                {"registerType", what, [type](DecalSystem& s) { return answer(s.registerType(type)); }});
        }
        if (std::isfinite(v) || std::isnan(v)) {
            if (name != "denormal") {
                const DecalType tint = typeWith("h", [x](DecalType& t) { t.tint.y = x; });
                const DecalType rough = typeWith("i", [x](DecalType& t) { t.roughness = x; });
                calls.push_back({"registerType", "tint.y = " + name,
                                 [tint](DecalSystem& s) { return answer(s.registerType(tint)); }});
                calls.push_back({"registerType", "roughness = " + name,
                                 [rough](DecalSystem& s) { return answer(s.registerType(rough)); }});
            }
        } else {
            const DecalType tint = typeWith("h", [x](DecalType& t) { t.tint.w = x; });
            const DecalType rough = typeWith("i", [x](DecalType& t) { t.roughness = x; });
            calls.push_back({"registerType", "tint.w = " + name,
                             [tint](DecalSystem& s) { return answer(s.registerType(tint)); }});
            calls.push_back({"registerType", "roughness = " + name,
                             [rough](DecalSystem& s) { return answer(s.registerType(rough)); }});
        }
    }

    // update.
    for (double dt : {kNaN, kInf, -kInf, -1.0, kDenormal, std::numeric_limits<double>::denorm_min()})
        calls.push_back({"update", "dt = " + num(dt), [dt](DecalSystem& s) { return answer(s.update(dt)); }});
    return calls;
}

// Settings and scenes that create or build must refuse.
void checkConstruction(StressResult& r, std::map<std::string, ApiTally>& tallies, uint64_t seed) {
    const Scene scene = targetScene();
    auto expectFailure = [&](const std::string& api, const std::string& what, const Answer& a) {
        ApiTally& t = tallies[api];
        t.calls++;
        if (!a.rejected) {
            t.accepted++;
            r.failure(api + " accepted " + what);
        } else if (a.reason.empty()) {
            t.silent++;
            r.failure(api + " rejected " + what + " without a reason");
        }
    };
    const std::vector<std::pair<std::string, std::function<void(DecalSettings&)>>> settings = {
        {"cellSize = NaN", [](DecalSettings& s) { s.cellSize = kNaNf; }},
        {"cellSize = Inf", [](DecalSettings& s) { s.cellSize = kInff; }},
        {"cellSize = denormal", [](DecalSettings& s) { s.cellSize = kDenormalf; }},
        {"depthMargin = NaN", [](DecalSettings& s) { s.depthMargin = kNaNf; }},
        {"depthMargin = Inf", [](DecalSettings& s) { s.depthMargin = kInff; }},
        {"depthMargin = denormal", [](DecalSettings& s) { s.depthMargin = kDenormalf; }},
        {"idSeparation = NaN", [](DecalSettings& s) { s.idSeparation = kNaN; }},
        {"idSeparation = Inf", [](DecalSettings& s) { s.idSeparation = kInf; }},
        {"idSeparation = denormal", [](DecalSettings& s) { s.idSeparation = kDenormal; }},
    };
    for (const auto& [what, change] : settings) {
        DecalSettings s = unlimitedSettings(seed);
        change(s);
        expectFailure("DecalSystem::create", what, answer(DecalSystem::create(scene, s)));
    }
    // Scenes with a bad vertex, normal or transform, and bad proxies.
    const std::vector<std::pair<std::string, std::function<void(Scene&)>>> scenes = {
        {"NaN vertex", [](Scene& s) { s.objects[0].editMesh().positions[3].y = kNaNf; }},
        {"+Inf vertex", [](Scene& s) { s.objects[1].editMesh().positions[0].x = kInff; }},
        {"-Inf vertex", [](Scene& s) { s.objects[0].editMesh().positions[0].z = -kInff; }},
        {"NaN normal", [](Scene& s) { s.objects[1].editMesh().normals[2].x = kNaNf; }},
        {"NaN transform", [](Scene& s) { s.objects[0].transform[3][1] = kNaN; }},
        {"Inf transform", [](Scene& s) { s.objects[1].transform[0][0] = kInf; }},
        {"projective transform", [](Scene& s) { s.objects[1].transform[2][3] = 0.5; }},
        {"index past the vertex count", [](Scene& s) { s.objects[0].editMesh().indices[4] = 1000000; }},
    };
    for (const auto& [what, change] : scenes) {
        Scene s = scene;
        change(s);
        expectFailure("CollisionWorld::build", what, answer(CollisionWorld::build(s)));
    }
    const std::vector<std::pair<std::string, std::function<void(Proxy&)>>> proxies = {
        {"proxy with a NaN vertex", [](Proxy& p) { p.mesh.positions[0].x = kNaNf; }},
        {"proxy with an Inf vertex", [](Proxy& p) { p.mesh.positions[1].y = kInff; }},
        {"proxy with a NaN error bound", [](Proxy& p) { p.errorBound = kNaN; }},
        {"proxy with an Inf error bound", [](Proxy& p) { p.errorBound = kInf; }},
    };
    for (const auto& [what, change] : proxies) {
        std::vector<std::shared_ptr<const Proxy>> list(scene.objects.size());
        Proxy p;
        p.mesh = *scene.objects[1].mesh;
        change(p);
        list[1] = shareProxy(p);
        expectFailure("CollisionWorld::build", what, answer(CollisionWorld::build(scene, list)));
    }
    // CollisionWorld::setTransform directly.
    Result<CollisionWorld> world = CollisionWorld::build(scene);
    if (world) {
        const glm::dmat4 before = world->object(1)->transform;
        for (const glm::dmat4& m : {glm::dmat4(kNaN), glm::dmat4(kInf), glm::dmat4(0.0)}) {
            expectFailure("CollisionWorld::setTransform", "a NaN, Inf or projective matrix",
                          answer(world->setTransform(1, m)));
        }
        if (world->object(1)->transform != before) {
            tallies["CollisionWorld::setTransform"].changed++;
            r.failure("CollisionWorld::setTransform changed the transform on bad input");
        }
    }
}

// Denormal coordinates of a position are accepted and act exactly like zero.
size_t denormalCoordinates(const Scene& scene, uint64_t seed, StressResult& r) {
    size_t differing = 0;
    Result<DecalSystem> a = makeSystem(scene, seed), b = makeSystem(scene, seed);
    if (!a || !b) return 1;
    Ray zero{{0.0, 3.0, 0.5}, {0.2, -1.0, 0.1}}, tiny = zero;
    tiny.origin.x = kDenormal;
    const SpawnResult ra = a->spawn(zero, 0), rb = b->spawn(tiny, 0);
    if (!ra.placed() || !rb.placed() || !sameDecal(*a->get(ra.handle), *b->get(rb.handle))) {
        differing++;
        r.failure("a ray from x = 4e-320 placed differently from x = 0");
    }
    const SpawnResult aa = a->spawnAttached(1, glm::vec3(0.0f, 0.5f, 0.0f), glm::vec3(0, 1, 0), 0);
    const SpawnResult ab =
        b->spawnAttached(1, glm::vec3(kDenormalf, 0.5f, 0.0f), glm::vec3(kDenormalf, 1, 0), 0);
    if (!aa.placed() || !ab.placed() || !sameDecal(*a->get(aa.handle), *b->get(ab.handle))) {
        // The position and the normal carry the denormal; only the centre may differ, by it.
        const Decal* da = a->get(aa.handle);
        const Decal* db = b->get(ab.handle);
        if (!da || !db || glm::length(glm::dvec3(da->center) - glm::dvec3(db->center)) > 1e-30 ||
            frameErrorOf(db->frame()) > 1e-6) {
            differing++;
            r.failure("spawnAttached with denormal coordinates differs from zero");
        }
    }
    return differing;
}

// Transforms that are finite and affine but singular or nearly so in single precision are taken: the
// object leaves the trace with a reason, its decals stay, shots pass through it, and its first
// transform brings it back. Returns the transforms that broke one of these.
size_t untracedTransforms(const Scene& scene, uint64_t seed, StressResult& r) {
    const glm::dmat4 base = scene.objects[1].transform;
    glm::dmat4 flat = base, near = base;
    flat[1] = flat[0];
    near[1] = near[0] + glm::dvec4(0.0, 1e-9, 0.0, 0.0);
    const std::vector<std::pair<std::string, glm::dmat4>> singular = {
        {"zero linear part", glm::dmat4(glm::dvec4(0.0), glm::dvec4(0.0), glm::dvec4(0.0), base[3])},
        {"denormal scale", glm::scale(base, glm::dvec3(kDenormal))},
        {"scale 1e-120 (determinant underflows)", glm::scale(base, glm::dvec3(1e-120))},
        {"scale 1e20", glm::scale(base, glm::dvec3(1e20))},
        {"rank 2", flat},
        {"columns equal in float", near}};
    const Ray atCube{{1.0, 5.0, 0.0}, {0.0, -1.0, 0.0}};
    size_t broken = 0;
    for (const auto& [what, m] : singular) {
        Result<DecalSystem> sys = makeSystem(scene, seed);
        if (!sys) return singular.size();
        const size_t decals = sys->decals().size();
        const Result<TransformUpdate> u = sys->setTransform(1, m);
        const std::optional<Hit> through = sys->world().intersect(atCube);
        const bool out = u && !u->traced && !u->warning.empty() && sys->decals().size() == decals &&
                         through && through->object == 0;
        const Result<TransformUpdate> back = sys->setTransform(1, base);
        const std::optional<Hit> again = sys->world().intersect(atCube);
        if (out && back && back->traced && again && again->object == 1) continue;
        broken++;
        r.failure("setTransform with " + what + ": not taken out of the trace and back as documented");
    }
    return broken;
}

} // namespace

StressResult runNonFinitePlacement(const StressConfig& cfg) {
    StressResult r;
    r.technique =
        "validation at every entry point before any state changes (rayProblem, finite and "
        "normal-range checks, affine transforms; single-precision singular ones leave the trace); random "
        "numbers drawn only after all checks";
    const Scene scene = targetScene();
    std::map<std::string, ApiTally> tallies;
    for (const BadCall& call : placementCalls())
        check(call, scene, cfg.seed, tallies, r);
    checkConstruction(r, tallies, cfg.seed);
    for (const auto& [api, t] : tallies)
        r.row(api + ": bad inputs accepted, silent or changing state (count)",
              double(t.accepted + t.silent + t.changed), 0.0, t.calls);
    r.row("denormal position coordinates acting unlike zero (count)",
          double(denormalCoordinates(scene, cfg.seed, r)), 0.0, 2);
    r.row("singular transforms not taken out of the trace and back (count)",
          double(untracedTransforms(scene, cfg.seed, r)), 0.0, 6);
    return r;
}

StressResult runNonFiniteRender(const StressConfig& cfg) {
    StressResult r;
    r.technique = "validateScene, validateCamera and transform checks before any state changes; invalid "
                  "decals skipped and counted";
    Result<Renderer> renderer = caseRenderer(cfg, 96, 72, r);
    if (!renderer) return r;
    const Scene scene = targetScene();
    if (!renderer->setScene(scene)) {
        r.failure("setScene failed");
        r.row("renderer", INFINITY, 0.0, 0);
        return r;
    }
    Camera cam;
    cam.eye = {0.0, 4.0, 8.0};
    cam.target = {0.5, 0.5, 0.0};
    auto image = [&]() -> std::vector<uint8_t> {
        Result<FrameStats> f = renderer->render(cam, View::Final);
        Result<Image> im = f ? renderer->readback() : Result<Image>(fail(f.error()));
        return im ? im->rgba : std::vector<uint8_t>();
    };
    const std::vector<uint8_t> reference = image();
    if (reference.empty()) {
        r.row("reference render", INFINITY, 0.0, 0);
        return r;
    }

    struct Tally {
        size_t calls = 0, bad = 0;
    };
    std::map<std::string, Tally> tallies;
    // `status` must be a rejection with a reason, and the next frame must equal the reference.
    auto expect = [&](const std::string& api, const std::string& what, const Answer& a) {
        Tally& t = tallies[api];
        t.calls++;
        const bool unchanged = image() == reference;
        if (!a.rejected || a.reason.empty() || !unchanged) {
            t.bad++;
            r.failure(api +
                      (a.rejected
                           ? (a.reason.empty() ? " rejected without a reason " : " changed the image on ")
                           : " accepted ") +
                      what);
        }
    };
    const glm::dmat4 place = scene.objects[1].transform;
    for (const auto& [what, m] : std::vector<std::pair<std::string, glm::dmat4>>{
             {"NaN matrix", glm::dmat4(kNaN)},
             {"Inf translation", glm::translate(place, glm::dvec3(kInf, 0, 0))},
             {"NaN scale", glm::scale(place, glm::dvec3(1.0, kNaN, 1.0))},
             {"projective bottom row", glm::dmat4(glm::dvec4(1, 0, 0, 0.5), place[1], place[2], place[3])},
             {"zero matrix", glm::dmat4(0.0)}})
        expect("Renderer::setObjectTransform", what, answer(renderer->setObjectTransform(1, m)));
    expect("Renderer::setObjectTransform", "object 99",
           answer(renderer->setObjectTransform(99, glm::dmat4(1.0))));

    for (const auto& [what, change] : std::vector<std::pair<std::string, std::function<void(Scene&)>>>{
             {"NaN vertex", [](Scene& s) { s.objects[0].editMesh().positions[2].x = kNaNf; }},
             {"Inf vertex", [](Scene& s) { s.objects[1].editMesh().positions[2].y = kInff; }},
             {"NaN normal", [](Scene& s) { s.objects[0].editMesh().normals[0].z = kNaNf; }},
             {"NaN transform", [](Scene& s) { s.objects[1].transform[3][2] = kNaN; }},
             {"projective transform", [](Scene& s) { s.objects[0].transform[2][3] = 0.5; }}}) {
        Scene s = scene;
        change(s);
        expect("Renderer::setScene", what, answer(renderer->setScene(s)));
    }

    for (const auto& [what, change] :
         std::vector<std::pair<std::string, std::function<void(LightSettings&)>>>{
             {"NaN direction", [](LightSettings& l) { l.direction.x = kNaNf; }},
             {"zero direction", [](LightSettings& l) { l.direction = glm::vec3(0.0f); }},
             {"denormal direction",
              [](LightSettings& l) { l.direction = glm::vec3(kDenormalf, 0.0f, kDenormalf); }},
             {"Inf intensity", [](LightSettings& l) { l.intensity = kInff; }},
             {"NaN colour", [](LightSettings& l) { l.color.y = kNaNf; }},
             {"NaN exposure", [](LightSettings& l) { l.exposure = kNaNf; }}}) {
        LightSettings l = renderer->settings().light;
        change(l);
        expect("Renderer::setLight", what, answer(renderer->setLight(l)));
    }

    // Cameras: render must fail and leave the output image as it was.
    image();
    const std::vector<std::pair<std::string, std::function<void(Camera&)>>> cameras = {
        {"NaN eye", [](Camera& c) { c.eye.x = kNaN; }},
        {"Inf target", [](Camera& c) { c.target.z = kInf; }},
        {"NaN up", [](Camera& c) { c.up.y = kNaN; }},
        {"zero up", [](Camera& c) { c.up = glm::dvec3(0.0); }},
        {"denormal up", [](Camera& c) { c.up = glm::dvec3(0.0, kDenormal, 0.0); }},
        {"eye == target", [](Camera& c) { c.target = c.eye; }},
        {"NaN fov", [](Camera& c) { c.fovYDeg = kNaN; }},
        {"fov 0", [](Camera& c) { c.fovYDeg = 0.0; }},
        {"fov 180", [](Camera& c) { c.fovYDeg = 180.0; }},
        {"denormal fov", [](Camera& c) { c.fovYDeg = kDenormal; }},
        {"fov 1e-30", [](Camera& c) { c.fovYDeg = 1e-30; }},
        {"NaN near plane", [](Camera& c) { c.nearPlane = kNaN; }},
        {"near plane 0", [](Camera& c) { c.nearPlane = 0.0; }},
        {"denormal near plane", [](Camera& c) { c.nearPlane = kDenormal; }},
        {"near plane 1e-300", [](Camera& c) { c.nearPlane = 1e-300; }},
        {"NaN far plane", [](Camera& c) { c.farPlane = kNaN; }},
        {"Inf far plane", [](Camera& c) { c.farPlane = kInf; }},
        {"far plane inside the near plane", [](Camera& c) { c.farPlane = 0.01; }},
    };
    for (const auto& [what, change] : cameras) {
        Camera c = cam;
        change(c);
        Result<FrameStats> f = renderer->render(c, View::Final);
        Result<Image> after = renderer->readback();
        const bool ok = !f.ok() && !f.error().empty() && after && after->rgba == reference;
        if (f.ok()) image(); // an accepted camera replaced the output: back to the reference
        Tally& t = tallies["Renderer::render (camera)"];
        t.calls++;
        if (!ok) {
            t.bad++;
            r.failure("render accepted the camera with " + what);
        }
    }
    for (const char* text :
         {"eye=nan,0,0;target=0,0,-1", "eye=0,0,0;target=inf,0,-1", "eye=0,0,0;target=0,0,-1;fov=nan",
          "eye=0,0,0;target=0,0,-1;up=0,0,0", "eye=1e999,0,0;target=0,0,-1"}) {
        Tally& t = tallies["parseCamera"];
        t.calls++;
        const Result<Camera> c = parseCamera(text);
        if (c.ok() || c.error().empty()) {
            t.bad++;
            r.failure(std::string("parseCamera accepted ") + text);
        }
    }

    // Decals with NaN, Inf or denormal fields are skipped and counted, and draw nothing.
    renderer->setDecalTypes({makeType("hole", 0.4f, 80.0f)});
    Decal good;
    good.center = glm::vec3(0.5f, 0.0f, 0.5f);
    good.setFrame(Frame{glm::vec3(1, 0, 0), glm::vec3(0, 0, -1), glm::vec3(0, 1, 0)});
    good.size = glm::vec2(0.4f);
    good.halfDepth = 0.1f;
    for (const auto& [what, change] : std::vector<std::pair<std::string, std::function<void(Decal&)>>>{
             {"NaN centre", [](Decal& d) { d.center.x = kNaNf; }},
             {"orientation without its frame bit", [](Decal& d) { d.packedFrame &= ~(uint64_t(1) << 63); }},
             {"NaN size", [](Decal& d) { d.size.y = kNaNf; }},
             {"Inf half-depth", [](Decal& d) { d.halfDepth = kInff; }},
             {"NaN slant", [](Decal& d) { d.slant = 0x7e00u; }},
             {"infinite slant", [](Decal& d) { d.slant = 0x7c00u << 16; }},
             {"no orientation", [](Decal& d) { d.packedFrame = kNoOrientation; }},
             {"denormal size", [](Decal& d) { d.size = glm::vec2(kDenormalf); }},
             {"denormal half-depth", [](Decal& d) { d.halfDepth = kDenormalf; }}}) {
        Decal d = good;
        change(d);
        renderer->setDecals({d});
        Result<FrameStats> f = renderer->render(cam, View::Final);
        Result<Image> after = f ? renderer->readback() : Result<Image>(fail(f.error()));
        const bool ok =
            f && f->decalsInvalid == 1 && f->decalsDrawn == 0 && after && after->rgba == reference;
        Tally& t = tallies["Renderer::setDecals"];
        t.calls++;
        if (!ok) {
            t.bad++;
            r.failure("a decal with " + what + " was not skipped as invalid, or changed the image");
        }
    }
    renderer->setDecals({});

    for (const auto& [api, t] : tallies)
        r.row(api + ": bad inputs accepted, silent or changing the image (count)", double(t.bad), 0.0,
              t.calls);
    return r;
}

} // namespace spatter::stress
