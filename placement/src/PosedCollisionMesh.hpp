#pragma once
// PosedCollisionMesh: what a skinned or morphed object's collision mesh needs to follow the pose that
// is drawn: its rest positions and the deformation of its vertices, its render mesh's own when the
// render mesh is the collision mesh, otherwise transferred from the render mesh (transferDeformation:
// each proxy vertex moves as the nearest point of the render surface does).
//
// It also anchors decals to the drawn surface: a shot's hit on the collision mesh is taken back to
// the rest pose and to the nearest point of the render mesh there (a triangle and barycentric
// coordinates, SurfaceAnchor), and that point's triangle, posed like the render mesh, gives the frame
// the decal rides at any later pose.

#include "spatter/core/Mesh.hpp"
#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/core/VertexDeformation.hpp"
#include "spatter/placement/CollisionWorld.hpp"

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <vector>

namespace spatter {

struct PosedCollisionMesh {
    std::vector<glm::vec3> rest; // collision mesh positions, object space, rest pose
    VertexDeformation deformation;
    size_t jointCount = 0; // joints of the object's skin (0 when not skinned)
    // The render mesh at rest (positions and indices), its deformation and a nearest-point query on
    // it, when the collision mesh is not the render mesh itself.
    struct Drawn {
        Mesh rest;
        VertexDeformation deformation;
        std::shared_ptr<const ClosestPointQuery> query;
        // Each vertex's first vertex at the same rest position, so that a mesh split along its UV or
        // normal seams is one surface to walk across; and the triangles around each such vertex w:
        // ring[ringStart[w] .. ringStart[w + 1]).
        std::vector<uint32_t> weld, ringStart, ring;
        // For each triangle t and corner k, the triangle across the edge opposite that corner
        // (neighbours[3 t + k]; kBorder when there is none), so that a walk steps without a search.
        std::vector<uint32_t> neighbours;
        static constexpr uint32_t kBorder = UINT32_MAX;
        // For each piece of each collision triangle (TrianglePieces.hpp), the render triangle nearest
        // to its centre at rest (seeds[kPiecesPerTriangle t + piece]; kBorder for none): where the
        // walk towards a hit in that piece starts.
        std::vector<uint32_t> seeds;
    };
    std::optional<Drawn> drawn;
};

// The posing data of `scene.objects[object]` for its collision mesh `collision` (the render mesh
// itself, a proxy or a collider, in object space); nothing for an object that neither is skinned nor
// has morph targets. Fails when the deformation cannot be transferred (the message says why).
Result<std::optional<PosedCollisionMesh>> posedCollisionMesh(const Scene& scene, size_t object,
                                                             const Mesh& collision);

// The collision mesh's positions at a pose: object-to-world `transform`, joint matrices `joints`
// (bind space to world, one per joint of the skin) and `morphWeights` (one per morph target), in the
// object's space at that pose. Fails, naming the problem, on joints or weights that do not fit, or
// when a posed position is not finite in float.
Result<std::vector<glm::vec3>> poseCollisionMesh(const PosedCollisionMesh& mesh, const glm::dmat4& transform,
                                                 const std::vector<glm::dmat4>& joints,
                                                 const std::vector<double>& morphWeights);

// A pose as setPose last gave it: joint matrices and morph weights (both empty before the first),
// and the inverse of the object's transform.
struct Pose {
    const std::vector<glm::dmat4>& joints;
    const std::vector<double>& morphWeights;
    glm::dmat4 toObject;
};

// A shot's hit on a posed collision mesh, in the object's space.
struct CollisionHit {
    const std::vector<glm::vec3>& posed;  // the collision mesh at the pose
    const std::vector<uint32_t>& indices; // its triangles
    uint32_t primitive = 0;               // the triangle hit
    glm::dvec3 bary{0.0};                 // the hit's barycentric coordinates in it
    glm::dvec3 position{0.0};             // the hit
    glm::dvec3 direction{0.0};            // the shot (zero: none)
    double reach = 0.0;                   // how far along the shot the drawn surface is sought
};

// The point of the drawn surface that `hit` stands for, at `pose`. With a shot: its line is taken
// to rest through the hit triangle's own deformation, and the render triangle it meets there (found
// by walking across the rest mesh from the seed of the hit's piece where that meet lies in front of
// the hit; otherwise the first from the reach before the hit to the reach beyond it; failing that,
// nearest the hit) is posed; the anchor is where the posed line meets that triangle or the neighbour it
// passes into, a few triangles on. Else where the line meets, nearest the hit, a render triangle around the
// one nearest the hit at rest (that triangle and those that share a corner with it, posed); failing both,
// where it meets the nearest one's plane (the foot of the hit without a shot). With the anchor's frame at
// `pose` (anchorFrame), from the corners posed to find it. Empty when the render mesh has no surface,
// the hit at rest is not finite, or the triangle found has collapsed at the pose.
std::optional<SurfaceLocation> anchorOf(const PosedCollisionMesh& mesh, const CollisionHit& hit,
                                        const Pose& pose);

// The frame of `anchor` at `pose`: columns the direction of its triangle's first edge, the in-plane
// perpendicular, the triangle's normal and, as translation, the anchor's point, in object space.
// Empty for a triangle out of range or one that has collapsed at the pose.
std::optional<glm::dmat4> anchorFrame(const PosedCollisionMesh& mesh, const std::vector<uint32_t>& indices,
                                      const SurfaceAnchor& anchor, const Pose& pose);

} // namespace spatter
