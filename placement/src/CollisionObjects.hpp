#pragma once
// Internal to placement: what the collision world keeps of each Scene object (ObjectData) and how it
// is filled from the scene. A receiver is traced as its proxy, its authored collider (with its bound
// measured here) or its render mesh; under a proxy or collider the world also keeps which way the
// drawn surface faces. Objects that place one mesh many times (proxySources: the same render mesh and
// collider) take the first one's collision mesh, bound and drawn normals instead of measuring them
// again, and dynamic ones that do not deform share its Embree scene (CollisionWorld.cpp).

#include "PosedCollisionMesh.hpp"
#include "WatertightTriangles.hpp"

#include "spatter/core/Bounds.hpp"
#include "spatter/core/DrawnNormals.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/core/TrianglePieces.hpp"
#include "spatter/placement/CollisionWorld.hpp"

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace spatter {

// A collision object: its triangles as Embree traces them (TracedTriangles: indices, the vertices
// Embree sees and their reach), and what the world keeps besides. An instanced object that shares
// another's scene traces that one's triangles (`tracedBy`), whose reach then covers both.
struct ObjectData : TracedTriangles {
    CollisionObject info;
    std::vector<glm::vec3> positions;          // collision mesh, object space
    glm::dmat4 inverse{1.0};                   // of info.transform, kept with it
    std::optional<PosedCollisionMesh> posable; // dynamic skinned or morphed objects: what setPose poses
    std::optional<DrawnNormals> drawnNormals;  // proxies and colliders of objects that do not deform
    std::vector<glm::dmat4> poseJoints;        // the joint matrices of the last setPose (empty: rest)
    std::vector<double> poseMorphs;            // the morph weights of the last setPose
    RTCScene scene = nullptr;                  // instanced objects: their object-space scene (a reference)
    // Instanced objects: the object whose triangles their scene holds, or their own index.
    uint32_t tracedBy = 0;
    unsigned geomId = kInvalidId; // in the static scene, or the instance in the top scene

    // The object whose `positions`, `indices` and `drawnNormals` are this one's collision mesh
    // (fillObjects): its own, or an earlier copy's, where its own stay empty but for the indices of
    // Embree geometry it holds.
    uint32_t shape() const { return info.collisionMeshOf; }

    // The barycentric coordinates of `local` (object space) in collision triangle `primitive` (in range).
    glm::dvec3 barycentricOn(uint32_t primitive, const glm::dvec3& local) const {
        const uint32_t* c = &indices[3 * size_t(primitive)];
        return barycentric(local, glm::dvec3(positions[c[0]]), glm::dvec3(positions[c[1]]),
                           glm::dvec3(positions[c[2]]));
    }
};

// Bounds of the vertices the triangles use: an unreferenced vertex is no part of the surface and
// must not move the origin of the float frame (one far away would cost the geometry its precision).
Bounds meshBounds(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices);

// What CollisionWorld::build asks of the proxy of object `name`.
Status checkProxy(const Proxy& proxy, const std::string& name);

// Fills `objects` (one per Scene object) from `scene`: each object's name, transform and kind, and for
// each receiver its collision mesh and bound h (its proxy's from `proxies`, empty or one entry per
// object; its collider's, measured; or its render mesh's, 0), what poses it (dynamic skinned or
// morphed objects) and, for a collision mesh standing in for a render mesh that does not deform, which
// way the drawn surface faces under it. A receiver with the same render mesh and collider as an
// earlier one (proxySources), both given no proxy or equal ones, takes that one's results and reads its
// collision mesh (ObjectData::shape()). Errors name the object.
Status fillObjects(const Scene& scene, const std::vector<std::shared_ptr<const Proxy>>& proxies,
                   const WorldSettings& settings, std::vector<ObjectData>& objects);

} // namespace spatter
