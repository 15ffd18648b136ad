#include "CollisionObjects.hpp"

#include "spatter/core/ProxyInstances.hpp"

#include <cmath>
#include <cstring>

namespace spatter {

namespace {

// CollisionObject::meshHash: FNV-1a over 32-bit little-endian words (a word at a time, so hashing a
// mesh costs a fraction of building its BVH).
uint64_t collisionMeshHash(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices,
                           double errorBound) {
    uint64_t h = 0xcbf29ce484222325ULL;
    auto word = [&h](uint32_t w) {
        h ^= w;
        h *= 0x100000001b3ULL;
    };
    auto bits = [](float f) {
        uint32_t u;
        std::memcpy(&u, &f, 4);
        return u;
    };
    word(uint32_t(positions.size()));
    for (const glm::vec3& p : positions) {
        word(bits(p.x));
        word(bits(p.y));
        word(bits(p.z));
    }
    word(uint32_t(indices.size()));
    for (uint32_t i : indices)
        word(i);
    uint64_t e;
    std::memcpy(&e, &errorBound, 8);
    word(uint32_t(e));
    word(uint32_t(e >> 32));
    return h;
}

// Whether a collision mesh is the render mesh itself (a small mesh's own proxy): then no surface is
// drawn under it but its own.
bool sameSurface(const Mesh& collision, const Mesh& render) {
    return &collision == &render ||
           (collision.positions == render.positions && collision.indices == render.indices);
}

// A receiver's collision mesh and its bound h: its proxy's, its collider's (measured here), or its
// render mesh with h = 0.
struct CollisionMesh {
    const Mesh* mesh;
    double h = 0.0;
    DrawnNormals drawn; // which way the drawn surface faces under it, if known already
};

Result<CollisionMesh> collisionMeshOf(const SceneObject& so, const Proxy* proxy,
                                      const WorldSettings& settings) {
    if (proxy) return CollisionMesh{&proxy->mesh, proxy->errorBound, proxy->drawnNormals};
    if (!settings.useColliders || !so.collider) return CollisionMesh{so.mesh.get(), 0.0, DrawnNormals()};
    // Certified, and at most 1% of the render mesh's diagonal above the measured distance.
    ProxySettings measure;
    measure.tolerance = 0.05f;
    measure.toleranceRelative = true;
    measure.marginFraction = 0.2f;
    Result<Proxy> measured = buildProxy(*so.mesh, measure, &*so.collider);
    if (!measured) return fail("collider of object '" + so.name + "': " + measured.error());
    return CollisionMesh{&*so.collider, measured->errorBound, std::move(measured->drawnNormals)};
}

// Fills `od` for receiver `i` of `scene`: its collision mesh and bound, what poses it (dynamic skinned
// or morphed objects) and, for a collision mesh standing in for a static render mesh, which way the
// drawn surface faces under it.
Status setCollisionMesh(const Scene& scene, size_t i, const Proxy* proxy, const WorldSettings& settings,
                        ObjectData& od) {
    const SceneObject& so = scene.objects[i];
    Result<CollisionMesh> c = collisionMeshOf(so, proxy, settings);
    if (!c) return fail(c.error());
    const Mesh& mesh = *c->mesh;
    od.info.inWorld = true;
    od.info.errorBound = c->h;
    od.positions = mesh.positions;
    od.indices.assign(mesh.indices.begin(), mesh.indices.begin() + mesh.triangleCount() * 3);
    od.info.triangles = mesh.triangleCount();
    od.info.localBounds = meshBounds(od.positions, od.indices);
    od.info.meshHash = collisionMeshHash(od.positions, od.indices, c->h);
    if (so.dynamic) {
        Result<std::optional<PosedCollisionMesh>> posable = posedCollisionMesh(scene, i, mesh);
        if (!posable) return fail("object '" + so.name + "': " + posable.error());
        od.posable = std::move(posable).value();
    }
    if (sameSurface(mesh, *so.mesh) || od.posable) return {};
    if (c->drawn.empty()) { // a proxy made elsewhere: found here, as buildProxy finds it
        Result<DrawnNormals> normals = DrawnNormals::build(*so.mesh, mesh, c->h);
        if (!normals) return fail("object '" + so.name + "': " + normals.error());
        c->drawn = std::move(normals).value();
    }
    od.drawnNormals = std::move(c->drawn);
    return {};
}

// Takes the collision mesh, bound and drawn normals that object `from` was given for the same input:
// its description, and its mesh and drawn normals to read (CollisionObject::collisionMeshOf).
void shareCollisionMesh(const ObjectData& from, uint32_t fromIndex, ObjectData& od) {
    od.info.inWorld = true;
    od.info.errorBound = from.info.errorBound;
    od.info.triangles = from.info.triangles;
    od.info.localBounds = from.info.localBounds;
    od.info.meshHash = from.info.meshHash;
    od.info.collisionMeshOf = fromIndex;
}

// Whether an object given `a` and one given `b` (proxies, or nullptr for none) get the same collision
// mesh, bound and drawn normals from the same render mesh and collider.
bool sameCollisionInput(const Proxy* a, const Proxy* b) {
    if (a == b) return true; // one proxy that the objects share, or none
    if (!a || !b) return false;
    return a->mesh.positions == b->mesh.positions && a->mesh.indices == b->mesh.indices &&
           a->errorBound == b->errorBound && a->drawnNormals.packed() == b->drawnNormals.packed();
}

} // namespace

Bounds meshBounds(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices) {
    Bounds b;
    for (uint32_t i : indices)
        b.extend(positions[i]);
    return b;
}

Status checkProxy(const Proxy& proxy, const std::string& name) {
    const std::string what = "proxy of object '" + name + "'";
    if (Status s = validateMesh(proxy.mesh); !s) return fail(what + ": " + s.error());
    if (!std::isfinite(proxy.errorBound) || proxy.errorBound < 0.0)
        return fail(what + " has an error bound that is not finite and >= 0");
    const DrawnNormals& drawn = proxy.drawnNormals;
    const size_t triangles = proxy.mesh.triangleCount();
    if (!drawn.empty() && !drawn.fits(triangles))
        return fail(what + " has " + std::to_string(drawn.packed().size()) + " drawn normals, not " +
                    std::to_string(kPiecesPerTriangle) + " for each of its " + std::to_string(triangles) +
                    " triangles");
    return {};
}

Status fillObjects(const Scene& scene, const std::vector<std::shared_ptr<const Proxy>>& proxies,
                   const WorldSettings& settings, std::vector<ObjectData>& objects) {
    const std::vector<size_t> sources = proxySources(scene);
    auto proxyOf = [&proxies](size_t i) { return proxies.empty() ? nullptr : proxies[i].get(); };
    objects.resize(scene.objects.size());
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& so = scene.objects[i];
        ObjectData& od = objects[i];
        od.info.name = so.name;
        od.info.dynamic = so.dynamic;
        od.info.transform = so.transform;
        od.tracedBy = od.info.collisionMeshOf = uint32_t(i);
        if (!so.receivesDecals) {
            od.info.localBounds = so.mesh->bounds();
            continue;
        }
        const size_t from = sources[i];
        if (from != i && sameCollisionInput(proxyOf(i), proxyOf(from))) {
            shareCollisionMesh(objects[from], uint32_t(from), od);
        } else if (Status s = setCollisionMesh(scene, i, proxyOf(i), settings, od); !s) {
            return s;
        }
    }
    return {};
}

} // namespace spatter
