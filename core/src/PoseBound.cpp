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

// The motion allowance of the interval from sample `a` to sample `b`: half the most the two surfaces
// move against each other over it, their points paired as they lie at either end
// (RelativeMotion.hpp). With the two sampled bounds it bounds the distance within the interval.
double motionBetween(const Mesh& render, const Mesh& collision, const Sample& a, const Sample& b) {
    const std::vector<glm::dvec3> dr = displacement(a.render, b.render);
    const std::vector<glm::dvec3> dc = displacement(a.collision, b.collision);
    const double atA = detail::relativeMotion({render, a.render, dr}, {collision, a.collision, dc}, a.bound);
    const double atB = detail::relativeMotion({render, b.render, dr}, {collision, b.collision, dc}, b.bound);
    return 0.5 * std::max(atA, atB);
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
    Result<HausdorffSurface> render = HausdorffSurface::create(withPositions(o.mesh, p.sample.render));
    if (!render) return fail("render mesh: " + render.error());
    Result<HausdorffSurface> proxy = HausdorffSurface::create(withPositions(collision, p.sample.collision));
    if (!proxy) return fail("collision mesh: " + proxy.error());
    p.render.emplace(std::move(render).value());
    p.collision.emplace(std::move(proxy).value());
    return p;
}

Result<Sample> sampleAt(const Scene& scene, size_t object, const Mesh& collision,
                        const VertexDeformation& deformation, const SceneEvaluator& evaluator,
                        double margin) {
    Result<Posed> p = posedAt(scene, object, collision, deformation, evaluator);
    if (!p) return fail(p.error());
    HausdorffSettings settings;
    settings.margin = margin;
    Result<HausdorffResult> h = boundHausdorff(*p->render, *p->collision, settings);
    if (!h) return fail(h.error());
    p->sample.bound = h->upper;
    return std::move(p->sample);
}

// The largest distance sampled between both meshes at the evaluator's pose, both ways.
Result<double> sampledAt(const Scene& scene, size_t object, const Mesh& collision,
                         const VertexDeformation& deformation, const SceneEvaluator& evaluator,
                         size_t maxTriangles) {
    Result<Posed> p = posedAt(scene, object, collision, deformation, evaluator);
    if (!p) return fail(p.error());
    const double inf = std::numeric_limits<double>::infinity();
    Result<double> ab = sampledLowerBound(*p->render, *p->collision, maxTriangles, inf);
    if (!ab) return ab;
    Result<double> ba = sampledLowerBound(*p->collision, *p->render, maxTriangles, inf);
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

// Takes the interval between samples `a` and `b` (of the same animation) into `out`.
void takeInterval(PoseBound& out, const Mesh& render, const Mesh& collision, const Sample& a,
                  const Sample& b) {
    const double motion = motionBetween(render, collision, a, b);
    out.motion = std::max(out.motion, motion);
    out.bound = std::max(out.bound, std::max(a.bound, b.bound) + motion);
}

} // namespace

Result<PoseBound> boundOverPoses(const Scene& scene, size_t object, const Mesh& collision,
                                 const VertexDeformation& deformation, int samples, double margin) {
    if (Status st = checkArguments(scene, object, collision, deformation, samples); !st)
        return fail(st.error());
    if (!(margin > 0.0) || !std::isfinite(margin))
        return fail("pose bound: the margin must be finite and > 0");
    SceneEvaluator evaluator(scene);
    PoseBound out;
    std::optional<Sample> previous;
    std::string error;
    forEachSampledPose(scene, samples, [&](int a, int step, double t) {
        if (!error.empty()) return;
        if (step == 0) previous.reset();
        evaluator.evaluate(a, t);
        Result<Sample> s = sampleAt(scene, object, collision, deformation, evaluator, margin);
        if (!s) {
            error = poseName(a, t) + ": " + s.error();
            return;
        }
        takePose(out, s->bound, a, t);
        if (previous) takeInterval(out, scene.objects[object].mesh, collision, *previous, s.value());
        previous = std::move(s).value();
    });
    if (!error.empty()) return fail(error);
    return out;
}

Result<PoseBound> sampledOverPoses(const Scene& scene, size_t object, const Mesh& collision,
                                   const VertexDeformation& deformation, int samples, size_t maxTriangles) {
    if (Status st = checkArguments(scene, object, collision, deformation, samples); !st)
        return fail(st.error());
    SceneEvaluator evaluator(scene);
    PoseBound out;
    std::string error;
    forEachSampledPose(scene, samples, [&](int a, int, double t) {
        if (!error.empty()) return;
        evaluator.evaluate(a, t);
        Result<double> d = sampledAt(scene, object, collision, deformation, evaluator, maxTriangles);
        if (!d) {
            error = poseName(a, t) + ": " + d.error();
            return;
        }
        takePose(out, d.value(), a, t);
    });
    if (!error.empty()) return fail(error);
    return out;
}

} // namespace spatter
