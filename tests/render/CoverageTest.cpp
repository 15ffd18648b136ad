// Decal coverage of the GPU decal pass against the CPU reference (rays through every pixel centre
// against the render meshes, the same inclusion rule in double precision), in spatter's renderer and
// in a foreign host of the projector (ForeignHost: standard Z, 24-bit depth, RGB10A2 world normals),
// deferred and forward.

#include "ForeignHost.hpp"
#include "RenderTestSupport.hpp"
#include "ShotDecals.hpp"

#include "TestData.hpp"

#include "spatter/core/GalleryScene.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/Random.hpp"
#include "spatter/core/SceneLoader.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace spatter;

namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 120;

std::vector<uint8_t> renderCoverage(const Scene& scene, const test::CoverageInputs& in, const Camera& cam) {
    Result<Renderer> r = test::makeRenderer(kWidth, kHeight);
    EXPECT_TRUE(r.ok()) << r.error();
    if (!r) return {};
    EXPECT_TRUE(r->setScene(scene).ok());
    EXPECT_TRUE(r->setObjectIds(in.objectIds).ok());
    r->setDecalTypes(in.types);
    r->setDecals(in.decals);
    Result<FrameStats> st = r->render(cam, View::Coverage);
    EXPECT_TRUE(st.ok()) << st.error();
    EXPECT_EQ(st->decalsInvalid, 0u);
    Result<Image> im = r->readback();
    EXPECT_TRUE(im.ok());
    return im ? test::whiteMask(im.value()) : std::vector<uint8_t>{};
}

// The coverage of the same decals in the foreign host: projected into its frame (deferred), or applied
// in its fragment shader through the forward path's tiles (forward).
std::vector<uint8_t> foreignCoverage(const Scene& scene, const test::CoverageInputs& in, const Camera& cam,
                                     bool forward) {
    Result<test::ForeignHost> host = test::ForeignHost::create(kWidth, kHeight);
    Result<DecalProjector> projector = DecalProjector::create();
    EXPECT_TRUE(host.ok() && projector.ok());
    if (!host || !projector) return {};
    std::vector<glm::dmat4> transforms;
    for (const SceneObject& o : scene.objects)
        transforms.push_back(o.transform);
    std::vector<uint8_t> ids = in.objectIds;
    ids.resize(transforms.size(), 0);
    host->setScene(scene);
    EXPECT_TRUE(projector->setObjects(transforms, ids).ok());
    projector->setDecalTypes(in.types);
    projector->setDecals(in.decals);
    if (forward) {
        Result<ProjectorStats> st = host->drawForward(transforms, ids, cam, projector.value());
        EXPECT_TRUE(st.ok()) << st.error();
        return test::whiteMask(host->read(host->coverageTexture()));
    }
    host->draw(transforms, ids, cam);
    host->clearCoverage();
    ProjectorDraw draw;
    draw.coverageTexture = host->coverageTexture();
    Result<ProjectorStats> st = projector->draw(host->frame(cam, scene.dynamicObjectCount() > 0), draw);
    EXPECT_TRUE(st.ok()) << st.error();
    return test::whiteMask(host->read(host->coverageTexture()));
}

// Compares one coverage mask with the reference.
void expectMaskMatches(const std::string& name, const std::vector<uint8_t>& gpu,
                       const std::vector<uint8_t>& cpu, size_t decals, double minIou) {
    test::dumpMask(name, gpu, kWidth, kHeight);
    const double v = test::iou(gpu, cpu);
    std::printf("%s: IoU %.4f (gpu %zu px, cpu %zu px, %zu decals)\n", name.c_str(), v, test::countSet(gpu),
                test::countSet(cpu), decals);
    EXPECT_GE(v, minIou) << name << ": gpu " << test::countSet(gpu) << " px, cpu " << test::countSet(cpu)
                         << " px";
}

// Renders the coverage view in spatter's renderer and in the foreign host and compares each with the
// reference.
void expectCoverageMatches(const std::string& name, const Scene& scene, const test::Placed& placed,
                           const Camera& cam, double minIou) {
    const std::vector<uint8_t> cpu = test::referenceCoverage(scene, placed.inputs, cam, kWidth, kHeight);
    test::dumpMask(name + "-cpu", cpu, kWidth, kHeight);
    // Enough covered pixels for the ratio to mean something.
    EXPECT_GT(test::countSet(cpu), size_t(kWidth * kHeight) / 20) << name;
    const size_t decals = placed.inputs.decals.size();
    expectMaskMatches(name + "-gpu", renderCoverage(scene, placed.inputs, cam), cpu, decals, minIou);
    // A host of the projector is held to 0.99 (the projector's own contract).
    expectMaskMatches(name + "-foreign", foreignCoverage(scene, placed.inputs, cam, false), cpu, decals,
                      std::max(minIou, 0.99));
    expectMaskMatches(name + "-forward", foreignCoverage(scene, placed.inputs, cam, true), cpu, decals,
                      std::max(minIou, 0.99));
}

Camera cameraFor(const Scene& scene, const glm::dvec3& direction) {
    const DBounds b = scene.worldBounds();
    Camera cam;
    cam.target = b.center();
    cam.eye = b.center() + glm::normalize(direction) * (b.diagonal() * 0.8);
    cam.nearPlane = b.diagonal() * 1e-3;
    return cam;
}

} // namespace

TEST(Coverage, MatchesCpuReferenceOnTheGallery) {
    SPATTER_REQUIRE_GL(gl);
    const test::GalleryShots g = test::galleryShots();
    ASSERT_GT(g.placed.placed, 40u);
    expectCoverageMatches("gallery", g.scene, g.placed, g.camera, 0.97);
}

TEST(Coverage, MatchesCpuReferenceOnSharedMeshes) {
    SPATTER_REQUIRE_GL(gl);
    for (const char* file : {"meshes/fandisk.obj", "meshes/rocker-arm.obj", "meshes/stanford-bunny.obj"}) {
        SPATTER_REQUIRE_SHARED(path, file);
        Result<Scene> scene = loadScene(path);
        ASSERT_TRUE(scene.ok()) << scene.error();
        const Camera cam = cameraFor(scene.value(), {0.6, 0.5, 1.0});
        const float s = float(scene->worldBounds().diagonal()) * 0.12f;
        const std::vector<DecalType> types = {
            test::makeType("a", {s, s}, DecalTexture::Paint),
            test::makeType("b", {1.5f * s, s}, DecalTexture::Blood, true),
            test::makeType("c", {s, s}, DecalTexture::Scorch, false, 0.7f * s)};
        const test::Placed placed = test::shootFromCamera(scene.value(), cam, types, 60, 11);
        ASSERT_GT(placed.placed, 10u) << file;
        expectCoverageMatches(std::string(file).substr(7), scene.value(), placed, cam, 0.97);
    }
}

TEST(Coverage, MatchesCpuReferenceOnDamagedHelmet) {
    SPATTER_REQUIRE_GL(gl);
    SPATTER_REQUIRE_SHARED(path, "gltf/DamagedHelmet/DamagedHelmet.glb");
    Result<Scene> scene = loadScene(path);
    ASSERT_TRUE(scene.ok()) << scene.error();
    const Camera cam = cameraFor(scene.value(), {0.4, 0.3, 1.0});
    const float s = float(scene->worldBounds().diagonal()) * 0.1f;
    const std::vector<DecalType> types = {test::makeType("a", {s, s}, DecalTexture::BulletHole),
                                          test::makeType("b", {1.5f * s, s}, DecalTexture::Blood, true),
                                          test::makeType("c", {s, s}, DecalTexture::Scorch, false, 0.5f * s)};
    const test::Placed placed = test::shootFromCamera(scene.value(), cam, types, 60, 13);
    ASSERT_GT(placed.placed, 10u);
    expectCoverageMatches("DamagedHelmet", scene.value(), placed, cam, 0.97);
}

// The eye inside deep decal boxes: the boxes are drawn by their far faces without the depth test,
// and the near plane clips the reference's rays as it clips the GPU's.
TEST(Coverage, MatchesCpuReferenceWithTheCameraInsideDecalBoxes) {
    SPATTER_REQUIRE_GL(gl);
    GallerySettings gs;
    gs.detail = 1;
    const Scene scene = makeGalleryScene(gs);
    Camera shooter;
    shooter.eye = {1.5, 2.2, 4.5};
    shooter.target = {-0.5, 1.0, -3.0};
    const std::vector<DecalType> types = {
        test::makeType("deep", {2.5f, 2.5f}, DecalTexture::Scorch, false, 3.0f),
        test::makeType("wrap", {2.0f, 2.0f}, DecalTexture::Blood, true, 3.0f)};
    const test::Placed placed = test::shootFromCamera(scene, shooter, types, 40, 17);
    ASSERT_GT(placed.placed, 20u);
    // The eye 1 m in front of the first decal on its projection axis (the shot's), looking at it:
    // inside its box and others.
    const Decal& d = placed.inputs.decals.front();
    const glm::dmat4& m = scene.objects[d.object].transform;
    const glm::dvec3 centre(m * glm::dvec4(glm::dvec3(d.center), 1.0));
    const glm::dvec3 normal =
        glm::normalize(glm::transpose(glm::inverse(glm::dmat3(m))) * glm::dvec3(d.frame().normal));
    const glm::dvec3 axis = glm::normalize(glm::dmat3(m) * glm::dvec3(d.projectionAxis()));
    Camera inside;
    inside.eye = centre + axis * (1.0 / glm::dot(axis, normal));
    inside.target = centre - glm::dvec3(0.3, 0.2, 0.1);
    const glm::dvec3 box(glm::inverse(m * glm::dmat4(d.boxToObject())) * glm::dvec4(inside.eye, 1.0));
    ASSERT_LE(std::max({std::fabs(box.x), std::fabs(box.y), std::fabs(box.z)}), 1.0)
        << "the eye is not in the box";
    expectCoverageMatches("inside", scene, placed, inside, 0.97);
}

// A decal shot at a face beside a ridge, the other face within the type's angle of the decal's
// normal but turned away from the shot: the GPU's paths leave it as the reference does.
TEST(Coverage, MatchesCpuReferenceBesideAFaceTheShotCannotReach) {
    SPATTER_REQUIRE_GL(gl);
    const test::RidgeShot ridge = test::ridgeShot(50.0, 60.0);
    ASSERT_EQ(ridge.inputs.decals.size(), 1u);
    const test::Placed placed{ridge.inputs, 1};
    expectCoverageMatches("ridge", ridge.scene, placed, test::lookAt({-0.2, -0.1, 0.45}, {0.0, 0.0, -0.03}),
                          0.97);
}

TEST(Coverage, DecalsPlacedThroughACoarseProxyCoverTheDrawnSurface) {
    SPATTER_REQUIRE_GL(gl);
    GallerySettings gs;
    gs.detail = 1;
    const Scene scene = makeGalleryScene(gs);
    // A coarse proxy for every object: h at most 2% of its bounding diagonal.
    ProxySettings ps;
    ps.tolerance = 0.02f;
    ps.backend = ProxyBackend::MeshOpt;
    ps.marginFraction = 0.5f; // a looser (still certified) bound keeps the measurement quick
    std::vector<std::shared_ptr<const Proxy>> proxies(scene.objects.size());
    size_t proxyTriangles = 0;
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        Result<Proxy> p = buildProxy(*scene.objects[i].mesh, ps);
        ASSERT_TRUE(p.ok()) << p.error();
        proxyTriangles += p->proxyTriangles;
        proxies[i] = shareProxy(std::move(p.value()));
    }
    ASSERT_LT(proxyTriangles * 3, scene.triangleCount()) << "the proxies are not coarse";

    Camera cam;
    cam.eye = {-1.0, 2.0, 5.0};
    cam.target = {0.5, 1.0, -3.0};
    DecalType t = test::makeType("splat", {0.6f, 0.6f}, DecalTexture::Blood);
    t.randomRotation = false; // the same ray gives the same footprint through either mesh
    const test::Placed render = test::shootFromCamera(scene, cam, {t}, 60, 5);
    const test::Placed proxy = test::shootFromCamera(scene, cam, {t}, 60, 5, proxies);
    ASSERT_GT(render.placed, 40u);
    ASSERT_GT(proxy.placed, 40u);
    // Every proxy decal's box holds the drawn surface: its half-depth covers h.
    const std::vector<uint8_t> a = renderCoverage(scene, render.inputs, cam);
    const std::vector<uint8_t> b = renderCoverage(scene, proxy.inputs, cam);
    test::dumpMask("proxy-render", a, kWidth, kHeight);
    test::dumpMask("proxy-proxy", b, kWidth, kHeight);
    EXPECT_GT(test::countSet(a), size_t(kWidth * kHeight) / 20);
    const double v = test::iou(a, b);
    std::printf("proxy vs render placement: IoU %.4f (%zu vs %zu px, proxies %zu of %zu triangles)\n", v,
                test::countSet(b), test::countSet(a), proxyTriangles, scene.triangleCount());
    EXPECT_GE(v, 0.95);
}
