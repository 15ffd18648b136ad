// A proxy search judges each run by sampled distances toward the render mesh, and its runs keep most
// of one another's triangles: SampleMemory carries what one judgement measured on a triangle to the
// next, which measures it again only where it could raise its answer. The answers are those without it.

#include "spatter/core/SampleMemory.hpp"
#include "spatter/core/HausdorffBound.hpp"

#include "ReferenceGeometry.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

using namespace spatter;
using namespace spatter::test;

namespace {

// `m` with every seventh vertex from `first` on pushed out from the origin by `push`: candidates that
// keep the triangles around the other vertices as they are.
Mesh pushedOut(Mesh m, uint32_t first, float push) {
    for (size_t v = first; v < m.positions.size(); v += 7)
        m.positions[v] *= 1.0f + push;
    return m;
}

} // namespace

TEST(SampleMemory, JudgementsThatShareTrianglesGiveTheAnswersTheyGiveAlone) {
    const Mesh render = latLongSphere(1.0f, 24, 32, 0.05f);
    Result<HausdorffSurface> to = HausdorffSurface::create(render);
    ASSERT_TRUE(to) << to.error();
    const double inf = std::numeric_limits<double>::infinity();
    SampleMemory memory;
    const std::vector<Mesh> candidates = {pushedOut(render, 0, 0.02f), pushedOut(render, 3, 0.05f),
                                          pushedOut(render, 0, 0.01f), pushedOut(render, 3, 0.05f),
                                          pushedOut(render, 5, 0.03f), render};
    for (size_t c = 0; c < candidates.size(); ++c) {
        for (size_t most : {size_t(100000), size_t(300)}) { // every triangle, then a stride
            Result<double> alone = sampledLowerBound(candidates[c], to.value(), most, inf);
            Result<double> remembered =
                sampledLowerBound(candidates[c], to.value(), most, inf, {}, 0, &memory);
            ASSERT_TRUE(alone && remembered);
            EXPECT_EQ(remembered.value(), alone.value()) << "candidate " << c << ", " << most << " triangles";
        }
    }
    EXPECT_GT(memory.size(), render.triangleCount());
    // Stopping early still answers "above".
    Result<double> early = sampledLowerBound(candidates[1], to.value(), 100000, 0.01, {}, 0, &memory);
    ASSERT_TRUE(early);
    EXPECT_GT(early.value(), 0.01);
}

TEST(SampleMemory, KeepsAnAttainedDistanceOverABoundAndTheLowerOfTwoBounds) {
    SampleMemory memory;
    const SampleMemory::TriangleKey key = SampleMemory::keyOf({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    EXPECT_EQ(SampleMemory::keyOf({0, 1, 0}, {0, 0, -0.0}, {1, 0, 0}), key);
    EXPECT_EQ(memory.find(key), nullptr);
    memory.keep(key, {0.5, false});
    memory.keep(key, {0.7, false});
    ASSERT_NE(memory.find(key), nullptr);
    EXPECT_EQ(memory.find(key)->farthest, 0.5);
    memory.keep(key, {0.6, true});
    EXPECT_EQ(memory.find(key)->farthest, 0.6);
    EXPECT_TRUE(memory.find(key)->attained);
    memory.keep(key, {0.2, false});
    EXPECT_EQ(memory.find(key)->farthest, 0.6);
    EXPECT_EQ(memory.size(), 1u);
}
