#include "ShotDecals.hpp"

#include "spatter/core/GalleryScene.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <cmath>

namespace spatter::test {

Placed shootFromCamera(const Scene& scene, const Camera& cam, const std::vector<DecalType>& types, int shots,
                       uint64_t seed, const std::vector<std::shared_ptr<const Proxy>>& proxies) {
    constexpr int kWidth = 160, kHeight = 120;
    Placed out;
    WorldSettings ws;
    ws.useColliders = false;
    Result<CollisionWorld> world = CollisionWorld::build(scene, proxies, ws);
    EXPECT_TRUE(world.ok()) << world.error();
    if (!world) return out;
    Result<DecalSystem> sys = DecalSystem::create(std::move(world.value()));
    EXPECT_TRUE(sys.ok()) << sys.error();
    if (!sys) return out;
    std::vector<uint16_t> typeIndex;
    for (const DecalType& t : types) {
        Result<uint16_t> idx = sys->registerType(t);
        EXPECT_TRUE(idx.ok()) << idx.error();
        if (!idx) return out;
        typeIndex.push_back(idx.value());
    }
    Rng rng(seed);
    for (int s = 0; s < shots; ++s) {
        const int i = int(rng.below(kWidth)), j = int(rng.below(kHeight));
        Ray ray;
        ray.origin = cam.eye;
        ray.direction = pixelDirection(cam, kWidth, kHeight, i, j);
        if (sys->spawn(ray, typeIndex[size_t(s) % typeIndex.size()]).placed()) ++out.placed;
    }
    out.inputs.decals = sys->decals();
    out.inputs.types = types;
    out.inputs.objectIds = sys->objectIds();
    return out;
}

DecalType makeType(const char* name, glm::vec2 size, DecalTexture tex, bool wrap, float halfDepth) {
    DecalType t;
    t.halfDepth = halfDepth; // deep boxes reach curved and hidden surfaces: the angle test must cut them
    t.name = name;
    t.size = size;
    t.texture = int(tex);
    t.wrapAround = wrap;
    return t;
}

GalleryShots galleryShots() {
    GallerySettings gs;
    gs.detail = 1;
    GalleryShots g;
    g.scene = makeGalleryScene(gs);
    g.camera.eye = {1.5, 2.2, 4.5};
    g.camera.target = {-0.5, 1.0, -3.0};
    const std::vector<DecalType> types = {
        makeType("hole", {0.45f, 0.45f}, DecalTexture::BulletHole),
        makeType("blood", {0.9f, 0.7f}, DecalTexture::Blood, true),
        makeType("scorch", {1.2f, 1.2f}, DecalTexture::Scorch, false, 0.8f)};
    g.placed = shootFromCamera(g.scene, g.camera, types, 60, 7);
    return g;
}

Mesh ridgeMesh(double fallDegrees) {
    const float a = float(fallDegrees * kPi / 180.0), drop = 0.5f * std::tan(a);
    const glm::vec3 flat(0.0f, 0.0f, 1.0f), falling(-std::sin(a), 0.0f, std::cos(a));
    Mesh m;
    m.positions = {{0.0f, -0.3f, 0.0f},   {0.5f, -0.3f, 0.0f}, {0.5f, 0.3f, 0.0f}, {0.0f, 0.3f, 0.0f},
                   {-0.5f, -0.3f, -drop}, {0.0f, -0.3f, 0.0f}, {0.0f, 0.3f, 0.0f}, {-0.5f, 0.3f, -drop}};
    m.normals = {flat, flat, flat, flat, falling, falling, falling, falling};
    m.uvs = {{0.52f, 0.2f}, {0.98f, 0.2f}, {0.98f, 0.8f}, {0.52f, 0.8f},
             {0.02f, 0.2f}, {0.48f, 0.2f}, {0.48f, 0.8f}, {0.02f, 0.8f}};
    m.indices = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
    computeTangents(m);
    return m;
}

DecalType paintType() {
    DecalType t;
    t.name = "paint";
    t.texture = int(DecalTexture::Paint);
    t.size = glm::vec2(0.3f);
    t.randomRotation = false;
    return t;
}

CoverageInputs shotFromTheRight(const Scene& scene, const DecalType& t, const glm::dvec3& aim,
                                double degrees) {
    CoverageInputs in;
    Result<DecalSystem> s = DecalSystem::create(scene);
    EXPECT_TRUE(s.ok()) << s.error();
    if (!s) return in;
    const uint16_t type = s->registerType(t).value();
    const double a = degrees * kPi / 180.0;
    const glm::dvec3 back(std::sin(a), 0.0, std::cos(a));
    Ray ray;
    ray.origin = aim + 2.0 * back;
    ray.direction = -back;
    const SpawnResult placed = s->spawn(ray, type);
    EXPECT_TRUE(placed.placed()) << placed.reason;
    in.decals = s->decals();
    in.types = {t};
    in.objectIds = s->objectIds();
    return in;
}

RidgeShot ridgeShot(double fallDegrees, double shotDegrees) {
    Scene scene;
    scene.source = "test:ridge";
    scene.objects.push_back(makeSceneObject("ridge", ridgeMesh(fallDegrees)));
    CoverageInputs in = shotFromTheRight(scene, paintType(), glm::dvec3(0.04, 0.0, 0.0), shotDegrees);
    return RidgeShot{std::move(scene), std::move(in)};
}

} // namespace spatter::test
