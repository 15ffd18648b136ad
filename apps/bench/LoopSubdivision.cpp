#include "LoopSubdivision.hpp"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

#include <algorithm>
#include <cstring>
#include <unordered_map>

namespace spatter::bench {

namespace {

using LoopMesh = OpenMesh::TriMesh_ArrayKernelT<>;

struct PositionKey {
    uint32_t x, y, z;
    bool operator==(const PositionKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct PositionKeyHash {
    size_t operator()(const PositionKey& k) const {
        return (size_t(k.x) * 73856093u) ^ (size_t(k.y) * 19349663u) ^ (size_t(k.z) * 83492791u);
    }
};

PositionKey keyOf(const glm::vec3& p) {
    PositionKey k;
    const glm::vec3 q = p + glm::vec3(0.0f); // -0 and +0 weld
    std::memcpy(&k.x, &q.x, 4);
    std::memcpy(&k.y, &q.y, 4);
    std::memcpy(&k.z, &q.z, 4);
    return k;
}

struct QuietOpenMesh {
    QuietOpenMesh() { omerr().disable(), omlog().disable(), omout().disable(); }
    ~QuietOpenMesh() { omerr().enable(), omlog().enable(), omout().enable(); }
};

} // namespace

Result<Mesh> loopSubdivide(const Mesh& mesh, int steps, size_t& dropped) {
    dropped = 0;
    if (steps <= 0) return mesh;
    QuietOpenMesh quiet;
    LoopMesh om;
    std::unordered_map<PositionKey, LoopMesh::VertexHandle, PositionKeyHash> welded;
    std::vector<LoopMesh::VertexHandle> handle(mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3& p = mesh.positions[i];
        auto [it, inserted] = welded.emplace(keyOf(p), LoopMesh::VertexHandle());
        if (inserted) it->second = om.add_vertex(LoopMesh::Point(p.x, p.y, p.z));
        handle[i] = it->second;
    }
    size_t added = 0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const LoopMesh::VertexHandle a = handle[mesh.indices[t]], b = handle[mesh.indices[t + 1]],
                                     c = handle[mesh.indices[t + 2]];
        if (a == b || b == c || a == c || !om.add_face(a, b, c).is_valid())
            ++dropped;
        else
            ++added;
    }
    if (added == 0) return fail("Loop subdivision: no face of the mesh could be added");
    om.request_vertex_status();
    om.request_edge_status();
    om.request_face_status();
    om.delete_isolated_vertices();
    om.garbage_collection();
    om.release_vertex_status();
    om.release_edge_status();
    om.release_face_status();
    // The subdivider's weight table is indexed by valence (50 entries by default); subdivision
    // keeps the valence of old vertices and gives new ones 6, so size it for the largest now.
    size_t maxValence = 6;
    for (const LoopMesh::VertexHandle v : om.vertices())
        maxValence = std::max(maxValence, size_t(om.valence(v)));
    OpenMesh::Subdivider::Uniform::LoopT<LoopMesh> loop;
    loop.init_weights(maxValence + 1);
    loop.attach(om);
    loop(size_t(steps));
    loop.detach();

    Mesh out;
    out.positions.reserve(om.n_vertices());
    for (const LoopMesh::VertexHandle v : om.vertices()) {
        const LoopMesh::Point& p = om.point(v);
        out.positions.emplace_back(p[0], p[1], p[2]);
    }
    out.indices.reserve(om.n_faces() * 3);
    for (const LoopMesh::FaceHandle f : om.faces())
        for (const LoopMesh::VertexHandle v : om.fv_range(f))
            out.indices.push_back(uint32_t(v.idx()));
    computeNormals(out);
    return out;
}

} // namespace spatter::bench
