#pragma once
// CollisionWorld: the Embree scene that shots are traced against. Every decal receiver of a Scene
// contributes its collision mesh (a proxy, an authored collider or the render mesh) and the error
// bound h within which that mesh stays of the render surface.
//
// Layout: one Embree device; every scene ROBUST. The collision meshes of the static receivers are
// one Embree scene (one geometry per object), stored in single precision relative to a
// double-precision origin (the centre of the static bounds), so that far from the world origin the
// geometry keeps float precision. Each dynamic receiver, and each static one whose collision
// triangles the world holds four times or more, is an instance of an object-space scene with its
// object-to-world transform; those that do not deform and use one collision mesh (collisionMeshOf)
// share one scene. The top-level scene holds the static scene (one instance) and the dynamic
// instances, so moving an object only updates its instance and recommits the top level.
// Objects with receivesDecals == false are not in the world (shots pass through them).
//
// Transforms: Embree traces in single precision, so an object is traced only while its transform
// keeps the rule of TraceTransform.hpp (its float matrix has a finite inverse, a condition number of
// at most 2^16 and scales within 2^+-25; the object lies within 2^32 of origin() and is not smaller
// than a few float steps there). An object in
// the world whose transform breaks it is left out of the trace (CollisionObject::traced is false,
// `untraced` says why, warnings() lists it) until setTransform gives it a usable one; no matrix that
// breaks the rule ever reaches Embree. Every ray handed to Embree is valid by construction: finite
// origin within +-1.844e18, unit finite direction, 0 = tnear <= tfar finite.
//
// Queries: rays are validated (rayProblem), normalised and clipped to the world bounds in double,
// moved into the float frame, traced (mask 0xFFFFFFFF, geomID and instID starting invalid), and the
// hit is refined in double on the hit triangle in object space. Among hits at exactly the same
// distance the one with the smallest (instance, geometry, primitive) wins whatever the traversal
// order.
// Triangles are intersected with the watertight test of Woop, Benthin and Wald 2013 (as Embree user
// geometry): a ray through an edge or a vertex shared by triangles always meets one of them.
//
// Threading: intersect and intersectBatch are const and may run concurrently from any number of
// threads; setTransform, setPose and removeObject must not run concurrently with anything else.

#include "spatter/core/Bounds.hpp"
#include "spatter/core/Mesh.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/placement/Ray.hpp"

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace spatter {

struct WorldSettings {
    // Use SceneObject::collider where an object has one and no Proxy is given; its error bound is
    // then measured at build time by buildProxy with the collider: certified (never below the true
    // two-sided Hausdorff distance) and at most about 1% of the render mesh's diagonal above the
    // measured distance. false: render meshes (h = 0) wherever no Proxy is given.
    bool useColliders = true;
    // Embree device configuration passed to rtcNewDevice, e.g. "threads=4" or "isa=avx2" (empty:
    // Embree's defaults). A configuration Embree rejects makes build fail.
    std::string deviceConfig;
};

// What the world knows about one Scene object.
struct CollisionObject {
    std::string name;
    bool dynamic = false;
    bool inWorld = false;      // receives decals and has not been removed
    bool traced = false;       // in the world and its transform keeps the rule of TraceTransform.hpp
    std::string untraced;      // why an object in the world is not traced; empty when traced
    glm::dmat4 transform{1.0}; // object to world, current
    double errorBound = 0.0;   // h, object-space units
    size_t triangles = 0;      // collision triangles (0 for an object never in the world; one
                               // removed keeps its value)
    Bounds localBounds;        // of the collision mesh (of the render mesh for an object never in
                               // the world; one removed keeps its collision mesh's)
    // What the decals on the object were placed against: a 64-bit hash (FNV-1a over little-endian
    // 32-bit words) of the collision mesh's vertex count, positions, index count and indices and of the
    // error bound; 0 for an object built outside the world. A save of a decal system keys its objects
    // by it (DecalPersistence.hpp).
    uint64_t meshHash = 0;
    // How the world traces it: as an instance of an object-space scene (dynamic objects, and static
    // ones whose collision triangles the world holds four times or more) rather than in the static
    // scene.
    bool instanced = false;
    // The object whose collision mesh (and measured bound) this one uses: an earlier object with the
    // same render mesh and collider, given no proxy or an equal one, or this object's own index.
    // Instanced objects that use one collision mesh and do not deform trace one Embree scene.
    uint32_t collisionMeshOf = 0;
};

// One ray hit. Normals are unit, geometric (the hit triangle's face normal, the vector Embree reports
// as Ng, recomputed in double), and face the ray: dot(normal, ray.direction) <= 0.
struct Hit {
    uint32_t object = 0;           // index into Scene::objects
    uint32_t primitive = 0;        // triangle index in the object's collision mesh
    double t = 0.0;                // ray parameter, in units of the ray's direction
    glm::dvec3 position{0.0};      // world space: origin + t * direction
    glm::dvec3 normal{0.0};        // world space, through the object's normal matrix
    glm::dvec3 localPosition{0.0}; // object space
    glm::dvec3 localNormal{0.0};   // object space
    // The ray meets the side the triangle's winding faces (counter-clockwise seen from that side,
    // through the normal matrix): for a closed mesh wound outwards, the ray enters it there.
    bool frontFace = true;
};

// A point of a deforming object's render surface: a triangle of its render mesh and barycentric
// coordinates in it, so that it moves with the surface at any pose.
struct SurfaceAnchor {
    uint32_t triangle = 0;
    glm::dvec3 bary{1.0, 0.0, 0.0};
};

// A surface anchor and its frame at the pose it was found at (CollisionWorld::anchorFrame).
struct SurfaceLocation {
    SurfaceAnchor surface;
    glm::dmat4 frame{1.0};
};

// What setTransform did with a transform it accepted.
struct TransformUpdate {
    bool traced = true;  // false: the transform breaks the rule of TraceTransform.hpp; shots pass
                         // through the object until a later setTransform gives it a usable one
    std::string warning; // why it is not traced, naming the object; empty when traced
};

class CollisionWorld {
public:
    // Builds the world for `scene` (validated with validateScene first). `proxies` is empty or has
    // one entry per Scene object; a present entry (from buildProxy) replaces that object's collision
    // mesh: its `mesh` (object space, validated with validateMesh), `errorBound` (object-space units,
    // finite and >= 0) and `drawnNormals` (nine a triangle, or empty: then found here) are used, the
    // other fields are not. Objects placed with one mesh take one proxy (proxySources): give them the
    // same entry, as they share the mesh. Objects with the same render mesh and collider, given no
    // proxy or equal ones, take the first one's collision mesh, measured bound and drawn normals
    // instead of measuring and keeping them again. Errors name the object. An object whose transform breaks
    // the rule of TraceTransform.hpp is no error: it is built untraced and warnings() names it.
    static Result<CollisionWorld> build(const Scene& scene,
                                        const std::vector<std::shared_ptr<const Proxy>>& proxies = {},
                                        const WorldSettings& settings = {});

    // Movable, not copyable. A moved-from CollisionWorld holds nothing: assign to it or destroy it, and call
    // nothing else on it.
    CollisionWorld(CollisionWorld&&) noexcept;
    CollisionWorld& operator=(CollisionWorld&&) noexcept;
    ~CollisionWorld();

    // Closest hit along `ray` with t in [tnear, tfar], or nothing (also for a ray that rayProblem
    // rejects).
    std::optional<Hit> intersect(const Ray& ray) const;
    // The hits of `rays`; element i equals intersect(rays[i]) exactly, bit for bit (bad rays hit
    // nothing; an empty batch gives an empty vector). Consecutive rays that start at one point
    // (within 1e-3 of the world's extent) in a narrow bundle, at least 4 of them within 3 degrees of
    // their mean direction (a shotgun burst), are traced together as an Embree packet (rtcIntersect4,
    // 8 or 16: the widest the device runs natively); other rays one by one with rtcIntersect1, which
    // is faster for them. The batch is not reordered: list the rays of a burst together. A burst of
    // 16 rays in a 3 degree cone takes about 0.7 of the time per ray of intersect; scattered rays and
    // cones of 7 degrees or more about the same time (docs/BENCHMARKS.md).
    std::vector<std::optional<Hit>> intersectBatch(const std::vector<Ray>& rays) const;

    // Moves a dynamic object (its instance transform; only the top level is recommitted). Fails, and
    // changes nothing, for an index out of range, a static object, an object not in the world, or a
    // transform that is not finite and affine (transformProblem). A transform that breaks the rule
    // of TraceTransform.hpp is taken: the object keeps it (its decals follow it) but is left out of
    // the trace until a later call gives it a usable one, and the result says so.
    Result<TransformUpdate> setTransform(uint32_t object, const glm::dmat4& transform);
    // Poses a dynamic skinned or morphed object as it is drawn: its object-to-world `transform` (as
    // setTransform), its skin's joint matrices `joints` (bind space to world, one per joint of the
    // skin, as SceneEvaluator::jointMatrices gives them or a host's own animation system computes
    // them; empty when not skinned) and its `morphWeights` (one per morph target). The collision mesh
    // moves as the render mesh does: a render mesh by its own weights and targets, a proxy or collider
    // by those transferred from the render mesh at build time (transferDeformation: each of its
    // vertices follows the nearest point of the render surface). Its hierarchy is refitted, not
    // rebuilt. The error bound stays the one certified at the rest pose (docs/ACCURACY.md says how
    // far it holds at other poses). Fails, and changes nothing, for an index out of range, a static
    // object, an object not in the world or without skin and morph targets, a transform setTransform
    // refuses, joints or weights that do not fit the object (their count, a non-finite or non-affine
    // matrix, a non-finite weight), or a pose that puts a vertex at a non-finite position.
    Result<TransformUpdate> setPose(uint32_t object, const glm::dmat4& transform,
                                    const std::vector<glm::dmat4>& joints,
                                    const std::vector<double>& morphWeights);
    // Whether `object` is in the world and deforms: skinned or morphed, its collision mesh posed by
    // setPose and its decals anchored by anchorAt.
    bool deforms(uint32_t object) const;
    // The point of a skinned or morphed object's drawn surface that a hit on its collision mesh
    // stands for: the hit (triangle `primitive`, Hit::primitive, at `localPosition`,
    // Hit::localPosition) and the shot (`localDirection`, object space; zero for none) taken back to
    // the rest pose, to the render triangle the shot's line meets there first, from a little before
    // the hit to a little beyond it (else nearest the hit; else the one nearest the hit, and those
    // around it), then where the shot meets that triangle, or the neighbour it passes into, at the
    // current pose (without a shot, the foot of the hit on it); with its frame at the current pose
    // (anchorFrame). Empty for an object that does not deform, is not in the world, a primitive out
    // of range, or a render triangle that has collapsed at the pose.
    std::optional<SurfaceLocation> anchorAt(uint32_t object, uint32_t primitive,
                                            const glm::dvec3& localPosition,
                                            const glm::dvec3& localDirection = glm::dvec3(0.0)) const;
    // Which way the drawn surface faces where a hit on a proxy or collider lands: the unit object-space
    // face normal of the render triangle nearest the centre of the part of the hit triangle
    // (`primitive`, Hit::primitive) that `localPosition` (Hit::localPosition) lies in, each collision
    // triangle cut into nine parts whose normals are found when the world is built. Empty for an
    // object whose collision mesh is its render mesh, one that deforms (anchorAt finds its drawn
    // surface), one not in the world, a primitive out of range, or a render triangle without area.
    std::optional<glm::dvec3> drawnNormalAt(uint32_t object, uint32_t primitive,
                                            const glm::dvec3& localPosition) const;
    // The frame of `anchor` at the object's current pose, in its object space: columns the direction
    // of the anchor's render triangle's first edge, the perpendicular in its plane and its normal,
    // and, as translation, the anchor's point. What a decal on a deforming surface rides. Empty for
    // an object that does not deform or a posed triangle that has collapsed.
    std::optional<glm::dmat4> anchorFrame(uint32_t object, const SurfaceAnchor& anchor) const;
    // Takes an object out of the world (later rays pass through it). Fails for an index out of range
    // or an object not in the world.
    Status removeObject(uint32_t object);

    // Number of Scene objects the world was built from (receivers or not).
    size_t objectCount() const;
    // The object at `index`, or nullptr when out of range.
    const CollisionObject* object(uint32_t index) const;
    // World-space bounds of the object's collision mesh under its current transform (of the render
    // mesh for objects never in the world); empty for an index out of range or an empty mesh.
    DBounds worldBounds(uint32_t index) const;
    // The object's error bound in world units under its current transform: errorBound times a bound
    // of how far the transform's linear part stretches (LinearStretch.hpp: its largest scale for TRS
    // transforms, more for a shear). 0 for an index out of range.
    double worldErrorBound(uint32_t index) const;
    // One line per object in the world that is not traced: "object 3 (crate): transform is singular
    // in single precision (condition number 4e+09, limit 65536); not traced".
    std::vector<std::string> warnings() const;
    // Origin of the single-precision frame the static geometry is stored in.
    glm::dvec3 origin() const;
    // Collision triangles of the objects in the world.
    size_t triangleCount() const;

private:
    struct Impl;
    explicit CollisionWorld(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

} // namespace spatter
