// Degenerate input: a closed sphere with zero-area triangles (repeated indices, three vertices at one
// position, collinear corners), slivers and needles, duplicate vertices (a seam of coincident but
// unconnected vertices), repeated and reversed triangles, and unreferenced vertices near and very far
// away. Held in memory and written to OBJ and glTF files; each is loaded, turned into proxies by both
// backends, and shot at. Everything must load, every normal must be unit and finite, and every decal
// must have a valid frame and sit where the ray meets the render mesh (computed here in double).

#include "StressCase.hpp"
#include "StressSupport.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/SceneLoader.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>

namespace spatter::stress {

namespace {

uint32_t addVertex(Mesh& m, const glm::vec3& p) {
    m.positions.push_back(p);
    m.normals.push_back(glm::vec3(0, 0, 1));
    return uint32_t(m.positions.size() - 1);
}

void addTriangle(Mesh& m, uint32_t a, uint32_t b, uint32_t c) {
    m.indices.insert(m.indices.end(), {a, b, c});
}

// The sphere and its degenerate additions (see the top of the file). Normals are recomputed.
Mesh degenerateSphere() {
    Mesh m = makeSphere(1.0f, 16, 32);
    m.uvs.clear();
    m.tangents.clear();
    const size_t baseTriangles = m.triangleCount();
    // Duplicate vertices: every other triangle with x > 0.2 uses copies of its corners.
    std::vector<int64_t> copyOf(m.positions.size(), -1);
    for (size_t t = 0; t < baseTriangles; t += 2) {
        uint32_t* tri = &m.indices[3 * t];
        if (!(m.positions[tri[0]].x > 0.2f && m.positions[tri[1]].x > 0.2f && m.positions[tri[2]].x > 0.2f))
            continue;
        for (int k = 0; k < 3; ++k) {
            if (copyOf[tri[k]] < 0) copyOf[tri[k]] = addVertex(m, m.positions[tri[k]]);
            tri[k] = uint32_t(copyOf[tri[k]]);
        }
    }
    for (size_t t = 0; t < baseTriangles; t += 7) {
        const uint32_t a = m.indices[3 * t], b = m.indices[3 * t + 1], c = m.indices[3 * t + 2];
        const glm::vec3 pa = m.positions[a], pb = m.positions[b];
        switch ((t / 7) % 7) {
        case 0: // repeated indices
            addTriangle(m, a, a, b);
            addTriangle(m, c, c, c);
            break;
        case 1: { // three vertices at one position
            const uint32_t x = addVertex(m, pa), y = addVertex(m, pa);
            addTriangle(m, a, x, y);
            break;
        }
        case 2: // collinear corners: the midpoint of an edge
            addTriangle(m, a, b, addVertex(m, (pa + pb) * 0.5f));
            break;
        case 3: // a sliver standing 1e-6 out of the surface over an edge
            addTriangle(m, a, b, addVertex(m, (pa + pb) * 0.5f + glm::normalize(pa + pb) * 1e-6f));
            break;
        case 4: // a needle 1e-7 wide
            addTriangle(m, a, addVertex(m, pa + glm::vec3(1e-7f, -1e-7f, 0.0f)), b);
            break;
        case 5: // the same triangle again, and reversed
            addTriangle(m, a, b, c);
            addTriangle(m, a, c, b);
            break;
        default: // a zero-length edge inside a real triangle's corner
            addTriangle(m, b, c, addVertex(m, m.positions[c]));
            break;
        }
    }
    // Unreferenced vertices: at the centre, a kilometre away and absurdly far away.
    addVertex(m, glm::vec3(0.0f));
    addVertex(m, glm::vec3(1000.0f, -20.0f, 5.0f));
    addVertex(m, glm::vec3(1e30f, -1e30f, 1e30f));
    computeNormals(m);
    return m;
}

// glTF with an external buffer: positions, the given normals (some zero, some not unit) and 32-bit
// indices.
bool writeGltf(const Mesh& m, const std::string& dir, const std::string& name) {
    std::vector<glm::vec3> normals = m.normals;
    for (size_t i = 0; i < normals.size(); i += 5)
        normals[i] = i % 2 ? glm::vec3(0.0f) : normals[i] * 3.0f;
    const size_t posBytes = m.positions.size() * 12, idxBytes = m.indices.size() * 4;
    std::ofstream bin(dir + "/" + name + ".bin", std::ios::binary);
    bin.write(reinterpret_cast<const char*>(m.positions.data()), std::streamsize(posBytes));
    bin.write(reinterpret_cast<const char*>(normals.data()), std::streamsize(posBytes));
    bin.write(reinterpret_cast<const char*>(m.indices.data()), std::streamsize(idxBytes));
    if (!bin) return false;
    const Bounds b = m.bounds();
    nlohmann::json j;
    j["asset"] = {{"version", "2.0"}};
    j["scene"] = 0;
    j["scenes"] = {{{"nodes", {0}}}};
    j["nodes"] = {{{"mesh", 0}, {"name", name}}};
    j["meshes"] = {
        {{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}, {"mode", 4}}}}}};
    j["buffers"] = {{{"uri", name + ".bin"}, {"byteLength", 2 * posBytes + idxBytes}}};
    j["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", posBytes}},
                        {{"buffer", 0}, {"byteOffset", posBytes}, {"byteLength", posBytes}},
                        {{"buffer", 0}, {"byteOffset", 2 * posBytes}, {"byteLength", idxBytes}}};
    j["accessors"] = {
        {{"bufferView", 0},
         {"componentType", 5126},
         {"count", m.positions.size()},
         {"type", "VEC3"},
         {"min", {b.min.x, b.min.y, b.min.z}},
         {"max", {b.max.x, b.max.y, b.max.z}}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", m.positions.size()}, {"type", "VEC3"}},
        {{"bufferView", 2}, {"componentType", 5125}, {"count", m.indices.size()}, {"type", "SCALAR"}}};
    std::ofstream out(dir + "/" + name + ".gltf");
    out << j.dump(1);
    return bool(out);
}

// Number of normals that are not finite and unit (to 1e-5).
size_t badNormals(const Mesh& m) {
    size_t bad = m.normals.size() == m.positions.size() ? 0 : 1;
    for (const glm::vec3& n : m.normals)
        if (!finite3(n) || !(std::fabs(double(glm::length(n)) - 1.0) <= 1e-5)) bad++;
    return bad;
}

// Where `ray` first meets the mesh (in the object's space, identity transform), in double, by
// testing every triangle of non-zero area with barycentric coordinates allowed 1e-9 outside (so
// that a ray through a vertex or an edge meets it); empty when it misses.
std::optional<glm::dvec3> exactHit(const Mesh& m, const Ray& ray) {
    double best = INFINITY;
    for (size_t t = 0; t < m.triangleCount(); ++t) {
        const glm::dvec3 p0(m.positions[m.indices[3 * t]]), p1(m.positions[m.indices[3 * t + 1]]),
            p2(m.positions[m.indices[3 * t + 2]]);
        const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0, q = glm::cross(ray.direction, e2);
        const double det = glm::dot(e1, q);
        if (!(std::fabs(det) > 1e-300)) continue;
        const glm::dvec3 s = ray.origin - p0;
        const double u = glm::dot(s, q) / det;
        const glm::dvec3 rr = glm::cross(s, e1);
        const double v = glm::dot(ray.direction, rr) / det;
        const double tt = glm::dot(e2, rr) / det;
        if (u >= -1e-9 && v >= -1e-9 && u + v <= 1.0 + 1e-9 && tt > 0.0 && tt < best) best = tt;
    }
    if (!std::isfinite(best)) return std::nullopt;
    return ray.origin + best * ray.direction;
}

struct Totals {
    size_t loadFailures = 0, badNormals = 0, normalsChecked = 0, proxyFailures = 0, proxies = 0;
    size_t misses = 0, rays = 0;
    double centreError = 0.0;
    size_t centres = 0;
    DecalCheck check;
};

void place(const std::string& what, const Scene& scene,
           const std::vector<std::shared_ptr<const Proxy>>& proxies, bool exact, const StressConfig& cfg,
           Totals& totals, StressResult& r) {
    WorldSettings ws;
    ws.useColliders = false;
    Result<CollisionWorld> world = CollisionWorld::build(scene, proxies, ws);
    Result<DecalSystem> sys = world
                                  ? DecalSystem::create(std::move(world).value(), unlimitedSettings(cfg.seed))
                                  : Result<DecalSystem>(fail(world.error()));
    if (!sys) {
        totals.loadFailures++;
        r.failure(what + ": " + sys.error());
        return;
    }
    const DecalType type = makeType("degenerate", 0.05f, 90.0f);
    const uint16_t ti = sys->registerType(type).value();
    const Mesh& mesh = *scene.objects[0].mesh;
    Rng rng(cfg.seed + 3);
    const size_t count = cfg.full ? 4000 : 300;
    for (size_t i = 0; i < count; ++i) {
        Ray ray;
        ray.origin = 4.0 * randomUnit(rng);
        ray.direction = 0.3 * randomUnit(rng) - ray.origin;
        // Every fourth ray aims at a vertex of an added (degenerate) triangle, from outside and into
        // the sphere (not along its tangent plane, where touching a convex vertex may miss).
        if (i % 4 == 0) {
            const glm::dvec3 target(mesh.positions[mesh.indices[mesh.indices.size() - 1 - (i / 4) % 200]]);
            ray.origin = target + 3.0 * glm::normalize(glm::normalize(target) + 0.5 * randomUnit(rng));
            ray.direction = target - ray.origin;
        }
        totals.rays++;
        const SpawnResult res = sys->spawn(ray, ti);
        if (!res.placed()) {
            totals.misses++;
            r.failure(what + ": ray from " + vec(ray.origin) + " along " + vec(ray.direction) + ": " +
                      toString(res.status) + " " + res.reason);
            continue;
        }
        const std::string why =
            checkDecal(sys.value(), *sys->get(res.handle), type, totals.check, 1e-6, 1e-5);
        if (!why.empty()) r.failure(what + ": " + why);
        if (exact) {
            const std::optional<glm::dvec3> e = exactHit(mesh, ray);
            const glm::dvec3 c = sys->worldBox(*sys->get(res.handle)).center;
            const double err = e ? glm::length(c - *e) / 2.0 : INFINITY; // sphere diameter 2
            totals.centreError = worse(totals.centreError, err);
            totals.centres++;
            if (!(err <= 1e-6))
                r.failure(what + ": ray from " + vec(ray.origin) + " along " + vec(ray.direction) +
                          ": centre " + vec(c) + " but the ray meets the mesh at " +
                          (e ? vec(*e) : "nothing"));
        }
    }
    // spawnAttached at every vertex of the added triangles, with the mesh's normal there.
    const uint32_t firstAdded = uint32_t(makeSphere(1.0f, 16, 32).indices.size());
    for (size_t k = firstAdded; k < mesh.indices.size() && exact; ++k) {
        const uint32_t v = mesh.indices[k];
        const SpawnResult res = sys->spawnAttached(0, mesh.positions[v], mesh.normals[v], ti);
        if (!res.placed()) {
            totals.misses++;
            r.failure(what + ": spawnAttached at vertex " + std::to_string(v) + ": " + res.reason);
            continue;
        }
        const std::string why =
            checkDecal(sys.value(), *sys->get(res.handle), type, totals.check, 1e-6, 1e-5);
        if (!why.empty()) r.failure(what + ": spawnAttached: " + why);
    }
}

void survey(const std::string& what, const Scene& scene, const StressConfig& cfg, Totals& totals,
            StressResult& r) {
    if (Status s = validateScene(scene); !s) {
        totals.loadFailures++;
        r.failure(what + ": invalid scene: " + s.error());
        return;
    }
    for (const SceneObject& o : scene.objects) {
        totals.normalsChecked += o.mesh->normals.size();
        if (size_t bad = badNormals(*o.mesh)) {
            totals.badNormals += bad;
            r.failure(what + ": " + std::to_string(bad) + " bad normals in " + o.name);
        }
    }
    place(what + " (render mesh)", scene, {}, true, cfg, totals, r);
    // Proxies by both backends, forced to simplify.
    for (ProxyBackend backend : {ProxyBackend::OpenMesh, ProxyBackend::MeshOpt}) {
        ProxySettings ps;
        ps.backend = backend;
        ps.smallMeshTriangles = 0;
        ps.tolerance = 0.01f;
        ps.maxAttempts = 2;
        std::vector<std::shared_ptr<const Proxy>> proxies(scene.objects.size());
        const std::string name = what + " (" + proxyBackendName(backend) + " proxy)";
        for (size_t i = 0; i < scene.objects.size(); ++i) {
            totals.proxies++;
            Result<Proxy> p = buildProxy(*scene.objects[i].mesh, ps);
            if (!p || !validateMesh(p->mesh) || !std::isfinite(p->errorBound) ||
                p->mesh.triangleCount() == 0) {
                totals.proxyFailures++;
                r.failure(name + ": " + (p ? "invalid proxy" : p.error()));
                continue;
            }
            totals.normalsChecked += p->mesh.normals.size();
            if (size_t bad = badNormals(p->mesh)) {
                totals.badNormals += bad;
                r.failure(name + ": " + std::to_string(bad) + " bad normals");
            }
            proxies[i] = shareProxy(std::move(p).value());
        }
        if (proxies[0]) place(name, scene, proxies, false, cfg, totals, r);
    }
}

} // namespace

StressResult runDegenerate(const StressConfig& cfg) {
    StressResult r;
    r.technique = "area-weighted normals in double with a +Z fallback (computeNormals, repairNormals); "
                  "degenerate triangles dropped from proxies; Embree ignores zero-area triangles; "
                  "the hit refined in double";
    Totals totals;
    const Mesh mesh = degenerateSphere();

    Scene memory;
    memory.source = "stress:degenerate";
    memory.objects.push_back(makeSceneObject("degenerate", mesh));
    survey("in memory", memory, cfg, totals, r);

    const std::string obj = cfg.scratchDir + "/degenerate.obj";
    const bool written = writeObj(mesh, obj).ok() && writeGltf(mesh, cfg.scratchDir, "degenerate");
    if (!written) {
        totals.loadFailures++;
        r.failure("cannot write into " + cfg.scratchDir);
    }
    for (const std::string& path : {obj, cfg.scratchDir + "/degenerate.gltf"}) {
        if (!written) break;
        Result<Scene> scene = loadScene(path);
        if (!scene) {
            totals.loadFailures++;
            r.failure(path + ": " + scene.error());
            continue;
        }
        survey(path.substr(path.rfind('.')), scene.value(), cfg, totals, r);
    }

    r.row("OBJ, glTF and in-memory scenes that failed to load or build (count)", double(totals.loadFailures),
          0.0, 3);
    r.row("normals of loaded meshes and proxies not unit or finite (count)", double(totals.badNormals), 0.0,
          totals.normalsChecked);
    r.row("proxies (OpenMesh, meshoptimizer) that failed (count)", double(totals.proxyFailures), 0.0,
          totals.proxies);
    r.row("spawns that did not place on the closed sphere (count)", double(totals.misses), 0.0, totals.rays);
    r.row("placed: frame error", totals.check.frameError, 1e-6, totals.check.checked);
    r.row("placed: decals with a NaN or Inf (count)", double(totals.check.nonFinite), 0.0,
          totals.check.checked);
    r.row("placed on the render mesh: centre vs the exact double hit / size", totals.centreError, 1e-6,
          totals.centres);
    return r;
}

} // namespace spatter::stress
