#include "spatter/placement/ObjectIds.hpp"

#include <gtest/gtest.h>

#include <limits>

using namespace spatter;

namespace {

DBounds box(glm::dvec3 lo, glm::dvec3 hi) {
    DBounds b;
    b.extend(lo);
    b.extend(hi);
    return b;
}

} // namespace

TEST(ObjectIds, StaticObjectsGetZeroAndDynamicOnesNonZero) {
    const std::vector<DBounds> bounds = {box({0, 0, 0}, {1, 1, 1}), box({0, 0, 0}, {1, 1, 1}),
                                         box({5, 0, 0}, {6, 1, 1})};
    const ObjectIdAssignment a = assignObjectIds(bounds, {false, true, true}, 1.0, 3);
    ASSERT_EQ(a.ids.size(), 3u);
    EXPECT_EQ(a.ids[0], 0);
    EXPECT_NE(a.ids[1], 0);
    EXPECT_NE(a.ids[2], 0);
    EXPECT_EQ(a.sharedPairs, 0u);
    // Missing flags count as static.
    EXPECT_EQ(assignObjectIds(bounds, {false, true}, 1.0, 3).ids[2], 0);
}

TEST(ObjectIds, ObjectsWithinTheSeparationNeverShareAnId) {
    // 400 unit boxes on a 20 x 20 grid 1.5 apart: 0.5 gaps (diagonals 0.71), separation 1.0, so each
    // box has 8 neighbours, plenty of IDs to go round.
    std::vector<DBounds> bounds;
    for (int i = 0; i < 400; ++i) {
        const glm::dvec3 lo(1.5 * (i % 20), 0.0, 1.5 * (i / 20));
        bounds.push_back(box(lo, lo + glm::dvec3(1.0)));
    }
    const std::vector<bool> dynamic(bounds.size(), true);
    const ObjectIdAssignment a = assignObjectIds(bounds, dynamic, 1.0, 17);
    EXPECT_EQ(a.sharedPairs, 0u);
    size_t checked = 0;
    for (size_t i = 0; i < bounds.size(); ++i)
        for (size_t j = i + 1; j < bounds.size(); ++j)
            if (boundsDistance(bounds[i], bounds[j]) <= 1.0) {
                EXPECT_NE(a.ids[i], a.ids[j]) << i << " and " << j;
                ++checked;
            }
    EXPECT_GT(checked, 1000u);
    EXPECT_EQ(assignObjectIds(bounds, dynamic, 1.0, 17).ids, a.ids); // deterministic
    EXPECT_NE(assignObjectIds(bounds, dynamic, 1.0, 18).ids, a.ids); // seeded
}

TEST(ObjectIds, ReportsWhenNeighboursMustShareIds) {
    std::vector<DBounds> bounds;
    for (int i = 0; i < 300; ++i)
        bounds.push_back(box(glm::dvec3(0.001 * i), glm::dvec3(1.0 + 0.001 * i)));
    std::vector<bool> dynamic(bounds.size(), true);
    const ObjectIdAssignment a = assignObjectIds(bounds, dynamic, 0.5, 1);
    // 300 mutual neighbours and 255 IDs: at least 45 objects repeat an ID.
    EXPECT_GE(a.sharedPairs, 45u);
    for (uint8_t id : a.ids)
        EXPECT_NE(id, 0);
    dynamic[7] = false;
    EXPECT_EQ(assignObjectIds(bounds, dynamic, 0.5, 1).ids[7], 0);
}

TEST(ObjectIds, BoundsDistanceMeasuresTheGap) {
    EXPECT_EQ(boundsDistance(box({0, 0, 0}, {1, 1, 1}), box({0.5, 0.5, 0.5}, {2, 2, 2})), 0.0);
    EXPECT_DOUBLE_EQ(boundsDistance(box({0, 0, 0}, {1, 1, 1}), box({4, 5, 1}, {5, 6, 2})), 5.0);
    EXPECT_EQ(boundsDistance(DBounds(), box({0, 0, 0}, {1, 1, 1})), std::numeric_limits<double>::infinity());
}
