// libFuzzer target: the spawn API. Each input is decoded into decal settings and a program of calls
// (registerType, spawn, spawnAt, spawnAttached, spawnBatch, setTransform, setPose, removeObject,
// update, remove) whose numbers include NaN, infinities, denormals and extreme magnitudes. The
// program runs twice on fresh systems over the same scene: as decoded (spawnBatch traced by up to 4
// threads) and with every spawnBatch replaced by spawns ray by ray. After every call the invariants the API
// documents are checked; at the end both runs must agree bit for bit.

#include "spatter/core/DeformingProxy.hpp"
#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SkinnedArm.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <fuzzer/FuzzedDataProvider.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <vector>

namespace {

using namespace spatter;

[[noreturn]] void violated(const char* what, size_t op) {
    std::fprintf(stderr, "FuzzSpawn: invariant violated after call %zu: %s\n", op, what);
    std::abort();
}

// The skinned arm (object 0, posed by setPose through a deforming proxy, so that shots on it are
// anchored to its drawn surface), a floor, a static sphere, a dynamic crate, a dynamic non-receiver
// and a dynamic scaled sphere.
Scene makeScene() {
    Scene s = makeSkinnedArm();
    s.source = "fuzz:spawn";
    const glm::dmat4 id(1.0);
    s.objects.push_back(makeSceneObject("floor", makeBox(glm::vec3(10.0f, 0.1f, 10.0f), 2),
                                        glm::translate(id, glm::dvec3(0.0, -0.1, 0.0)), false));
    s.objects.push_back(
        makeSceneObject("pillar", makeSphere(1.0f, 8, 12), glm::translate(id, glm::dvec3(3, 1, 0)), false));
    s.objects.push_back(makeSceneObject("crate", makeBox(glm::vec3(0.5f), 1),
                                        glm::translate(id, glm::dvec3(0, 1, -3)), true));
    s.objects.push_back(makeSceneObject("ghost", makeBox(glm::vec3(0.5f), 1),
                                        glm::translate(id, glm::dvec3(-3, 1, 0)), true));
    s.objects.back().receivesDecals = false;
    s.objects.push_back(makeSceneObject(
        "ball", makeSphere(0.5f, 6, 8),
        glm::scale(glm::translate(id, glm::dvec3(0, 1, 3)), glm::dvec3(1.0, 2.0, 0.5)), true));
    return s;
}

const Scene& scene() {
    static const Scene s = makeScene();
    return s;
}

// The collision meshes: the arm's deforming proxy at 2% of its diagonal, the others' render meshes.
const std::vector<std::shared_ptr<const Proxy>>& proxies() {
    static const std::vector<std::shared_ptr<const Proxy>> p = [] {
        ProxySettings settings;
        settings.tolerance = 0.02f;
        settings.toleranceRelative = true;
        Result<DeformingProxy> arm = buildDeformingProxy(scene(), 0, settings, 8);
        if (!arm) violated("the arm's deforming proxy does not build", 0);
        std::vector<std::shared_ptr<const Proxy>> out(scene().objects.size());
        out[0] = arm->proxy;
        return out;
    }();
    return p;
}

double pickDouble(FuzzedDataProvider& in, double lo, double hi) {
    static const double kSpecial[] = {0.0,
                                      -0.0,
                                      1.0,
                                      -1.0,
                                      std::numeric_limits<double>::quiet_NaN(),
                                      std::numeric_limits<double>::infinity(),
                                      -std::numeric_limits<double>::infinity(),
                                      DBL_MIN,
                                      std::numeric_limits<double>::denorm_min(),
                                      -std::numeric_limits<double>::denorm_min(),
                                      DBL_MAX,
                                      -DBL_MAX,
                                      1e-300,
                                      1e300,
                                      1e-160,
                                      1e154,
                                      double(FLT_MIN),
                                      double(FLT_MAX),
                                      1e-45,
                                      1e-30,
                                      1e30};
    switch (in.ConsumeIntegralInRange<int>(0, 5)) {
    case 0:
        return kSpecial[in.ConsumeIntegralInRange<size_t>(0, sizeof kSpecial / sizeof kSpecial[0] - 1)];
    case 1:
        return in.ConsumeFloatingPoint<double>();
    default:
        return in.ConsumeFloatingPointInRange<double>(lo, hi);
    }
}

float pickFloat(FuzzedDataProvider& in, float lo, float hi) {
    return float(pickDouble(in, double(lo), double(hi)));
}

glm::dvec3 pickVec(FuzzedDataProvider& in, double lo, double hi) {
    const double x = pickDouble(in, lo, hi), y = pickDouble(in, lo, hi);
    return {x, y, pickDouble(in, lo, hi)};
}

// A ray; half of them aimed at a point near an object's place (`places`: where the program has
// moved each object so far; the arm's middle), exactly at it one time in four (a collapsed object is only a
// point, a line or a plane there), from somewhere around the scene.
Ray pickRay(FuzzedDataProvider& in, const std::vector<glm::dvec3>& places) {
    Ray r;
    if (in.ConsumeBool()) {
        const size_t k = in.ConsumeIntegralInRange<size_t>(0, places.size() - 1);
        glm::dvec3 target = places[k];
        const double spread = k == 0 ? 0.15 : 1.0; // the arm is a bar 0.2 across
        if (in.ConsumeIntegralInRange<int>(0, 3) != 0)
            target += spread * glm::dvec3(in.ConsumeFloatingPointInRange(-1.0, 1.0),
                                          in.ConsumeFloatingPointInRange(-1.0, 1.0),
                                          in.ConsumeFloatingPointInRange(-1.0, 1.0));
        r.origin = pickVec(in, -15.0, 15.0);
        r.direction = (target - r.origin) * pickDouble(in, 0.5, 2.0);
    } else {
        r.origin = pickVec(in, -15.0, 15.0);
        r.direction = pickVec(in, -1.0, 1.0);
    }
    if (in.ConsumeIntegralInRange<int>(0, 7) == 0) {
        r.tnear = pickDouble(in, 0.0, 10.0);
        r.tfar = pickDouble(in, 0.0, 100.0);
    }
    return r;
}

// A ray of a shotgun burst: from the origin of `previous`, its direction nudged by up to about 2
// degrees (spawnBatch traces such runs as Embree packets), sometimes with a range of its own.
Ray burstRay(FuzzedDataProvider& in, const Ray& previous) {
    Ray r = previous;
    r.direction += glm::length(previous.direction) * pickVec(in, -0.02, 0.02);
    if (in.ConsumeIntegralInRange<int>(0, 7) == 0) r.tfar = pickDouble(in, 0.0, 100.0);
    return r;
}

// A transform that single precision can barely use or not at all (TraceTransform.hpp), on a placed
// and turned object: two columns whose components differ by a factor 1 + k 2^-n, n from 10 to 60
// (equal once rounded to float from n = 24 on, while the double matrix stays invertible), a column
// scaled by 2^-80 to 2^80, a shear up to 1e7, or a mirror.
glm::dmat4 pickFloatSingular(FuzzedDataProvider& in) {
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), pickVec(in, -12.0, 12.0));
    const glm::dvec3 axis(1.0 + in.ConsumeFloatingPointInRange(0.0, 1.0), 2.0, 3.0);
    m = glm::rotate(m, in.ConsumeFloatingPointInRange(0.1, 3.0), glm::normalize(axis));
    const int c = in.ConsumeIntegralInRange<int>(0, 2);
    const int d = (c + in.ConsumeIntegralInRange<int>(1, 2)) % 3;
    switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0: {
        const double delta = std::ldexp(1.0, -in.ConsumeIntegralInRange<int>(10, 60));
        for (int r = 0; r < 3; ++r)
            m[d][r] = m[c][r] * (1.0 + delta * double(r + 1));
        break;
    }
    case 1:
        m[c] *= std::ldexp(1.0, in.ConsumeIntegralInRange<int>(-80, 80));
        break;
    case 2:
        m[d] += glm::dvec4(pickVec(in, -1e7, 1e7), 0.0);
        break;
    default:
        m[c] *= -pickDouble(in, 1e-9, 1.0);
        break;
    }
    return m;
}

glm::dmat4 pickTransform(FuzzedDataProvider& in) {
    const int kind = in.ConsumeIntegralInRange<int>(0, 3);
    if (kind == 1) return pickFloatSingular(in);
    if (kind == 0) { // any affine matrix
        glm::dmat4 m(1.0);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 3; ++r)
                m[c][r] = pickDouble(in, -3.0, 3.0);
        if (in.ConsumeIntegralInRange<int>(0, 7) == 0) m[0][3] = pickDouble(in, -1.0, 1.0); // not affine
        return m;
    }
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), pickVec(in, -12.0, 12.0));
    glm::dvec3 axis = pickVec(in, -1.0, 1.0);
    const double angle = pickDouble(in, -7.0, 7.0);
    if (std::isfinite(glm::dot(axis, axis)) && glm::dot(axis, axis) > 1e-12 && std::isfinite(angle))
        m = glm::rotate(m, angle, glm::normalize(axis));
    return glm::scale(m, pickVec(in, 0.1, 3.0));
}

DecalType pickType(FuzzedDataProvider& in, size_t serial) {
    DecalType t;
    const int naming = in.ConsumeIntegralInRange<int>(0, 15);
    t.name = naming == 0 ? std::string() : naming == 1 ? "t0" : "t" + std::to_string(serial);
    t.size = glm::vec2(pickFloat(in, 0.01f, 2.0f), pickFloat(in, 0.01f, 2.0f));
    t.sizeJitter = in.ConsumeBool() ? 0.0f : pickFloat(in, 0.0f, 0.99f);
    t.randomRotation = in.ConsumeBool();
    t.maxAngleDeg = in.ConsumeBool() ? 80.0f : pickFloat(in, 1.0f, 90.0f);
    t.lifetime = in.ConsumeBool() ? 0.0f : pickFloat(in, 0.0f, 10.0f);
    t.fadeOutTime = pickFloat(in, 0.0f, 5.0f);
    t.halfDepth = in.ConsumeBool() ? 0.0f : pickFloat(in, 0.0f, 1.0f);
    t.onDynamic = in.ConsumeIntegralInRange<int>(0, 3) != 0;
    return t;
}

struct Op {
    enum Kind {
        Register,
        Spawn,
        SpawnAt,
        SpawnAttached,
        SpawnBatch,
        Move,
        RemoveObject,
        Update,
        Remove,
        Pose
    };
    Kind kind = Spawn;
    DecalType type;
    uint16_t typeIndex = 0;
    Ray ray;
    std::vector<Ray> rays;
    glm::dvec3 position{0.0}, normal{0.0};
    glm::vec3 localPosition{0.0f}, localNormal{0.0f};
    uint32_t object = 0;
    glm::dmat4 transform{1.0};
    double dt = 0.0;                // Update's step; Pose's time of the arm's animation
    std::vector<glm::dmat4> joints; // Pose: joint matrices of its own when not empty
    size_t handle = 0;              // index into the handles placed so far (modulo their count)
    DecalHandle raw;                // used when `useRaw`
    bool useRaw = false;
};

std::vector<Op> decode(FuzzedDataProvider& in) {
    std::vector<Op> ops;
    const uint32_t objects = uint32_t(scene().objects.size());
    std::vector<glm::dvec3> places;
    for (const SceneObject& o : scene().objects)
        places.push_back(glm::dvec3(o.transform[3]));
    places[0] += glm::dvec3(0.0, 0.5, 0.0); // the arm's middle: it stands on its origin
    while (in.remaining_bytes() > 0 && ops.size() < 48) {
        Op op;
        op.kind = Op::Kind(in.ConsumeIntegralInRange<int>(0, 9));
        op.typeIndex =
            uint16_t(in.ConsumeIntegralInRange<int>(0, 3) == 0 ? in.ConsumeIntegral<uint16_t>()
                                                               : in.ConsumeIntegralInRange<int>(0, 3));
        op.object = in.ConsumeIntegralInRange<int>(0, 7) == 0
                        ? in.ConsumeIntegral<uint32_t>()
                        : in.ConsumeIntegralInRange<uint32_t>(0, objects);
        switch (op.kind) {
        case Op::Register:
            op.type = pickType(in, ops.size());
            break;
        case Op::Spawn:
            op.ray = pickRay(in, places);
            break;
        case Op::SpawnAt:
            op.position = pickVec(in, -10.0, 10.0);
            op.normal = pickVec(in, -1.0, 1.0);
            break;
        case Op::SpawnAttached:
            op.localPosition = glm::vec3(pickVec(in, -1.0, 1.0));
            op.localNormal = glm::vec3(pickVec(in, -1.0, 1.0));
            break;
        case Op::SpawnBatch:
            op.rays.resize(in.ConsumeIntegralInRange<size_t>(0, 24));
            for (size_t k = 0; k < op.rays.size(); ++k)
                op.rays[k] = k == 0 || in.ConsumeBool() ? pickRay(in, places) : burstRay(in, op.rays[k - 1]);
            break;
        case Op::Move:
            op.transform = pickTransform(in);
            if (op.object < objects) places[op.object] = glm::dvec3(op.transform[3]);
            break;
        case Op::RemoveObject:
            break;
        case Op::Update:
            op.dt = in.ConsumeBool() ? pickDouble(in, 0.0, 3.0) : in.ConsumeFloatingPointInRange(0.0, 0.5);
            break;
        case Op::Pose:
            if (in.ConsumeIntegralInRange<int>(0, 3) != 0) op.object = 0; // mostly the arm
            op.dt = pickDouble(in, -1.0, 3.0);
            if (in.ConsumeIntegralInRange<int>(0, 3) == 0) op.joints = {pickTransform(in), pickTransform(in)};
            op.transform = in.ConsumeBool() ? glm::dmat4(1.0) : pickTransform(in);
            break;
        case Op::Remove:
            op.useRaw = in.ConsumeIntegralInRange<int>(0, 3) == 0;
            op.handle = in.ConsumeIntegral<uint8_t>();
            op.raw = DecalHandle{in.ConsumeIntegralInRange<uint32_t>(0, 300), in.ConsumeIntegral<uint32_t>()};
            break;
        }
        ops.push_back(std::move(op));
    }
    return ops;
}

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// What one run did, for the checks and the comparison of the two runs.
struct Run {
    DecalSystem system;
    std::vector<DecalHandle> handles; // every handle placed, in order
    std::vector<bool> gone;           // handle i has gone stale
    uint64_t placed = 0, rejected = 0;

    // `fresh`: the call that placed it was a single spawn, so nothing can have evicted it yet (in a
    // batch a later ray may evict the decal of an earlier one).
    void record(const SpawnResult& r, size_t op, bool fresh = true) {
        if (r.placed()) {
            if (!r.reason.empty()) violated("a placed result has a reason", op);
            if (fresh && !system.get(r.handle)) violated("a fresh handle does not resolve", op);
            const std::optional<WorldDecal> w = system.worldBox(r.handle);
            if (fresh && (!w || !std::isfinite(w->center.x) || !std::isfinite(w->center.y) ||
                          !std::isfinite(w->center.z) || !std::isfinite(w->size.x) ||
                          !std::isfinite(w->size.y) || !std::isfinite(w->halfDepth)))
                violated("the world box of a fresh decal is not finite", op);
            handles.push_back(r.handle);
            gone.push_back(false);
            placed++;
        } else {
            if (r.reason.empty()) violated("a rejection without a reason", op);
            rejected++;
        }
    }

    void check(size_t op) {
        const DecalStats& st = system.stats();
        const std::vector<Decal>& decals = system.decals();
        if (st.alive != decals.size()) violated("stats().alive != decals().size()", op);
        if (st.fading > st.alive) violated("more decals fading than alive", op);
        if (st.placed != st.alive - st.fading + st.evicted + st.expired + st.removed)
            violated("placed != alive - fading + evicted + expired + removed", op);
        if (st.placed != placed) violated("stats().placed differs from the placed results", op);
        if (st.rejectedTotal() != rejected)
            violated("stats().rejected differs from the rejected results", op);
        for (const Decal& d : decals) {
            if (d.object >= system.world().objectCount() || d.type >= system.typeCount())
                violated("a decal refers to an object or type that does not exist", op);
            const Frame f = d.frame();
            if (!finite(d.center) || !finite(f.normal) || !finite(f.tangent) || !finite(f.bitangent) ||
                !(frameError(f) < 1e-3f))
                violated("a decal's centre or frame is not finite and orthonormal", op);
            if (!std::isfinite(d.size.x) || !std::isfinite(d.size.y) || !(d.size.x > 0.0f) ||
                !(d.size.y > 0.0f) || !std::isfinite(d.halfDepth) || !(d.halfDepth > 0.0f)) {
                std::fprintf(stderr, "decal on object %u: size %g x %g, half-depth %g\n", d.object,
                             double(d.size.x), double(d.size.y), double(d.halfDepth));
                violated("a decal's size or half-depth is not finite and positive", op);
            }
            if (!validSlant(d.slant)) violated("a decal's slant is not one a projection axis packs to", op);
            if (d.objectId != system.objectId(d.object))
                violated("a decal's object ID is not its object's", op);
        }
        for (size_t i = 0; i < handles.size(); ++i) {
            const bool resolves = system.get(handles[i]) != nullptr;
            if (gone[i] && resolves) violated("a stale handle resolves again", op);
            gone[i] = !resolves;
        }
    }
};

std::string text(const glm::dvec3& v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.17g, %.17g, %.17g)", v.x, v.y, v.z);
    return buf;
}

std::string text(const Ray& r) {
    return "origin " + text(r.origin) + " direction " + text(r.direction) + " t [" + std::to_string(r.tnear) +
           ", " + std::to_string(r.tfar) + "]";
}

// With SPATTER_FUZZ_TRACE set, each call is printed before it runs (to turn a crash into a test).
void trace(const Op& op, size_t i) {
    static const bool enabled = std::getenv("SPATTER_FUZZ_TRACE") != nullptr;
    if (!enabled) return;
    std::string d;
    switch (op.kind) {
    case Op::Register:
        d = "registerType name '" + op.type.name + "' size " + std::to_string(op.type.size.x) + "x" +
            std::to_string(op.type.size.y) + " jitter " + std::to_string(op.type.sizeJitter) + " maxAngle " +
            std::to_string(op.type.maxAngleDeg) + " lifetime " + std::to_string(op.type.lifetime) + " fade " +
            std::to_string(op.type.fadeOutTime) + " halfDepth " + std::to_string(op.type.halfDepth);
        break;
    case Op::Spawn:
        d = "spawn type " + std::to_string(op.typeIndex) + " " + text(op.ray);
        break;
    case Op::SpawnAt:
        d = "spawnAt type " + std::to_string(op.typeIndex) + " position " + text(op.position) + " normal " +
            text(op.normal);
        break;
    case Op::SpawnAttached:
        d = "spawnAttached type " + std::to_string(op.typeIndex) + " object " + std::to_string(op.object) +
            " " + text(glm::dvec3(op.localPosition)) + " normal " + text(glm::dvec3(op.localNormal));
        break;
    case Op::SpawnBatch:
        d = "spawnBatch type " + std::to_string(op.typeIndex) + " rays " + std::to_string(op.rays.size());
        for (const Ray& r : op.rays)
            d += "\n    " + text(r);
        break;
    case Op::Move:
        d = "setTransform object " + std::to_string(op.object) + " columns";
        for (int c = 0; c < 4; ++c)
            d += " " + text(glm::dvec3(op.transform[c])) + "/" + std::to_string(op.transform[c][3]);
        break;
    case Op::RemoveObject:
        d = "removeObject " + std::to_string(op.object);
        break;
    case Op::Update:
        d = "update " + text(glm::dvec3(op.dt));
        break;
    case Op::Pose:
        d = "setPose object " + std::to_string(op.object) + " time " + text(glm::dvec3(op.dt)) +
            (op.joints.empty() ? " (the animation's joints)" : " (joints of its own)");
        break;
    case Op::Remove:
        d = "remove " + (op.useRaw
                             ? "raw " + std::to_string(op.raw.slot) + "/" + std::to_string(op.raw.generation)
                             : "placed #" + std::to_string(op.handle));
        break;
    }
    std::fprintf(stderr, "call %zu: %s\n", i, d.c_str());
}

// The arm's joint matrices at time t of its animation (the time as the evaluator takes it).
std::vector<glm::dmat4> armJoints(double t) {
    SceneEvaluator evaluator(scene());
    evaluator.evaluate(0, t);
    return evaluator.jointMatrices(0);
}

void execute(Run& run, const std::vector<Op>& ops, bool batchesRayByRay) {
    for (size_t i = 0; i < ops.size(); ++i) {
        const Op& op = ops[i];
        DecalSystem& s = run.system;
        trace(op, i);
        switch (op.kind) {
        case Op::Register: {
            const size_t before = s.typeCount();
            Result<uint16_t> r = s.registerType(op.type);
            if (r ? r.value() != before || s.typeCount() != before + 1 : s.typeCount() != before)
                violated("registerType's result and typeCount disagree", i);
            break;
        }
        case Op::Spawn:
            run.record(s.spawn(op.ray, op.typeIndex), i);
            break;
        case Op::SpawnAt:
            run.record(s.spawnAt(op.position, op.normal, op.typeIndex), i);
            break;
        case Op::SpawnAttached:
            run.record(s.spawnAttached(op.object, op.localPosition, op.localNormal, op.typeIndex), i);
            break;
        case Op::SpawnBatch:
            if (batchesRayByRay) {
                for (const Ray& r : op.rays)
                    run.record(s.spawn(r, op.typeIndex), i);
            } else {
                std::vector<SpawnResult> results;
                s.spawnBatch(op.rays, op.typeIndex, results);
                if (results.size() != op.rays.size()) violated("spawnBatch returned a result per ray", i);
                for (const SpawnResult& r : results)
                    run.record(r, i, false);
            }
            break;
        case Op::Move:
            (void)s.setTransform(op.object, op.transform);
            break;
        case Op::RemoveObject:
            (void)s.removeObject(op.object);
            break;
        case Op::Update: {
            const double before = s.time();
            const Status st = s.update(op.dt);
            const bool good = std::isfinite(op.dt) && op.dt >= 0.0 && (op.dt == 0.0 || op.dt >= DBL_MIN);
            if (st.ok() != good) violated("update's verdict on dt is not the documented one", i);
            if (!st.ok() && s.time() != before) violated("a failed update changed the clock", i);
            break;
        }
        case Op::Pose:
            (void)s.setPose(op.object, op.transform, op.joints.empty() ? armJoints(op.dt) : op.joints, {});
            break;
        case Op::Remove: {
            const DecalHandle h =
                op.useRaw || run.handles.empty() ? op.raw : run.handles[op.handle % run.handles.size()];
            const bool existed = s.get(h) != nullptr;
            if (s.remove(h) != existed || s.get(h)) violated("remove disagrees with get", i);
            break;
        }
        }
        run.check(i);
    }
}

bool sameDecals(const std::vector<Decal>& a, const std::vector<Decal>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i) {
        const Decal &x = a[i], &y = b[i];
        if (x.packedFrame != y.packedFrame || std::memcmp(&x.center, &y.center, sizeof x.center) ||
            std::memcmp(&x.size, &y.size, sizeof x.size) || x.halfDepth != y.halfDepth ||
            x.object != y.object || x.objectId != y.objectId || x.id != y.id || x.type != y.type ||
            x.spawnTime != y.spawnTime || x.opacity.bits() != y.opacity.bits() || x.slant != y.slant)
            return false;
    }
    return true;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    FuzzedDataProvider in(data, size);
    DecalSettings settings;
    settings.seed = in.ConsumeIntegral<uint64_t>();
    settings.cellSize = in.ConsumeBool() ? 0.5f : pickFloat(in, 0.01f, 4.0f);
    settings.maxPerCell = in.ConsumeIntegralInRange<uint32_t>(0, 8);
    settings.budget = in.ConsumeIntegralInRange<uint32_t>(0, 24);
    settings.maxPerObject = in.ConsumeIntegralInRange<uint32_t>(0, 16);
    settings.policy = LimitPolicy(in.ConsumeIntegralInRange<int>(0, 2));
    settings.depthMargin = in.ConsumeBool() ? 0.25f : pickFloat(in, 0.0f, 2.0f);
    settings.idSeparation = in.ConsumeBool() ? 1.0 : pickDouble(in, 0.0, 10.0);
    settings.batchThreads = in.ConsumeIntegralInRange<uint32_t>(0, 4);
    const std::vector<Op> ops = decode(in);
    if (std::getenv("SPATTER_FUZZ_TRACE"))
        std::fprintf(stderr,
                     "settings: seed %llu cellSize %.9g maxPerCell %u budget %u maxPerObject %u policy %d "
                     "depthMargin %.9g idSeparation %.17g batchThreads %u\n",
                     (unsigned long long)settings.seed, double(settings.cellSize), settings.maxPerCell,
                     settings.budget, settings.maxPerObject, int(settings.policy),
                     double(settings.depthMargin), settings.idSeparation, settings.batchThreads);

    DecalSettings serial = settings;
    serial.batchThreads = 1;
    Result<CollisionWorld> worldA = CollisionWorld::build(scene(), proxies());
    Result<CollisionWorld> worldB = CollisionWorld::build(scene(), proxies());
    if (!worldA || !worldB) violated("the scene does not build", 0);
    Result<DecalSystem> a = DecalSystem::create(std::move(worldA).value(), settings);
    Result<DecalSystem> b = DecalSystem::create(std::move(worldB).value(), serial);
    if (a.ok() != b.ok()) violated("create depends on batchThreads", 0);
    if (!a) return 0;

    DecalType standard;
    standard.name = "standard";
    standard.lifetime = 2.0f;
    Run runA{std::move(a).value(), {}, {}, 0, 0};
    Run runB{std::move(b).value(), {}, {}, 0, 0};
    if (!runA.system.registerType(standard) || !runB.system.registerType(standard))
        violated("the standard type does not register", 0);
    execute(runA, ops, false);
    execute(runB, ops, true);
    if (runA.system.stats() != runB.system.stats() || !sameDecals(runA.system.decals(), runB.system.decals()))
        violated("spawnBatch and spawn ray by ray disagree", ops.size());
    return 0;
}
