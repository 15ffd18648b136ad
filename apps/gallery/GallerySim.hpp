#pragma once
// GallerySim: the shooting gallery without its window: the scene, its collision proxies, the decal
// system with the gallery's decal types, and the targets moving on their rails. The headless run
// and the window both drive it.

#include "GalleryOptions.hpp"

#include "spatter/core/DecalType.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/placement/DecalPersistence.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace spatter::gallery {

enum class ShotKind { Bullet, Paint, Scorch, Crater };

// The builtin gallery's cloth banners ("banner_*"): they wave instead of riding a rail.
bool isBanner(const SceneObject& object);

// A dynamic object sliding along its rail and turning about the vertical through its origin.
struct Rail {
    uint32_t object = 0;
    glm::dmat4 base{1.0}; // transform at the rail's centre
    double amplitude = 1.0;
    double speed = 0.8; // radians per second of the slide
    double phase = 0.0;
    double turn = 0.5; // largest turn, radians
};

struct ShotCounters {
    uint64_t shots = 0;
    uint64_t onMovingTargets = 0;  // decals placed on dynamic objects
    uint64_t onSkinnedTargets = 0; // of those, on skinned or morphed ones (which follow the skin)
    double placementSeconds = 0.0; // spent in spawn calls
};

// Proxies built at one tolerance, waiting to be used (GallerySim::buildProxies).
struct ProxySet {
    // Per scene object (the objects placed with one mesh share its proxy); none for those that receive
    // no decals.
    std::vector<std::shared_ptr<const Proxy>> proxies;
    float tolerancePercent = 0.0f;
    double seconds = 0.0;
};

class GallerySim {
public:
    static Result<GallerySim> create(const GalleryOptions& options);

    // Builds the proxies of every receiver at `tolerancePercent` of its bounding diagonal (cached on
    // disk), and a fresh decal system on them. Decals placed so far are dropped.
    Status rebuildProxies(float tolerancePercent);
    // The proxies alone, object by object on several threads, saying each cold build on stderr. It
    // reads only the scene and the options, so it may run on a thread of its own while the gallery
    // plays on; `progress` (when given) follows the fraction of the receivers' triangles done.
    Result<ProxySet> buildProxies(float tolerancePercent, std::atomic<float>* progress = nullptr) const;
    // A fresh collision world and decal system on `set`; decals placed so far are dropped.
    Status useProxies(ProxySet set);

    // Advances the clock: targets move along their rails, the scene's first animation plays
    // (looping, from GalleryOptions::startTime), decals age.
    void advance(double dt);
    // A shot fired: its ray, the decal type it fired and what it gave.
    struct Shot {
        Ray ray;
        uint16_t type = 0;
        SpawnResult result;
    };
    // Fires one shot and counts it.
    Shot shoot(const Ray& ray, ShotKind kind);

    // Lays a decal on the drawn surface where a renderer found it (DecalSystem::layOnDrawnSurface).
    Result<DrawnSurfaceLaying> layOnDrawnSurface(DecalHandle handle, const glm::dvec3& point,
                                                 const glm::dvec3& normal);
    // Places the decal of a shot that the collision surface refused where a renderer found it meeting
    // the drawn surface (DecalSystem::spawnOnDrawnSurface), and counts it as the shots' decals are counted.
    SpawnResult spawnOnDrawnSurface(const Shot& shot, const glm::dvec3& point, const glm::dvec3& normal);
    // Replaces the decal of `shot` by the one the shot places where it met the drawn surface before
    // the decal's box (DecalSystem::replaceOnDrawnSurface), counted as the shots' decals are counted.
    SpawnResult replaceOnDrawnSurface(const Shot& shot, const glm::dvec3& point, const glm::dvec3& normal);
    // Counts the decal systems this gallery has had (new proxies, a load): a handle is good only with
    // the number it was given under.
    uint64_t systemNumber() const { return systemNumber_; }

    // Writes the decal system's state to `path` (DecalPersistence.hpp).
    Status save(const std::string& path) const;
    // Loads a state that save() wrote; on failure nothing changes. The clock takes the saved time, and
    // the targets their places on the rails then. Objects whose proxy differs (another tolerance, or
    // another scene) drop their decals, as the report says.
    Result<DecalLoadReport> load(const std::string& path);

    const Scene& scene() const { return *scene_; }
    // The scene posed at the clock's time of its first animation; null for a scene without animations.
    const SceneEvaluator* evaluator() const { return evaluator_.get(); }
    const DecalSystem& decals() const { return *system_; }
    const std::vector<Rail>& rails() const { return rails_; }
    // Dynamic decal receivers: the targets on rails and the waving banners.
    const std::vector<uint32_t>& movingObjects() const { return moving_; }
    const ShotCounters& counters() const { return counters_; }
    // Decal types in registry order (Decal::type indexes them), for the renderer.
    const std::vector<DecalType>& types() const { return types_; }
    // Object decal IDs of every scene object, for the renderer.
    std::vector<uint8_t> objectIds() const;
    glm::dmat4 transform(uint32_t object) const;

    float tolerancePercent() const { return tolerancePercent_; }
    size_t renderTriangles() const { return scene_->triangleCount(); }
    size_t proxyTriangles() const;
    double errorBound() const; // largest world-space proxy error bound h
    double proxySeconds() const { return proxySeconds_; }
    double time() const { return time_; }

    // The collision mesh of every object (object space; empty for objects that receive no decals),
    // for the proxy wireframe overlay.
    const std::vector<Mesh>& proxyMeshes() const { return proxyMeshes_; }

    // Types set in the HUD: wrap-around on the paint types.
    void setPaintWrapAround(bool on);

private:
    GallerySim() = default;
    Status registerTypes();
    // Poses the animation at the clock's time and moves its dynamic receivers in the decal system.
    void pose();
    // Counts a placed decal on a moving or a skinned target.
    void countPlaced(const SpawnResult& result);

    GalleryOptions options_;
    std::unique_ptr<Scene> scene_; // on the heap: the evaluator keeps a reference to it
    std::unique_ptr<SceneEvaluator> evaluator_;
    std::vector<uint32_t> animated_; // objects the animation places (they ride no rail)
    std::optional<DecalSystem> system_;
    std::vector<DecalType> types_;
    std::vector<uint16_t> typeOf_[4]; // registry indices per ShotKind
    std::vector<Mesh> proxyMeshes_;
    std::vector<Rail> rails_;
    std::vector<uint32_t> moving_;
    ShotCounters counters_;
    Rng rng_{1};
    float tolerancePercent_ = 0.0f;
    double proxySeconds_ = 0.0;
    double time_ = 0.0;
    uint64_t systemNumber_ = 0;
};

} // namespace spatter::gallery
