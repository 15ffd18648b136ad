#include "spatter/core/Frame.hpp"
#include "spatter/core/Random.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace spatter;

TEST(Frame, BasisFromNormalIsOrthonormalOnEveryAxisBothSigns) {
    for (int axis = 0; axis < 3; ++axis)
        for (float sign : {1.0f, -1.0f}) {
            glm::vec3 n(0.0f);
            n[axis] = sign;
            EXPECT_LT(frameError(basisFromNormal(n)), 1e-6f) << "axis " << axis << " sign " << sign;
        }
}

TEST(Frame, BasisFromNormalHoldsNearThePoles) {
    for (float eps : {1e-9f, 1e-7f, 1e-5f, 1e-3f})
        for (float z : {1.0f, -1.0f}) {
            const glm::vec3 n = glm::normalize(glm::vec3(eps, -eps, z));
            EXPECT_LT(frameError(basisFromNormal(n)), 1e-6f) << "eps " << eps << " z " << z;
        }
}

TEST(Frame, BasisFromNormalIsOrthonormalForRandomNormals) {
    Rng rng(7);
    for (int i = 0; i < 100000; ++i) {
        const float z = rng.uniform(-1.0f, 1.0f), phi = rng.uniform(0.0f, 6.2831853f);
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const glm::vec3 n = glm::normalize(glm::vec3(r * std::cos(phi), r * std::sin(phi), z));
        ASSERT_LT(frameError(basisFromNormal(n)), 1e-6f) << i;
    }
}

TEST(Frame, TangentFollowsTheProjectedHint) {
    const Frame f = frameFromNormalAndHint(glm::vec3(0, 0, 1), glm::vec3(3, 0, -5));
    EXPECT_NEAR(f.tangent.x, 1.0f, 1e-6f);
    EXPECT_NEAR(f.bitangent.y, 1.0f, 1e-6f);
    EXPECT_LT(frameError(f), 1e-6f);
}

TEST(Frame, HintAlongTheNormalFallsBackToAFixedAxis) {
    const Frame f = frameFromNormalAndHint(glm::vec3(0, 1, 0), glm::vec3(0, -2, 0));
    EXPECT_NEAR(f.tangent.x, 1.0f, 1e-6f);
    EXPECT_LT(frameError(f), 1e-6f);
}

TEST(Frame, DegenerateHintAndAxisFallBackToDuff) {
    const Frame f = frameFromNormalAndHint(glm::vec3(1, 0, 0), glm::vec3(NAN, 0, 0));
    EXPECT_LT(frameError(f), 1e-6f);
    EXPECT_EQ(f.normal, glm::vec3(1, 0, 0));
}

TEST(Frame, RotationAboutTheNormalKeepsTheFrameOrthonormal) {
    const Frame f = frameFromNormalAndHint(glm::normalize(glm::vec3(1, 2, 3)), glm::vec3(0, 0, -1));
    for (float a = -10.0f; a < 10.0f; a += 0.37f) {
        const Frame r = rotateAboutNormal(f, a);
        EXPECT_LT(frameError(r), 1e-6f);
        EXPECT_NEAR(glm::dot(r.tangent, f.tangent), std::cos(a), 1e-5f);
    }
}

TEST(Frame, FrameErrorReportsNaN) {
    Frame f;
    f.tangent.x = NAN;
    EXPECT_TRUE(std::isinf(frameError(f)));
}
