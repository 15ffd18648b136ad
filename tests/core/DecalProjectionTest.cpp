#include "spatter/core/DecalProjection.hpp"
#include "spatter/core/Decal.hpp"
#include "spatter/core/Opacity.hpp"
#include "spatter/core/Random.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace spatter;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A decal with a turned frame, centred off the origin.
Decal turnedDecal() {
    Decal d;
    EXPECT_TRUE(d.setFrame(
        Frame{glm::normalize(glm::vec3(1, 1, 0)), glm::normalize(glm::vec3(-1, 1, 0)), glm::vec3(0, 0, 1)}));
    d.center = glm::vec3(2, -1, 3);
    d.size = glm::vec2(0.4f, 0.2f);
    d.halfDepth = 0.1f;
    return d;
}

// The shot's reversed direction `angle` radians from the normal, at azimuth `azimuth` in the plane.
glm::vec3 axisAt(const Decal& d, double angle, double azimuth) {
    const Frame f = d.frame();
    const glm::vec3 across = float(std::cos(azimuth)) * f.tangent + float(std::sin(azimuth)) * f.bitangent;
    return float(std::cos(angle)) * f.normal + float(std::sin(angle)) * across;
}

} // namespace

// Every point of the box's axis (u = v = 0) lies on the shot's line through the centre, and w keeps
// measuring the distance from the decal plane in half-depths.
TEST(DecalProjection, ShotAxisRunsThroughTheBoxCentreLine) {
    Rng rng(3);
    for (int i = 0; i < 200; ++i) {
        Decal d = turnedDecal();
        const double angle = rng.uniform(0.0f, 84.0f) * kPi / 180.0, azimuth = rng.uniform(0.0f, 6.283f);
        const glm::vec3 axis = axisAt(d, angle, azimuth);
        d.setProjectionAxis(axis * 3.0f); // need not be unit
        EXPECT_LT(glm::length(d.projectionAxis() - axis), 2e-3f) << "angle " << angle;
        const glm::mat4 m = d.boxToObject();
        for (float w : {-1.0f, 0.5f, 1.0f}) {
            const glm::vec3 p(m * glm::vec4(0.0f, 0.0f, w, 1.0f));
            const glm::vec3 v = p - d.center;
            EXPECT_LT(glm::length(glm::cross(glm::normalize(v), axis)), 2e-3f);
            EXPECT_NEAR(glm::dot(v, d.frame().normal), w * d.halfDepth, 1e-5f);
        }
    }
}

TEST(DecalProjection, AlongTheNormalIsTheRightBox) {
    Decal d = turnedDecal();
    d.setProjectionAxis(d.frame().normal);
    EXPECT_EQ(d.slant, 0u);
    const glm::vec3 corner(d.boxToObject() * glm::vec4(0, 0, 1, 1));
    EXPECT_LT(glm::length(corner - (d.center + d.halfDepth * d.frame().normal)), 1e-6f);
}

TEST(DecalProjection, AxisIntoTheSurfaceZeroOrNotFiniteProjectsAlongTheNormal) {
    Decal d = turnedDecal();
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (const glm::vec3& axis : {-d.frame().normal, glm::vec3(0.0f), glm::vec3(nan, 0, 1),
                                  glm::vec3(inf, 0, 1), d.frame().tangent}) {
        d.slant = 12345u;
        d.setProjectionAxis(axis);
        EXPECT_EQ(d.slant, 0u) << axis.x << " " << axis.y << " " << axis.z;
    }
}

TEST(DecalProjection, GrazingAxisTurnsToTheLargestSlantInItsPlane) {
    Decal d = turnedDecal();
    const double azimuth = 0.7;
    d.setProjectionAxis(axisAt(d, 89.5 * kPi / 180.0, azimuth));
    const glm::vec3 expected = axisAt(d, kMaxSlantDeg * kPi / 180.0, azimuth);
    EXPECT_LT(glm::length(d.projectionAxis() - expected), 1e-3f);
    EXPECT_TRUE(validSlant(d.slant));
}

TEST(DecalProjection, SlantsThatNoAxisPacksToAreInvalid) {
    EXPECT_TRUE(validSlant(0u));
    EXPECT_TRUE(validSlant(packSlant(glm::vec2(3.0f, -4.0f))));
    EXPECT_TRUE(validSlant(packSlant(glm::vec2(1e6f, 0.0f)))); // clamped when packed
    EXPECT_FALSE(validSlant(0x7c00u));                         // +infinity
    EXPECT_FALSE(validSlant(0x7e00u << 16));                   // NaN
    EXPECT_FALSE(validSlant(0x4d00u));                         // 20: steeper than 85 degrees
    EXPECT_EQ(packSlant(glm::vec2(std::numeric_limits<float>::quiet_NaN(), 0.0f)), 0u);
}

TEST(Opacity, KeepsTheNearestStepAndClampsTheRest) {
    EXPECT_EQ(Opacity().bits(), 255u);
    EXPECT_EQ(Opacity(0.5f).bits(), 128u);
    EXPECT_FLOAT_EQ(float(Opacity(0.5f)), 128.0f / 255.0f);
    EXPECT_EQ(Opacity(2.0f).bits(), 255u);
    EXPECT_EQ(Opacity(-1.0f).bits(), 0u);
    EXPECT_EQ(Opacity(std::numeric_limits<float>::quiet_NaN()).bits(), 0u);
    EXPECT_EQ(Opacity(std::numeric_limits<float>::infinity()).bits(), 0u);
    for (int b = 0; b < 256; ++b)
        EXPECT_EQ(Opacity(float(Opacity::fromBits(uint8_t(b)))).bits(), b) << "a step reads back as itself";
}
