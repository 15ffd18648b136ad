// Random meshes made to trouble the certifier and the proxy search: strips folded back and forth and
// flattened tubes (wound to face up, so that only their geometry shows the folds), steps, holes,
// turned triangles, crossing sheets, seams along every edge, turned and moved off the origin. Their
// bounds are checked against dense estimates. (Every draw of the generator is a statement of its own,
// so that the meshes do not depend on the compiler's order of evaluating arguments.)
#include "spatter/core/DrawnNormals.hpp"
#include "spatter/core/HausdorffBound.hpp"
#include "spatter/core/ProxyBuilder.hpp"
#include "spatter/core/Random.hpp"

#include "ReferenceGeometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

using namespace spatter;
using namespace spatter::test;

namespace {

// A grid of nx x ny cells over [x0, x1] x [0, 1] at height z(x, y), two triangles a cell.
template <class Height> Mesh sheet(uint32_t nx, uint32_t ny, float x0, float x1, Height z) {
    Mesh m;
    for (uint32_t i = 0; i <= nx; ++i)
        for (uint32_t j = 0; j <= ny; ++j) {
            const float x = x0 + (x1 - x0) * float(i) / float(nx), y = float(j) / float(ny);
            m.positions.push_back({x, y, z(x, y)});
        }
    for (uint32_t i = 0; i < nx; ++i)
        for (uint32_t j = 0; j < ny; ++j) {
            const uint32_t v = i * (ny + 1) + j, w = v + ny + 1;
            m.indices.insert(m.indices.end(), {v, w, w + 1, v, w + 1, v + 1});
        }
    return m;
}

void append(Mesh& m, const Mesh& other) {
    const uint32_t base = uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), other.positions.begin(), other.positions.end());
    for (uint32_t i : other.indices)
        m.indices.push_back(base + i);
}

// A strip folded back and forth along x over [x0, x0 + width], its layers `gap` apart in z and joined
// by thin wedges at the folds; each triangle wound to face up, or either way at random.
Mesh foldedStrip(Rng& rng, bool faceUp, float x0, float width) {
    const uint32_t folds = 2 + rng.below(4), cells = 2 + rng.below(6), rows = 2 + rng.below(10);
    const float gap = rng.uniform(0.002f, 0.05f);
    Mesh m = sheet(folds * cells, rows, 0.0f, 1.0f, [](float, float) { return 0.0f; });
    for (size_t v = 0; v < m.positions.size(); ++v) {
        const uint32_t column = uint32_t(v / (rows + 1)), layer = std::min(column / cells, folds - 1);
        const float along = float(column - layer * cells) / float(cells);
        const bool fold = column % cells == 0 && column > 0 && column < folds * cells;
        m.positions[v].x = x0 + width * (layer % 2 ? 1.0f - along : along);
        m.positions[v].z = gap * (float(layer) + (fold ? 0.5f : 0.0f));
    }
    for (size_t t = 0; t < m.triangleCount(); ++t) {
        uint32_t* c = &m.indices[3 * t];
        const glm::vec3 n =
            glm::cross(m.positions[c[1]] - m.positions[c[0]], m.positions[c[2]] - m.positions[c[0]]);
        if (faceUp ? n.z < 0.0f : rng.uniform() < 0.5f) std::swap(c[1], c[2]);
    }
    return m;
}

// Flattened tubes along y, open at y = 0 and 1, side by side with gaps between them: tube k over
// [x0[k], x0[k] + width[k]] in x, its two sheets `thickness` apart in z, every triangle wound to face
// up, so that only their geometry shows the folds along their sides.
Mesh flatTubes(Rng& rng) {
    Mesh m;
    const uint32_t tubes = 1 + rng.below(3), rows = 2 + rng.below(10), half = 2 + rng.below(8);
    float x = rng.uniform(0.0f, 0.2f);
    for (uint32_t k = 0; k < tubes; ++k) {
        const float width = rng.uniform(0.1f, 0.4f), thickness = rng.uniform(0.002f, 0.03f);
        Mesh tube = sheet(2 * half, rows, 0.0f, 1.0f, [](float, float) { return 0.0f; });
        for (size_t v = 0; v < tube.positions.size(); ++v) {
            const uint32_t column = uint32_t(v / (rows + 1)) % (2 * half); // the last closes the loop
            const bool top = column < half;
            tube.positions[v].x = x + width * float(top ? column : 2 * half - column) / float(half);
            tube.positions[v].z = top ? thickness : 0.0f;
        }
        // The loop's last column lies on its first: weld them.
        const uint32_t last = 2 * half * (rows + 1);
        for (uint32_t& i : tube.indices)
            if (i >= last) i -= last;
        for (size_t t = 0; t < tube.triangleCount(); ++t) {
            uint32_t* c = &tube.indices[3 * t];
            const glm::vec3 n = glm::cross(tube.positions[c[1]] - tube.positions[c[0]],
                                           tube.positions[c[2]] - tube.positions[c[0]]);
            if (n.z < 0.0f) std::swap(c[1], c[2]);
        }
        append(m, tube);
        x += width + rng.uniform(0.05f, 0.3f);
    }
    return m;
}

// A folded strip, flattened tubes, or a stepped or crossing sheet.
Mesh shape(Rng& rng) {
    const uint32_t n = 4 + rng.below(30);
    switch (rng.below(4)) {
    case 0: {
        const bool faceUp = rng.below(2) == 0;
        const float x0 = rng.uniform(0.0f, 0.4f);
        return foldedStrip(rng, faceUp, x0, rng.uniform(0.2f, 0.6f));
    }
    case 1:
        return flatTubes(rng);
    case 2: {
        const float step = rng.uniform(0.01f, 0.2f), at = rng.uniform(0.2f, 0.8f),
                    wave = rng.uniform(1.0f, 30.0f);
        return sheet(n, n, 0.0f, 1.0f,
                     [&](float x, float y) { return (x > at ? step : 0.0f) + 0.01f * std::sin(wave * y); });
    }
    default: {
        Mesh m = sheet(n, n, 0.0f, 1.0f, [](float x, float) { return 0.2f * (x - 0.5f); });
        append(m, sheet(n / 2 + 2, n, 0.0f, 1.0f, [](float x, float) { return 0.01f - 0.3f * (x - 0.5f); }));
        return m;
    }
    }
}

// A shape with holes, turned triangles and, at random, a seam along every edge.
Mesh troublesome(Rng& rng) {
    Mesh out = shape(rng);
    const float holes = rng.below(2) ? rng.uniform(0.0f, 0.1f) : 0.0f,
                turns = rng.below(2) ? rng.uniform(0.0f, 0.3f) : 0.0f;
    const bool seams = rng.uniform() < 0.3f;
    std::vector<uint32_t> kept;
    for (size_t t = 0; t < out.triangleCount(); ++t) {
        uint32_t c[3] = {out.indices[3 * t], out.indices[3 * t + 1], out.indices[3 * t + 2]};
        if (rng.uniform() < holes) continue;
        if (rng.uniform() < turns) std::swap(c[1], c[2]);
        kept.insert(kept.end(), {c[0], c[1], c[2]});
    }
    out.indices = std::move(kept);
    return seams ? unshared(out) : out;
}

// A coarse tilted sheet of a few cells over about the unit square, short of the shapes' open ends at
// y = 0 and 1 (so that its pieces lie over folds, not borders).
Mesh coarseSheet(Rng& rng) {
    const float z0 = rng.uniform(-0.05f, 0.08f), sx = rng.uniform(-0.1f, 0.1f), sy = rng.uniform(-0.1f, 0.1f);
    const float y0 = rng.uniform(0.02f, 0.2f), y1 = rng.uniform(0.8f, 0.98f);
    const uint32_t nx = 1 + rng.below(5), ny = 1 + rng.below(5);
    const float x0 = rng.uniform(-0.2f, 0.3f), x1 = rng.uniform(0.7f, 1.2f);
    Mesh m = sheet(nx, ny, x0, x1, [&](float x, float y) { return z0 + sx * x + sy * y; });
    for (glm::vec3& p : m.positions)
        p.y = y0 + (y1 - y0) * p.y;
    return m;
}

// Both meshes turned and moved by the same random rigid motion, and scaled by 1 or 1,000 (returned).
float place(Rng& rng, Mesh& a, Mesh& b) {
    glm::vec3 axis(0.0f, 0.0f, 1.0f), offset(0.0f);
    for (int k = 0; k < 2; ++k)
        axis[k] = rng.uniform(-1.0f, 1.0f);
    for (int k = 0; k < 3; ++k)
        offset[k] = rng.uniform(-1.0f, 1.0f);
    axis = glm::normalize(axis);
    const float angle = rng.uniform(0.0f, 6.28f), scale = rng.below(5) == 0 ? 1000.0f : 1.0f;
    const glm::mat3 k(0.0f, axis.z, -axis.y, -axis.z, 0.0f, axis.x, axis.y, -axis.x, 0.0f);
    const glm::mat3 turn = glm::mat3(1.0f) + std::sin(angle) * k + (1.0f - std::cos(angle)) * k * k;
    for (Mesh* m : {&a, &b})
        for (glm::vec3& p : m->positions)
            p = scale * (turn * p + offset);
    return scale;
}

} // namespace

// The bound from either mesh to the other is never below a distance the dense samples attain, and
// the early answer at a tolerance just under that distance is never "within". Turning the overlay's
// check for a neighbour folded back over its triangle off makes this fail on flattened tubes under a
// coarse sheet (six of the ninety pairs).
TEST(HausdorffRandom, BoundsStayAboveTheDistancesAttainedOverFoldsStepsHolesAndSeams) {
    for (uint64_t seed = 0; seed < 90; ++seed) {
        Rng rng(seed);
        // A third of the pairs a shape as it is under a coarse sheet, a third edited, a third two edited.
        Mesh a = seed % 3 == 0 ? shape(rng) : troublesome(rng);
        Mesh b = seed % 3 == 2 ? troublesome(rng) : coarseSheet(rng);
        const double scale = place(rng, a, b);
        Result<HausdorffSurface> sa = HausdorffSurface::create(a), sb = HausdorffSurface::create(b);
        ASSERT_TRUE(sa && sb);
        if (sa->surfaceTriangleCount() == 0 || sb->surfaceTriangleCount() == 0) continue;
        for (int way = 0; way < 2; ++way) {
            const std::string which = "seed " + std::to_string(seed) + (way ? ", b to a" : ", a to b");
            const HausdorffSurface& from = way ? sb.value() : sa.value();
            const HausdorffSurface& to = way ? sa.value() : sb.value();
            const double dense = denseOneSided(way ? b : a, way ? a : b, 20000, seed);
            HausdorffSettings s;
            s.margin = 1e-4 * scale;
            Result<HausdorffResult> sharp = boundOneSided(from, to, s);
            ASSERT_TRUE(sharp) << which << ": " << sharp.error();
            EXPECT_GE(sharp->upper, dense) << which;
            s.tolerance = 0.995 * dense;
            s.roomShare = 0.25;
            Result<HausdorffResult> early = boundOneSided(from, to, s);
            ASSERT_TRUE(early) << which << ": " << early.error();
            EXPECT_FALSE(early->within(s.tolerance))
                << which << ": within " << s.tolerance << ", dense " << dense;
        }
    }
}

// Proxies of such meshes, built as the builder's search builds them, at tolerances from 0.3% to 3% of
// the diagonal: the proxy's h is never below the dense estimate of the two-sided distance, and a
// proxy that meets the tolerance is within it by the dense estimate too; its table of drawn normals
// fits it and holds unit normals.
TEST(ProxyBuilder, ProxiesOfFoldedSteppedHoledAndSeamedMeshesHoldTheirBound) {
    uint32_t met = 0;
    for (uint64_t seed = 0; seed < 24; ++seed) {
        Rng rng(seed + 1000);
        Mesh render = troublesome(rng);
        Mesh unused = coarseSheet(rng);
        place(rng, render, unused);
        ProxySettings settings;
        settings.tolerance = rng.uniform(0.003f, 0.03f);
        settings.smallMeshTriangles = 0; // simplify every mesh, however small
        Result<Proxy> proxy = buildProxy(render, settings);
        const std::string which = "seed " + std::to_string(seed);
        ASSERT_TRUE(proxy) << which << ": " << proxy.error();
        if (proxy->source != ProxySource::Simplified) continue;
        const double dense = std::max(denseOneSided(proxy->mesh, render, 20000, seed),
                                      denseOneSided(render, proxy->mesh, 20000, seed));
        EXPECT_GE(proxy->errorBound, dense) << which;
        if (proxy->toleranceMet) {
            EXPECT_LE(dense, proxy->tolerance) << which;
            ++met;
        }
        EXPECT_LE(proxy->proxyTriangles, proxy->inputTriangles) << which;
        ASSERT_TRUE(proxy->drawnNormals.fits(proxy->mesh.triangleCount())) << which;
        for (uint32_t t = 0; t < proxy->mesh.triangleCount(); ++t) {
            const std::optional<glm::dvec3> n = proxy->drawnNormals.at(t, glm::dvec3(1.0 / 3.0));
            if (n) {
                EXPECT_NEAR(glm::length(*n), 1.0, 1e-3) << which << ", triangle " << t;
            }
        }
    }
    EXPECT_GE(met, 20u); // simplified and certified: the checks above are not vacuous
}
