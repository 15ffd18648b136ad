#include "spatter/core/Decal.hpp"
#include "spatter/core/Random.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace spatter;

namespace {

glm::vec3 randomUnit(Rng& rng) {
    const float z = rng.uniform(-1.0f, 1.0f), phi = rng.uniform(0.0f, 6.2831853f);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return glm::normalize(glm::vec3(r * std::cos(phi), r * std::sin(phi), z));
}

float largestDifference(const Frame& a, const Frame& b) {
    const glm::vec3 d[3] = {a.tangent - b.tangent, a.bitangent - b.bitangent, a.normal - b.normal};
    float m = 0.0f;
    for (const glm::vec3& v : d)
        m = std::max({m, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
    return m;
}

bool zeroFrame(const Frame& f) {
    return f.tangent == glm::vec3(0.0f) && f.bitangent == glm::vec3(0.0f) && f.normal == glm::vec3(0.0f);
}

} // namespace

TEST(Decal, PackedFrameComesBackOrthonormalAndWithinItsBound) {
    Rng rng(11);
    for (int i = 0; i < 200000; ++i) {
        const Frame f = frameFromNormalAndHint(randomUnit(rng), randomUnit(rng));
        Decal d;
        ASSERT_TRUE(d.setFrame(f)) << i;
        const Frame back = d.frame();
        ASSERT_LE(frameError(back), 1e-6f) << i;
        ASSERT_LE(largestDifference(back, f), float(kPackedFrameError)) << i;
        ASSERT_FALSE(d.mirrored()) << i;
    }
}

TEST(Decal, LeftHandedFrameIsKeptAsMirrored) {
    Rng rng(12);
    for (int i = 0; i < 10000; ++i) {
        Frame f = frameFromNormalAndHint(randomUnit(rng), randomUnit(rng));
        f.bitangent = -f.bitangent;
        Decal d;
        ASSERT_TRUE(d.setFrame(f)) << i;
        ASSERT_TRUE(d.mirrored()) << i;
        ASSERT_LE(largestDifference(d.frame(), f), float(kPackedFrameError)) << i;
    }
}

TEST(Decal, SkewedAndScaledFrameIsOrthonormalisedAroundItsNormal) {
    Decal d;
    ASSERT_TRUE(d.setFrame(Frame{glm::vec3(3, 0, 1), glm::vec3(0, 7, 0), glm::vec3(0, 0, 2)}));
    const Frame f = d.frame();
    EXPECT_LE(frameError(f), 1e-6f);
    EXPECT_NEAR(f.normal.z, 1.0f, 1e-7f);
    EXPECT_NEAR(f.tangent.x, 1.0f, 1e-7f);
    EXPECT_NEAR(f.bitangent.y, 1.0f, 1e-7f);
}

TEST(Decal, FrameWithoutOrientationIsRefusedAndUnpacksToZero) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const Frame bad[] = {
        {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0.0f)},      // zero normal
        {glm::vec3(0, 0, 1), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)},   // tangent along the normal
        {glm::vec3(0.0f), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)},      // zero tangent
        {glm::vec3(nan, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)}, // NaN
        {glm::vec3(1, 0, 0), glm::vec3(0, inf, 0), glm::vec3(0, 0, 1)}, // Inf
    };
    for (const Frame& f : bad) {
        Decal d;
        d.setOrientation(glm::dquat(1.0, 0.0, 0.0, 0.0), true);
        EXPECT_FALSE(d.setFrame(f));
        EXPECT_EQ(d.packedFrame, kNoOrientation);
        EXPECT_EQ(d.orientation(), glm::dquat(0.0, 0.0, 0.0, 0.0));
        EXPECT_FALSE(d.mirrored());
        EXPECT_TRUE(zeroFrame(d.frame()));
    }
}

TEST(Decal, NonFiniteOrZeroQuaternionPacksToNoOrientation) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(packOrientation(glm::dquat(nan, 0.0, 0.0, 0.0), false), kNoOrientation);
    EXPECT_EQ(packOrientation(glm::dquat(0.0, 0.0, 0.0, 0.0), true), kNoOrientation);
    Decal d;
    d.packedFrame = ~(uint64_t(1) << 63); // every bit but the frame bit: still no orientation
    EXPECT_TRUE(zeroFrame(d.frame()));
}

// A NaN or an infinity off the diagonal, which the trace and the diagonal do not show.
TEST(Decal, FrameWithANonFiniteComponentPacksToNoOrientation) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_EQ(packFrame({1.0, 0.0, 0.0}, {0.0, 1.0, nan}, {0.0, 0.0, 1.0}, false), kNoOrientation);
    EXPECT_EQ(packFrame({1.0, 0.0, 0.0}, {0.0, 1.0, inf}, {0.0, 0.0, 1.0}, false), kNoOrientation);
    EXPECT_EQ(packFrame({1.0, -inf, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, true), kNoOrientation);
}

TEST(Decal, EveryPackedValueWithItsFrameBitUnpacksToAUnitQuaternion) {
    // Bits a frame never packs to (a sum of squares above 1) still unpack to a rotation.
    Rng rng(13);
    for (int i = 0; i < 100000; ++i) {
        const uint64_t bits = uint64_t(1) << 63 | uint64_t(rng.next()) << 32 | rng.next();
        const glm::dquat q = unpackOrientation(bits);
        ASSERT_NEAR(glm::length(q), 1.0, 1e-12) << std::hex << bits;
    }
}

TEST(Decal, IdentityAndQuarterTurnsPackExactly) {
    Decal d;
    EXPECT_EQ(d.packedFrame, kIdentityOrientation);
    EXPECT_EQ(d.frame().tangent, glm::vec3(1, 0, 0));
    EXPECT_EQ(d.frame().normal, glm::vec3(0, 0, 1));
    ASSERT_TRUE(d.setFrame(Frame{glm::vec3(0, 1, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 0, 1)}));
    EXPECT_LE(
        largestDifference(d.frame(), Frame{glm::vec3(0, 1, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 0, 1)}),
        1e-7f);
}

TEST(Decal, BoxToObjectSpansTheBox) {
    Decal d;
    ASSERT_TRUE(d.setFrame(Frame{glm::vec3(0, 1, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 0, 1)}));
    d.center = glm::vec3(1, 2, 3);
    d.size = glm::vec2(4, 6);
    d.halfDepth = 0.5f;
    const glm::mat4 m = d.boxToObject();
    const glm::vec3 corner = glm::vec3(m * glm::vec4(1, 1, 1, 1));
    EXPECT_NEAR(corner.x, 1.0f - 3.0f, 1e-6f);
    EXPECT_NEAR(corner.y, 2.0f + 2.0f, 1e-6f);
    EXPECT_NEAR(corner.z, 3.0f + 0.5f, 1e-6f);
}

TEST(Decal, HalfTurnsAboutAnyAxisComeBack) {
    // Rotations by 180 degrees, where w is 0 and the signs of x, y and z must come from the matrix's
    // off-diagonal sums: about the coordinate axes and about diagonals with mixed signs.
    const glm::vec3 axes[] = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1}, {1, -1, 0},
                              {0, 1, -1}, {-1, 0, 1}, {1, -1, 1}};
    for (const glm::vec3& a : axes) {
        const glm::dmat3 r = glm::mat3_cast(glm::angleAxis(glm::pi<double>(), glm::normalize(glm::dvec3(a))));
        const Frame f{glm::vec3(r[0]), glm::vec3(r[1]), glm::vec3(r[2])};
        Decal d;
        ASSERT_TRUE(d.setFrame(f));
        EXPECT_LE(largestDifference(d.frame(), f), float(kPackedFrameError))
            << a.x << " " << a.y << " " << a.z;
    }
}
