// Decals shot through a proxy face the drawn surface: the world keeps, for each part of a collision
// triangle, the normal of the render triangle nearest it, and a decal shot along it is laid on that
// normal with a box deep enough to hold the point where the shot meets the drawn surface.

#include "PlacementTestUtil.hpp"

#include "spatter/core/TrianglePieces.hpp"

#include <cmath>

using namespace spatter;
using namespace spatter::test;

namespace {

// A drawn floor y = 0 under `transform`, traced through the proxy `proxy` with bound `h`.
DecalSystem floorThroughProxy(Mesh proxy, double h, const glm::dmat4& transform,
                              const DecalSettings& settings = {}) {
    Scene scene;
    scene.source = "test:floor under a proxy";
    scene.objects.push_back(makeSceneObject("floor", makeGrid({-2.0f, 2.0f}, {-2.0f, 2.0f}), transform));
    std::vector<std::shared_ptr<const Proxy>> proxies;
    if (!proxy.positions.empty()) proxies.push_back(shareProxy(makeProxy(std::move(proxy), h)));
    Result<DecalSystem> s = DecalSystem::create(buildWorld(scene, proxies), settings);
    EXPECT_TRUE(s.ok()) << s.error();
    return std::move(s).value();
}

// The shot at the floor's object-space point `target` from `degrees` off its normal, turned about it
// by `azimuth`, in the world of `toWorld`.
Ray shotAt(const glm::dmat4& toWorld, const glm::dvec3& target, double degrees, double azimuth) {
    const glm::dvec3 worldBack =
        glm::normalize(glm::transpose(glm::inverse(glm::dmat3(toWorld))) * shotFrom(degrees, azimuth));
    const glm::dvec3 at(toWorld * glm::dvec4(target, 1.0));
    return ray(at + 3.0 * worldBack, -worldBack);
}

// Where `shot` (world space) meets the floor y = 0 of object space `toWorld`, in object space.
glm::dvec3 floorMeet(const Ray& shot, const glm::dmat4& toWorld) {
    const glm::dmat4 toObject = glm::inverse(toWorld);
    const glm::dvec3 o(toObject * glm::dvec4(shot.origin, 1.0)),
        d(toObject * glm::dvec4(shot.direction, 0.0));
    return o - d * (o.y / d.y);
}

} // namespace

// A flat proxy over a drawn roof: each part of a proxy triangle keeps the normal of the roof's side
// under it; a world traced on the render mesh itself keeps none.
TEST(DrawnFacing, TheWorldKeepsTheDrawnSurfacesNormalUnderEachPartOfAProxyTriangle) {
    const double slope = 30.0 * kPi / 180.0;
    Mesh roof = makeGrid({-2.0f, -1.0f, 0.0f, 1.0f, 2.0f}, {-2.0f, 2.0f});
    for (glm::vec3& p : roof.positions)
        p.y = std::fabs(p.x) * float(std::tan(slope));
    Scene scene;
    scene.source = "test:roof";
    scene.objects.push_back(makeSceneObject("roof", roof));
    std::vector<std::shared_ptr<const Proxy>> proxies;
    proxies.push_back(shareProxy(makeProxy(tiltedPlane(0.0, 0.6f), 0.6)));
    const CollisionWorld world = buildWorld(scene, proxies), drawn = buildWorld(scene);
    for (double x : {-1.7, -1.4, 1.4, 1.7})
        for (double z : {-1.5, 0.0, 1.5}) {
            const std::optional<Hit> hit = world.intersect(ray({x, 3.0, z}, {0.0, -1.0, 0.0}));
            ASSERT_TRUE(hit.has_value());
            const std::optional<glm::dvec3> n =
                world.drawnNormalAt(hit->object, hit->primitive, hit->localPosition);
            ASSERT_TRUE(n.has_value()) << x << ", " << z;
            const glm::dvec3 side(x < 0.0 ? std::sin(slope) : -std::sin(slope), std::cos(slope), 0.0);
            EXPECT_LT(glm::length(*n - side), 1e-4) << x << ", " << z;
            const std::optional<Hit> own = drawn.intersect(ray({x, 3.0, z}, {0.0, -1.0, 0.0}));
            ASSERT_TRUE(own.has_value());
            EXPECT_FALSE(drawn.drawnNormalAt(own->object, own->primitive, own->localPosition).has_value());
        }
    EXPECT_FALSE(world.drawnNormalAt(0, 2, glm::dvec3(0.0)).has_value()) << "primitive out of range";
    EXPECT_FALSE(world.drawnNormalAt(1, 0, glm::dvec3(0.0)).has_value()) << "object out of range";
}

// A proxy that comes with its table (buildProxy makes one, the cache keeps it) is taken as it is: the
// world searches no render mesh for it. One that does not fit its triangles is refused, named.
TEST(DrawnFacing, TheWorldTakesTheTableAProxyCarries) {
    Scene scene;
    scene.source = "test:floor";
    scene.objects.push_back(makeSceneObject("floor", makeGrid({-2.0f, 2.0f}, {-2.0f, 2.0f})));
    Proxy proxy = makeProxy(tiltedPlane(0.0, 0.1f), 0.1);
    const DrawnNormals::Packed carried = {int16_t(0.6 * 32767), int16_t(0.8 * 32767), 0};
    proxy.drawnNormals = DrawnNormals(
        std::vector<DrawnNormals::Packed>(proxy.mesh.triangleCount() * kPiecesPerTriangle, carried));
    std::vector<std::shared_ptr<const Proxy>> proxies{shareProxy(proxy)};
    const CollisionWorld world = buildWorld(scene, proxies);
    const std::optional<Hit> hit = world.intersect(ray({0.3, 3.0, -0.4}, {0.0, -1.0, 0.0}));
    ASSERT_TRUE(hit.has_value());
    const std::optional<glm::dvec3> n = world.drawnNormalAt(hit->object, hit->primitive, hit->localPosition);
    ASSERT_TRUE(n.has_value());
    EXPECT_LT(glm::length(*n - glm::dvec3(0.6, 0.8, 0.0)), 1e-4) << "the carried table, not the floor's up";

    std::vector<DrawnNormals::Packed> fewer = proxy.drawnNormals.packed();
    fewer.pop_back();
    proxy.drawnNormals = DrawnNormals(fewer);
    proxies[0] = shareProxy(proxy);
    Result<CollisionWorld> refused = CollisionWorld::build(scene, proxies);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().find(
                  "proxy of object 'floor' has 17 drawn normals, not 9 for each of its 2 triangles"),
              std::string::npos)
        << refused.error();
}

// Through a proxy tilted 6 degrees against the drawn floor of an object turned and scaled unevenly, a
// shot's decal has the frame (its random rotation included) and slant that the same shot's decal on
// the floor has, and the floor's meet with the shot on its axis, inside its box. A type projected
// along the normal keeps the facet's frame.
TEST(DrawnFacing, AShotThroughATiltedProxyIsLaidFacingTheDrawnSurface) {
    for (double degrees : {10.0, 35.0, 60.0})
        for (double azimuth : {0.3, 2.0, 4.1}) {
            const std::string where =
                std::to_string(degrees) + " degrees, azimuth " + std::to_string(azimuth);
            DecalSystem throughProxy = floorThroughProxy(tiltedPlane(6.0), 0.5, turnedTransform());
            DecalSystem onFloor = floorThroughProxy(Mesh{}, 0.0, turnedTransform());
            const Ray shot = shotAt(turnedTransform(), {0.2, 0.0, 0.3}, degrees, azimuth);
            const SpawnResult a = throughProxy.spawn(shot, addType(throughProxy, plainType()));
            const SpawnResult b = onFloor.spawn(shot, addType(onFloor, plainType()));
            ASSERT_TRUE(a.placed() && b.placed()) << a.reason << b.reason;
            const Decal d = *throughProxy.get(a.handle), drawn = *onFloor.get(b.handle);
            const Frame f = d.frame(), g = drawn.frame();
            EXPECT_LT(glm::length(f.normal - g.normal), 1e-4f) << where;
            EXPECT_LT(glm::length(f.tangent - g.tangent), 2e-3f) << where;
            EXPECT_LT(glm::length(unpackSlant(d.slant) - unpackSlant(drawn.slant)), 2e-3f) << where;
            const glm::dvec3 meet = inBox(d, floorMeet(shot, turnedTransform()));
            EXPECT_LT(std::max(std::fabs(meet.x), std::fabs(meet.y)), 1e-3) << where;
            EXPECT_LE(std::fabs(meet.z), 1.0) << where;

            DecalType normal = plainType("normal");
            normal.projection = Projection::Normal;
            const SpawnResult c = throughProxy.spawn(shot, addType(throughProxy, normal));
            ASSERT_TRUE(c.placed()) << c.reason;
            EXPECT_GT(glm::length(throughProxy.get(c.handle)->frame().normal - g.normal), 0.05f) << where;
        }
}

// With no margin, the box is as deep as the bound asks: through a proxy tilted 20 degrees against the
// floor, the shot meets the floor inside every decal's box, on its axis, also where the floor faces
// the shot more squarely than the proxy does and the box is deeper than h; most decals face the floor
// (the others, where facing it would take a box more than twice h deep, face the proxy).
TEST(DrawnFacing, TheBoxHoldsWhereTheShotMeetsTheDrawnSurface) {
    DecalSettings settings;
    settings.depthMargin = 0.0f;
    const double h = 0.75; // the plane y = z tan 20 lies within 0.73 of the floor over [-2, 2]^2
    DecalSystem s = floorThroughProxy(tiltedPlane(20.0), h, glm::dmat4(1.0), settings);
    DecalType shallow = plainType("shallow", glm::vec2(0.5f));
    shallow.halfDepth = 0.001f;
    const uint16_t t = addType(s, shallow);
    int placed = 0, facing = 0, deeper = 0;
    for (double degrees : {5.0, 25.0, 45.0, 60.0})
        for (double azimuth = 0.0; azimuth < 6.2; azimuth += 0.5)
            for (double z : {-1.2, 0.0, 1.2}) {
                const Ray shot = shotAt(glm::dmat4(1.0), {0.1, 0.0, z}, degrees, azimuth);
                const SpawnResult r = s.spawn(shot, t);
                if (!r.placed()) continue;
                const Decal d = *s.get(r.handle);
                const glm::dvec3 meet = inBox(d, floorMeet(shot, glm::dmat4(1.0)));
                const std::string where = std::to_string(degrees) + " degrees, azimuth " +
                                          std::to_string(azimuth) + ", z " + std::to_string(z);
                // On the axis to the precision of the half-float slopes over a box deeper than wide.
                EXPECT_LT(std::max(std::fabs(meet.x), std::fabs(meet.y)), 1e-2) << where;
                EXPECT_LE(std::fabs(meet.z), 1.0 + 1e-6) << where;
                ++placed;
                if (glm::length(d.frame().normal - glm::vec3(0.0f, 1.0f, 0.0f)) < 1e-4f) ++facing;
                if (d.halfDepth > 1.01 * h) ++deeper;
            }
    EXPECT_GT(facing, placed * 3 / 4) << "most decals face the floor";
    EXPECT_GT(deeper, 0) << "no shot met the floor more squarely than the proxy";
}
