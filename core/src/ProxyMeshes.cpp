#include "ProxyMeshes.hpp"

#include "Pi.hpp"
#include "SurfaceGeometry.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace spatter::detail {

size_t surfaceTriangleCount(const Mesh& m) {
    size_t n = 0;
    for (size_t t = 0; t < m.triangleCount(); ++t)
        n += isSurfaceTriangle(m.positions, m.indices[3 * t], m.indices[3 * t + 1], m.indices[3 * t + 2]);
    return n;
}

// Positions and indices only: vertices with bit-identical positions merged, triangles with a repeated
// index or zero area dropped, unreferenced vertices removed.
Mesh weldedSurface(const Mesh& in) {
    std::vector<glm::vec3> positions(in.positions.size());
    for (size_t i = 0; i < positions.size(); ++i)
        positions[i] = in.positions[i] + glm::vec3(0.0f); // -0 -> +0
    Mesh out;
    if (in.indices.empty() || positions.empty()) return out;
    std::vector<unsigned int> remap(positions.size());
    const size_t unique = meshopt_generateVertexRemap(remap.data(), in.indices.data(), in.indices.size(),
                                                      positions.data(), positions.size(), sizeof(glm::vec3));
    std::vector<glm::vec3> welded(unique);
    meshopt_remapVertexBuffer(welded.data(), positions.data(), positions.size(), sizeof(glm::vec3),
                              remap.data());
    std::vector<uint32_t> indices;
    indices.reserve(in.indices.size());
    for (size_t t = 0; t < in.triangleCount(); ++t) {
        const uint32_t a = remap[in.indices[3 * t]], b = remap[in.indices[3 * t + 1]],
                       c = remap[in.indices[3 * t + 2]];
        if (!isSurfaceTriangle(welded, a, b, c)) continue;
        indices.insert(indices.end(), {a, b, c});
    }
    // Compact: dropping triangles can leave vertices unreferenced.
    std::vector<uint32_t> slot(welded.size(), UINT32_MAX);
    for (uint32_t& i : indices) {
        if (slot[i] == UINT32_MAX) {
            slot[i] = uint32_t(out.positions.size());
            out.positions.push_back(welded[i]);
        }
        i = slot[i];
    }
    out.indices = std::move(indices);
    return out;
}

// Gives each vertex one copy per fan of triangles joined across edges whose dihedral angle is at most
// `angleDegrees`; edges used by other than two triangles separate fans too. Afterwards vertices along
// sharp edges are split, which keeps normals crisp there and makes meshoptimizer treat the edges as
// seams (collapsible only along themselves).
void splitCreases(Mesh& m, float angleDegrees) {
    const size_t corners = m.indices.size();
    const size_t triangles = m.triangleCount();
    std::vector<glm::dvec3> normal(triangles);
    for (size_t t = 0; t < triangles; ++t) {
        const glm::dvec3 a(m.positions[m.indices[3 * t]]);
        const glm::dvec3 n = glm::cross(glm::dvec3(m.positions[m.indices[3 * t + 1]]) - a,
                                        glm::dvec3(m.positions[m.indices[3 * t + 2]]) - a);
        const double len = glm::length(n);
        normal[t] = len > 0.0 ? n / len : glm::dvec3(0.0);
    }
    struct EdgeUse {
        uint64_t key;
        uint32_t corner; // the edge runs from indices[corner] to the next corner of its triangle
    };
    auto nextCorner = [](uint32_t c) { return c % 3 == 2 ? c - 2 : c + 1; };
    std::vector<EdgeUse> uses(corners);
    for (uint32_t c = 0; c < corners; ++c) {
        const uint32_t a = m.indices[c], b = m.indices[nextCorner(c)];
        uses[c] = {(uint64_t(std::min(a, b)) << 32) | std::max(a, b), c};
    }
    std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
        return x.key != y.key ? x.key < y.key : x.corner < y.corner;
    });
    std::vector<uint32_t> parent(corners);
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](uint32_t c) {
        while (parent[c] != c)
            c = parent[c] = parent[parent[c]];
        return c;
    };
    auto unite = [&](uint32_t x, uint32_t y) {
        x = find(x);
        y = find(y);
        if (x != y) parent[std::max(x, y)] = std::min(x, y);
    };
    // The corner of triangle t that holds vertex v.
    auto cornerOf = [&](uint32_t t, uint32_t v) {
        for (uint32_t k = 0; k < 3; ++k)
            if (m.indices[3 * t + k] == v) return 3 * t + k;
        return 3 * t;
    };
    const double cosLimit = std::cos(double(angleDegrees) * kPi / 180.0);
    for (size_t i = 0; i < uses.size();) {
        size_t j = i + 1;
        while (j < uses.size() && uses[j].key == uses[i].key)
            ++j;
        if (j - i == 2) {
            const uint32_t t1 = uses[i].corner / 3, t2 = uses[i + 1].corner / 3;
            if (glm::dot(normal[t1], normal[t2]) >= cosLimit) {
                const uint32_t a = uint32_t(uses[i].key >> 32), b = uint32_t(uses[i].key & 0xffffffffu);
                unite(cornerOf(t1, a), cornerOf(t2, a));
                unite(cornerOf(t1, b), cornerOf(t2, b));
            }
        }
        i = j;
    }
    std::vector<uint32_t> vertexOfRoot(corners, UINT32_MAX);
    std::vector<bool> used(m.positions.size(), false);
    for (uint32_t c = 0; c < corners; ++c) {
        const uint32_t root = find(c);
        if (vertexOfRoot[root] == UINT32_MAX) {
            const uint32_t v = m.indices[c];
            if (!used[v]) {
                used[v] = true;
                vertexOfRoot[root] = v;
            } else {
                vertexOfRoot[root] = uint32_t(m.positions.size());
                m.positions.push_back(m.positions[v]);
            }
        }
        m.indices[c] = vertexOfRoot[root];
    }
}

Mesh meshoptInputOf(Mesh welded, const ProxySettings& s) {
    if (s.keepSharpFeatures) splitCreases(welded, s.featureAngleDegrees);
    return welded;
}

// A welded run made into a proxy: creases split (so that normals stay crisp along sharp edges),
// normals computed.
Mesh finishProxy(Mesh welded, const ProxySettings& s) {
    splitCreases(welded, s.featureAngleDegrees);
    computeNormals(welded);
    return welded;
}

} // namespace spatter::detail
