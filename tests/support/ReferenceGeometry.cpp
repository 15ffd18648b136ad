#include "ReferenceGeometry.hpp"

#include "spatter/core/GalleryScene.hpp"
#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/Random.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace spatter::test {

std::shared_ptr<const Mesh> galleryMesh(const std::string& name) {
    for (const SceneObject& o : makeGalleryScene().objects)
        if (o.name == name) return o.mesh;
    return nullptr;
}

namespace {
constexpr float kPi = 3.14159265358979f;
} // namespace

Mesh latLongSphere(float radius, uint32_t stacks, uint32_t slices, float bump) {
    Mesh m;
    auto at = [&](float theta, float phi) {
        const float r = radius * (1.0f + bump * std::sin(8.0f * theta) * std::sin(8.0f * phi));
        return r *
               glm::vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    };
    m.positions.push_back({0, 0, radius});
    for (uint32_t i = 1; i < stacks; ++i)
        for (uint32_t j = 0; j < slices; ++j)
            m.positions.push_back(at(kPi * float(i) / float(stacks), 2.0f * kPi * float(j) / float(slices)));
    m.positions.push_back({0, 0, -radius});
    const uint32_t south = uint32_t(m.positions.size() - 1);
    auto ring = [&](uint32_t i, uint32_t j) { return 1 + (i - 1) * slices + j % slices; };
    for (uint32_t j = 0; j < slices; ++j)
        m.indices.insert(m.indices.end(), {0, ring(1, j), ring(1, j + 1)});
    for (uint32_t i = 1; i + 1 < stacks; ++i)
        for (uint32_t j = 0; j < slices; ++j)
            m.indices.insert(m.indices.end(), {ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j),
                                               ring(i + 1, j + 1), ring(i, j + 1)});
    for (uint32_t j = 0; j < slices; ++j)
        m.indices.insert(m.indices.end(), {ring(stacks - 1, j), south, ring(stacks - 1, j + 1)});
    computeNormals(m);
    return m;
}

Mesh box(float h) {
    Mesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back({i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h});
    m.indices = {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4,
                 2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6};
    computeNormals(m);
    return m;
}

Mesh withUnusedVertices(Mesh m, size_t count) {
    for (size_t k = 0; k < count; ++k) {
        m.positions.push_back(m.positions[0]);
        if (!m.normals.empty()) m.normals.push_back(m.normals[0]);
        if (!m.uvs.empty()) m.uvs.push_back(m.uvs[0]);
        if (!m.tangents.empty()) m.tangents.push_back(m.tangents[0]);
    }
    return m;
}

Mesh unshared(const Mesh& m) {
    Mesh out;
    for (uint32_t i : m.indices) {
        out.indices.push_back(uint32_t(out.positions.size()));
        out.positions.push_back(m.positions[i]);
    }
    return out;
}

double segmentDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 d = b - a;
    const double len2 = glm::dot(d, d);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
    return glm::length(p - (a + t * d));
}

double triangleDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double len = glm::length(n);
    const double edges =
        std::min({segmentDistance(p, a, b), segmentDistance(p, b, c), segmentDistance(p, c, a)});
    if (len == 0.0) return edges;
    const glm::dvec3 u = n / len;
    const double height = glm::dot(p - a, u);
    const glm::dvec3 q = p - height * u;
    if (glm::dot(glm::cross(b - q, c - q), u) >= 0.0 && glm::dot(glm::cross(c - q, a - q), u) >= 0.0 &&
        glm::dot(glm::cross(a - q, b - q), u) >= 0.0)
        return std::fabs(height);
    return edges;
}

double bruteMeshDistance(const glm::dvec3& p, const Mesh& m) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t t = 0; t < m.triangleCount(); ++t)
        best = std::min(best, triangleDistance(p, glm::dvec3(m.positions[m.indices[3 * t]]),
                                               glm::dvec3(m.positions[m.indices[3 * t + 1]]),
                                               glm::dvec3(m.positions[m.indices[3 * t + 2]])));
    return best;
}

std::vector<glm::dvec3> surfacePoints(const Mesh& m, size_t count, uint64_t seed) {
    auto corner = [&m](size_t t, int k) { return glm::dvec3(m.positions[m.indices[3 * t + size_t(k)]]); };
    std::vector<double> cumulative;
    std::vector<glm::dvec3> out;
    double total = 0.0;
    for (size_t t = 0; t < m.triangleCount(); ++t) {
        const double area = glm::length(glm::cross(corner(t, 1) - corner(t, 0), corner(t, 2) - corner(t, 0)));
        total += area;
        cumulative.push_back(total);
        if (area > 0.0)
            for (int k = 0; k < 3; ++k)
                out.push_back(corner(t, k));
    }
    Rng rng(seed);
    for (size_t i = 0; i < count && !cumulative.empty(); ++i) {
        const size_t t =
            std::min(size_t(std::upper_bound(cumulative.begin(), cumulative.end(), rng.uniform() * total) -
                            cumulative.begin()),
                     cumulative.size() - 1);
        double u = rng.uniform(), v = rng.uniform();
        if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
        out.push_back(corner(t, 0) + u * (corner(t, 1) - corner(t, 0)) + v * (corner(t, 2) - corner(t, 0)));
    }
    return out;
}

double denseOneSided(const Mesh& from, const Mesh& to, size_t count, uint64_t seed) {
    Result<ClosestPointQuery> q = ClosestPointQuery::create(to);
    EXPECT_TRUE(q) << q.error();
    if (!q) return 0.0;
    double worst = 0.0;
    for (const glm::dvec3& p : surfacePoints(from, count, seed))
        worst = std::max(worst, q->closest(p)->distance);
    return worst;
}

} // namespace spatter::test
