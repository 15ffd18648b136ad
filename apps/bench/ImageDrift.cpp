#include "ImageDrift.hpp"

#include "BenchSupport.hpp"
#include "CoverageProbe.hpp"
#include "DecalMarker.hpp"
#include "SkinPoints.hpp"
#include "SkinnedModels.hpp"

#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/VertexDeformation.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/render/GlContext.hpp"
#include "spatter/render/Renderer.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>

namespace spatter::bench {

namespace {

constexpr int kSplatTexels = 1024;

using tracking::Marker;

// A followed decal: its handle, the surface point it was placed on, its record at spawn and the
// joint that carries it the engines' way.
struct Followed {
    DecalHandle handle;
    SurfaceAnchor point;
    Decal atSpawn;
    uint16_t joint = 0;
};

class DriftRig {
public:
    DriftRig(const ImageDriftInput& in, std::unique_ptr<GlContext> gl, Renderer renderer, DecalSystem system)
        : in_(in), gl_(std::move(gl)), renderer_(std::move(renderer)), system_(std::move(system)),
          evaluator_(*in.scene), skin_(size_t(in.scene->objects[in.object].skin)) {}

    static Result<DriftRig> create(const ImageDriftInput& in) {
        Result<GlContext> gl = GlContext::createHeadless();
        if (!gl) return fail(gl.error());
        auto context = std::make_unique<GlContext>(std::move(gl).value());
        RendererSettings rs;
        rs.width = in.width;
        rs.height = in.height;
        rs.waitForTimers = true;
        Result<Renderer> renderer = Renderer::create(*context, rs);
        if (!renderer) return fail(renderer.error());
        if (Status s = renderer->setScene(*in.scene); !s) return fail(s.error());
        Result<DecalType> marker = tracking::markerType(renderer.value(), coverageType(in.decalSize));
        if (!marker) return fail(marker.error());
        const DecalType& type = marker.value();
        renderer->setDecalTypes({type});
        Result<DecalSystem> system =
            coverageSystem(CollisionWorld::build(*in.scene), type, 20.0 * in.decalSize, 5);
        if (!system) return fail(system.error());
        if (Status s = renderer->setObjectIds(system->objectIds()); !s) return fail(s.error());
        return DriftRig(in, std::move(context), std::move(renderer).value(), std::move(system).value());
    }

    // Poses the decal system and the renderer at `t`.
    Status pose(double t) {
        evaluator_.evaluate(0, t);
        const uint32_t o = in_.object;
        if (Result<TransformUpdate> u =
                system_.setPose(o, evaluator_.objectTransform(o), evaluator_.jointMatrices(skin_),
                                evaluator_.morphWeights(o));
            !u)
            return fail(u.error());
        positions_ = worldPositionsOf(*in_.scene, o, evaluator_);
        return renderer_.setPose(evaluator_);
    }

    // The albedo view with `decals`, and its FrameStats.
    Result<Image> draw(const std::vector<Decal>& decals, FrameStats* stats = nullptr) {
        return tracking::drawAlone(renderer_, in_.camera, View::Albedo, decals, stats);
    }

    // The render surface in world space at the last pose.
    const std::vector<glm::dvec3>& worldPositions() const { return positions_; }

    // The surface point `a` in the current pose, in the world, and how squarely it faces the eye.
    struct SeenPoint {
        glm::dvec3 world{0.0};
        double cosine = 0.0;
    };
    SeenPoint seen(const SurfaceAnchor& a) const {
        const Mesh& mesh = *in_.scene->objects[in_.object].mesh;
        const std::vector<glm::dvec3>& p = worldPositions();
        const uint32_t* c = cornersOf(mesh, a);
        const glm::dvec3 world = pointOf(mesh, p, a);
        return {world, tracking::facingCosine(p[c[0]], p[c[1]], p[c[2]], world, in_.camera.eye)};
    }

    // The pixel of a world point, and the decal's size in pixels there.
    glm::dvec2 project(const glm::dvec3& world) const {
        return tracking::pixelOf(in_.camera, in_.width, in_.height, world);
    }
    double sizePixels(const glm::dvec3& world) const {
        return tracking::pixelsAcross(in_.camera, in_.height, in_.decalSize, world);
    }

    // The decal `f` as the nearest joint carries it to the current pose from its spawn pose.
    Decal carriedByJoint(const Followed& f, const glm::dmat4& spawnTransform,
                         const glm::dmat4& spawnJoint) const {
        const glm::dmat4 m = glm::inverse(evaluator_.objectTransform(in_.object)) *
                             evaluator_.jointMatrices(skin_)[f.joint] * glm::inverse(spawnJoint) *
                             spawnTransform;
        Decal d = f.atSpawn;
        d.center = glm::vec3(m * glm::dvec4(f.atSpawn.center, 1.0));
        const Frame a = f.atSpawn.frame();
        const glm::dmat3 l(m);
        Frame moved;
        moved.tangent = glm::vec3(glm::normalize(l * glm::dvec3(a.tangent)));
        moved.bitangent = glm::vec3(glm::normalize(l * glm::dvec3(a.bitangent)));
        moved.normal = glm::vec3(glm::normalize(l * glm::dvec3(a.normal)));
        d.setFrame(moved);
        return d;
    }

    Renderer& renderer() { return renderer_; }
    DecalSystem& system() { return system_; }
    const SceneEvaluator& evaluator() const { return evaluator_; }
    size_t skin() const { return skin_; }

private:
    const ImageDriftInput& in_;
    std::unique_ptr<GlContext> gl_;
    Renderer renderer_;
    DecalSystem system_;
    SceneEvaluator evaluator_;
    size_t skin_;
    std::vector<glm::dvec3> positions_; // the render surface in world space at the last pose
};

// One method's drift: `record(f, frame)` gives decal f's record at the posed frame (frame -1: the
// spawn pose, which the rig stands in when it is called).
using RecordAt = std::function<Result<Decal>(const Followed&, int)>;

class DriftMeasure {
public:
    DriftMeasure(DriftRig& rig, const ImageDriftInput& in) : rig_(rig), in_(in) {}

    // Shoots until in.decals decals land visibly on the object, and draws the frames without decals.
    Status prepare() {
        if (Status s = rig_.pose(in_.spawnTime); !s) return s;
        spawnTransform_ = rig_.evaluator().objectTransform(in_.object);
        spawnJoints_ = rig_.evaluator().jointMatrices(rig_.skin());
        const Mesh& rest = *in_.scene->objects[in_.object].mesh;
        const std::vector<glm::dvec3>& p = rig_.worldPositions();
        Result<ClosestPointQuery> query = ClosestPointQuery::create(withPositions(rest, p));
        if (!query) return fail(query.error());
        Result<Image> bare = rig_.draw({});
        if (!bare) return fail(bare.error());
        spawnBare_ = std::move(bare).value();
        for (const Ray& ray : in_.shots) {
            if (followed_.size() >= in_.decals) break;
            const SpawnResult r = rig_.system().spawn(ray, 0);
            if (!r.placed() || rig_.system().get(r.handle)->object != in_.object) continue;
            const glm::dvec3 centre = rig_.system().worldBox(r.handle)->center;
            Followed f{r.handle, nearestPoint(query.value(), rest, p, centre), *rig_.system().get(r.handle),
                       carryingJoint(in_.scene->objects[in_.object].skinWeights, p, centre)};
            Result<Image> with = rig_.draw({f.atSpawn});
            if (!with) return fail(with.error());
            const std::optional<double> seen =
                drawnCentreDrift(f, tracking::findMarker(with.value(), spawnBare_));
            if (seen) followed_.push_back(f);
        }
        for (double t : in_.frameTimes) {
            if (Status s = rig_.pose(t); !s) return s;
            Result<Image> frame = rig_.draw({});
            if (!frame) return fail(frame.error());
            bare_.push_back(std::move(frame).value());
        }
        return {};
    }

    Result<ImageDriftRow> skinAnchors() {
        return measure("skin anchors, projected",
                       [&](const Followed& f, int) -> Result<Decal> { return *rig_.system().get(f.handle); });
    }

    Result<ImageDriftRow> nearestJoint() {
        return measure("nearest joint", [&](const Followed& f, int frame) -> Result<Decal> {
            if (frame < 0) return f.atSpawn;
            return rig_.carriedByJoint(f, spawnTransform_, spawnJoints_[f.joint]);
        });
    }

    // Splats each decal alone at its spawn pose, then draws the object's decal texture as it poses.
    Result<ImageDriftRow> textureSpace() {
        const char* method = "texture-space splat";
        Renderer& r = rig_.renderer();
        if (Status s = r.setObjectDecalMode(in_.object, DecalMode::TextureSpace, kSplatTexels); !s) {
            ImageDriftRow row;
            row.method = method;
            row.unavailable = s.error();
            return row;
        }
        std::vector<double> splatMs;
        Result<ImageDriftRow> row = measure(method, [&](const Followed& f, int frame) -> Result<Decal> {
            if (frame >= 0) return *rig_.system().get(f.handle); // not splatted again
            if (Status s = r.clearObjectDecals(in_.object); !s) return fail(s.error());
            FrameStats stats;
            if (Result<Image> splat = rig_.draw({f.atSpawn}, &stats); !splat) return fail(splat.error());
            splatMs.push_back(stats.gpu.splatMs);
            return f.atSpawn;
        });
        if (Status s = r.setObjectDecalMode(in_.object, DecalMode::Projected); !s) return fail(s.error());
        if (row) row->splatMs = median(splatMs);
        return row;
    }

private:
    // Decal f drawn alone at the spawn pose and at every frame, its marker against its point.
    Result<ImageDriftRow> measure(const char* method, const RecordAt& record) {
        ImageDriftRow row;
        row.method = method;
        row.decals = followed_.size();
        for (const Followed& f : followed_) {
            if (Status s = rig_.pose(in_.spawnTime); !s) return fail(s.error());
            Result<std::optional<double>> atSpawn = driftOf(f, record, -1, spawnBare_);
            if (!atSpawn) return fail(atSpawn.error());
            row.atSpawnMax = std::max(row.atSpawnMax, atSpawn->value_or(0.0));
            for (size_t k = 0; k < in_.frameTimes.size(); ++k) {
                if (Status s = rig_.pose(in_.frameTimes[k]); !s) return fail(s.error());
                Result<std::optional<double>> d = driftOf(f, record, int(k), bare_[k]);
                if (!d) return fail(d.error());
                if (d->has_value()) row.drift.push_back(d->value());
            }
        }
        return row;
    }

    // Decal f drawn alone at the posed frame, and its drift there (drawnCentreDrift).
    Result<std::optional<double>> driftOf(const Followed& f, const RecordAt& record, int frame,
                                          const Image& bare) {
        Result<Decal> decal = record(f, frame);
        if (!decal) return fail(decal.error());
        Result<Image> with = rig_.draw({decal.value()});
        if (!with) return fail(with.error());
        return drawnCentreDrift(f, tracking::findMarker(with.value(), bare));
    }

    // The distance from f's marker to its point in the current pose, or nothing where the marker does
    // not show whole (tracking::showsWhole: hidden in part, clipped where the decal slid, or the point
    // seen nearly edge-on).
    std::optional<double> drawnCentreDrift(const Followed& f, const Marker& m) const {
        const DriftRig::SeenPoint at = rig_.seen(f.point);
        const double size = rig_.sizePixels(at.world);
        if (!tracking::showsWhole(m, at.cosine, size)) return std::nullopt;
        return glm::length(m.centre - rig_.project(at.world)) / size;
    }

    DriftRig& rig_;
    const ImageDriftInput& in_;
    std::vector<Followed> followed_;
    glm::dmat4 spawnTransform_{1.0};
    std::vector<glm::dmat4> spawnJoints_;
    Image spawnBare_;
    std::vector<Image> bare_; // per frame
};

} // namespace

Result<std::vector<ImageDriftRow>> measureImageDrift(const ImageDriftInput& in) {
    if (!in.scene || in.object >= in.scene->objects.size() || in.scene->objects[in.object].skin < 0)
        return fail("image drift: the object is not skinned");
    Result<DriftRig> rig = DriftRig::create(in);
    if (!rig) return fail("image drift: " + rig.error());
    DriftMeasure measure(rig.value(), in);
    if (Status s = measure.prepare(); !s) return fail("image drift: " + s.error());
    std::vector<ImageDriftRow> rows;
    for (auto method :
         {&DriftMeasure::skinAnchors, &DriftMeasure::textureSpace, &DriftMeasure::nearestJoint}) {
        Result<ImageDriftRow> row = (measure.*method)();
        if (!row) return fail("image drift: " + row.error());
        rows.push_back(std::move(row).value());
    }
    return rows;
}

} // namespace spatter::bench
