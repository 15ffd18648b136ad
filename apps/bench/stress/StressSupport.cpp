#include "StressSupport.hpp"

#include "spatter/core/Frame.hpp"
#include "spatter/core/MeshBuilder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

namespace spatter::stress {

Scene planeScene(double half) {
    const std::vector<float> s = makeSamples(float(-half), float(half), float(half / 2.0));
    Scene scene;
    scene.source = "stress:plane";
    scene.objects.push_back(makeSceneObject("plane", makeGrid(s, s)));
    return scene;
}

DecalType makeType(const std::string& name, float size, float maxAngleDeg, float jitter,
                   bool randomRotation) {
    DecalType t;
    t.name = name;
    t.size = glm::vec2(size);
    t.maxAngleDeg = maxAngleDeg;
    t.sizeJitter = jitter;
    t.randomRotation = randomRotation;
    return t;
}

DecalSettings unlimitedSettings(uint64_t seed) {
    DecalSettings s;
    s.seed = seed;
    s.maxPerCell = UINT32_MAX;
    s.maxPerObject = UINT32_MAX;
    s.budget = UINT32_MAX;
    return s;
}

double uniform(Rng& rng, double lo, double hi) {
    const double u =
        double(rng.next()) * (1.0 / 4294967296.0) + double(rng.next()) * (1.0 / 18446744073709551616.0);
    return lo + (hi - lo) * u;
}

glm::dvec3 randomUnit(Rng& rng) {
    const double z = uniform(rng, -1.0, 1.0);
    const double phi = uniform(rng, 0.0, 2.0 * kPi);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return glm::dvec3(r * std::cos(phi), r * std::sin(phi), z);
}

bool finite3(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool finite3(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

double frameErrorOf(const Frame& f) {
    if (!finite3(f.tangent) || !finite3(f.bitangent) || !finite3(f.normal)) return INFINITY;
    return double(frameError(f));
}

std::string checkDecal(const DecalSystem& sys, const Decal& d, const DecalType& type, DecalCheck& check,
                       double frameBound, double relBound) {
    check.checked++;
    const WorldDecal w = sys.worldBox(d);
    const bool finite = finite3(d.frame().tangent) && finite3(d.frame().bitangent) &&
                        finite3(d.frame().normal) && finite3(d.center) && std::isfinite(d.size.x) &&
                        std::isfinite(d.size.y) && std::isfinite(d.halfDepth) && finite3(w.center) &&
                        finite3(w.frame.tangent) && finite3(w.frame.bitangent) && finite3(w.frame.normal) &&
                        std::isfinite(w.size.x) && std::isfinite(w.size.y) && std::isfinite(w.halfDepth);
    if (!finite) {
        check.nonFinite++;
        return "decal with a non-finite value at " + vec(w.center);
    }
    const double fe = std::max(frameErrorOf(d.frame()), frameErrorOf(w.frame));
    check.frameError = worse(check.frameError, fe);

    const double fx = double(w.size.x) / double(type.size.x), fy = double(w.size.y) / double(type.size.y);
    const double se = std::max({std::fabs(fx - 1.0) - double(type.sizeJitter),
                                std::fabs(fy - 1.0) - double(type.sizeJitter), std::fabs(fx - fy) / fx, 0.0});
    check.sizeError = worse(check.sizeError, se);

    const double h = sys.world().worldErrorBound(d.object);
    const double automatic = h + double(sys.settings().depthMargin) * double(std::max(w.size.x, w.size.y));
    const double expected = std::max(double(type.halfDepth), automatic);
    const double de = std::fabs(double(w.halfDepth) / expected - 1.0);
    check.depthError = worse(check.depthError, de);

    const glm::dmat4 box(d.boxToObject());
    const glm::dmat4 product = box * glm::inverse(box);
    double be = 0.0;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            be = worse(be, std::fabs(product[c][r] - (c == r ? 1.0 : 0.0)));
    check.boxInverse = worse(check.boxInverse, be);

    if (!(fe <= frameBound)) return "frame error " + num(fe) + " at " + vec(w.center);
    if (!(se <= relBound))
        return "size " + num(w.size.x) + " x " + num(w.size.y) + " for type size " + num(type.size.x) +
               " at " + vec(w.center);
    if (!(de <= relBound)) return "half-depth " + num(w.halfDepth) + ", expected " + num(expected);
    if (!(be <= relBound)) return "box inverse error " + num(be) + " at " + vec(w.center);
    return {};
}

namespace {

using EdgeKey = std::pair<uint32_t, uint32_t>;

bool hasArea(const Mesh& m, size_t t, glm::dvec3& normal) {
    const uint32_t* tri = &m.indices[3 * t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) return false;
    const glm::dvec3 p0(m.positions[tri[0]]), p1(m.positions[tri[1]]), p2(m.positions[tri[2]]);
    const glm::dvec3 c = glm::cross(p1 - p0, p2 - p0);
    const double len = glm::length(c);
    if (!(len > 0.0)) return false;
    normal = c / len;
    return true;
}

// Triangles of non-zero area per undirected edge.
std::map<EdgeKey, std::vector<size_t>> edgeTriangles(const Mesh& m, std::vector<glm::dvec3>& normals) {
    std::map<EdgeKey, std::vector<size_t>> edges;
    normals.assign(m.triangleCount(), glm::dvec3(0.0));
    for (size_t t = 0; t < m.triangleCount(); ++t) {
        if (!hasArea(m, t, normals[t])) continue;
        for (int k = 0; k < 3; ++k) {
            uint32_t a = m.indices[3 * t + size_t(k)], b = m.indices[3 * t + size_t((k + 1) % 3)];
            if (a > b) std::swap(a, b);
            edges[{a, b}].push_back(t);
        }
    }
    return edges;
}

} // namespace

std::vector<SharedEdge> sharedEdges(const Mesh& mesh) {
    std::vector<glm::dvec3> normals;
    std::vector<SharedEdge> out;
    for (const auto& [key, tris] : edgeTriangles(mesh, normals)) {
        if (tris.size() != 2) continue;
        SharedEdge e;
        e.a = key.first;
        e.b = key.second;
        e.n0 = normals[tris[0]];
        e.n1 = normals[tris[1]];
        out.push_back(e);
    }
    return out;
}

std::vector<InteriorVertex> interiorVertices(const Mesh& mesh) {
    std::vector<glm::dvec3> normals;
    const auto edges = edgeTriangles(mesh, normals);
    std::vector<int> state(mesh.positions.size(), 0); // 0 unused, 1 interior so far, -1 on a boundary
    for (const auto& [key, tris] : edges) {
        const int s = tris.size() == 2 ? 1 : -1;
        for (uint32_t v : {key.first, key.second})
            state[v] = (state[v] == -1 || s == -1) ? -1 : 1;
    }
    std::vector<InteriorVertex> out(mesh.positions.size());
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        if (normals[t] == glm::dvec3(0.0)) continue;
        for (int k = 0; k < 3; ++k)
            out[mesh.indices[3 * t + size_t(k)]].normals.push_back(normals[t]);
    }
    std::vector<InteriorVertex> kept;
    for (uint32_t v = 0; v < out.size(); ++v) {
        if (state[v] != 1) continue;
        out[v].v = v;
        kept.push_back(std::move(out[v]));
    }
    return kept;
}

bool closedMesh(const Mesh& mesh) {
    std::map<EdgeKey, int> directed;
    for (size_t t = 0; t < mesh.triangleCount(); ++t)
        for (int k = 0; k < 3; ++k)
            directed[{mesh.indices[3 * t + size_t(k)], mesh.indices[3 * t + size_t((k + 1) % 3)]}]++;
    if (directed.empty()) return false;
    for (const auto& [key, count] : directed) {
        if (count != 1) return false;
        const auto opposite = directed.find({key.second, key.first});
        if (opposite == directed.end() || opposite->second != 1) return false;
    }
    return true;
}

Result<Renderer> caseRenderer(const StressConfig& cfg, int width, int height, StressResult& r,
                              std::optional<size_t> gpuCullingFrom) {
    if (!cfg.gl) {
        r.skipped = "no headless OpenGL context: " + cfg.glError;
        return fail(r.skipped);
    }
    RendererSettings rs;
    rs.width = width;
    rs.height = height;
    rs.gpuCullingFrom = gpuCullingFrom;
    Result<Renderer> renderer = Renderer::create(*cfg.gl, rs);
    if (!renderer) {
        r.failure(renderer.error());
        r.row("renderer", INFINITY, 0.0, 0);
    }
    return renderer;
}

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

std::string vec(const glm::dvec3& v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.17g, %.17g, %.17g)", v.x, v.y, v.z);
    return buf;
}

} // namespace spatter::stress
