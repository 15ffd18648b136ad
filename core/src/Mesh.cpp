#include "spatter/core/Mesh.hpp"

#include <cmath>
#include <string>

namespace spatter {

Bounds Mesh::bounds() const {
    Bounds b;
    for (const glm::vec3& p : positions)
        b.extend(p);
    return b;
}

static bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

Status validateMesh(const Mesh& mesh) {
    const size_t n = mesh.positions.size();
    if (mesh.indices.size() % 3 != 0)
        return fail("index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
    if (n > size_t(UINT32_MAX)) return fail("too many vertices (" + std::to_string(n) + ")");
    for (size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= n)
            return fail("index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) +
                        ", past the vertex count " + std::to_string(n));
    for (size_t i = 0; i < n; ++i)
        if (!finite(mesh.positions[i]))
            return fail("position " + std::to_string(i) + " is not finite (NaN or Inf)");
    if (mesh.normals.size() != n)
        return fail("has " + std::to_string(mesh.normals.size()) + " normals for " + std::to_string(n) +
                    " positions");
    for (size_t i = 0; i < n; ++i)
        if (!finite(mesh.normals[i]))
            return fail("normal " + std::to_string(i) + " is not finite (NaN or Inf)");
    if (!mesh.uvs.empty() && mesh.uvs.size() != n)
        return fail("has " + std::to_string(mesh.uvs.size()) + " UVs for " + std::to_string(n) +
                    " positions");
    if (!mesh.tangents.empty() && mesh.tangents.size() != n)
        return fail("has " + std::to_string(mesh.tangents.size()) + " tangents for " + std::to_string(n) +
                    " positions");
    for (size_t s = 0; s < mesh.submeshes.size(); ++s) {
        const Submesh& sm = mesh.submeshes[s];
        if (sm.firstIndex % 3 != 0 || sm.indexCount % 3 != 0 ||
            uint64_t(sm.firstIndex) + sm.indexCount > mesh.indices.size())
            return fail("submesh " + std::to_string(s) + " is not a triangle range inside the index buffer");
    }
    return {};
}

// Area-weighted face normal sums per vertex (cross product length is twice the area).
static std::vector<glm::dvec3> accumulateFaceNormals(const Mesh& mesh) {
    std::vector<glm::dvec3> sum(mesh.positions.size(), glm::dvec3(0.0));
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
        if (i0 >= sum.size() || i1 >= sum.size() || i2 >= sum.size()) continue;
        const glm::dvec3 p0(mesh.positions[i0]), p1(mesh.positions[i1]), p2(mesh.positions[i2]);
        const glm::dvec3 fn = glm::cross(p1 - p0, p2 - p0);
        if (!std::isfinite(fn.x) || !std::isfinite(fn.y) || !std::isfinite(fn.z)) continue;
        sum[i0] += fn;
        sum[i1] += fn;
        sum[i2] += fn;
    }
    return sum;
}

static glm::vec3 unitOr(const glm::dvec3& v, const glm::vec3& fallback) {
    const double len = glm::length(v);
    if (!(len > 1e-300) || !std::isfinite(len)) return fallback;
    return glm::vec3(v / len);
}

void computeNormals(Mesh& mesh) {
    const std::vector<glm::dvec3> sum = accumulateFaceNormals(mesh);
    mesh.normals.resize(mesh.positions.size());
    for (size_t i = 0; i < sum.size(); ++i)
        mesh.normals[i] = unitOr(sum[i], glm::vec3(0, 0, 1));
}

size_t repairNormals(Mesh& mesh) {
    if (mesh.normals.size() != mesh.positions.size()) {
        computeNormals(mesh);
        return mesh.positions.size();
    }
    std::vector<glm::dvec3> faceSum;
    size_t repaired = 0;
    for (size_t i = 0; i < mesh.normals.size(); ++i) {
        const glm::vec3 n = mesh.normals[i];
        const float len = glm::length(n);
        if (finite(n) && len > 1e-12f && std::isfinite(len)) {
            mesh.normals[i] = n / len;
            continue;
        }
        if (faceSum.empty()) faceSum = accumulateFaceNormals(mesh);
        mesh.normals[i] = unitOr(faceSum[i], glm::vec3(0, 0, 1));
        ++repaired;
    }
    return repaired;
}

void computeTangents(Mesh& mesh) {
    const size_t n = mesh.positions.size();
    if (mesh.normals.size() != n) computeNormals(mesh);
    std::vector<glm::dvec3> tan(n, glm::dvec3(0.0)), bit(n, glm::dvec3(0.0));
    if (mesh.uvs.size() == n) {
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            const uint32_t i[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
            if (i[0] >= n || i[1] >= n || i[2] >= n) continue;
            const glm::dvec3 e1 = glm::dvec3(mesh.positions[i[1]]) - glm::dvec3(mesh.positions[i[0]]);
            const glm::dvec3 e2 = glm::dvec3(mesh.positions[i[2]]) - glm::dvec3(mesh.positions[i[0]]);
            const glm::dvec2 d1 = glm::dvec2(mesh.uvs[i[1]]) - glm::dvec2(mesh.uvs[i[0]]);
            const glm::dvec2 d2 = glm::dvec2(mesh.uvs[i[2]]) - glm::dvec2(mesh.uvs[i[0]]);
            const double det = d1.x * d2.y - d2.x * d1.y;
            if (!(std::fabs(det) > 1e-20) || !std::isfinite(det)) continue;
            const glm::dvec3 sdir = (e1 * d2.y - e2 * d1.y) / det;
            const glm::dvec3 tdir = (e2 * d1.x - e1 * d2.x) / det;
            if (!std::isfinite(sdir.x + sdir.y + sdir.z + tdir.x + tdir.y + tdir.z)) continue;
            for (uint32_t k : i) {
                tan[k] += sdir;
                bit[k] += tdir;
            }
        }
    }
    mesh.tangents.resize(n);
    for (size_t v = 0; v < n; ++v) {
        const glm::dvec3 nv(mesh.normals[v]);
        glm::dvec3 t = tan[v] - nv * glm::dot(nv, tan[v]);
        double len = glm::length(t);
        // Where the UV directions of the triangles around a vertex cancel (every closed UV-mapped
        // mesh has such points), what is left is rounding noise: compare with the summed lengths.
        if (!(len > 1e-6 * glm::length(tan[v])) || !(len > 1e-12) || !std::isfinite(len)) {
            // No usable UV direction: any tangent perpendicular to the normal.
            const glm::dvec3 axis = std::fabs(nv.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
            t = glm::cross(axis, nv);
            len = glm::length(t);
            if (!(len > 1e-12)) {
                mesh.tangents[v] = glm::vec4(1, 0, 0, 1);
                continue;
            }
        }
        t /= len;
        const double w = glm::dot(glm::cross(nv, t), bit[v]) < 0.0 ? -1.0 : 1.0;
        mesh.tangents[v] = glm::vec4(glm::vec3(t), float(w));
    }
}

} // namespace spatter
