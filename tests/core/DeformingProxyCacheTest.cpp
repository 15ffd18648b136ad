#include "spatter/core/DeformingProxy.hpp"
#include "spatter/core/SkinnedArm.hpp"

#include "TestData.hpp"

#include <gtest/gtest.h>

#include <filesystem>

using namespace spatter;
using spatter::test::scratchForTest;

namespace {

ProxySettings cachedIn(const std::string& directory) {
    ProxySettings settings;
    settings.tolerance = 0.02f;
    settings.toleranceRelative = true;
    settings.cacheDirectory = directory;
    return settings;
}

size_t entries(const std::string& directory) {
    size_t n = 0;
    for (const auto& e : std::filesystem::directory_iterator(directory))
        n += e.path().extension() == ".bin" ? 1 : 0;
    return n;
}

} // namespace

TEST(DeformingProxyCache, AStartFromTheCacheGivesTheProxyAndBoundThePosesGave) {
    const std::string dir = scratchForTest("deforming-cache");
    const Scene arm = makeSkinnedArm();
    Result<Proxy> built = buildObjectProxy(arm, 0, cachedIn(dir));
    ASSERT_TRUE(built.ok()) << built.error();
    EXPECT_FALSE(built->cached) << "its poses were measured";
    EXPECT_EQ(entries(dir), 3u) << "the proxies simplified at rest and in the worst pose, and this one";

    Result<Proxy> again = buildObjectProxy(arm, 0, cachedIn(dir));
    ASSERT_TRUE(again.ok()) << again.error();
    EXPECT_TRUE(again->cached);
    EXPECT_EQ(again->mesh.positions, built->mesh.positions);
    EXPECT_EQ(again->mesh.indices, built->mesh.indices);
    EXPECT_EQ(again->errorBound, built->errorBound) << "the bound over the poses, not the rest proxy's";
    EXPECT_EQ(again->toleranceMet, built->toleranceMet);
    EXPECT_TRUE(again->drawnNormals.empty());

    // buildObjectProxy samples 32 poses an animation.
    Result<DeformingProxy> direct = buildDeformingProxy(arm, 0, cachedIn(""), 32);
    ASSERT_TRUE(direct.ok()) << direct.error();
    EXPECT_EQ(direct->proxy.errorBound, built->errorBound);
}

TEST(DeformingProxyCache, AnotherAnimationOrSkinIsMeasuredAgain) {
    const std::string dir = scratchForTest("deforming-cache");
    ASSERT_TRUE(buildObjectProxy(makeSkinnedArm(), 0, cachedIn(dir)).ok());

    SkinnedArmSettings bent;
    bent.bendDeg *= 0.5;
    Result<Proxy> lessBent = buildObjectProxy(makeSkinnedArm(bent), 0, cachedIn(dir));
    ASSERT_TRUE(lessBent.ok()) << lessBent.error();
    EXPECT_FALSE(lessBent->cached) << "the same mesh and skin, another animation";

    Scene reweighted = makeSkinnedArm();
    for (size_t v = 0; v < reweighted.objects[0].mesh->positions.size(); ++v)
        if (reweighted.objects[0].skinWeights.weights[2 * v + 1] !=
            reweighted.objects[0].skinWeights.weights[2 * v]) {
            std::swap(reweighted.objects[0].skinWeights.weights[2 * v],
                      reweighted.objects[0].skinWeights.weights[2 * v + 1]);
            break;
        }
    Result<Proxy> other = buildObjectProxy(reweighted, 0, cachedIn(dir));
    ASSERT_TRUE(other.ok()) << other.error();
    EXPECT_FALSE(other->cached) << "the same mesh and animation, another skin weight";
}

TEST(DeformingProxyCache, AnObjectOutOfRangeIsNamed) {
    Result<Proxy> p = buildObjectProxy(makeSkinnedArm(), 1, cachedIn(""));
    ASSERT_FALSE(p.ok());
    EXPECT_NE(p.error().find("object 1 out of range"), std::string::npos) << p.error();
}
