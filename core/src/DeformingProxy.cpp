#include "spatter/core/DeformingProxy.hpp"

#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/ProxyCache.hpp"
#include "spatter/core/SceneEvaluator.hpp"

#include "ValueHasher.hpp"

#include <chrono>
#include <string>

namespace spatter {

namespace {

// Poses sampled per animation for buildObjectProxy: on the gallery's dummy, 32 give a bound over the
// poses of 0.035 (64: 0.022 in twice the time, 16: 0.058 in half), in 0.4 to 0.7 s on two cores
// (boundOverPoses certifies each sample).
constexpr int kObjectPoseSamples = 32;

// Changes whenever buildDeformingProxy makes something else of the same inputs.
constexpr uint32_t kDeformingVersion = 3;

// The cache key of the proxy buildObjectProxy makes for deforming object `object`: the key of its
// rest proxy, its joint influences and morph targets, and at every pose boundOverPoses samples the
// object's transform, its skin's joint matrices and its morph weights (so that a change of the
// hierarchy, the skin or the animations that moves the object in a sampled pose changes the key).
uint64_t deformingProxyCacheKey(const Scene& scene, size_t object, const ProxySettings& settings,
                                int samples) {
    const SceneObject& o = scene.objects[object];
    detail::ValueHasher h;
    h.u32(kDeformingVersion);
    h.u64(proxyCacheKey(*o.mesh, settings, nullptr));
    h.u32(uint32_t(samples));
    h.u32(uint32_t(o.skinWeights.influences));
    h.each(o.skinWeights.joints, [&](uint16_t j) { h.u32(j); });
    h.each(o.skinWeights.weights, [&](double w) { h.f64(w); });
    h.each(o.morphTargets,
           [&](const MorphTarget& m) { h.each(m.positions, [&](const glm::vec3& p) { h.vec3(p); }); });
    SceneEvaluator evaluator(scene);
    forEachSampledPose(scene, samples, [&](int animation, int, double t) {
        evaluator.evaluate(animation, t);
        h.mat4(evaluator.objectTransform(object));
        if (o.skin != -1)
            h.each(evaluator.jointMatrices(size_t(o.skin)), [&](const glm::dmat4& m) { h.mat4(m); });
        h.each(evaluator.morphWeights(object), [&](double w) { h.f64(w); });
    });
    return h.h;
}

struct PoseCandidate {
    Proxy proxy;
    VertexDeformation deformation;
    PoseBound poses;
};

// Triangles a direction that sampledOverPoses looks at per pose, to find where the rest proxy strays
// most and how far at least.
constexpr size_t kSampledTriangles = 4096;

// `proxy` with the deformation transferred to it; its poses not measured yet.
Result<PoseCandidate> candidate(const Scene& scene, size_t object, Proxy proxy) {
    const SceneObject& o = scene.objects[object];
    Result<VertexDeformation> d = transferDeformation(*o.mesh, deformationOf(o), proxy.mesh);
    if (!d) return fail(d.error());
    return PoseCandidate{std::move(proxy), std::move(d).value(), PoseBound{}};
}

// `proxy` with its deformation and the distances over the poses, sampled (sampledOverPoses).
Result<PoseCandidate> sampled(const Scene& scene, size_t object, Proxy proxy, int samples, unsigned threads) {
    Result<PoseCandidate> c = candidate(scene, object, std::move(proxy));
    if (!c) return c;
    Result<PoseBound> b =
        sampledOverPoses(scene, object, c->proxy.mesh, c->deformation, samples, kSampledTriangles, threads);
    if (!b) return fail(b.error());
    c->poses = b.value();
    return c;
}

// `c` with its bound over the poses certified (boundOverPoses).
Status judge(const Scene& scene, size_t object, PoseCandidate& c, int samples, unsigned threads) {
    const SceneObject& o = scene.objects[object];
    const double margin =
        0.1 *
        std::max(c.proxy.errorBound, 1e-9 * double(glm::length(o.mesh->bounds().max - o.mesh->bounds().min)));
    Result<PoseBound> b =
        boundOverPoses(scene, object, c.proxy.mesh, c.deformation, samples, margin, threads);
    if (!b) return fail(b.error());
    c.poses = b.value();
    return {};
}

// `posed` (a mesh of the render mesh's pose `render`) brought back to the rest pose: each vertex to the
// rest position of the nearest point of the posed render surface.
Result<Mesh> toRest(const Mesh& posed, const Mesh& render, const Mesh& renderRest) {
    Result<ClosestPointQuery> query = ClosestPointQuery::create(render);
    if (!query) return fail(query.error());
    Mesh out = posed;
    for (glm::vec3& p : out.positions) {
        const std::optional<ClosestPoint> near = query->closest(glm::dvec3(p));
        if (!near) return fail("the posed render mesh has no surface");
        const uint32_t* c = &render.indices[3 * size_t(near->triangle)];
        const glm::dvec3 b =
            barycentric(near->point, glm::dvec3(render.positions[c[0]]), glm::dvec3(render.positions[c[1]]),
                        glm::dvec3(render.positions[c[2]]));
        p = glm::vec3(b.x * glm::dvec3(renderRest.positions[c[0]]) +
                      b.y * glm::dvec3(renderRest.positions[c[1]]) +
                      b.z * glm::dvec3(renderRest.positions[c[2]]));
    }
    computeNormals(out);
    return out;
}

// The proxy simplified in the pose (animation, t), brought back to rest.
Result<Proxy> simplifiedInPose(const Scene& scene, size_t object, int animation, double t,
                               const ProxySettings& settings) {
    const SceneObject& o = scene.objects[object];
    SceneEvaluator evaluator(scene);
    evaluator.evaluate(animation, t);
    Mesh posed = withPositions(*o.mesh, posedPositions(scene, object, evaluator));
    computeNormals(posed);
    Result<Proxy> proxy = buildProxy(posed, settings);
    if (!proxy) return fail(proxy.error());
    Result<Mesh> rest = toRest(proxy->mesh, posed, *o.mesh);
    if (!rest) return fail(rest.error());
    proxy->mesh = std::move(rest).value();
    return proxy;
}

// Where the rest proxy `rest` (its distances over the poses sampled) strays beyond its own bound in
// some pose, the proxy simplified in the pose where it strays most, certified over the poses; nothing
// where it does not.
Result<std::optional<PoseCandidate>> posedCandidate(const Scene& scene, size_t object,
                                                    const PoseCandidate& rest, const ProxySettings& settings,
                                                    int samples) {
    if (!(rest.poses.bound > rest.proxy.errorBound)) return std::optional<PoseCandidate>();
    Result<Proxy> posed =
        simplifiedInPose(scene, object, rest.poses.worstAnimation, rest.poses.worstTime, settings);
    if (!posed) return fail(posed.error());
    Result<PoseCandidate> c = candidate(scene, object, std::move(posed).value());
    if (!c) return fail(c.error());
    if (Status st = judge(scene, object, c.value(), samples, settings.threads); !st) return fail(st.error());
    return std::optional<PoseCandidate>(std::move(c).value());
}

} // namespace

Result<DeformingProxy> buildDeformingProxy(const Scene& scene, size_t object, const ProxySettings& settings,
                                           int samples) {
    if (object >= scene.objects.size())
        return fail("deforming proxy: object " + std::to_string(object) + " out of range");
    const SceneObject& o = scene.objects[object];
    const std::string name = "deforming proxy of '" + o.name + "': ";
    if (!o.deforms()) return fail(name + "the object is neither skinned nor morphed");
    Result<Proxy> rest = buildProxy(*o.mesh, settings);
    if (!rest) return fail(name + rest.error());
    if (rest->source == ProxySource::OwnMesh) { // the render mesh moves exactly as it is drawn
        DeformingProxy own;
        own.proxy = std::move(rest).value();
        own.deformation = deformationOf(o);
        own.restCertified = true;
        return own;
    }
    Result<PoseCandidate> best = sampled(scene, object, std::move(rest).value(), samples, settings.threads);
    if (!best) return fail(name + best.error());
    Result<std::optional<PoseCandidate>> posed =
        posedCandidate(scene, object, best.value(), settings, samples);
    if (!posed) return fail(name + posed.error());
    std::optional<PoseCandidate>& other = posed.value();
    DeformingProxy out;
    // The rest proxy's bound would be at least its sampled distances: below them, it loses uncertified.
    bool posedWins = other && other->poses.bound < best->poses.bound;
    if (!posedWins) {
        if (Status st = judge(scene, object, best.value(), samples, settings.threads); !st)
            return fail(name + st.error());
        out.restCertified = true;
        posedWins = other && other->poses.bound < best->poses.bound;
    }
    out.restPoses = best->poses;
    if (posedWins) {
        best = std::move(*other);
        out.simplifiedPosed = true;
    }
    out.proxy = std::move(best->proxy);
    // A deforming object's world finds the drawn surface itself, in every pose; the table faced the
    // drawn surface of one pose (and, simplified in another pose, of that one).
    out.proxy.drawnNormals = DrawnNormals();
    out.proxy.errorBound = best->poses.bound;
    out.proxy.toleranceMet = out.proxy.errorBound <= out.proxy.tolerance;
    out.deformation = std::move(best->deformation);
    out.poses = best->poses;
    return out;
}

namespace {

// buildDeformingProxy's proxy of `object` with kObjectPoseSamples, through the cache when `settings`
// name one (deformingProxyCacheKey): a start from the cache samples no pose.
Result<Proxy> objectDeformingProxy(const Scene& scene, size_t object, const ProxySettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    auto finish = [&](Proxy& p) {
        p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    const bool caching = !settings.cacheDirectory.empty();
    const uint64_t key = caching ? deformingProxyCacheKey(scene, object, settings, kObjectPoseSamples) : 0;
    std::vector<std::string> notes;
    if (caching) {
        Result<Proxy> hit = loadCachedProxy(settings.cacheDirectory, key);
        if (hit) {
            finish(hit.value());
            return hit;
        }
        if (hit.error().rfind("no cache entry", 0) != 0) notes.push_back(hit.error() + "; rebuilt");
    }
    Result<DeformingProxy> built = buildDeformingProxy(scene, object, settings, kObjectPoseSamples);
    if (!built) return fail(built.error());
    Proxy p = std::move(built->proxy);
    p.cached = false; // its rest proxy may come from the cache, but its poses were measured
    p.notes.insert(p.notes.begin(), notes.begin(), notes.end());
    if (caching && p.source != ProxySource::OwnMesh)
        if (Status st = storeCachedProxy(settings.cacheDirectory, key, p); !st) p.notes.push_back(st.error());
    finish(p);
    return p;
}

} // namespace

bool takesDeformingProxy(const SceneObject& o) {
    return o.dynamic && o.deforms();
}

Result<Proxy> buildObjectProxy(const Scene& scene, size_t object, const ProxySettings& settings,
                               const ProgressCallback& progress) {
    if (object >= scene.objects.size())
        return fail("object proxy: object " + std::to_string(object) + " out of range");
    const SceneObject& o = scene.objects[object];
    if (!takesDeformingProxy(o))
        return buildProxy(*o.mesh, settings, o.collider ? &*o.collider : nullptr, progress);
    return objectDeformingProxy(scene, object, settings);
}

} // namespace spatter
