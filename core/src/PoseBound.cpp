#include "spatter/core/PoseBound.hpp"

#include "spatter/core/HausdorffBound.hpp"
#include "spatter/core/SceneEvaluator.hpp"

#include "RelativeMotion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace spatter {

namespace {

struct Sample {
    std::vector<glm::dvec3> render, collision;
    double bound = 0.0;
};

std::vector<glm::dvec3> displacement(const std::vector<glm::dvec3>& from, const std::vector<glm::dvec3>& to) {
    std::vector<glm::dvec3> d(from.size());
    for (size_t v = 0; v < d.size(); ++v)
        d[v] = to[v] - from[v];
    return d;
}

// The most the two surfaces move against each other over the interval from `before` to `at` and the
// one from `at` to `after` (either may be null: no such interval), their points paired as they lie at
// `at` (RelativeMotion.hpp).
detail::Motions motionsAt(const Mesh& render, const Mesh& collision, const Sample* before, const Sample& at,
                          const Sample* after, unsigned threads) {
    std::vector<glm::dvec3> dr[2], dc[2];
    if (before) {
        dr[0] = displacement(before->render, at.render);
        dc[0] = displacement(before->collision, at.collision);
    }
    if (after) {
        dr[1] = displacement(at.render, after->render);
        dc[1] = displacement(at.collision, after->collision);
    }
    return detail::relativeMotion(
        {render, at.render, {before ? &dr[0] : nullptr, after ? &dr[1] : nullptr}},
        {collision, at.collision, {before ? &dc[0] : nullptr, after ? &dc[1] : nullptr}}, at.bound, threads);
}

// Both meshes at the evaluator's pose, and their surfaces.
struct Posed {
    Sample sample;
    std::optional<HausdorffSurface> render, collision;
};

Result<Posed> posedAt(const Scene& scene, size_t object, const Mesh& collision,
                      const VertexDeformation& deformation, const SceneEvaluator& evaluator) {
    const SceneObject& o = scene.objects[object];
    Posed p;
    p.sample.render = posedPositions(scene, object, evaluator);
    const std::vector<glm::dmat4> none;
    p.sample.collision = posePositions(
        collision.positions, deformation, o.skin == -1 ? none : evaluator.jointMatrices(size_t(o.skin)),
        evaluator.morphWeights(object), glm::inverse(evaluator.objectTransform(object)));
    Result<HausdorffSurface> render = HausdorffSurface::create(withPositions(*o.mesh, p.sample.render));
    if (!render) return fail("render mesh: " + render.error());
    Result<HausdorffSurface> proxy = HausdorffSurface::create(withPositions(collision, p.sample.collision));
    if (!proxy) return fail("collision mesh: " + proxy.error());
    p.render.emplace(std::move(render).value());
    p.collision.emplace(std::move(proxy).value());
    return p;
}

Result<Sample> sampleAt(const Scene& scene, size_t object, const Mesh& collision,
                        const VertexDeformation& deformation, const SceneEvaluator& evaluator, double margin,
                        unsigned threads) {
    Result<Posed> p = posedAt(scene, object, collision, deformation, evaluator);
    if (!p) return fail(p.error());
    HausdorffSettings settings;
    settings.margin = margin;
    settings.threads = threads;
    Result<HausdorffResult> h = boundHausdorff(*p->render, *p->collision, settings);
    if (!h) return fail(h.error());
    p->sample.bound = h->upper;
    return std::move(p->sample);
}

// The largest distance sampled between both meshes at the evaluator's pose, both ways.
Result<double> sampledAt(const Scene& scene, size_t object, const Mesh& collision,
                         const VertexDeformation& deformation, const SceneEvaluator& evaluator,
                         size_t maxTriangles, unsigned threads) {
    Result<Posed> p = posedAt(scene, object, collision, deformation, evaluator);
    if (!p) return fail(p.error());
    const double inf = std::numeric_limits<double>::infinity();
    Result<double> ab = sampledLowerBound(*p->render, *p->collision, maxTriangles, inf, {}, threads);
    if (!ab) return ab;
    Result<double> ba = sampledLowerBound(*p->collision, *p->render, maxTriangles, inf, {}, threads);
    if (!ba) return ba;
    return std::max(ab.value(), ba.value());
}

Status checkArguments(const Scene& scene, size_t object, const Mesh& collision,
                      const VertexDeformation& deformation, int samples) {
    if (object >= scene.objects.size())
        return fail("pose bound: object " + std::to_string(object) + " out of range");
    if (samples < 1) return fail("pose bound: at least one sample per animation is needed");
    const SceneObject& o = scene.objects[object];
    if (deformation.skin.influences != o.skinWeights.influences ||
        deformation.skin.joints.size() != collision.positions.size() * size_t(deformation.skin.influences) ||
        deformation.morphs.size() != o.morphTargets.size())
        return fail("pose bound: the deformation does not match the collision mesh and the object");
    return {};
}

std::string poseName(int animation, double t) {
    return "pose bound at " + std::to_string(t) + " s of animation " + std::to_string(animation);
}

// Takes the bound `bound` sampled at time `t` of animation `a` into `out`.
void takePose(PoseBound& out, double bound, int a, double t) {
    ++out.poses;
    if (bound > out.sampledMax) {
        out.sampledMax = bound;
        out.worstAnimation = a;
        out.worstTime = t;
    }
    out.bound = std::max(out.bound, bound);
}

// The samples of one animation walked so far: the last two, and the relative motion measured at the
// earlier one over the interval after it.
struct Walk {
    std::optional<Sample> before, at;
    double motionAfterBefore = 0.0;
};

// Measures the relative motion at `w.at` over the intervals from `w.before` and to `next` (null at the
// animation's end), and takes the interval from `w.before` to `w.at`, both its ends now measured, into
// `out`: the larger sampled bound plus half the larger motion at either end.
void advance(PoseBound& out, const Mesh& render, const Mesh& collision, Walk& w, const Sample* next,
             unsigned threads) {
    const Sample* before = w.before ? &*w.before : nullptr;
    const detail::Motions m = motionsAt(render, collision, before, *w.at, next, threads);
    if (before) {
        const double motion = 0.5 * std::max(w.motionAfterBefore, m[0]);
        out.motion = std::max(out.motion, motion);
        out.bound = std::max(out.bound, std::max(before->bound, w.at->bound) + motion);
    }
    w.motionAfterBefore = m[1];
}

// Calls `step(animation, index, t, evaluator)` (returning a Status) at every pose forEachSampledPose
// names, the evaluator set to it; stops at the first failure and names its pose.
template <class Step> Status walkPoses(const Scene& scene, int samples, Step&& step) {
    SceneEvaluator evaluator(scene);
    std::string error;
    forEachSampledPose(scene, samples, [&](int a, int i, double t) {
        if (!error.empty()) return;
        evaluator.evaluate(a, t);
        if (Status st = step(a, i, t, evaluator); !st) error = poseName(a, t) + ": " + st.error();
    });
    if (!error.empty()) return fail(error);
    return {};
}

} // namespace

Result<PoseBound> boundOverPoses(const Scene& scene, size_t object, const Mesh& collision,
                                 const VertexDeformation& deformation, int samples, double margin,
                                 unsigned threads) {
    if (Status st = checkArguments(scene, object, collision, deformation, samples); !st)
        return fail(st.error());
    if (!(margin > 0.0) || !std::isfinite(margin))
        return fail("pose bound: the margin must be finite and > 0");
    const Mesh& render = *scene.objects[object].mesh;
    PoseBound out;
    Walk walk;
    Status st =
        walkPoses(scene, samples, [&](int a, int i, double t, const SceneEvaluator& evaluator) -> Status {
            if (i == 0) walk = Walk{};
            Result<Sample> s = sampleAt(scene, object, collision, deformation, evaluator, margin, threads);
            if (!s) return fail(s.error());
            takePose(out, s->bound, a, t);
            if (walk.at) {
                advance(out, render, collision, walk, &s.value(), threads);
                walk.before = std::move(walk.at);
            }
            walk.at = std::move(s).value();
            if (i == samples && walk.before) advance(out, render, collision, walk, nullptr, threads);
            return {};
        });
    if (!st) return fail(st.error());
    return out;
}

Result<PoseBound> sampledOverPoses(const Scene& scene, size_t object, const Mesh& collision,
                                   const VertexDeformation& deformation, int samples, size_t maxTriangles,
                                   unsigned threads) {
    if (Status st = checkArguments(scene, object, collision, deformation, samples); !st)
        return fail(st.error());
    PoseBound out;
    Status st =
        walkPoses(scene, samples, [&](int a, int, double t, const SceneEvaluator& evaluator) -> Status {
            Result<double> d =
                sampledAt(scene, object, collision, deformation, evaluator, maxTriangles, threads);
            if (!d) return fail(d.error());
            takePose(out, d.value(), a, t);
            return {};
        });
    if (!st) return fail(st.error());
    return out;
}

} // namespace spatter
