#include "spatter/core/PoseBound.hpp"

#include "spatter/core/HausdorffBound.hpp"
#include "spatter/core/SceneEvaluator.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace spatter {

namespace {

struct Sample {
    std::vector<glm::dvec3> render, collision;
    double bound = 0.0;
};

double largestDisplacement(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b) {
    double d = 0.0;
    for (size_t v = 0; v < a.size(); ++v)
        d = std::max(d, glm::length(a[v] - b[v]));
    return d;
}

Result<Sample> sampleAt(const Scene& scene, size_t object, const Mesh& collision,
                        const VertexDeformation& deformation, const SceneEvaluator& evaluator,
                        double margin) {
    const SceneObject& o = scene.objects[object];
    Sample s;
    s.render = posedPositions(scene, object, evaluator);
    const std::vector<glm::dmat4> none;
    s.collision = posePositions(
        collision.positions, deformation, o.skin == -1 ? none : evaluator.jointMatrices(size_t(o.skin)),
        evaluator.morphWeights(object), glm::inverse(evaluator.objectTransform(object)));
    Result<HausdorffSurface> render = HausdorffSurface::create(withPositions(o.mesh, s.render));
    if (!render) return fail("render mesh: " + render.error());
    Result<HausdorffSurface> proxy = HausdorffSurface::create(withPositions(collision, s.collision));
    if (!proxy) return fail("collision mesh: " + proxy.error());
    HausdorffSettings settings;
    settings.margin = margin;
    Result<HausdorffResult> h = boundHausdorff(render.value(), proxy.value(), settings);
    if (!h) return fail(h.error());
    s.bound = h->upper;
    return s;
}

// Takes sample `s`, at time `t` of animation `a`, into `out`, with the interval from the sample before
// it in the same animation (`previous`) when there is one.
void take(PoseBound& out, const std::optional<Sample>& previous, const Sample& s, int a, double t) {
    ++out.poses;
    if (s.bound > out.sampledMax) {
        out.sampledMax = s.bound;
        out.worstAnimation = a;
        out.worstTime = t;
    }
    out.bound = std::max(out.bound, s.bound);
    if (!previous) return;
    const double motion = 0.5 * (largestDisplacement(previous->render, s.render) +
                                 largestDisplacement(previous->collision, s.collision));
    out.motion = std::max(out.motion, motion);
    out.bound = std::max(out.bound, std::max(previous->bound, s.bound) + motion);
}

} // namespace

Result<PoseBound> boundOverPoses(const Scene& scene, size_t object, const Mesh& collision,
                                 const VertexDeformation& deformation, int samples, double margin) {
    if (object >= scene.objects.size())
        return fail("pose bound: object " + std::to_string(object) + " out of range");
    if (samples < 1) return fail("pose bound: at least one sample per animation is needed");
    if (!(margin > 0.0) || !std::isfinite(margin))
        return fail("pose bound: the margin must be finite and > 0");
    const SceneObject& o = scene.objects[object];
    if (deformation.skin.influences != o.skinWeights.influences ||
        deformation.skin.joints.size() != collision.positions.size() * size_t(deformation.skin.influences) ||
        deformation.morphs.size() != o.morphTargets.size())
        return fail("pose bound: the deformation does not match the collision mesh and the object");
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
            error = "pose bound at " + std::to_string(t) + " s of animation " + std::to_string(a) + ": " +
                    s.error();
            return;
        }
        take(out, previous, s.value(), a, t);
        previous = std::move(s).value();
    });
    if (!error.empty()) return fail(error);
    return out;
}

} // namespace spatter
