#include "spatter/core/MeshBuilder.hpp"
#include "Pi.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace spatter {

static constexpr float kMergeDistance = 1e-4f;

static bool finitePositive(float v) {
    return std::isfinite(v) && v > 0.0f;
}

static glm::vec2 boxProjectUv(const glm::vec3& p, const glm::vec3& n) {
    const glm::vec3 a = glm::abs(n);
    if (a.x >= a.y && a.x >= a.z) return {p.z, p.y};
    if (a.y >= a.z) return {p.x, p.z};
    return {p.x, p.y};
}

// Normals from the geometry, box-projected UVs, tangents.
static void finishBoxProjected(Mesh& mesh) {
    computeNormals(mesh);
    mesh.uvs.resize(mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i)
        mesh.uvs[i] = boxProjectUv(mesh.positions[i], mesh.normals[i]);
    computeTangents(mesh);
}

Mesh makeUnitCube() {
    Mesh mesh;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 p((i & 1) ? 0.5f : -0.5f, (i & 2) ? 0.5f : -0.5f, (i & 4) ? 0.5f : -0.5f);
        mesh.positions.push_back(p);
        mesh.normals.push_back(glm::normalize(p));
        mesh.uvs.emplace_back(p.x + 0.5f, p.y + 0.5f);
    }
    mesh.indices = {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4,
                    2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6};
    computeTangents(mesh);
    return mesh;
}

std::vector<float> makeSamples(float lo, float hi, float maxStep, const std::vector<float>& breaks) {
    if (!std::isfinite(lo) || !std::isfinite(hi)) return {};
    if (!(hi > lo)) return {lo};
    if (hi - lo < kMergeDistance) return {lo, hi};
    const float step = std::isfinite(maxStep) ? std::max(maxStep, 1e-3f) : (hi - lo);

    std::vector<float> inside;
    for (float v : breaks)
        if (std::isfinite(v) && v > lo && v < hi) inside.push_back(v);
    std::sort(inside.begin(), inside.end());
    std::vector<float> fixed{lo};
    for (float v : inside)
        if (v - fixed.back() >= kMergeDistance && hi - v >= kMergeDistance) fixed.push_back(v);
    fixed.push_back(hi);

    std::vector<float> out;
    for (size_t i = 0; i + 1 < fixed.size(); ++i) {
        const float a = fixed[i], gap = fixed[i + 1] - a;
        const int pieces = int(std::min(65536.0f, std::max(1.0f, std::ceil(gap / step))));
        out.push_back(a);
        for (int k = 1; k < pieces; ++k)
            out.push_back(a + gap * float(k) / float(pieces));
    }
    out.push_back(hi);
    return out;
}

// Lattice samples for one axis of a (bevelled) box: bevelSteps rows on each rounded side, the
// flat part from makeSamples.
static std::vector<float> boxAxisSamples(float h, float bevel, int steps, float maxEdge,
                                         const std::vector<float>& breaks) {
    if (bevel <= 0.0f) return makeSamples(-h, h, maxEdge, breaks);
    const float inner = h - bevel;
    const std::vector<float> flat = makeSamples(-inner, inner, maxEdge, breaks);
    std::vector<float> side; // offsets beyond `inner`, increasing, last = bevel
    for (int k = 1; k <= steps; ++k)
        side.push_back(k == steps ? bevel : bevel * std::tan(0.25f * kPiF * float(k) / float(steps)));
    std::vector<float> out;
    out.push_back(-h);
    for (int k = steps - 2; k >= 0; --k)
        out.push_back(-inner - side[size_t(k)]);
    out.insert(out.end(), flat.begin(), flat.end());
    for (int k = 0; k + 1 < steps; ++k)
        out.push_back(inner + side[size_t(k)]);
    out.push_back(h);
    return out;
}

// The box lattice: every lattice point on the surface of the sample grid becomes one vertex,
// mapped onto the rounded box.
static Mesh buildLatticeBox(const glm::vec3& h, float bevel,
                            const std::array<std::vector<float>, 3>& samples) {
    Mesh mesh;
    const glm::vec3 inner = h - glm::vec3(bevel);
    const size_t n[3] = {samples[0].size(), samples[1].size(), samples[2].size()};
    std::unordered_map<uint64_t, uint32_t> lookup;

    auto vertex = [&](const size_t idx[3]) -> uint32_t {
        const uint64_t key =
            uint64_t(idx[0]) + uint64_t(n[0]) * (uint64_t(idx[1]) + uint64_t(n[1]) * uint64_t(idx[2]));
        auto found = lookup.find(key);
        if (found != lookup.end()) return found->second;
        const glm::vec3 q(samples[0][idx[0]], samples[1][idx[1]], samples[2][idx[2]]);
        glm::vec3 p = q;
        if (bevel > 0.0f) {
            const glm::vec3 c = glm::clamp(q, -inner, inner);
            const glm::vec3 d = q - c;
            const int outside = int(d.x != 0.0f) + int(d.y != 0.0f) + int(d.z != 0.0f);
            if (outside >= 2) p = glm::clamp(c + d * (bevel / glm::length(d)), -h, h);
        }
        const uint32_t id = uint32_t(mesh.positions.size());
        mesh.positions.push_back(p);
        lookup.emplace(key, id);
        return id;
    };

    for (int a = 0; a < 3; ++a) {
        const int u = (a + 1) % 3, v = (a + 2) % 3;
        for (int s = 0; s < 2; ++s) {
            const size_t fixed = s == 0 ? 0 : n[a] - 1;
            std::vector<uint32_t> ids(n[u] * n[v]);
            for (size_t j = 0; j < n[v]; ++j)
                for (size_t i = 0; i < n[u]; ++i) {
                    size_t idx[3];
                    idx[a] = fixed;
                    idx[u] = i;
                    idx[v] = j;
                    ids[i + j * n[u]] = vertex(idx);
                }
            for (size_t j = 0; j + 1 < n[v]; ++j)
                for (size_t i = 0; i + 1 < n[u]; ++i) {
                    const uint32_t v00 = ids[i + j * n[u]], v10 = ids[i + 1 + j * n[u]];
                    const uint32_t v01 = ids[i + (j + 1) * n[u]], v11 = ids[i + 1 + (j + 1) * n[u]];
                    if (s == 1)
                        mesh.indices.insert(mesh.indices.end(), {v00, v10, v11, v00, v11, v01});
                    else
                        mesh.indices.insert(mesh.indices.end(), {v00, v11, v10, v00, v01, v11});
                }
        }
    }
    finishBoxProjected(mesh);
    return mesh;
}

static bool validExtents(const glm::vec3& h) {
    return finitePositive(h.x) && finitePositive(h.y) && finitePositive(h.z);
}

Mesh makeBox(glm::vec3 halfExtents, int subdivisions) {
    if (!validExtents(halfExtents)) return {};
    const int n = std::clamp(subdivisions, 1, 256);
    std::array<std::vector<float>, 3> samples;
    for (int a = 0; a < 3; ++a) {
        const float h = halfExtents[a];
        for (int i = 0; i <= n; ++i)
            samples[size_t(a)].push_back(i == 0 ? -h : i == n ? h : -h + 2.0f * h * float(i) / float(n));
    }
    return buildLatticeBox(halfExtents, 0.0f, samples);
}

Mesh makeBeveledBox(const BoxSettings& settings) {
    const glm::vec3 h = settings.halfExtents;
    if (!validExtents(h)) return {};
    const float minExtent = std::min(h.x, std::min(h.y, h.z));
    const float bevel =
        std::isfinite(settings.bevel) ? std::clamp(settings.bevel, 0.0f, 0.45f * minExtent) : 0.0f;
    const int steps = std::clamp(settings.bevelSteps, 1, 16);
    const float maxEdge = std::isfinite(settings.maxEdge) ? std::max(settings.maxEdge, 1e-3f) : 1.0f;
    std::array<std::vector<float>, 3> samples;
    for (int a = 0; a < 3; ++a)
        samples[size_t(a)] = boxAxisSamples(h[a], bevel, steps, maxEdge, settings.breaks[size_t(a)]);
    return buildLatticeBox(h, bevel, samples);
}

Mesh makeGrid(const std::vector<float>& xs, const std::vector<float>& zs) {
    auto increasing = [](const std::vector<float>& s) {
        if (s.size() < 2) return false;
        for (size_t i = 0; i < s.size(); ++i)
            if (!std::isfinite(s[i]) || (i > 0 && !(s[i] > s[i - 1]))) return false;
        return true;
    };
    if (!increasing(xs) || !increasing(zs)) return {};
    Mesh mesh;
    const size_t nx = xs.size(), nz = zs.size();
    for (size_t j = 0; j < nz; ++j)
        for (size_t i = 0; i < nx; ++i) {
            mesh.positions.emplace_back(xs[i], 0.0f, zs[j]);
            mesh.uvs.emplace_back(xs[i], zs[j]);
        }
    for (size_t j = 0; j + 1 < nz; ++j)
        for (size_t i = 0; i + 1 < nx; ++i) {
            const uint32_t v00 = uint32_t(i + j * nx), v10 = v00 + 1;
            const uint32_t v01 = uint32_t(i + (j + 1) * nx), v11 = v01 + 1;
            // Seen from +Y, +X then +Z turns clockwise, so (v00, v01, v11) is counter-clockwise.
            mesh.indices.insert(mesh.indices.end(), {v00, v01, v11, v00, v11, v10});
        }
    computeNormals(mesh);
    computeTangents(mesh);
    return mesh;
}

Mesh makeLathe(const std::vector<glm::vec2>& profile, int segments) {
    const size_t count = profile.size();
    if (count < 2) return {};
    for (size_t i = 0; i < count; ++i) {
        const glm::vec2 p = profile[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) return {};
        const bool end = i == 0 || i + 1 == count;
        if (end ? p.x < 0.0f : p.x <= 0.0f) return {};
    }
    const bool ring0 = profile.front().x > 0.0f, ringN = profile.back().x > 0.0f;
    if (count == 2 && !ring0 && !ringN) return {};
    const uint32_t seg = uint32_t(std::clamp(segments, 3, 4096));

    float rMax = 0.0f;
    for (const glm::vec2& p : profile)
        rMax = std::max(rMax, p.x);

    Mesh mesh;
    std::vector<uint32_t> first(count); // first vertex of each profile point
    float arc = 0.0f;
    for (size_t i = 0; i < count; ++i) {
        if (i > 0) arc += glm::length(profile[i] - profile[i - 1]);
        first[i] = uint32_t(mesh.positions.size());
        const float r = profile[i].x, y = profile[i].y;
        if (r == 0.0f) {
            mesh.positions.emplace_back(0.0f, y, 0.0f);
            mesh.uvs.emplace_back(0.0f, arc);
            continue;
        }
        for (uint32_t k = 0; k < seg; ++k) {
            const float t = 2.0f * kPiF * float(k) / float(seg);
            mesh.positions.emplace_back(r * std::sin(t), y, r * std::cos(t));
            mesh.uvs.emplace_back(rMax * t, arc);
        }
    }
    for (size_t i = 0; i + 1 < count; ++i) {
        const bool ringA = profile[i].x > 0.0f, ringB = profile[i + 1].x > 0.0f;
        const uint32_t a = first[i], b = first[i + 1];
        for (uint32_t k = 0; k < seg; ++k) {
            const uint32_t k1 = (k + 1) % seg;
            if (ringA && ringB)
                mesh.indices.insert(mesh.indices.end(), {a + k, a + k1, b + k1, a + k, b + k1, b + k});
            else if (ringB)
                mesh.indices.insert(mesh.indices.end(), {a, b + k1, b + k});
            else if (ringA)
                mesh.indices.insert(mesh.indices.end(), {a + k, a + k1, b});
        }
    }
    computeNormals(mesh);
    computeTangents(mesh);
    return mesh;
}

Mesh makeSphere(float radius, int rings, int segments) {
    if (!finitePositive(radius)) return {};
    const int n = std::clamp(rings, 2, 4096);
    std::vector<glm::vec2> profile;
    for (int i = 0; i <= n; ++i) {
        if (i == 0 || i == n) {
            profile.emplace_back(0.0f, i == 0 ? -radius : radius);
            continue;
        }
        const float phi = kPiF * float(i) / float(n);
        profile.emplace_back(radius * std::sin(phi), -radius * std::cos(phi));
    }
    Mesh mesh = makeLathe(profile, segments);
    for (size_t i = 0; i < mesh.positions.size(); ++i)
        mesh.normals[i] = glm::normalize(mesh.positions[i]);
    computeTangents(mesh);
    return mesh;
}

Mesh makeCylinder(float radius, float height, int segments, float bevel) {
    if (!finitePositive(radius) || !finitePositive(height)) return {};
    const float b =
        std::isfinite(bevel) ? std::clamp(bevel, 0.0f, 0.45f * std::min(radius, 0.5f * height)) : 0.0f;
    std::vector<glm::vec2> profile;
    profile.emplace_back(0.0f, 0.0f);
    if (b > 0.0f) {
        constexpr int kSteps = 4;
        for (int k = 0; k <= kSteps; ++k) { // bottom rim: from the cap round to the side
            const float t = 0.5f * kPiF * float(k) / float(kSteps);
            profile.emplace_back(radius - b + b * std::sin(t), b - b * std::cos(t));
        }
        for (int k = 0; k <= kSteps; ++k) { // top rim: from the side round to the cap
            const float t = 0.5f * kPiF * float(k) / float(kSteps);
            profile.emplace_back(radius - b + b * std::cos(t), height - b + b * std::sin(t));
        }
    } else {
        profile.emplace_back(radius, 0.0f);
        profile.emplace_back(radius, height);
    }
    profile.emplace_back(0.0f, height);
    return makeLathe(profile, segments);
}

void displace(Mesh& mesh, const std::function<float(const glm::vec3&, const glm::vec3&)>& height) {
    if (mesh.normals.size() != mesh.positions.size() || !height) return;
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const float d = height(mesh.positions[i], mesh.normals[i]);
        if (std::isfinite(d)) mesh.positions[i] += mesh.normals[i] * d;
    }
    computeNormals(mesh);
    computeTangents(mesh);
}

static glm::vec3 unitOr(const glm::vec3& v, const glm::vec3& fallback) {
    const float len = glm::length(v);
    return (std::isfinite(len) && len > 1e-20f) ? v / len : fallback;
}

void appendMesh(Mesh& dst, const Mesh& src, const glm::mat4& xf) {
    const bool dstEmpty = dst.positions.empty() && dst.indices.empty();
    const size_t n = src.positions.size();
    const uint32_t base = uint32_t(dst.positions.size());
    const size_t oldIndexCount = dst.indices.size();
    auto keep = [&](size_t dstSize, size_t srcSize) {
        return dstEmpty ? srcSize == n : (dstSize == dst.positions.size() && srcSize == n);
    };
    const bool keepNormals = keep(dst.normals.size(), src.normals.size());
    const bool keepUvs = keep(dst.uvs.size(), src.uvs.size());
    const bool keepTangents = keep(dst.tangents.size(), src.tangents.size());

    const glm::mat3 linear(xf);
    const float det = glm::determinant(linear);
    const float orientation = det < 0.0f ? -1.0f : 1.0f;
    // Cofactor matrix (det * inverse transpose), defined even when xf is singular.
    const glm::mat3 cofactor(glm::cross(linear[1], linear[2]), glm::cross(linear[2], linear[0]),
                             glm::cross(linear[0], linear[1]));

    for (size_t i = 0; i < n; ++i)
        dst.positions.push_back(glm::vec3(xf * glm::vec4(src.positions[i], 1.0f)));
    if (keepNormals)
        for (size_t i = 0; i < n; ++i)
            dst.normals.push_back(unitOr(orientation * (cofactor * src.normals[i]), glm::vec3(0, 0, 1)));
    else
        dst.normals.clear();
    if (keepUvs)
        dst.uvs.insert(dst.uvs.end(), src.uvs.begin(), src.uvs.end());
    else
        dst.uvs.clear();
    if (keepTangents)
        for (size_t i = 0; i < n; ++i) {
            const glm::vec4 t = src.tangents[i];
            dst.tangents.emplace_back(unitOr(linear * glm::vec3(t), glm::vec3(1, 0, 0)), t.w * orientation);
        }
    else
        dst.tangents.clear();

    const size_t m = src.indices.size();
    for (size_t i = 0; i + 2 < m; i += 3) {
        const uint32_t a = src.indices[i], b = src.indices[i + 1], c = src.indices[i + 2];
        if (det < 0.0f)
            dst.indices.insert(dst.indices.end(), {a + base, c + base, b + base});
        else
            dst.indices.insert(dst.indices.end(), {a + base, b + base, c + base});
    }
    for (size_t i = m - m % 3; i < m; ++i)
        dst.indices.push_back(src.indices[i] + base);

    if (!dst.submeshes.empty() || !src.submeshes.empty()) {
        if (dst.submeshes.empty() && oldIndexCount > 0)
            dst.submeshes.push_back({0, uint32_t(oldIndexCount), -1});
        if (src.submeshes.empty()) {
            if (m > 0) dst.submeshes.push_back({uint32_t(oldIndexCount), uint32_t(m), -1});
        } else {
            for (Submesh s : src.submeshes) {
                s.firstIndex += uint32_t(oldIndexCount);
                dst.submeshes.push_back(s);
            }
        }
    }
}

} // namespace spatter
