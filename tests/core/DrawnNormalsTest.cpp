// The drawn surface's normals under a proxy come with the proxy: buildProxy finds, for each piece of
// each proxy or collider triangle, the render triangle nearest the piece's centre (checked here by
// brute force over every render triangle) and keeps its face normal; the render mesh as its own proxy
// keeps none.

#include "spatter/core/DrawnNormals.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/TrianglePieces.hpp"

#include "ReferenceGeometry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace spatter;
using namespace spatter::test;

namespace {

glm::dvec3 corner(const Mesh& m, size_t t, int k) {
    return glm::dvec3(m.positions[m.indices[3 * t + size_t(k)]]);
}

// Whether `n` is the unit face normal, to the table's 16-bit precision, of a triangle of `render` as
// near `p` as the nearest one (by brute force over every triangle).
::testing::AssertionResult facesAsANearestTriangle(const glm::dvec3& n, const glm::dvec3& p,
                                                   const Mesh& render) {
    const double nearest = bruteMeshDistance(p, render);
    for (size_t t = 0; t < render.triangleCount(); ++t) {
        const glm::dvec3 a = corner(render, t, 0), b = corner(render, t, 1), c = corner(render, t, 2);
        if (triangleDistance(p, a, b, c) > nearest + 1e-12) continue;
        if (glm::length(n - glm::normalize(glm::cross(b - a, c - a))) < 1e-4)
            return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "no render triangle nearest the piece faces that way";
}

// Every piece of every triangle of `collision` reads back the normal of a render triangle nearest its
// centre.
void expectNearestFaces(const DrawnNormals& table, const Mesh& collision, const Mesh& render) {
    ASSERT_TRUE(table.fits(collision.triangleCount()));
    for (size_t t = 0; t < collision.triangleCount(); ++t) {
        const glm::dvec3 p0 = corner(collision, t, 0), e1 = corner(collision, t, 1) - p0,
                         e2 = corner(collision, t, 2) - p0;
        forEachPieceCentre(p0, e1, e2, [&](const glm::dvec3& centre) {
            // The centre's barycentric coordinates, to read the table back where placement reads it.
            const glm::dmat2 gram(glm::dot(e1, e1), glm::dot(e1, e2), glm::dot(e1, e2), glm::dot(e2, e2));
            const glm::dvec2 uv =
                glm::inverse(gram) * glm::dvec2(glm::dot(centre - p0, e1), glm::dot(centre - p0, e2));
            const std::optional<glm::dvec3> n = table.at(uint32_t(t), {1.0 - uv.x - uv.y, uv.x, uv.y});
            ASSERT_TRUE(n.has_value()) << "triangle " << t;
            EXPECT_TRUE(facesAsANearestTriangle(*n, centre, render)) << "triangle " << t;
        });
    }
}

// Builds the proxy of `render` at `tolerance` (of the diagonal) into `out`; fails unless the builder
// simplified it.
::testing::AssertionResult buildSimplified(const Mesh& render, float tolerance, Proxy& out) {
    ProxySettings s;
    s.tolerance = tolerance;
    Result<Proxy> p = buildProxy(render, s);
    if (!p) return ::testing::AssertionFailure() << p.error();
    if (p->source != ProxySource::Simplified) return ::testing::AssertionFailure() << "not simplified";
    out = std::move(p).value();
    return ::testing::AssertionSuccess();
}

} // namespace

TEST(DrawnNormals, AProxyCarriesTheNormalOfTheRenderTriangleNearestEachPieceOfIt) {
    const Mesh render = latLongSphere(1.0f, 24, 32, 0.05f);
    Proxy p;
    ASSERT_TRUE(buildSimplified(render, 0.02f, p));
    expectNearestFaces(p.drawnNormals, p.mesh, render);
}

// At a fine tolerance the proxy keeps many render triangles as they are (a fifth of them here); each
// piece of such a triangle takes that triangle's normal without a search: the table a search gives.
TEST(DrawnNormals, ProxyTrianglesKeptFromTheRenderMeshTakeTheirOwnNormals) {
    const Mesh render = latLongSphere(1.0f, 48, 64, 0.05f);
    Proxy p;
    ASSERT_TRUE(buildSimplified(render, 0.004f, p));
    Result<HausdorffSurface> surface = HausdorffSurface::create(render);
    ASSERT_TRUE(surface) << surface.error();
    const std::vector<uint32_t> same = surface->sameTriangles(p.mesh);
    EXPECT_GT(std::count_if(same.begin(), same.end(), [](uint32_t t) { return t != UINT32_MAX; }),
              std::ptrdiff_t(p.mesh.triangleCount() / 5));
    Result<DrawnNormals> searched = DrawnNormals::build(render, p.mesh, p.errorBound);
    ASSERT_TRUE(searched) << searched.error();
    EXPECT_EQ(p.drawnNormals.packed(), searched->packed());
}

TEST(DrawnNormals, AnAuthoredColliderCarriesThemToo) {
    const Mesh render = latLongSphere(1.0f, 24, 32), collider = box(1.0f);
    Result<Proxy> p = buildProxy(render, ProxySettings{}, &collider);
    ASSERT_TRUE(p) << p.error();
    ASSERT_EQ(p->source, ProxySource::AuthoredCollider);
    expectNearestFaces(p->drawnNormals, collider, render);
}

TEST(DrawnNormals, TheRenderMeshAsItsOwnProxyCarriesNone) {
    Result<Proxy> p = buildProxy(box(1.0f), ProxySettings{});
    ASSERT_TRUE(p) << p.error();
    EXPECT_EQ(p->source, ProxySource::OwnMesh);
    EXPECT_TRUE(p->drawnNormals.empty());
}

// The reach only speeds the search: one too short for every piece (0) gives the table an unbounded
// search gives.
TEST(DrawnNormals, AReachTooShortStillFindsTheNearestTriangle) {
    const Mesh render = latLongSphere(1.0f, 24, 32, 0.05f), collider = box(1.1f);
    Result<DrawnNormals> within = DrawnNormals::build(render, collider, 0.0);
    Result<DrawnNormals> anywhere =
        DrawnNormals::build(render, collider, std::numeric_limits<double>::infinity());
    ASSERT_TRUE(within && anywhere);
    EXPECT_EQ(within->packed(), anywhere->packed());
    expectNearestFaces(within.value(), collider, render);
}

// A surface prepared from another mesh than the render mesh names triangles the render mesh may lack:
// their pieces get no normal, and nothing is read past the render mesh.
TEST(DrawnNormals, ASurfaceOfAnotherMeshGivesNoNormalPastTheRenderMesh) {
    const Mesh render = box(1.0f), other = latLongSphere(1.0f, 24, 32);
    Result<HausdorffSurface> wrong = HausdorffSurface::create(other);
    ASSERT_TRUE(wrong) << wrong.error();
    const DrawnNormals table = DrawnNormals::build(render, wrong.value(), other, 1.0);
    ASSERT_TRUE(table.fits(other.triangleCount()));
    size_t none = 0;
    for (const DrawnNormals::Packed& n : table.packed())
        none += n == DrawnNormals::Packed{0, 0, 0} ? 1 : 0;
    EXPECT_GT(none, 0u);
}

TEST(DrawnNormals, ABrokenRenderMeshIsNamed) {
    Mesh render = box(1.0f);
    render.indices[4] = 99;
    Result<DrawnNormals> table = DrawnNormals::build(render, box(1.1f), 1.0);
    ASSERT_FALSE(table);
    EXPECT_NE(table.error().find("index 4"), std::string::npos) << table.error();
}
