#include "spatter/placement/Ray.hpp"
#include "spatter/placement/RayParser.hpp"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <limits>

using namespace spatter;

namespace {

Ray good() {
    Ray r;
    r.origin = glm::dvec3(1.0, 2.0, 3.0);
    r.direction = glm::dvec3(0.0, 0.0, -2.0);
    return r;
}

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

} // namespace

TEST(RayProblem, AcceptsFiniteRayWithInfiniteFar) {
    EXPECT_EQ(rayProblem(good()), nullptr);
    Ray r = good();
    r.tnear = 0.5;
    r.tfar = 0.75;
    EXPECT_EQ(rayProblem(r), nullptr);
}

TEST(RayProblem, AcceptsTinyButNormalDirection) {
    Ray r = good();
    r.direction = glm::dvec3(1e-150, 0.0, 0.0);
    EXPECT_EQ(rayProblem(r), nullptr);
}

TEST(RayProblem, RejectsNaNOrInfinityAnywhere) {
    for (int c = 0; c < 3; ++c) {
        for (double bad : {kNaN, kInf, -kInf}) {
            Ray r = good();
            r.origin[c] = bad;
            EXPECT_NE(rayProblem(r), nullptr) << "origin " << c << " = " << bad;
            r = good();
            r.direction[c] = bad;
            EXPECT_NE(rayProblem(r), nullptr) << "direction " << c << " = " << bad;
        }
    }
    Ray r = good();
    r.tnear = kNaN;
    EXPECT_NE(rayProblem(r), nullptr);
    r = good();
    r.tnear = kInf;
    EXPECT_NE(rayProblem(r), nullptr);
    r = good();
    r.tfar = kNaN;
    EXPECT_NE(rayProblem(r), nullptr);
}

TEST(RayProblem, RejectsZeroAndDenormalDirections) {
    Ray r = good();
    r.direction = glm::dvec3(0.0);
    EXPECT_STREQ(rayProblem(r), "ray direction is zero");
    r.direction = glm::dvec3(-0.0, 0.0, -0.0);
    EXPECT_STREQ(rayProblem(r), "ray direction is zero");
    r.direction = glm::dvec3(DBL_TRUE_MIN, 0.0, 0.0);
    EXPECT_NE(rayProblem(r), nullptr);
    r.direction = glm::dvec3(1e-200, 1e-200, 0.0); // normal components, squared length underflows
    EXPECT_NE(rayProblem(r), nullptr);
    r.direction = glm::dvec3(1e200, 0.0, 0.0); // squared length overflows
    EXPECT_NE(rayProblem(r), nullptr);
}

TEST(RayProblem, RejectsBadRanges) {
    Ray r = good();
    r.tnear = -1e-9;
    EXPECT_STREQ(rayProblem(r), "ray tnear is negative");
    r = good();
    r.tnear = 2.0;
    r.tfar = 2.0;
    EXPECT_STREQ(rayProblem(r), "ray tfar is not greater than tnear");
    r.tfar = 1.0;
    EXPECT_STREQ(rayProblem(r), "ray tfar is not greater than tnear");
    r = good();
    r.tfar = -kInf;
    EXPECT_NE(rayProblem(r), nullptr);
}

// A ray line holds six decimal numbers: hexadecimal, "nan" or "inf" make it an error, not a value.
TEST(RayParser, ReadsSixDecimalNumbersAndNothingElse) {
    const RayLine good = parseRayLine("1e-3 0 3.5 0 0 -1 # a comment", 4);
    ASSERT_TRUE(good.ok) << good.error;
    EXPECT_EQ(good.ray.origin, glm::dvec3(1e-3, 0.0, 3.5));
    for (const char* line : {"0x10 0 3 0 0 -1", "nan 0 3 0 0 -1", "0 0 3 0 0 -inf", "0 0 3 0 0"}) {
        const RayLine bad = parseRayLine(line, 4);
        EXPECT_TRUE(bad.isRay) << line;
        EXPECT_FALSE(bad.ok) << line;
        EXPECT_EQ(bad.error.rfind("line 4: expected 6 decimal numbers", 0), 0u) << bad.error;
    }
    EXPECT_FALSE(parseRayLine("  # only a comment", 5).isRay);
}
