// Watertightness: rays aimed exactly at the shared edges and interior vertices of closed meshes (the
// unit cube, fandisk, the builtin gallery's closed objects). A ray whose segment contains a point of
// the surface must hit the surface no later than that point: none may pass between two triangles.
//
// Directions are drawn so that the ray crosses the surface there cleanly (from the front of every
// adjacent triangle, or from the back of every one, at least 3 degrees away from each plane): a ray
// that only grazes a convex edge may legitimately miss after the rounding of its origin, but one of
// these can only miss through a crack.

#include "StressCase.hpp"
#include "StressSupport.hpp"

#include "spatter/core/GalleryScene.hpp"
#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/SceneLoader.hpp"
#include "spatter/placement/CollisionWorld.hpp"

#include <cmath>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

namespace spatter::stress {

namespace {

struct Target {
    glm::dvec3 point;                // world space, on the surface
    std::vector<glm::dvec3> normals; // world space, of the triangles meeting there
    std::string what;
};

struct Tally {
    size_t rays = 0, misses = 0, targets = 0, skipped = 0;
    double lateness = 0.0; // largest (t_hit - t_target) / scene size over hits (0 when earlier)
};

// A direction crossing every plane of `normals` at least `minSin` away from it, from the front
// (front = true: against every normal) or from the back; false when 32 tries find none.
bool crossingDirection(const std::vector<glm::dvec3>& normals, bool front, Rng& rng, glm::dvec3& out) {
    glm::dvec3 mean(0.0);
    for (const glm::dvec3& n : normals)
        mean += n;
    const double minSin = std::sin(3.0 * kPi / 180.0);
    for (int attempt = 0; attempt < 32; ++attempt) {
        const double spread = attempt < 16 ? 0.8 : 0.2;
        glm::dvec3 d = mean + spread * double(normals.size()) * randomUnit(rng);
        if (!(glm::length(d) > 1e-9)) continue;
        d = glm::normalize(front ? -d : d);
        bool good = true;
        for (const glm::dvec3& n : normals) {
            const double c = glm::dot(d, n);
            if (front ? !(c < -minSin) : !(c > minSin)) good = false;
        }
        if (good) {
            out = d;
            return true;
        }
    }
    return false;
}

// The targets of one object: its shared edges at their midpoints and at random points, and its
// interior vertices. `stride` thins them out for CI.
void objectTargets(const SceneObject& o, size_t stride, Rng& rng, std::vector<Target>& out) {
    const glm::dmat4& m = o.transform;
    const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(m)));
    auto world = [&](const glm::dvec3& p) { return glm::dvec3(m * glm::dvec4(p, 1.0)); };
    auto worldNormal = [&](const glm::dvec3& n) { return glm::normalize(normalMatrix * n); };
    const std::vector<SharedEdge> edges = sharedEdges(*o.mesh);
    for (size_t i = 0; i < edges.size(); i += stride) {
        const SharedEdge& e = edges[i];
        const glm::dvec3 a(o.mesh->positions[e.a]), b(o.mesh->positions[e.b]);
        // Points on the edge, away from its ends: near a vertex (within the float resolution of the
        // frame) the ray meets the whole fan, which the vertex targets test with their own directions.
        for (double s : {0.5, uniform(rng, 0.01, 0.99)}) {
            Target t;
            t.point = world(a + (b - a) * s);
            t.normals = {worldNormal(e.n0), worldNormal(e.n1)};
            t.what = o.name + " edge " + std::to_string(e.a) + "-" + std::to_string(e.b) + " at " + num(s);
            out.push_back(std::move(t));
        }
    }
    const std::vector<InteriorVertex> verts = interiorVertices(*o.mesh);
    for (size_t i = 0; i < verts.size(); i += stride) {
        Target t;
        t.point = world(glm::dvec3(o.mesh->positions[verts[i].v]));
        for (const glm::dvec3& n : verts[i].normals)
            t.normals.push_back(worldNormal(n));
        t.what = o.name + " vertex " + std::to_string(verts[i].v);
        out.push_back(std::move(t));
    }
}

// Shoots `perSide` rays from the front and from the back at every target, through intersectBatch
// and through intersect, and counts the ones that pass through.
void shoot(const CollisionWorld& world, const std::vector<Target>& targets, int perSide, double sceneSize,
           Rng& rng, Tally& tally, StressResult& r) {
    std::vector<Ray> rays;
    std::vector<size_t> owner;
    for (size_t i = 0; i < targets.size(); ++i) {
        for (int k = 0; k < 2 * perSide; ++k) {
            glm::dvec3 d;
            if (!crossingDirection(targets[i].normals, k % 2 == 0, rng, d)) {
                tally.skipped++;
                continue;
            }
            // From a hundredth of the scene to a hundred scenes away; t is in units of the direction.
            const double distance = sceneSize * std::pow(10.0, uniform(rng, -2.0, 2.0));
            Ray ray;
            ray.origin = targets[i].point - d * distance;
            ray.direction = d;
            rays.push_back(ray);
            owner.push_back(i);
        }
    }
    tally.targets += targets.size();
    const std::vector<std::optional<Hit>> hits = world.intersectBatch(rays);
    for (size_t k = 0; k < rays.size(); ++k) {
        tally.rays++;
        const Target& t = targets[owner[k]];
        const double tTarget = glm::length(t.point - rays[k].origin);
        // Every 16th ray is traced alone as well: the single-ray path must agree.
        std::optional<Hit> single;
        if (k % 16 == 0) single = world.intersect(rays[k]);
        const bool batchHit = hits[k] && hits[k]->t <= tTarget + 1e-6 * sceneSize;
        const bool singleHit = k % 16 != 0 || (single && single->t <= tTarget + 1e-6 * sceneSize);
        if (hits[k]) tally.lateness = worse(tally.lateness, std::max(0.0, hits[k]->t - tTarget) / sceneSize);
        if (!batchHit || !singleHit) {
            tally.misses++;
            r.failure("ray through " + t.what + " at " + vec(t.point) + " from " + vec(rays[k].origin) +
                      (hits[k] ? " hit late at t = " + num(hits[k]->t) + " (target " + num(tTarget) + ")"
                               : " passed through"));
        }
    }
}

void addRows(StressResult& r, const std::string& name, const Tally& t) {
    r.row(name + ": rays that passed between triangles (count)", double(t.misses), 0.0, t.rays,
          std::to_string(t.targets) + " edge and vertex targets");
    r.row(name + ": hit beyond the target / scene size", t.lateness, 1e-6, t.rays);
}

} // namespace

StressResult runWatertight(const StressConfig& cfg) {
    StressResult r;
    r.technique = "Embree in robust mode (RTC_SCENE_FLAG_ROBUST): watertight ray/triangle intersection "
                  "(Woop et al. 2013); static geometry in a float frame around a double origin";
    Rng rng(cfg.seed + 7);
    const int perSide = cfg.full ? 16 : 4;

    // The unit cube from MeshBuilder: as it is, turned and scaled (static), and as a dynamic instance.
    {
        Scene scene;
        scene.source = "stress:cubes";
        scene.objects.push_back(makeSceneObject("cube", makeUnitCube()));
        glm::dmat4 turned = glm::translate(glm::dmat4(1.0), glm::dvec3(3.0, 0.5, -2.0));
        turned = glm::rotate(turned, 0.61, glm::normalize(glm::dvec3(0.3, 1.0, -0.2)));
        turned = glm::scale(turned, glm::dvec3(1.7, 0.6, 2.3));
        scene.objects.push_back(makeSceneObject("turned_cube", makeUnitCube(), turned));
        glm::dmat4 moving = glm::translate(glm::dmat4(1.0), glm::dvec3(-3.0, 1.0, 1.0));
        moving = glm::rotate(moving, -1.3, glm::normalize(glm::dvec3(1.0, 0.2, 0.7)));
        scene.objects.push_back(makeSceneObject("dynamic_cube", makeUnitCube(), moving, true));
        Result<CollisionWorld> world = CollisionWorld::build(scene);
        if (!world) {
            r.failure("cube world: " + world.error());
            r.row("cube: world", INFINITY, 0.0, 0);
        } else {
            std::vector<Target> targets;
            for (const SceneObject& o : scene.objects)
                objectTargets(o, 1, rng, targets);
            Tally t;
            // The cube is tiny: many rays per target.
            shoot(world.value(), targets, perSide * 16, scene.worldBounds().diagonal(), rng, t, r);
            addRows(r, "unit cube (3 placements)", t);
        }
    }

    // A flat floor (every box of its hierarchy is flat) and a dynamic cube that moves 1e6 away, which
    // enlarges the region rays start in (the triangles' boxes are grown again): the floor shot from
    // up to 1e6 away stays watertight; then the cube moves back and both are shot again.
    {
        Scene scene = planeScene(5.0);
        const glm::dmat4 near = glm::translate(glm::dmat4(1.0), glm::dvec3(1.0, 1.0, -1.0));
        scene.objects.push_back(makeSceneObject("dynamic_cube", makeUnitCube(), near, true));
        Result<CollisionWorld> world = CollisionWorld::build(scene);
        Tally moved;
        if (!world ||
            !world->setTransform(1, glm::translate(glm::dmat4(1.0), glm::dvec3(7e5, -2e5, 7e5)) * near)) {
            moved.misses++;
            r.failure("floor world: " + (world ? std::string("setTransform failed") : world.error()));
        } else {
            const double size = scene.worldBounds().diagonal();
            std::vector<Target> floor, all;
            objectTargets(scene.objects[0], 1, rng, floor);
            shoot(world.value(), floor, perSide * 4, 1e3 * size, rng, moved, r);
            if (!world->setTransform(1, near)) moved.misses++;
            for (const SceneObject& o : scene.objects)
                objectTargets(o, 1, rng, all);
            shoot(world.value(), all, perSide * 4, size, rng, moved, r);
        }
        addRows(r, "floor, with a cube moved 1e6 away and back", moved);
    }

    // fandisk from the shared data.
    {
        const std::string path = cfg.dataDir.empty() ? "" : cfg.dataDir + "/meshes/fandisk.obj";
        std::error_code ec;
        if (path.empty()) {
            r.row("fandisk: skipped, no shared data directory", 0.0, 0.0, 0).informational = true;
        } else if (!std::filesystem::exists(path, ec)) {
            r.failure(path + " does not exist");
            r.row("fandisk: not found", INFINITY, 0.0, 0).note = path;
        } else {
            Result<Scene> scene = loadScene(path);
            Result<CollisionWorld> world =
                scene ? CollisionWorld::build(scene.value()) : Result<CollisionWorld>(fail(scene.error()));
            if (!world) {
                r.failure("fandisk: " + world.error());
                r.row("fandisk: load and build", INFINITY, 0.0, 0);
            } else {
                std::vector<Target> targets;
                for (const SceneObject& o : scene->objects)
                    objectTargets(o, cfg.full ? 1 : 3, rng, targets);
                Tally t;
                shoot(world.value(), targets, perSide, scene->worldBounds().diagonal(), rng, t, r);
                addRows(r, "fandisk", t);
            }
        }
    }

    // The builtin gallery's closed objects (walls, pillars, crates, arch, dynamic targets).
    {
        GallerySettings gs;
        gs.detail = cfg.full ? 2 : 0;
        const Scene scene = makeGalleryScene(gs);
        Result<CollisionWorld> world = CollisionWorld::build(scene);
        if (!world) {
            r.failure("gallery: " + world.error());
            r.row("gallery: build", INFINITY, 0.0, 0);
        } else {
            std::vector<Target> targets;
            size_t closed = 0;
            for (const SceneObject& o : scene.objects) {
                if (!closedMesh(*o.mesh)) continue;
                closed++;
                objectTargets(o, cfg.full ? 1 : 4, rng, targets);
            }
            Tally t;
            shoot(world.value(), targets, perSide, scene.worldBounds().diagonal(), rng, t, r);
            addRows(r, "gallery, " + std::to_string(closed) + " closed objects", t);
            // The gallery must offer closed objects at all, or this part tests nothing.
            r.row("gallery: closed objects found (missing of 15)", double(closed >= 15 ? 0 : 15 - closed),
                  0.0, scene.objects.size());
        }
    }
    return r;
}

} // namespace spatter::stress
