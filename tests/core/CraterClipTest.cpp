#include "spatter/core/CraterClip.hpp"

#include "spatter/core/Random.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace spatter;

namespace {

glm::vec3 randomDirection(Rng& rng) {
    for (;;) {
        const glm::vec3 v(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f));
        const float l = glm::length(v);
        if (l > 0.1f && l <= 1.0f) return v / l;
    }
}

} // namespace

TEST(CraterClip, PackedPlaneNeverKeepsAPointTheExactPlaneCutsAway) {
    Rng rng(7);
    for (int k = 0; k < 2000; ++k) {
        const glm::vec3 n = randomDirection(rng);
        const float offset = rng.uniform(-1.5f, 1.5f);
        const glm::vec4 packed = unpackCraterClip(packCraterClip(n, offset));
        ASSERT_NEAR(glm::length(glm::vec3(packed)), 1.0f, 1e-5f);
        EXPECT_GT(glm::dot(glm::vec3(packed), n), 0.999f); // within about 2.5 degrees
        EXPECT_LE(offset - packed.w, 0.05f);               // and it keeps nearly as much
        for (int i = 0; i < 50; ++i) {
            const glm::vec3 p = randomDirection(rng) * rng.uniform(0.0f, kCraterClipReach);
            if (glm::dot(glm::vec3(packed), p) <= packed.w) {
                EXPECT_LE(glm::dot(n, p), offset + 1e-5f);
            }
        }
    }
}

TEST(CraterClip, FarPlaneOrBadInputGivesAnInactiveClipThatKeepsEverything) {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::nanf("");
    for (const CraterClip c :
         {packCraterClip({1, 0, 0}, 3.0f), packCraterClip({0, 0, 0}, 0.5f), packCraterClip({nan, 0, 1}, 0.5f),
          packCraterClip({0, inf, 0}, 0.5f), packCraterClip({0, 0, 1}, nan), CraterClip{}}) {
        EXPECT_FALSE(c.active());
        EXPECT_EQ(unpackCraterClip(c), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    }
}

TEST(CraterClip, PlaneBeyondTheOffsetRangeStillCutsEverything) {
    const CraterClip c = packCraterClip({0, 0, 1}, -100.0f);
    ASSERT_TRUE(c.active());
    EXPECT_LE(unpackCraterClip(c).w, -kCraterClipReach);
}
