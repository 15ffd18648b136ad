#include "PosedCollisionMesh.hpp"

#include "spatter/core/TrianglePieces.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>
#include <utility>

namespace spatter {

namespace {

// Each vertex's first vertex at the same rest position (Drawn::weld).
std::vector<uint32_t> weldedVertices(const std::vector<glm::vec3>& positions) {
    std::vector<uint32_t> order(positions.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        const glm::vec3 &p = positions[a], &q = positions[b];
        return std::tie(p.x, p.y, p.z, a) < std::tie(q.x, q.y, q.z, b);
    });
    std::vector<uint32_t> weld(positions.size());
    for (size_t i = 0; i < order.size(); ++i)
        weld[order[i]] =
            i > 0 && positions[order[i]] == positions[order[i - 1]] ? weld[order[i - 1]] : order[i];
    return weld;
}

// The render triangle across the edge of triangle `t` that is opposite its corner `k`: the other
// triangle around both of the edge's vertices; nothing at a border.
std::optional<uint32_t> acrossEdge(const PosedCollisionMesh::Drawn& drawn, uint32_t t, int k) {
    const std::vector<uint32_t>& w = drawn.weld;
    const uint32_t* c = &drawn.rest.indices[3 * size_t(t)];
    const uint32_t a = w[c[(k + 1) % 3]], b = w[c[(k + 2) % 3]];
    for (uint32_t i = drawn.ringStart[a]; i < drawn.ringStart[a + 1]; ++i) {
        const uint32_t other = drawn.ring[i];
        const uint32_t* d = &drawn.rest.indices[3 * size_t(other)];
        if (other != t && (w[d[0]] == b || w[d[1]] == b || w[d[2]] == b)) return other;
    }
    return std::nullopt;
}

// The welded vertices of `drawn.rest`, the triangles around each and each triangle's neighbours
// (Drawn::weld, ringStart, ring, neighbours).
void linkRings(PosedCollisionMesh::Drawn& drawn) {
    const std::vector<uint32_t>& indices = drawn.rest.indices;
    drawn.weld = weldedVertices(drawn.rest.positions);
    drawn.ringStart.assign(drawn.rest.positions.size() + 1, 0);
    for (uint32_t v : indices)
        ++drawn.ringStart[drawn.weld[v] + 1];
    for (size_t v = 1; v < drawn.ringStart.size(); ++v)
        drawn.ringStart[v] += drawn.ringStart[v - 1];
    drawn.ring.resize(indices.size());
    std::vector<uint32_t> fill(drawn.ringStart.begin(), drawn.ringStart.end() - 1);
    for (size_t i = 0; i < indices.size(); ++i)
        drawn.ring[fill[drawn.weld[indices[i]]]++] = uint32_t(i / 3);
    drawn.neighbours.resize(indices.size());
    for (uint32_t t = 0; t < uint32_t(indices.size() / 3); ++t)
        for (int k = 0; k < 3; ++k)
            drawn.neighbours[3 * size_t(t) + size_t(k)] =
                acrossEdge(drawn, t, k).value_or(PosedCollisionMesh::Drawn::kBorder);
}

} // namespace

Result<std::optional<PosedCollisionMesh>> posedCollisionMesh(const Scene& scene, size_t object,
                                                             const Mesh& collision) {
    const SceneObject& so = scene.objects[object];
    if (!so.deforms()) return std::optional<PosedCollisionMesh>();
    PosedCollisionMesh out;
    out.rest = collision.positions;
    if (so.skin != -1) out.jointCount = scene.animation.skins[size_t(so.skin)].joints.size();
    if (&collision == so.mesh.get()) {
        out.deformation = deformationOf(so);
        return std::optional<PosedCollisionMesh>(std::move(out));
    }
    Result<VertexDeformation> moved = transferDeformation(*so.mesh, deformationOf(so), collision);
    if (!moved) return fail(moved.error());
    out.deformation = std::move(moved).value();
    PosedCollisionMesh::Drawn drawn;
    drawn.rest.positions = so.mesh->positions;
    drawn.rest.indices.assign(so.mesh->indices.begin(),
                              so.mesh->indices.begin() + so.mesh->triangleCount() * 3);
    drawn.deformation = deformationOf(so);
    linkRings(drawn);
    Result<ClosestPointQuery> query = ClosestPointQuery::create(drawn.rest);
    if (!query) return fail(query.error());
    drawn.query = std::make_shared<const ClosestPointQuery>(std::move(query).value());
    drawn.seeds = nearestTrianglePerPiece(*drawn.query, collision, PosedCollisionMesh::Drawn::kBorder);
    out.drawn = std::move(drawn);
    return std::optional<PosedCollisionMesh>(std::move(out));
}

Result<std::vector<glm::vec3>> poseCollisionMesh(const PosedCollisionMesh& mesh, const glm::dmat4& transform,
                                                 const std::vector<glm::dmat4>& joints,
                                                 const std::vector<double>& morphWeights) {
    if (const std::string problem = poseProblem(mesh.deformation, mesh.jointCount, joints, morphWeights);
        !problem.empty())
        return fail(problem);
    const std::vector<glm::dvec3> posed =
        posePositions(mesh.rest, mesh.deformation, joints, morphWeights, glm::inverse(transform));
    std::vector<glm::vec3> out(posed.size());
    for (size_t v = 0; v < posed.size(); ++v) {
        out[v] = glm::vec3(posed[v]);
        if (!std::isfinite(out[v].x) || !std::isfinite(out[v].y) || !std::isfinite(out[v].z))
            return fail("the pose puts vertex " + std::to_string(v) +
                        " of the collision mesh at a position "
                        "that is not finite");
    }
    return out;
}

namespace {

// Vertex `v` of `rest` deformed by `deformation` at `pose` (its rest position before the first pose).
glm::dvec3 posedAt(const std::vector<glm::vec3>& rest, const VertexDeformation& deformation, uint32_t v,
                   const Pose& pose) {
    return pose.joints.empty() && pose.morphWeights.empty()
               ? glm::dvec3(rest[v])
               : posedVertex(rest, deformation, v, pose.joints, pose.morphWeights, pose.toObject);
}

// The corners of render triangle `triangle` at `pose`.
std::array<glm::dvec3, 3> posedCorners(const PosedCollisionMesh& mesh, const std::vector<uint32_t>& indices,
                                       uint32_t triangle, const Pose& pose) {
    const std::vector<glm::vec3>& rest = mesh.drawn ? mesh.drawn->rest.positions : mesh.rest;
    const VertexDeformation& deformation = mesh.drawn ? mesh.drawn->deformation : mesh.deformation;
    const uint32_t* c = &(mesh.drawn ? mesh.drawn->rest.indices : indices)[3 * size_t(triangle)];
    return {posedAt(rest, deformation, c[0], pose), posedAt(rest, deformation, c[1], pose),
            posedAt(rest, deformation, c[2], pose)};
}

// Where the shot through `hit` along `direction` meets the plane of triangle `t`; `hit` itself for no
// direction or a shot along the plane.
glm::dvec3 alongShot(const glm::dvec3& hit, const glm::dvec3& direction, const std::array<glm::dvec3, 3>& t) {
    const glm::dvec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
    const double across = glm::dot(n, direction);
    if (!(std::abs(across) > 1e-9 * glm::length(n) * glm::length(direction))) return hit;
    const glm::dvec3 p = hit + direction * (glm::dot(n, t[0] - hit) / across);
    return std::isfinite(p.x + p.y + p.z) ? p : hit;
}

// Where the line through `hit` along `direction` meets the plane of triangle `t`, as the line's
// parameter and the point's barycentric coordinates, inside the triangle or not; nothing when it runs
// along the plane.
std::optional<std::pair<double, glm::dvec3>> lineOnPlane(const glm::dvec3& hit, const glm::dvec3& direction,
                                                         const std::array<glm::dvec3, 3>& t) {
    const glm::dvec3 e1 = t[1] - t[0], e2 = t[2] - t[0], p = glm::cross(direction, e2);
    const double det = glm::dot(e1, p);
    if (!(std::abs(det) > 1e-12 * glm::length(e1) * glm::length(e2) * glm::length(direction)))
        return std::nullopt;
    const glm::dvec3 o = hit - t[0], q = glm::cross(o, e1);
    const double u = glm::dot(o, p) / det, v = glm::dot(direction, q) / det;
    return std::make_pair(glm::dot(e2, q) / det, glm::dvec3(1.0 - u - v, u, v));
}

// The corner of a triangle opposite the edge beyond which barycentric coordinates `bary` lie (their
// smallest): a walk steps across that edge, to drawn.neighbours[3 t + k].
int cornerFacing(const glm::dvec3& bary) {
    return bary.x <= bary.y && bary.x <= bary.z ? 0 : bary.y <= bary.z ? 1 : 2;
}

// Whether barycentric coordinates lie in their triangle (within rounding).
bool within(const glm::dvec3& bary) {
    constexpr double kSlack = 1e-9;
    return bary.y >= -kSlack && bary.z >= -kSlack && bary.y + bary.z <= 1.0 + kSlack;
}

// Where the line through `hit` along `direction` meets triangle `t` (within rounding); nothing when it
// misses or runs along it.
std::optional<std::pair<double, glm::dvec3>> lineMeets(const glm::dvec3& hit, const glm::dvec3& direction,
                                                       const std::array<glm::dvec3, 3>& t) {
    std::optional<std::pair<double, glm::dvec3>> meet = lineOnPlane(hit, direction, t);
    if (meet && !within(meet->second)) return std::nullopt;
    return meet;
}

// The render triangles around triangle `near` of the drawn mesh: it and those sharing a corner with
// it, each once.
std::vector<uint32_t> ringAround(const PosedCollisionMesh::Drawn& drawn, uint32_t near) {
    std::vector<uint32_t> triangles;
    for (int k = 0; k < 3; ++k) {
        const uint32_t v = drawn.weld[drawn.rest.indices[3 * size_t(near) + size_t(k)]];
        for (uint32_t i = drawn.ringStart[v]; i < drawn.ringStart[v + 1]; ++i)
            if (std::find(triangles.begin(), triangles.end(), drawn.ring[i]) == triangles.end())
                triangles.push_back(drawn.ring[i]);
    }
    return triangles;
}

// `anchor` with its frame on its triangle's posed `corners`; nothing when the triangle has collapsed.
std::optional<SurfaceLocation> located(const SurfaceAnchor& anchor,
                                       const std::array<glm::dvec3, 3>& corners) {
    const std::optional<glm::dmat4> frame = triangleFrame(corners[0], corners[1], corners[2], anchor.bary);
    if (!frame) return std::nullopt;
    return SurfaceLocation{anchor, *frame};
}

// The triangle around render triangle `near` (it and those sharing a corner with it) that the line
// through `hit` along `direction` meets nearest `hit`, at `pose`. Each vertex of the ring is posed
// once, however many of its triangles share it.
std::optional<SurfaceLocation> shotOnRing(const PosedCollisionMesh& mesh, uint32_t near,
                                          const glm::dvec3& hit, const glm::dvec3& direction,
                                          const Pose& pose) {
    const PosedCollisionMesh::Drawn& drawn = *mesh.drawn;
    std::vector<std::pair<uint32_t, glm::dvec3>> posed; // vertex, its position at the pose
    auto at = [&](uint32_t v) {
        for (const auto& [vertex, p] : posed)
            if (vertex == v) return p;
        const glm::dvec3 p = posedAt(drawn.rest.positions, drawn.deformation, v, pose);
        posed.emplace_back(v, p);
        return p;
    };
    std::optional<SurfaceAnchor> best;
    std::array<glm::dvec3, 3> bestCorners;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (const uint32_t triangle : ringAround(drawn, near)) {
        const uint32_t* c = &drawn.rest.indices[3 * size_t(triangle)];
        const std::array<glm::dvec3, 3> corners{at(c[0]), at(c[1]), at(c[2])};
        const std::optional<std::pair<double, glm::dvec3>> meet = lineMeets(hit, direction, corners);
        if (meet && std::abs(meet->first) < bestDistance) {
            bestDistance = std::abs(meet->first);
            best = SurfaceAnchor{triangle, meet->second};
            bestCorners = corners;
        }
    }
    if (!best) return std::nullopt;
    return located(*best, bestCorners);
}

// Where the posed line through `hit` along `direction` meets render triangle `t` (its posed
// `corners`) or, where it passes beyond one of its edges, the triangle across that edge, a few
// triangles on: a shot found at rest near an edge lands on the triangle the posed line crosses,
// posing one vertex a step. Nothing when the walk reaches a border or runs out of steps.
std::optional<SurfaceLocation> walkToShot(const PosedCollisionMesh& mesh, uint32_t t,
                                          std::array<glm::dvec3, 3> corners, const glm::dvec3& hit,
                                          const glm::dvec3& direction, const Pose& pose) {
    constexpr int kSteps = 4; // triangles tested
    const PosedCollisionMesh::Drawn& drawn = *mesh.drawn;
    for (int step = 0; step < kSteps; ++step) {
        const std::optional<std::pair<double, glm::dvec3>> meet = lineOnPlane(hit, direction, corners);
        if (!meet) return std::nullopt;
        const glm::dvec3& bary = meet->second;
        if (within(bary)) return located(SurfaceAnchor{t, bary}, corners);
        const int k = cornerFacing(bary);
        const uint32_t next = drawn.neighbours[3 * size_t(t) + size_t(k)];
        if (next == PosedCollisionMesh::Drawn::kBorder) return std::nullopt;
        const std::vector<uint32_t>& w = drawn.weld;
        const uint32_t* c = &drawn.rest.indices[3 * size_t(t)];
        const uint32_t* d = &drawn.rest.indices[3 * size_t(next)];
        std::array<glm::dvec3, 3> nextCorners;
        for (int j = 0; j < 3; ++j)
            nextCorners[size_t(j)] = w[d[j]] == w[c[(k + 1) % 3]] ? corners[size_t((k + 1) % 3)]
                                     : w[d[j]] == w[c[(k + 2) % 3]]
                                         ? corners[size_t((k + 2) % 3)]
                                         : posedAt(drawn.rest.positions, drawn.deformation, d[j], pose);
        t = next;
        corners = nextCorners;
    }
    return std::nullopt;
}

// `direction` taken from triangle `posed` to triangle `rest` by the affine map between them (their
// edges, and their normals scaled to the edges' size), unit; nothing for a collapsed triangle.
std::optional<glm::dvec3> restDirection(const std::array<glm::dvec3, 3>& rest,
                                        const std::array<glm::dvec3, 3>& posed, const glm::dvec3& direction) {
    auto frame = [](const std::array<glm::dvec3, 3>& t) {
        const glm::dvec3 e1 = t[1] - t[0], e2 = t[2] - t[0], n = glm::cross(e1, e2);
        const double size = std::sqrt(glm::length(n));
        return glm::dmat3(e1, e2, size > 0.0 ? n / size : n);
    };
    const glm::dmat3 from = frame(posed);
    if (!(std::abs(glm::determinant(from)) > 0.0)) return std::nullopt;
    const glm::dvec3 d = frame(rest) * (glm::inverse(from) * direction);
    const double length = glm::length(d);
    if (!(length > 0.0) || !std::isfinite(length)) return std::nullopt;
    return d / length;
}

// Where the line through `atRest` along `along` meets the drawn surface at rest, found by walking
// from render triangle `seed` across the edge beyond which the line meets each triangle's plane;
// nothing when the walk reaches a border or takes too many steps, or when the meet it reaches lies
// behind `atRest` along the line beyond rounding (a layer in front of it, which the shot meets first,
// may lie within the reach) or farther than `reach` before it. The steps read a few rest positions
// each, where a ray query descends a hierarchy from its root.
std::optional<ClosestPointQuery::RayMeet> restWalk(const PosedCollisionMesh::Drawn& drawn, uint32_t seed,
                                                   const glm::dvec3& atRest, const glm::dvec3& along,
                                                   double reach) {
    constexpr int kSteps = 8; // triangles tested
    uint32_t t = seed;
    for (int step = 0; step < kSteps && t != PosedCollisionMesh::Drawn::kBorder; ++step) {
        const uint32_t* c = &drawn.rest.indices[3 * size_t(t)];
        const std::array<glm::dvec3, 3> corners = {glm::dvec3(drawn.rest.positions[c[0]]),
                                                   glm::dvec3(drawn.rest.positions[c[1]]),
                                                   glm::dvec3(drawn.rest.positions[c[2]])};
        const std::optional<std::pair<double, glm::dvec3>> meet = lineOnPlane(atRest, along, corners);
        if (!meet) return std::nullopt;
        const glm::dvec3& bary = meet->second;
        if (within(bary)) {
            // A hit on a proxy triangle that the drawn surface shares meets it within rounding.
            if (!(meet->first >= -reach && meet->first <= 1e-9 * reach)) return std::nullopt;
            return ClosestPointQuery::RayMeet{t, meet->first};
        }
        t = drawn.neighbours[3 * size_t(t) + size_t(cornerFacing(bary))];
    }
    return std::nullopt;
}

// The seed of the piece of the hit triangle that the hit lies in (Drawn::seeds).
uint32_t seedOf(const PosedCollisionMesh::Drawn& drawn, const CollisionHit& hit) {
    const size_t k = size_t(hit.primitive) * kPiecesPerTriangle + pieceOf(hit.bary);
    return k < drawn.seeds.size() ? drawn.seeds[k] : PosedCollisionMesh::Drawn::kBorder;
}

// The nearer of the line's meets with the drawn surface at rest from `atRest` along `along` and
// against it, within `reach`.
std::optional<ClosestPointQuery::RayMeet>
nearestMeet(const ClosestPointQuery& query, const glm::dvec3& atRest, const glm::dvec3& along, double reach) {
    std::optional<ClosestPointQuery::RayMeet> found = query.firstMeet(atRest, along, reach);
    const std::optional<ClosestPointQuery::RayMeet> back =
        query.firstMeet(atRest, -along, found ? found->t : reach);
    if (back && (!found || back->t < found->t)) found = back;
    return found;
}

// The render triangle the shot meets, found at rest (see anchorOf), and where the posed line meets it
// or the triangle it passes into (walkToShot); nothing when no search at rest finds one. The first
// search walks across the rest mesh from the render triangle nearest to the hit's piece of its
// triangle (restWalk): the layer of the drawn surface that the proxy stands for there, where it lies
// in front of the hit. Otherwise the second takes the drawn surface the shot's line meets first from
// the reach before the hit to the reach beyond it, in front of the proxy or behind it; where that is
// another layer of the body, one the line crosses at rest but not at the pose, the third takes the
// meet nearest the hit.
std::optional<SurfaceLocation> shotThroughRest(const PosedCollisionMesh& mesh,
                                               const std::array<glm::dvec3, 3>& rest,
                                               const std::array<glm::dvec3, 3>& posed,
                                               const glm::dvec3& atRest, const CollisionHit& hit,
                                               const Pose& pose) {
    const std::optional<glm::dvec3> along = restDirection(rest, posed, hit.direction);
    if (!along) return std::nullopt;
    const ClosestPointQuery& query = *mesh.drawn->query;
    auto walkFrom =
        [&](const std::optional<ClosestPointQuery::RayMeet>& found) -> std::optional<SurfaceLocation> {
        if (!found) return std::nullopt;
        const std::array<glm::dvec3, 3> corners = posedCorners(mesh, hit.indices, found->triangle, pose);
        return walkToShot(mesh, found->triangle, corners, hit.position, hit.direction, pose);
    };
    if (std::optional<SurfaceLocation> met =
            walkFrom(restWalk(*mesh.drawn, seedOf(*mesh.drawn, hit), atRest, *along, hit.reach)))
        return met;
    if (std::optional<SurfaceLocation> met =
            walkFrom(query.firstMeet(atRest - hit.reach * *along, *along, 2.0 * hit.reach)))
        return met;
    return walkFrom(nearestMeet(query, atRest, *along, hit.reach));
}

} // namespace

std::optional<SurfaceLocation> anchorOf(const PosedCollisionMesh& mesh, const CollisionHit& hit,
                                        const Pose& pose) {
    if (!mesh.drawn)
        return located(SurfaceAnchor{hit.primitive, hit.bary},
                       posedCorners(mesh, hit.indices, hit.primitive, pose));
    // The collision mesh is not the render mesh: the hit at rest, the render triangle the shot meets
    // there or the nearest render point, then that point's barycentric coordinates refined at the pose
    // (the foot of the hit on the render triangle as it stands).
    const uint32_t* c = &hit.indices[3 * size_t(hit.primitive)];
    std::array<glm::dvec3, 3> rest, posed;
    for (size_t k = 0; k < 3; ++k) {
        rest[k] = glm::dvec3(mesh.rest[c[k]]);
        posed[k] = glm::dvec3(hit.posed[c[k]]);
    }
    const glm::dvec3 atRest = hit.bary.x * rest[0] + hit.bary.y * rest[1] + hit.bary.z * rest[2];
    if (hit.direction != glm::dvec3(0.0))
        if (std::optional<SurfaceLocation> met = shotThroughRest(mesh, rest, posed, atRest, hit, pose))
            return met;
    const std::optional<ClosestPoint> near = mesh.drawn->query->closest(atRest);
    if (!near) return std::nullopt;
    if (hit.direction != glm::dvec3(0.0))
        if (std::optional<SurfaceLocation> met =
                shotOnRing(mesh, near->triangle, hit.position, hit.direction, pose))
            return met;
    const std::array<glm::dvec3, 3> render = posedCorners(mesh, hit.indices, near->triangle, pose);
    return located({near->triangle, barycentric(alongShot(hit.position, hit.direction, render), render[0],
                                                render[1], render[2])},
                   render);
}

std::optional<glm::dmat4> anchorFrame(const PosedCollisionMesh& mesh, const std::vector<uint32_t>& indices,
                                      const SurfaceAnchor& anchor, const Pose& pose) {
    // An anchor from a save may name any triangle.
    const size_t triangles = (mesh.drawn ? mesh.drawn->rest.indices : indices).size() / 3;
    if (size_t(anchor.triangle) >= triangles) return std::nullopt;
    const std::array<glm::dvec3, 3> p = posedCorners(mesh, indices, anchor.triangle, pose);
    return triangleFrame(p[0], p[1], p[2], anchor.bary);
}

} // namespace spatter
