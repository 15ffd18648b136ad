#include "spatter/core/UvOverlap.hpp"

#include <algorithm>
#include <cmath>

namespace spatter {

namespace {

struct Tri {
    glm::vec2 p[3];
    glm::vec2 lo, hi;
};

// True when some edge normal of a or b separates the two triangles by at least -tol (touching
// within the tolerance counts as separated).
bool separated(const Tri& a, const Tri& b, float tol) {
    const Tri* ts[2] = {&a, &b};
    for (const Tri* t : ts)
        for (int e = 0; e < 3; ++e) {
            const glm::vec2 d = t->p[(e + 1) % 3] - t->p[e];
            const glm::vec2 n(-d.y, d.x);
            const float len = std::sqrt(n.x * n.x + n.y * n.y);
            if (!(len > 0.0f)) continue;
            float minA = 1e30f, maxA = -1e30f, minB = 1e30f, maxB = -1e30f;
            for (int k = 0; k < 3; ++k) {
                const float pa = glm::dot(a.p[k], n) / len, pb = glm::dot(b.p[k], n) / len;
                minA = std::min(minA, pa);
                maxA = std::max(maxA, pa);
                minB = std::min(minB, pb);
                maxB = std::max(maxB, pb);
            }
            if (maxA <= minB + tol || maxB <= minA + tol) return true;
        }
    return false;
}

} // namespace

std::string UvOverlapReport::summary() const {
    std::string s = std::to_string(overlappingPairs) + " overlapping triangle pairs";
    if (!pairs.empty())
        s += " (first: " + std::to_string(pairs.front().first) + " and " +
             std::to_string(pairs.front().second) + ")";
    s += ", " + std::to_string(outOfRange) + " out of [0, 1], " + std::to_string(degenerate) + " degenerate";
    return s;
}

Result<UvOverlapReport> findUvOverlaps(const Mesh& mesh, size_t maxPairs, float tolerance) {
    if (Status s = validateMesh(mesh); !s) return fail("uv overlap: " + s.error());
    if (mesh.uvs.size() != mesh.positions.size() || mesh.positions.empty())
        return fail("uv overlap: the mesh has no UVs");
    const float tol = std::isfinite(tolerance) ? std::max(tolerance, 0.0f) : 1e-6f;
    UvOverlapReport r;
    r.triangles = mesh.triangleCount();

    std::vector<Tri> tris;
    std::vector<uint32_t> ids;
    tris.reserve(r.triangles);
    for (size_t t = 0; t < r.triangles; ++t) {
        Tri tri;
        bool finite = true, inside = true;
        for (int k = 0; k < 3; ++k) {
            tri.p[k] = mesh.uvs[mesh.indices[3 * t + size_t(k)]];
            finite = finite && std::isfinite(tri.p[k].x) && std::isfinite(tri.p[k].y);
            inside = inside && tri.p[k].x >= 0.0f && tri.p[k].x <= 1.0f && tri.p[k].y >= 0.0f &&
                     tri.p[k].y <= 1.0f;
        }
        if (!finite || !inside) {
            ++r.outOfRange;
            continue;
        }
        const glm::vec2 e1 = tri.p[1] - tri.p[0], e2 = tri.p[2] - tri.p[0];
        if (std::fabs(e1.x * e2.y - e1.y * e2.x) * 0.5f <= tol * tol) {
            ++r.degenerate;
            continue;
        }
        tri.lo = glm::min(tri.p[0], glm::min(tri.p[1], tri.p[2]));
        tri.hi = glm::max(tri.p[0], glm::max(tri.p[1], tri.p[2]));
        tris.push_back(tri);
        ids.push_back(uint32_t(t));
    }

    const int g = std::clamp(int(std::sqrt(double(tris.size()))), 1, 1024);
    auto cell = [g](float v) { return std::clamp(int(v * float(g)), 0, g - 1); };
    std::vector<std::vector<uint32_t>> grid(size_t(g) * size_t(g));
    for (size_t i = 0; i < tris.size(); ++i)
        for (int y = cell(tris[i].lo.y); y <= cell(tris[i].hi.y); ++y)
            for (int x = cell(tris[i].lo.x); x <= cell(tris[i].hi.x); ++x)
                grid[size_t(y) * size_t(g) + size_t(x)].push_back(uint32_t(i));

    std::vector<uint32_t> stamp(tris.size(), UINT32_MAX);
    for (size_t i = 0; i < tris.size(); ++i) {
        const Tri& a = tris[i];
        for (int y = cell(a.lo.y); y <= cell(a.hi.y); ++y)
            for (int x = cell(a.lo.x); x <= cell(a.hi.x); ++x)
                for (uint32_t j : grid[size_t(y) * size_t(g) + size_t(x)]) {
                    if (j <= i || stamp[j] == uint32_t(i)) continue;
                    stamp[j] = uint32_t(i);
                    const Tri& b = tris[j];
                    if (a.hi.x <= b.lo.x + tol || b.hi.x <= a.lo.x + tol || a.hi.y <= b.lo.y + tol ||
                        b.hi.y <= a.lo.y + tol)
                        continue;
                    if (separated(a, b, tol)) continue;
                    ++r.overlappingPairs;
                    if (r.pairs.size() < maxPairs) r.pairs.emplace_back(ids[i], ids[j]);
                }
    }
    return r;
}

void fitUvsToUnitSquare(Mesh& mesh, float margin) {
    if (mesh.uvs.empty()) return;
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (const glm::vec2& uv : mesh.uvs) {
        if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return;
        lo = glm::min(lo, uv);
        hi = glm::max(hi, uv);
    }
    const float m = std::isfinite(margin) ? std::clamp(margin, 0.0f, 0.25f) : 0.01f;
    const float extent = std::max(hi.x - lo.x, hi.y - lo.y);
    const float scale = extent > 0.0f ? (1.0f - 2.0f * m) / extent : 0.0f;
    for (glm::vec2& uv : mesh.uvs)
        uv = glm::vec2(m) + (uv - lo) * scale;
}

} // namespace spatter
