// DecalSystem::memory: the bytes a decal system holds for its decals, by what they serve.

#include "PlacementTestUtil.hpp"

#include "spatter/core/DecalChanges.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <gtest/gtest.h>

using namespace spatter;
using namespace spatter::test;

namespace {

constexpr int kDecals = 1000;

// A system of `settings` with kDecals decals spawned on the range's first target, in cells small
// enough that no limit removes one, and a budget of `budget` decals (no fewer than kDecals).
DecalSystem withDecals(DecalSettings settings, uint32_t budget = 2 * kDecals) {
    settings.budget = budget;
    settings.cellSize = 0.01f;
    DecalSystem s = makeSystem(rangeScene(1), settings);
    const uint16_t type = addType(s, plainType());
    Rng rng(9);
    for (int i = 0; i < kDecals; ++i)
        EXPECT_TRUE(
            s.spawnAttached(2, {rng.uniform(-0.4f, 0.4f), rng.uniform(-0.4f, 0.4f), 0.5f}, {0, 0, 1}, type)
                .placed());
    return s;
}

} // namespace

TEST(DecalSystemMemory, CountsTheRecordsHandlesAreaListsAndChangesOfItsDecals) {
    const DecalSystem s = withDecals({});
    ASSERT_EQ(s.decals().size(), size_t(kDecals));
    const DecalSystemMemory m = s.memory();
    EXPECT_EQ(m.records, s.decals().capacity() * sizeof(Decal));
    // A slot (its dense index and generation) and the decal's slot index each.
    EXPECT_GE(m.handles, size_t(kDecals) * 12);
    // The world's and the object's spawn order (two 32-bit links in each), the cell's (one: the default
    // cell limit lets a walk find the link back), and a cell index.
    EXPECT_GE(m.areaLimits, size_t(kDecals) * (2 * 8 + 4 + 4));
    EXPECT_GE(m.changeLog, size_t(kDecals) * 5); // every spawn is still there: its index and kind
    EXPECT_EQ(m.total(), m.records + m.handles + m.areaLimits + m.changeLog + m.other);
}

TEST(DecalSystemMemory, LimitsAtTheBudgetKeepNoSpawnOrderOfTheirOwn) {
    DecalSettings open;
    open.maxPerCell = 2 * kDecals;
    open.maxPerObject = 2 * kDecals;
    const DecalSystemMemory ordered = withDecals({}).memory();
    const DecalSystemMemory unordered = withDecals(open).memory();
    // Without a cell's or an object's order each counted decal keeps 12 bytes of links fewer.
    EXPECT_LE(unordered.areaLimits + size_t(kDecals) * 12, ordered.areaLimits);
    EXPECT_EQ(unordered.records, ordered.records);
}

TEST(DecalSystemMemory, SmallCellLimitsKeepOneLinkPerDecalInTheCellsOrder) {
    DecalSettings small, large;
    small.maxPerCell = kSmallCellLimit;
    large.maxPerCell = kSmallCellLimit + 1;
    // At the budget the per-decal arrays hold exactly what they need (CappedGrowth.hpp).
    const DecalSystemMemory singly = withDecals(small, kDecals).memory();
    const DecalSystemMemory doubly = withDecals(large, kDecals).memory();
    EXPECT_LE(singly.areaLimits + size_t(kDecals) * 4, doubly.areaLimits);
}
