// DecalSystem::changesSince: a consumer that keeps its own copy of decals() and applies only the
// changes stays equal to decals(), byte for byte, through every kind of mutation.

#include "PlacementTestUtil.hpp"

#include "spatter/core/DecalChanges.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <vector>

using namespace spatter;
using namespace spatter::test;

namespace {

// Every byte of two decals that holds a value (all but the padding) equal, field by field.
bool sameBytes(const Decal& a, const Decal& b) {
    auto same = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof x) == 0; };
    return same(a.packedFrame, b.packedFrame) && same(a.center, b.center) && same(a.size, b.size) &&
           same(a.halfDepth, b.halfDepth) && same(a.object, b.object) && same(a.id, b.id) &&
           same(a.type, b.type) && same(a.objectId, b.objectId) && same(a.spawnTime, b.spawnTime) &&
           same(a.opacity, b.opacity) && same(a.slant, b.slant);
}
// A field added to Decal must be added to sameBytes (the record has no padding: its fields fill it).
static_assert(sizeof(glm::vec3) + sizeof(float) + sizeof(uint64_t) + sizeof(glm::vec2) + sizeof(double) +
                      2 * sizeof(uint32_t) + sizeof(uint16_t) + sizeof(uint8_t) + sizeof(Opacity) +
                      sizeof(uint32_t) ==
                  sizeof(Decal),
              "Decal has fields sameBytes does not compare");

::testing::AssertionResult sameArray(const std::vector<Decal>& a, const std::vector<Decal>& b) {
    if (a.size() != b.size()) return ::testing::AssertionFailure() << a.size() << " decals vs " << b.size();
    for (size_t i = 0; i < a.size(); ++i)
        if (!sameBytes(a[i], b[i])) return ::testing::AssertionFailure() << "decal " << i << " differs";
    return ::testing::AssertionSuccess();
}

// A consumer of the change list: its own copy of the decals, brought up to date by replaying the
// changes with a stale flag per record and reading the stale records from decals() at the end.
struct Mirror {
    std::vector<Decal> decals;
    uint64_t version = 0;
    DecalChanges changes; // reused between polls
    size_t wholeCopies = 0;
    size_t uploads = 0; // records read from decals() by the last poll

    ::testing::AssertionResult poll(const DecalSystem& s) {
        s.changesSince(version, changes);
        uploads = 0;
        if (!changes.complete) {
            if (!changes.changes.empty()) return ::testing::AssertionFailure() << "incomplete with changes";
            decals = s.decals();
            version = changes.version;
            uploads = decals.size();
            ++wholeCopies;
            return sameArray(decals, s.decals());
        }
        std::vector<uint8_t> stale(decals.size(), 0);
        for (const DecalChange& c : changes.changes) {
            switch (c.kind) {
            case DecalChangeKind::Added:
                if (c.index != decals.size() || c.from != c.index)
                    return ::testing::AssertionFailure()
                           << "Added at " << c.index << " with size " << decals.size();
                decals.emplace_back();
                stale.push_back(1);
                break;
            case DecalChangeKind::Changed:
                if (c.index >= decals.size() || c.from != c.index)
                    return ::testing::AssertionFailure()
                           << "Changed at " << c.index << " with size " << decals.size();
                stale[c.index] = 1;
                break;
            case DecalChangeKind::Removed:
                if (decals.empty() || c.from != decals.size() - 1 || c.index > c.from)
                    return ::testing::AssertionFailure()
                           << "Removed " << c.index << " from " << c.from << " with size " << decals.size();
                decals[c.index] = decals[c.from];
                stale[c.index] = stale[c.from];
                decals.pop_back();
                stale.pop_back();
                break;
            }
        }
        if (decals.size() != s.decals().size())
            return ::testing::AssertionFailure()
                   << decals.size() << " decals replayed, " << s.decals().size() << " live";
        for (size_t i = 0; i < decals.size(); ++i)
            if (stale[i]) {
                decals[i] = s.decals()[i];
                ++uploads;
            }
        version = changes.version;
        return sameArray(decals, s.decals());
    }
};

// Types for the random sequences: permanent, timed (fading during the end of its life), fading its
// whole life, jittered permanent, volumetric timed.
std::vector<uint16_t> addTypes(DecalSystem& s) {
    std::vector<uint16_t> types;
    DecalType permanent = plainType("permanent");
    permanent.fadeOutTime = 0.5f; // when evicted under FadeOldest
    types.push_back(addType(s, permanent));
    DecalType timed = plainType("timed");
    timed.lifetime = 2.0f;
    timed.fadeOutTime = 0.7f;
    types.push_back(addType(s, timed));
    DecalType brief = plainType("brief", glm::vec2(0.15f));
    brief.lifetime = 0.5f;
    brief.fadeOutTime = 0.5f;
    types.push_back(addType(s, brief));
    DecalType jitter = plainType("jitter", glm::vec2(0.2f, 0.1f));
    jitter.sizeJitter = 0.3f;
    jitter.fadeOutTime = 0.0f; // evicted at once even under FadeOldest
    types.push_back(addType(s, jitter));
    DecalType crater = plainType("crater");
    crater.volumetric = true;
    crater.lifetime = 1.5f;
    crater.fadeOutTime = 0.4f;
    types.push_back(addType(s, crater));
    return types;
}

// One random mutation of a range scene with `targets` dynamic targets (objects 2..): every spawn call,
// remove (handles live or stale), update, removeObject (rarely, the targets in turn).
void randomStep(DecalSystem& s, Rng& rng, const std::vector<uint16_t>& types,
                std::vector<DecalHandle>& handles, uint32_t& nextRemoved, uint32_t targets) {
    const uint16_t type = types[rng.below(uint32_t(types.size()))];
    const uint32_t op = rng.below(1000);
    auto keep = [&](const SpawnResult& r) {
        if (r.placed()) handles.push_back(r.handle);
    };
    if (op < 300) {
        const glm::dvec3 from(rng.uniform(-4.0f, 8.0f), rng.uniform(0.5f, 4.0f), rng.uniform(2.0f, 6.0f));
        const glm::dvec3 to(rng.uniform(-2.0f, 6.0f), rng.uniform(0.0f, 3.0f), rng.uniform(-5.0f, 0.5f));
        keep(s.spawn(ray(from, to - from), type));
    } else if (op < 420) {
        const glm::dvec3 p(rng.uniform(-4.0f, 8.0f), 0.0, rng.uniform(-4.0f, 4.0f));
        keep(s.spawnAt(p, {0.0, 1.0, 0.0}, type));
    } else if (op < 600) {
        const uint32_t object = 2 + rng.below(targets);
        const glm::vec3 p(rng.uniform(-0.4f, 0.4f), rng.uniform(-0.4f, 0.4f), 0.5f);
        keep(s.spawnAttached(object, p, {0.0f, 0.0f, 1.0f}, type));
    } else if (op < 650) {
        std::vector<Ray> rays = rayFan(1 + rng.below(24), glm::dvec3(2.0, 1.0, -2.0), 8.0, 4.0, rng.next());
        std::vector<SpawnResult> results;
        s.spawnBatch(rays, type, results);
        for (const SpawnResult& r : results)
            keep(r);
    } else if (op < 800) {
        if (!handles.empty()) {
            const size_t k = rng.below(uint32_t(handles.size()));
            s.remove(handles[k]); // may be stale
            handles[k] = handles.back();
            handles.pop_back();
        }
    } else if (op < 997) {
        static const double steps[] = {0.0, 0.02, 0.1, 0.3, 0.8};
        ASSERT_TRUE(s.update(steps[rng.below(5)]).ok());
    } else if (nextRemoved < targets) {
        ASSERT_TRUE(s.removeObject(2 + nextRemoved++).ok());
    }
}

// Under every limit policy, a long random sequence of every mutation: one consumer polling after
// every call and one every few calls both stay byte-equal to decals().
TEST(DecalChanges, ReplayedOnAMirrorTheyGiveDecalsUnderEveryMutation) {
    constexpr uint32_t kTargets = 5;
    const Scene scene = rangeScene(int(kTargets));
    for (LimitPolicy policy : {LimitPolicy::EvictOldest, LimitPolicy::FadeOldest, LimitPolicy::Reject}) {
        DecalSettings settings;
        settings.policy = policy;
        settings.maxPerCell = 3;
        settings.maxPerObject = 40;
        settings.budget = 250;
        settings.seed = 7;
        DecalSystem s = makeSystem(scene, settings);
        const std::vector<uint16_t> types = addTypes(s);
        Rng rng(1234 + uint64_t(policy));
        std::vector<DecalHandle> handles;
        uint32_t removedObjects = 0;
        Mirror eager, lazy;
        size_t changed = 0, removed = 0;
        for (int step = 0; step < 6000; ++step) {
            randomStep(s, rng, types, handles, removedObjects, kTargets);
            ASSERT_TRUE(eager.poll(s)) << "step " << step;
            for (const DecalChange& c : eager.changes.changes) {
                changed += c.kind == DecalChangeKind::Changed;
                removed += c.kind == DecalChangeKind::Removed;
            }
            if (step % 37 == 0 || rng.below(10) == 0) {
                ASSERT_TRUE(lazy.poll(s)) << "step " << step;
            }
        }
        ASSERT_TRUE(lazy.poll(s));
        EXPECT_EQ(eager.wholeCopies, 0u);
        EXPECT_EQ(lazy.wholeCopies, 0u);
        EXPECT_EQ(eager.version, s.version());
        EXPECT_GT(s.stats().placed, 1000u);
        EXPECT_GT(changed, 200u);
        EXPECT_GT(removed, 500u);
        if (policy == LimitPolicy::FadeOldest) {
            EXPECT_GT(s.stats().evicted, 50u);
        }
        // Version = entries logged: one per placement and removal, plus the opacity changes.
        EXPECT_EQ(s.version(), s.stats().placed + (s.stats().placed - s.stats().alive) + changed);
    }
}

// A consumer that polled too rarely gets complete == false, takes decals() whole, and from there on
// follows the changes again; versions within the newest half of the bound stay available.
TEST(DecalChanges, AConsumerBehindTheBoundTakesTheDecalsWholeAndRecovers) {
    DecalSettings settings;
    settings.budget = 50;
    settings.maxPerCell = 1000;
    settings.maxPerObject = 1000;
    DecalSystem s = makeSystem(rangeScene(1), settings);
    const uint16_t type = addType(s, plainType());
    Rng rng(5);
    auto spawnSome = [&](int n) {
        for (int i = 0; i < n; ++i)
            ASSERT_TRUE(s.spawnAttached(2, {rng.uniform(-0.4f, 0.4f), rng.uniform(-0.4f, 0.4f), 0.5f},
                                        {0, 0, 1}, type)
                            .placed());
    };
    spawnSome(10);
    Mirror behind;
    ASSERT_TRUE(behind.poll(s));
    EXPECT_EQ(behind.wholeCopies, 0u);
    spawnSome(5000); // past the budget each spawn evicts one: two entries per spawn, 4096 kept at most
    EXPECT_EQ(s.version(), 10u + 2u * 5000u - 40u);

    const DecalChanges lost = s.changesSince(behind.version);
    EXPECT_FALSE(lost.complete);
    EXPECT_TRUE(lost.changes.empty());
    EXPECT_EQ(lost.version, s.version());
    ASSERT_TRUE(behind.poll(s));
    EXPECT_EQ(behind.wholeCopies, 1u);
    EXPECT_EQ(behind.version, s.version());
    spawnSome(30);
    ASSERT_TRUE(behind.poll(s));
    EXPECT_EQ(behind.wholeCopies, 1u);
    EXPECT_EQ(behind.uploads, 30u);

    // The log always keeps at least the newest 2048 entries and never more than 4096 (under 16384
    // decals).
    for (int round = 0; round < 3; ++round) {
        spawnSome(int(rng.below(3000)));
        const uint64_t now = s.version();
        const DecalChanges kept = s.changesSince(now - 2048);
        EXPECT_TRUE(kept.complete);
        EXPECT_EQ(kept.changes.size(), 2048u);
        EXPECT_FALSE(s.changesSince(now - 4097).complete);
    }
}

TEST(DecalChanges, TheCurrentVersionHasNoChangesAndAFutureOneIsUnknown) {
    DecalSystem s = makeSystem(boxScene());
    EXPECT_EQ(s.version(), 0u);
    DecalChanges c = s.changesSince(0);
    EXPECT_TRUE(c.complete);
    EXPECT_TRUE(c.changes.empty());
    EXPECT_EQ(c.version, 0u);
    const uint16_t type = addType(s, plainType());
    ASSERT_TRUE(s.spawn(ray({0.0, 0.0, 3.0}, {0.0, 0.0, -1.0}), type).placed());
    ASSERT_TRUE(s.spawn(ray({0.2, 0.0, 3.0}, {0.0, 0.0, -1.0}), type).placed());
    EXPECT_EQ(s.version(), 2u);

    // The overload reuses and overwrites what `out` held.
    c.changes.assign(100, DecalChange{7, 7, DecalChangeKind::Changed});
    c.complete = false;
    s.changesSince(s.version(), c);
    EXPECT_TRUE(c.complete);
    EXPECT_TRUE(c.changes.empty());
    EXPECT_EQ(c.version, 2u);
    EXPECT_GE(c.changes.capacity(), 100u);

    s.changesSince(0, c);
    ASSERT_TRUE(c.complete);
    ASSERT_EQ(c.changes.size(), 2u);
    EXPECT_EQ(c.changes[0].kind, DecalChangeKind::Added);
    EXPECT_EQ(c.changes[0].index, 0u);
    EXPECT_EQ(c.changes[1].index, 1u);

    for (uint64_t future : {uint64_t(3), uint64_t(1000), UINT64_MAX}) {
        s.changesSince(future, c);
        EXPECT_FALSE(c.complete) << future;
        EXPECT_TRUE(c.changes.empty()) << future;
        EXPECT_EQ(c.version, 2u) << future;
    }
}

TEST(DecalChanges, UpdateLogsNothingForPermanentDecals) {
    DecalSettings settings;
    settings.maxPerCell = 1000;
    DecalSystem s = makeSystem(rangeScene(1), settings);
    const uint16_t type = addType(s, plainType());
    for (int i = 0; i < 200; ++i)
        ASSERT_TRUE(s.spawnAttached(2, {-0.4f + 0.004f * float(i), 0.1f, 0.5f}, {0, 0, 1}, type).placed());
    const uint64_t v = s.version();
    EXPECT_EQ(v, 200u);
    for (double dt : {0.0, 0.5, 1000.0, 1e9})
        ASSERT_TRUE(s.update(dt).ok());
    EXPECT_EQ(s.version(), v);
    EXPECT_TRUE(s.changesSince(v).changes.empty());
    for (const Decal& d : s.decals())
        EXPECT_EQ(d.opacity, 1.0f);
}

TEST(DecalChanges, AFadingDecalLogsAChangeEachUpdateItsOpacityChanges) {
    DecalSystem s = makeSystem(rangeScene(1));
    DecalType fading = plainType("fading");
    fading.lifetime = 2.0f;
    fading.fadeOutTime = 1.0f;
    const uint16_t type = addType(s, fading);
    const uint16_t permanent = addType(s, plainType("permanent"));
    ASSERT_TRUE(s.spawnAttached(2, {0.0f, 0.0f, 0.5f}, {0, 0, 1}, permanent).placed());
    ASSERT_TRUE(s.spawnAttached(2, {0.2f, 0.0f, 0.5f}, {0, 0, 1}, type).placed());
    ASSERT_TRUE(s.spawnAttached(2, {-0.2f, 0.0f, 0.5f}, {0, 0, 1}, permanent).placed());
    uint64_t v = s.version();
    auto expectOnly = [&](DecalChangeKind kind, uint32_t index, const char* what) {
        const DecalChanges c = s.changesSince(v);
        ASSERT_TRUE(c.complete) << what;
        ASSERT_EQ(c.changes.size(), 1u) << what;
        EXPECT_EQ(c.changes[0].kind, kind) << what;
        EXPECT_EQ(c.changes[0].index, index) << what;
        v = c.version;
    };
    ASSERT_TRUE(s.update(0.75).ok()); // age 0.75: still opaque
    EXPECT_EQ(s.version(), v);
    ASSERT_TRUE(s.update(0.5).ok()); // age 1.25: fading
    expectOnly(DecalChangeKind::Changed, 1, "fading");
    EXPECT_EQ(s.decals()[1].opacity.bits(), Opacity(0.75f).bits()); // kept in steps of 1/255
    ASSERT_TRUE(s.update(0.0).ok());                                // same age, same opacity
    EXPECT_EQ(s.version(), v);
    ASSERT_TRUE(s.update(0.25).ok());
    expectOnly(DecalChangeKind::Changed, 1, "fading further");
    ASSERT_TRUE(s.update(1.0).ok()); // expired: the last decal moves into its index
    {
        const DecalChanges c = s.changesSince(v);
        ASSERT_EQ(c.changes.size(), 1u);
        EXPECT_EQ(c.changes[0].kind, DecalChangeKind::Removed);
        EXPECT_EQ(c.changes[0].index, 1u);
        EXPECT_EQ(c.changes[0].from, 2u);
        v = c.version;
    }
    ASSERT_TRUE(s.update(5.0).ok());
    EXPECT_EQ(s.version(), v);

    // A permanent decal evicted under FadeOldest fades from then on.
    DecalSettings settings;
    settings.policy = LimitPolicy::FadeOldest;
    settings.maxPerObject = 2;
    DecalSystem f = makeSystem(rangeScene(1), settings);
    DecalType slow = plainType("slow");
    slow.fadeOutTime = 2.0f;
    const uint16_t slowType = addType(f, slow);
    Mirror mirror;
    for (int i = 0; i < 3; ++i)
        ASSERT_TRUE(f.spawnAttached(2, {-0.3f + 0.3f * float(i), 0.0f, 0.5f}, {0, 0, 1}, slowType).placed());
    ASSERT_TRUE(mirror.poll(f));
    EXPECT_EQ(mirror.version, 3u); // the eviction itself changes no decal
    for (int i = 0; i < 3; ++i) {
        ASSERT_TRUE(f.update(0.5).ok());
        ASSERT_TRUE(mirror.poll(f));
        ASSERT_EQ(mirror.changes.changes.size(), 1u);
        EXPECT_EQ(mirror.changes.changes[0].kind, DecalChangeKind::Changed);
        EXPECT_EQ(mirror.changes.changes[0].index, 0u);
        EXPECT_EQ(mirror.uploads, 1u);
    }
    ASSERT_TRUE(f.update(0.5).ok()); // the fade ends
    ASSERT_TRUE(mirror.poll(f));
    ASSERT_EQ(mirror.changes.changes.size(), 1u);
    EXPECT_EQ(mirror.changes.changes[0].kind, DecalChangeKind::Removed);
    EXPECT_EQ(f.decals().size(), 2u);
    EXPECT_EQ(mirror.uploads, 0u); // the record that moved was up to date
}

TEST(DecalChanges, ACallThatChangesNoDecalLogsNothing) {
    DecalSettings settings;
    settings.policy = LimitPolicy::Reject;
    settings.maxPerCell = 1;
    settings.cellSize = 1.0f;
    DecalSystem s = makeSystem(rangeScene(2), settings);
    DecalType t = plainType();
    t.maxAngleDeg = 30.0f;
    t.onDynamic = false;
    const uint16_t type = addType(s, t);
    ASSERT_TRUE(s.spawn(ray({0.2, 1.3, 0.0}, {0.0, 0.0, -1.0}), type).placed());
    const uint64_t v = s.version();
    EXPECT_EQ(v, 1u);
    EXPECT_EQ(s.spawn(ray({0.3, 1.3, 0.0}, {0.0, 0.0, -1.0}), type).status, SpawnStatus::AreaLimit);
    EXPECT_EQ(s.spawn(ray({0.0, 1.0, 3.0}, {0.0, 1.0, 0.0}), type).status, SpawnStatus::Missed);
    EXPECT_EQ(s.spawn(ray({0.0, 1.0, 3.0}, {0.0, 0.0, 0.0}), type).status, SpawnStatus::InvalidRay);
    EXPECT_EQ(s.spawn(ray({0.2, 1.3, 0.0}, {0.0, 0.0, -1.0}), 9).status, SpawnStatus::InvalidType);
    EXPECT_EQ(s.spawn(ray({-3.0, 0.5, 3.0}, {1.0, -0.1, -1.0}), type).status, SpawnStatus::GrazingAngle);
    EXPECT_EQ(s.spawnAttached(2, {0.0f, 0.0f, 0.5f}, {0, 0, 1}, type).status, SpawnStatus::NotReceiver);
    EXPECT_EQ(s.spawnAt({3.0, 0.0, 3.0}, {0.0, 0.0, 0.0}, type).status, SpawnStatus::InvalidArgument);
    std::vector<SpawnResult> results;
    s.spawnBatch({ray({0.0, 10.0, 0.0}, {0.0, 1.0, 0.0})}, type, results);
    EXPECT_EQ(results[0].status, SpawnStatus::Missed);
    EXPECT_FALSE(s.remove(DecalHandle{}));
    EXPECT_TRUE(s.setTransform(2, glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 1.0, 3.0))).ok());
    EXPECT_TRUE(s.removeObject(3).ok()); // no decals on it
    ASSERT_TRUE(s.update(1.0).ok());
    EXPECT_EQ(s.version(), v);
    EXPECT_TRUE(s.changesSince(v).changes.empty());
    EXPECT_EQ(s.stats().rejectedTotal(), 8u);
}

// The state update() keeps of a decal, as the test can see it without fading evictions: what a walk
// over every decal from the last down gives, removing expired ones by moving the last into the hole.
void referenceUpdate(std::vector<Decal>& decals, const DecalSystem& s, double time) {
    for (size_t i = decals.size(); i-- > 0;) {
        Decal& d = decals[i];
        const DecalType& t = *s.type(d.type);
        float opacity = 1.0f;
        if (t.lifetime > 0.0f) {
            const double age = time - d.spawnTime;
            if (age >= double(t.lifetime)) {
                decals[i] = decals.back();
                decals.pop_back();
                continue;
            }
            const double fadeStart = std::max(0.0, double(t.lifetime) - double(t.fadeOutTime));
            if (age > fadeStart)
                opacity = float((double(t.lifetime) - age) / (double(t.lifetime) - fadeStart));
        }
        d.opacity = opacity;
    }
}

// update() visits only the decals that can change, yet leaves decals() exactly as the walk over all
// of them does, across thousands of decals with few timed ones spread among them.
TEST(DecalChanges, UpdateVisitingTimedDecalsOnlyMatchesTheWalkOverAllDecals) {
    DecalSettings settings;
    settings.budget = 20000;
    settings.maxPerCell = 20000;
    settings.maxPerObject = 20000;
    DecalSystem s = makeSystem(rangeScene(2), settings);
    const uint16_t permanent = addType(s, plainType("permanent"));
    std::vector<uint16_t> timed;
    for (int k = 0; k < 4; ++k) {
        DecalType t = plainType("timed" + std::to_string(k));
        t.lifetime = 0.5f + 0.75f * float(k);
        t.fadeOutTime = 0.4f * float(k);
        timed.push_back(addType(s, t));
    }
    Rng rng(77);
    std::vector<DecalHandle> handles;
    Mirror mirror;
    for (int round = 0; round < 12; ++round) {
        const int spawns = round < 3 ? 3000 : 300;
        for (int i = 0; i < spawns; ++i) {
            const uint32_t pick = rng.below(100);
            const uint16_t type = pick < 90 ? permanent : timed[pick % timed.size()];
            const SpawnResult r =
                s.spawnAttached(2 + rng.below(2), {rng.uniform(-0.4f, 0.4f), rng.uniform(-0.4f, 0.4f), 0.5f},
                                {0, 0, 1}, type);
            ASSERT_TRUE(r.placed()) << r.reason;
            handles.push_back(r.handle);
        }
        for (int i = 0; i < 100 && !handles.empty(); ++i) {
            const size_t k = rng.below(uint32_t(handles.size()));
            s.remove(handles[k]);
            handles[k] = handles.back();
            handles.pop_back();
        }
        for (int u = 0; u < 3; ++u) {
            std::vector<Decal> expected = s.decals();
            const double dt = 0.1 + 0.2 * rng.uniform();
            const uint64_t expired = s.stats().expired;
            ASSERT_TRUE(s.update(dt).ok());
            referenceUpdate(expected, s, s.time());
            ASSERT_TRUE(sameArray(expected, s.decals())) << "round " << round << ", update " << u;
            EXPECT_EQ(s.stats().expired - expired,
                      s.stats().placed - s.stats().removed - s.stats().alive - expired);
            ASSERT_TRUE(mirror.poll(s));
        }
    }
    EXPECT_GT(s.decals().size(), 5000u);
    EXPECT_GT(s.stats().expired, 500u);
}

} // namespace
