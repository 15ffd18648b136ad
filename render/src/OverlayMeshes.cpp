#include "OverlayMeshes.hpp"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <numeric>
#include <string>

namespace spatter::render_detail {

namespace {

// Vertex of the line buffer: object-space position and the index of its object.
struct LineVertex {
    glm::vec3 position;
    uint32_t object;
};
static_assert(sizeof(LineVertex) == 16, "tightly packed line vertex");

} // namespace

EdgeList uniqueEdges(const Mesh& mesh) {
    const std::vector<glm::vec3>& p = mesh.positions;
    const size_t n = p.size();
    // Weld: vertices with equal positions share the first of them in sorted order.
    std::vector<uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        if (p[a].x != p[b].x) return p[a].x < p[b].x;
        if (p[a].y != p[b].y) return p[a].y < p[b].y;
        if (p[a].z != p[b].z) return p[a].z < p[b].z;
        return a < b;
    });
    std::vector<uint32_t> canonical(n);
    for (size_t i = 0; i < n; ++i)
        canonical[order[i]] = (i > 0 && p[order[i]] == p[order[i - 1]]) ? canonical[order[i - 1]] : order[i];

    std::vector<uint64_t> keys;
    keys.reserve(mesh.indices.size());
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
        for (int e = 0; e < 3; ++e) {
            uint32_t a = canonical[mesh.indices[t + size_t(e)]];
            uint32_t b = canonical[mesh.indices[t + size_t((e + 1) % 3)]];
            if (a == b) continue;
            if (a > b) std::swap(a, b);
            keys.push_back((uint64_t(a) << 32) | b);
        }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());

    EdgeList out;
    std::vector<uint32_t> remap(n, std::numeric_limits<uint32_t>::max());
    out.lines.reserve(keys.size() * 2);
    for (uint64_t k : keys)
        for (uint32_t v : {uint32_t(k >> 32), uint32_t(k & 0xffffffffu)}) {
            if (remap[v] == std::numeric_limits<uint32_t>::max()) {
                remap[v] = uint32_t(out.positions.size());
                out.positions.push_back(p[v]);
            }
            out.lines.push_back(remap[v]);
        }
    return out;
}

Status OverlayMeshes::set(const std::vector<Mesh>& meshes, size_t objectCount) {
    if (meshes.empty()) {
        clear();
        return {};
    }
    if (meshes.size() != objectCount)
        return fail("renderer: " + std::to_string(meshes.size()) + " overlay meshes for " +
                    std::to_string(objectCount) + " objects");
    for (size_t i = 0; i < meshes.size(); ++i)
        if (Status s = validateMesh(meshes[i]); !s)
            return fail("renderer: overlay mesh of object " + std::to_string(i) + ": " + s.error());

    std::vector<LineVertex> vertices;
    std::vector<uint32_t> indices;
    for (size_t i = 0; i < meshes.size(); ++i) {
        const EdgeList edges = uniqueEdges(meshes[i]);
        if (vertices.size() + edges.positions.size() > std::numeric_limits<uint32_t>::max())
            return fail("renderer: overlay meshes have more than 2^32 vertices");
        const uint32_t base = uint32_t(vertices.size());
        for (const glm::vec3& q : edges.positions)
            vertices.push_back({q, uint32_t(i)});
        for (uint32_t v : edges.lines)
            indices.push_back(base + v);
    }
    clear();
    if (indices.empty()) return {};
    vertices_ = createBuffer();
    indices_ = createBuffer();
    glNamedBufferStorage(vertices_.get(), GLsizeiptr(vertices.size() * sizeof(LineVertex)), vertices.data(),
                         0);
    glNamedBufferStorage(indices_.get(), GLsizeiptr(indices.size() * sizeof(uint32_t)), indices.data(), 0);
    vao_ = createVertexArray();
    const GLuint vao = vao_.get();
    glVertexArrayVertexBuffer(vao, 0, vertices_.get(), 0, sizeof(LineVertex));
    glVertexArrayElementBuffer(vao, indices_.get());
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(LineVertex, position));
    glVertexArrayAttribBinding(vao, 0, 0);
    glEnableVertexArrayAttrib(vao, 1);
    glVertexArrayAttribIFormat(vao, 1, 1, GL_UNSIGNED_INT, offsetof(LineVertex, object));
    glVertexArrayAttribBinding(vao, 1, 0);
    indexCount_ = indices.size();
    return {};
}

void OverlayMeshes::clear() {
    vao_.reset();
    vertices_.reset();
    indices_.reset();
    indexCount_ = 0;
}

} // namespace spatter::render_detail
