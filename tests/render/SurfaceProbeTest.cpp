// The drawn surface found in the depth buffer (DecalProjector::findSurface through the renderer): where
// a line meets it and its normal there, nothing where the camera does not see the meet, and decals shot
// through a coarse proxy laid again there as the render mesh would have placed them.

#include "HostedWall.hpp"
#include "RenderTestSupport.hpp"
#include "ShotDecals.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

using namespace spatter;
using namespace spatter::test;

namespace {

constexpr double kTiltDeg = 10.0;

// A floor 4 x 4 with its top face at y = 0 before it is turned kTiltDeg about X, and a post standing
// on it at (0.6, 0.2) seen in front of the floor from the camera below.
Scene tiltedFloor() {
    Scene s;
    s.source = "test:tilted floor";
    const glm::dmat4 tilt = glm::rotate(glm::dmat4(1.0), glm::radians(kTiltDeg), glm::dvec3(1.0, 0.0, 0.0));
    s.objects.push_back(makeSceneObject("floor", makeBox(glm::vec3(2.0f, 0.05f, 2.0f), 4),
                                        tilt * glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, -0.05, 0.0))));
    s.objects.push_back(makeSceneObject("post", makeBox(glm::vec3(0.05f, 0.3f, 0.05f), 1),
                                        tilt * glm::translate(glm::dmat4(1.0), glm::dvec3(0.6, 0.3, 0.2))));
    return s;
}

glm::dvec3 floorNormal() {
    const double a = glm::radians(kTiltDeg);
    return {0.0, std::cos(a), std::sin(a)};
}

// Where the vertical line through (x, z) meets the floor's top plane (through the origin).
glm::dvec3 onFloor(double x, double z) {
    const glm::dvec3 n = floorNormal();
    return {x, -(n.z * z) / n.y, z};
}

SurfaceLine vertical(double x, double z) {
    const glm::dvec3 p = onFloor(x, z);
    return {p + glm::dvec3(0.0, 0.2, 0.0), p - glm::dvec3(0.0, 0.2, 0.0)};
}

Camera aboveTheFloor() {
    return lookAt({0.0, 2.0, 2.5}, {0.0, 0.0, 0.0});
}

// The renderer after one frame of the tilted floor, from aboveTheFloor() at w x h.
Result<Renderer> renderedFloor(int w, int h) {
    Result<Renderer> r = makeRenderer(w, h);
    if (!r) return r;
    if (Status s = r->setScene(tiltedFloor()); !s) return fail(s.error());
    renderView(r.value(), aboveTheFloor(), View::Final);
    return r;
}

std::vector<SurfacePoint> found(Renderer& r, const std::vector<SurfaceLine>& lines) {
    Result<uint64_t> request = r.findSurface(lines);
    EXPECT_TRUE(request.ok()) << request.error();
    if (!request) return {};
    std::optional<std::vector<SurfacePoint>> points = r.surfaceFound(request.value(), true);
    EXPECT_TRUE(points.has_value());
    return points.value_or(std::vector<SurfacePoint>{});
}

// A ball of radius 1 at the origin, drawn finely.
Scene ball() {
    Scene s;
    s.source = "test:ball";
    s.objects.push_back(makeSceneObject("ball", makeSphere(1.0f, 48, 96)));
    return s;
}

// The decals of `shots` placed by a system over `scene` (through `proxies` when given), one paint type
// along the shot, and the results of their spawns.
struct ShotSystem {
    std::optional<DecalSystem> system;
    std::vector<SpawnResult> results;
};
ShotSystem shoot(const Scene& scene, const std::vector<Ray>& shots,
                 const std::vector<std::shared_ptr<const Proxy>>& proxies = {}) {
    ShotSystem out;
    Result<CollisionWorld> world = CollisionWorld::build(scene, proxies);
    EXPECT_TRUE(world.ok()) << world.error();
    if (!world) return out;
    Result<DecalSystem> sys = DecalSystem::create(std::move(world.value()));
    EXPECT_TRUE(sys.ok()) << sys.error();
    if (!sys) return out;
    DecalType t = paintType();
    t.size = glm::vec2(0.25f);
    EXPECT_TRUE(sys->registerType(t).ok());
    sys->spawnBatch(shots, 0, out.results);
    out.system.emplace(std::move(sys).value());
    return out;
}

std::vector<uint8_t> coverageOf(Renderer& r, const Camera& cam, const std::vector<Decal>& decals) {
    r.setDecals(decals);
    return whiteMask(renderView(r, cam, View::Coverage));
}

} // namespace

// Lines from above the floor, and the same lines from beneath it (a shot from behind the surface the
// camera sees), which meet it where they come out in front of it.
TEST(SurfaceProbe, FindsWhereALineMeetsTheDrawnSurfaceAndItsNormalFromEitherSide) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = renderedFloor(320, 240);
    ASSERT_TRUE(r.ok()) << r.error();
    const std::vector<glm::dvec2> at = {{0.0, 0.0}, {-0.7, 0.3}, {0.5, -0.6}, {0.9, 0.8}};
    std::vector<SurfaceLine> lines;
    for (const glm::dvec2& p : at)
        lines.push_back(vertical(p.x, p.y));
    for (const glm::dvec2& p : at)
        lines.push_back({vertical(p.x, p.y).to, vertical(p.x, p.y).from});
    const std::vector<SurfacePoint> points = found(r.value(), lines);
    ASSERT_EQ(points.size(), lines.size());
    for (size_t i = 0; i < lines.size(); ++i) {
        const glm::dvec2& p = at[i % at.size()];
        ASSERT_TRUE(points[i].found) << "line " << i;
        // A pixel here is about 0.01 wide; the point lies on the line, near the plane.
        EXPECT_LT(glm::length(points[i].point - onFloor(p.x, p.y)), 0.01) << "line " << i;
        EXPECT_GT(glm::dot(points[i].normal, floorNormal()), std::cos(glm::radians(1.0))) << "line " << i;
    }
}

TEST(SurfaceProbe, FindsNothingWhereTheCameraDoesNotSeeTheMeet) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = renderedFloor(320, 240);
    ASSERT_TRUE(r.ok()) << r.error();
    // The floor behind the post: the camera's ray through the post's centre, met with the floor's plane.
    const glm::dvec3 eye = aboveTheFloor().eye, post(tiltedFloor().objects[1].transform[3]);
    const glm::dvec3 behindPost =
        eye + (post - eye) * (-glm::dot(floorNormal(), eye) / glm::dot(floorNormal(), post - eye));
    const std::vector<SurfaceLine> lines = {
        vertical(0.0, 0.0), // seen: the control
        {onFloor(0.0, 0.0) + glm::dvec3(0.0, 0.3, 0.0),
         onFloor(0.0, 0.0) + glm::dvec3(0.0, 0.1, 0.0)}, // above it
        vertical(30.0, 0.0),                             // off screen
        {{0.0, 2.2, 3.0}, {0.0, 2.2, 2.8}},              // behind the camera
        {behindPost + glm::dvec3(0.0, 0.05, 0.0), behindPost - glm::dvec3(0.0, 0.05, 0.0)}, // hidden
    };
    const std::vector<SurfacePoint> points = found(r.value(), lines);
    ASSERT_EQ(points.size(), lines.size());
    EXPECT_TRUE(points[0].found);
    for (size_t i = 1; i < lines.size(); ++i)
        EXPECT_FALSE(points[i].found) << "line " << i;
}

TEST(SurfaceProbe, RefusesLinesThatAreNotFiniteTooManyLinesAndFramesBeforeTheFirstRender) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> fresh = makeRenderer(64, 48);
    ASSERT_TRUE(fresh.ok()) << fresh.error();
    const Result<uint64_t> early = fresh->findSurface({vertical(0.0, 0.0)});
    ASSERT_FALSE(early.ok());
    EXPECT_NE(early.error().find("nothing rendered"), std::string::npos) << early.error();

    Result<Renderer> r = renderedFloor(64, 48);
    ASSERT_TRUE(r.ok()) << r.error();
    const double nan = std::nan("");
    const Result<uint64_t> bad = r->findSurface({vertical(0.0, 0.0), {{nan, 0.0, 0.0}, {0.0, 0.0, 0.0}}});
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().find("surface line 1"), std::string::npos) << bad.error();
    const Result<uint64_t> many = r->findSurface(std::vector<SurfaceLine>(kMaxSurfaceLines + 1));
    ASSERT_FALSE(many.ok()); // more work groups than a dispatch takes
    EXPECT_NE(many.error().find("more than the"), std::string::npos) << many.error();
    EXPECT_FALSE(r->surfaceFound(12345, true).has_value()); // never made
    const Result<uint64_t> good = r->findSurface({vertical(0.0, 0.0)});
    ASSERT_TRUE(good.ok()) << good.error();
    ASSERT_TRUE(r->surfaceFound(good.value(), true).has_value());
    EXPECT_FALSE(r->surfaceFound(good.value(), true).has_value()); // taken already
}

TEST(SurfaceProbe, DecalsShotThroughACoarseProxyLaidOnTheDrawnSurfaceCoverWhatTheRenderMeshPlaces) {
    SPATTER_REQUIRE_GL(gl);
    const Scene scene = ball();
    ProxySettings ps;
    ps.tolerance = 0.03f; // of the diagonal: facets tilted several degrees against the ball
    ps.backend = ProxyBackend::MeshOpt;
    Result<Proxy> proxy = buildProxy(*scene.objects[0].mesh, ps);
    ASSERT_TRUE(proxy.ok()) << proxy.error();
    ASSERT_LT(proxy->proxyTriangles, scene.objects[0].mesh->triangleCount() / 4);
    // Shots from the camera's side, within 50 degrees of it, at random points of the ball it sees.
    const Camera cam = lookAt({0.0, 0.6, 3.2}, {0.0, 0.0, 0.0});
    Rng rng(7);
    std::vector<Ray> shots;
    for (int i = 0; i < 40; ++i) {
        const glm::dvec3 aim =
            glm::normalize(glm::dvec3(rng.uniform(-0.6f, 0.6f), rng.uniform(-0.5f, 0.7f), 1.0));
        Ray ray;
        ray.origin = aim * 3.0 + glm::dvec3(rng.uniform(-0.8f, 0.8f), rng.uniform(-0.8f, 0.8f), 0.0);
        ray.direction = aim * 0.999 - ray.origin;
        shots.push_back(ray);
    }
    ShotSystem onRender = shoot(scene, shots),
               throughProxy = shoot(scene, shots, {shareProxy(proxy.value())});
    ASSERT_TRUE(onRender.system && throughProxy.system);
    ASSERT_GT(onRender.system->decals().size(), 30u);

    Result<Renderer> r = makeRenderer(kW, kH);
    ASSERT_TRUE(r.ok()) << r.error();
    ASSERT_TRUE(r->setScene(scene).ok());
    DecalType t = paintType();
    t.size = glm::vec2(0.25f);
    r->setDecalTypes({t});
    const std::vector<uint8_t> reference = coverageOf(r.value(), cam, onRender.system->decals());
    const double before = iou(reference, coverageOf(r.value(), cam, throughProxy.system->decals()));

    // A frame at four times the size finds each decal's axis line in its depth.
    Result<Renderer> probe = makeRenderer(4 * kW, 4 * kH);
    ASSERT_TRUE(probe.ok()) << probe.error();
    ASSERT_TRUE(probe->setScene(scene).ok());
    renderView(probe.value(), cam, View::Final);
    std::vector<SurfaceLine> lines;
    std::vector<DecalHandle> handles;
    for (const SpawnResult& s : throughProxy.results)
        if (s.placed()) {
            const std::optional<DecalAxisLine> line = throughProxy.system->axisLine(s.handle);
            ASSERT_TRUE(line.has_value());
            lines.push_back({line->from, line->to, 0});
            handles.push_back(s.handle);
        }
    const std::vector<SurfacePoint> points = found(probe.value(), lines);
    ASSERT_EQ(points.size(), lines.size());
    size_t laid = 0;
    for (size_t i = 0; i < points.size(); ++i)
        if (points[i].found) {
            const Result<DrawnSurfaceLaying> s =
                throughProxy.system->layOnDrawnSurface(handles[i], points[i].point, points[i].normal);
            EXPECT_TRUE(s.ok()) << s.error();
            laid += s.ok() && s.value() == DrawnSurfaceLaying::Laid ? 1 : 0;
        }
    EXPECT_GT(laid, 3 * lines.size() / 4);
    const double after = iou(reference, coverageOf(r.value(), cam, throughProxy.system->decals()));
    EXPECT_GT(after, before + 0.02) << "before " << before;
    EXPECT_GT(after, 0.97) << "before " << before;
}

TEST(SurfaceProbe, FindsTheSurfaceInAForeignHostsDepthAndKeepsToTheLinesObjectUnlessAnyWillDo) {
    SPATTER_REQUIRE_GL(gl);
    // Standard Z in GL's default clip depth, and an object ID target: the wall (ID 0) at z = 0 and
    // the crate (ID 7) in front of it, its front face at z = 0.8 around (0.8, 0.8).
    std::optional<HostedWall> h = HostedWall::make();
    ASSERT_TRUE(h);
    const HostFrame frame = h->host.frame(h->wall.camera, true);
    const std::vector<SurfaceLine> lines = {
        {{-0.6, 1.0, 0.3}, {-0.6, 1.0, -0.3}, 0},    // the wall
        {{0.8, 0.8, 1.1}, {0.8, 0.8, 0.6}, 7},       // the crate
        {{0.8, 0.8, 1.1}, {0.8, 0.8, 0.6}, 0},       // the crate, asked for the wall's ID
        {{0.8, 0.8, 0.3}, {0.8, 0.8, -0.3}, 0},      // the wall behind the crate: hidden
        {{0.8, 0.8, 1.1}, {0.8, 0.8, 0.6}, 0, true}, // the crate, for a shot that met no proxy: any ID
    };
    Result<uint64_t> request = h->projector.findSurface(frame, lines);
    ASSERT_TRUE(request.ok()) << request.error();
    const std::optional<std::vector<SurfacePoint>> points = h->projector.surfaceFound(request.value(), true);
    ASSERT_TRUE(points.has_value());
    ASSERT_EQ(points->size(), lines.size());
    ASSERT_TRUE((*points)[0].found);
    EXPECT_LT(glm::length((*points)[0].point - glm::dvec3(-0.6, 1.0, 0.0)), 0.01);
    EXPECT_GT((*points)[0].normal.z, 0.9999);
    ASSERT_TRUE((*points)[1].found);
    EXPECT_NEAR((*points)[1].point.z, 0.8, 0.01);
    EXPECT_GT((*points)[1].normal.z, 0.9999);
    EXPECT_FALSE((*points)[2].found);
    EXPECT_FALSE((*points)[3].found);
    ASSERT_TRUE((*points)[4].found);
    EXPECT_NEAR((*points)[4].point.z, 0.8, 0.01);
    EXPECT_EQ((*points)[4].objectId, 7) << "the crate's ID, read where the line met it";
    EXPECT_EQ((*points)[0].objectId, 0) << "the wall's";

    // A face normal texture in the host's encoding (world, n * 0.5 + 0.5) holding +Z everywhere: the
    // wall's and the crate's front faces.
    GLuint faces = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &faces);
    glTextureStorage2D(faces, 1, GL_RGB10_A2, kWallWidth, kWallHeight);
    const float up[4] = {0.5f, 0.5f, 1.0f, 1.0f};
    glClearTexImage(faces, 0, GL_RGBA, GL_FLOAT, up);
    HostFrame withFaces = frame;
    withFaces.faceNormalTexture = faces;
    Result<uint64_t> faced = h->projector.findSurface(withFaces, {lines[0], lines[1]});
    ASSERT_TRUE(faced.ok()) << faced.error();
    const std::optional<std::vector<SurfacePoint>> facePoints =
        h->projector.surfaceFound(faced.value(), true);
    ASSERT_TRUE(facePoints.has_value() && facePoints->size() == 2);
    for (const SurfacePoint& p : *facePoints) {
        ASSERT_TRUE(p.found);
        EXPECT_GT(p.normal.z, 0.99999);
    }
    EXPECT_LT(glm::length((*facePoints)[0].point - glm::dvec3(-0.6, 1.0, 0.0)), 1e-4);
    EXPECT_NEAR((*facePoints)[1].point.z, 0.8, 1e-4);
    glDeleteTextures(1, &faces);

    HostFrame noDepth = frame;
    noDepth.depth.texture = 0;
    const Result<uint64_t> refused = h->projector.findSurface(noDepth, lines);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().find("HostFrame.depth.texture"), std::string::npos) << refused.error();
}

TEST(SurfaceProbe, EmptyDegenerateAndAbsurdLinesFindNothingAndNeverBreakTheSearch) {
    SPATTER_REQUIRE_GL(gl);
    Result<Renderer> r = renderedFloor(64, 48);
    ASSERT_TRUE(r.ok()) << r.error();
    EXPECT_TRUE(found(r.value(), {}).empty());
    const glm::dvec3 p = onFloor(0.0, 0.0);
    const std::vector<SurfaceLine> lines = {
        {p, p},                                                         // a point
        {{1e30, 1e30, 1e30}, {-1e30, -1e30, -1e30}},                    // past float's range in view space
        {{0.0, -1e6, 0.0}, {0.0, -2e6, 0.0}},                           // far under the floor
        {p + glm::dvec3(0.0, 0.2, 0.0), p - glm::dvec3(0.0, 0.2, 0.0)}, // the control
    };
    const std::vector<SurfacePoint> points = found(r.value(), lines);
    ASSERT_EQ(points.size(), lines.size());
    for (size_t i = 0; i < points.size(); ++i)
        if (points[i].found) {
            EXPECT_TRUE(std::isfinite(points[i].point.x) && std::isfinite(points[i].point.y) &&
                        std::isfinite(points[i].point.z))
                << "line " << i;
            EXPECT_NEAR(glm::length(points[i].normal), 1.0, 1e-6) << "line " << i;
        }
    EXPECT_FALSE(points[0].found);
    EXPECT_FALSE(points[1].found);
    EXPECT_FALSE(points[2].found);
    EXPECT_TRUE(points[3].found);
}

// With the renderer's face normal target, the normal found is the normal of the triangle the line
// meets (what placement takes on a render mesh), and the point lies on that triangle, but where the
// meet lies within a pixel of the triangle's edge; from the depth alone, a faceted ball's pixels give
// normals bent across its edges.
TEST(SurfaceProbe, AFaceNormalTargetGivesTheNormalOfTheTriangleTheLineMeets) {
    SPATTER_REQUIRE_GL(gl);
    Scene scene;
    scene.source = "test:faceted ball";
    scene.objects.push_back(makeSceneObject("ball", makeSphere(1.0f, 8, 16)));
    Result<CollisionWorld> world = CollisionWorld::build(scene);
    ASSERT_TRUE(world.ok()) << world.error();
    const Camera cam = lookAt({0.0, 1.0, 4.0}, {0.0, 0.0, 0.0});
    std::vector<SurfaceLine> lines;
    std::vector<Hit> hits;
    Rng rng(11);
    while (lines.size() < 200) {
        Ray r;
        r.origin = cam.eye + glm::dvec3(rng.uniform(-0.8f, 0.8f), rng.uniform(-0.8f, 0.8f), 0.0);
        r.direction = glm::dvec3(rng.uniform(-0.5f, 0.5f), rng.uniform(-0.5f, 0.5f), 0.0) - r.origin;
        const std::optional<Hit> h = world->intersect(r);
        if (!h) continue;
        const glm::dvec3 along = 0.2 * glm::normalize(r.direction);
        lines.push_back({h->position - along, h->position + along});
        hits.push_back(*h);
    }
    size_t exact[2] = {0, 0}, seen[2] = {0, 0};
    for (bool faces : {true, false}) {
        RendererSettings settings;
        settings.faceNormals = faces;
        Result<Renderer> r = makeRenderer(4 * kW, 4 * kH, settings);
        ASSERT_TRUE(r.ok()) << r.error();
        ASSERT_TRUE(r->setScene(scene).ok());
        renderView(r.value(), cam, View::Final);
        const std::vector<SurfacePoint> points = found(r.value(), lines);
        ASSERT_EQ(points.size(), lines.size());
        for (size_t i = 0; i < points.size(); ++i) {
            if (!points[i].found) continue;
            ++seen[faces];
            const double deg =
                glm::degrees(std::acos(std::min(1.0, glm::dot(points[i].normal, hits[i].normal))));
            if (deg < 0.1 && glm::length(points[i].point - hits[i].position) < 1e-3) ++exact[faces];
        }
        EXPECT_GT(seen[faces], 190u);
    }
    EXPECT_GT(exact[1], 9 * seen[1] / 10) << "the triangle's own normal and plane";
    EXPECT_LT(exact[0] + 20, exact[1]) << "the depth's normal bends across the ball's edges";
}

namespace {

// A roof 2 wide along X from z = -1 to 1: two slopes meeting at x's axis lifted by `rise` (a ridge,
// a convex edge) or lowered by it (a valley, a concave one).
Scene roof(float rise) {
    Mesh m;
    m.positions = {{-1.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 1.0f},   {1.0f, rise, 0.0f},
                   {-1.0f, rise, 0.0f}, {-1.0f, 0.0f, -1.0f}, {1.0f, 0.0f, -1.0f}};
    m.indices = {0, 1, 2, 0, 2, 3, 3, 2, 5, 3, 5, 4};
    computeNormals(m);
    Scene s;
    s.source = "test:roof";
    s.objects.push_back(makeSceneObject("roof", std::move(m)));
    return s;
}

} // namespace

// A pixel shows one triangle; a line that meets the other triangle within a pixel of their edge takes
// that triangle's normal and plane, across a ridge and across a valley (where the line enters the
// surface at the later and at the earlier of the two planes' crossings).
TEST(SurfaceProbe, AMeetWithinAPixelOfAnEdgeTakesTheTriangleTheLineMeets) {
    SPATTER_REQUIRE_GL(gl);
    for (float rise : {0.5f, -0.5f}) {
        const Scene scene = roof(rise);
        Result<CollisionWorld> world = CollisionWorld::build(scene);
        ASSERT_TRUE(world.ok()) << world.error();
        RendererSettings settings;
        settings.faceNormals = true;
        Result<Renderer> r = makeRenderer(320, 240, settings);
        ASSERT_TRUE(r.ok()) << r.error();
        ASSERT_TRUE(r->setScene(scene).ok());
        renderView(r.value(), lookAt({0.0, 3.0, 1.0}, {0.0, 0.0, 0.0}), View::Final); // both slopes in view
        // Vertical lines through points within about two pixels (0.01 each here) of the edge.
        std::vector<SurfaceLine> lines;
        std::vector<Hit> hits;
        Rng rng(5);
        while (lines.size() < 200) {
            const double x = rng.uniform(-0.5f, 0.5f), z = rng.uniform(-0.02f, 0.02f);
            const glm::dvec3 p(x, double(rise) * (1.0 - std::abs(z)), z), up(0.0, 0.2, 0.0);
            const std::optional<Hit> h = world->intersect(Ray{p + up, -2.0 * up, 0.0, 1.0});
            ASSERT_TRUE(h.has_value());
            lines.push_back({p + up, p - up});
            hits.push_back(*h);
        }
        const std::vector<SurfacePoint> points = found(r.value(), lines);
        ASSERT_EQ(points.size(), lines.size());
        size_t exact = 0;
        for (size_t i = 0; i < points.size(); ++i) {
            ASSERT_TRUE(points[i].found) << "rise " << rise << ", line " << i;
            const double deg =
                glm::degrees(std::acos(std::min(1.0, glm::dot(points[i].normal, hits[i].normal))));
            if (deg < 0.5 && glm::length(points[i].point - hits[i].position) < 1e-3) ++exact;
        }
        EXPECT_GE(exact, 196u) << "rise " << rise;
    }
}
