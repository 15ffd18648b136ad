// Saving and loading a DecalSystem (DecalPersistence.hpp): a load carries on bit for bit where the
// save stopped, in this process and in another one, under every limit policy; objects that no longer
// match drop their decals; every kind of bad input is refused and leaves the system as it was.

#include "spatter/placement/DecalPersistence.hpp"
#include "PlacementTestUtil.hpp"
#include "spatter/core/SkinnedArm.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace spatter::test {
namespace {

constexpr uint32_t kHalf = 10000; // spawn steps before and after the save

const char* kChildVariable = "SPATTER_PERSISTENCE_CHILD";

std::string policyName(LimitPolicy p) {
    return p == LimitPolicy::EvictOldest  ? "EvictOldest"
           : p == LimitPolicy::FadeOldest ? "FadeOldest"
                                          : "Reject";
}

DecalSettings settingsFor(LimitPolicy policy) {
    DecalSettings s;
    s.seed = 77;
    s.policy = policy;
    s.budget = 1200;
    s.maxPerCell = 6;
    s.maxPerObject = 300;
    return s;
}

std::vector<DecalType> gameTypes() {
    DecalType hole;
    hole.name = "hole";
    hole.fadeOutTime = 0.5f;
    DecalType scorch;
    scorch.name = "scorch";
    scorch.size = glm::vec2(0.3f, 0.2f);
    scorch.sizeJitter = 0.3f;
    scorch.lifetime = 3.0f;
    scorch.fadeOutTime = 1.0f;
    DecalType crater;
    crater.name = "crater";
    crater.volumetric = true;
    crater.size = glm::vec2(0.15f);
    return {hole, scorch, crater};
}

DecalSystem gameSystem(LimitPolicy policy, bool reversedTypes = false) {
    DecalSystem s = makeSystem(rangeScene(3), settingsFor(policy));
    std::vector<DecalType> types = gameTypes();
    if (reversedTypes) std::reverse(types.begin(), types.end());
    for (const DecalType& t : types)
        addType(s, t);
    return s;
}

glm::dmat4 targetPose(uint32_t target, uint32_t step) {
    const double t = 0.001 * step + target;
    glm::dmat4 m =
        glm::translate(glm::dmat4(1.0), glm::dvec3(2.0 * target + 0.5 * std::sin(t), 1.0, 0.3 * t - 3.0));
    m = glm::rotate(m, 0.3 + t, glm::dvec3(0.0, 1.0, 0.0));
    return glm::scale(m, glm::dvec3(0.5 + 0.25 * target));
}

Ray shot(uint32_t step, uint32_t k) {
    Rng rng(step * 16u + k + 1u);
    const glm::dvec3 eye(rng.uniform(-6.0f, 6.0f), rng.uniform(0.5f, 4.0f), rng.uniform(4.0f, 8.0f));
    const glm::dvec3 aim(rng.uniform(-6.0f, 8.0f), rng.uniform(-0.5f, 3.0f), rng.uniform(-5.2f, 1.0f));
    return ray(eye, aim - eye);
}

// The game's calls for steps [from, to): moving targets, spawns of every kind, batches, the clock,
// removals of its own handles and, once, the removal of an object. The same steps give the same calls
// whether or not the system was saved and loaded in between.
void play(DecalSystem& s, uint32_t from, uint32_t to) {
    std::vector<DecalHandle> handles;
    std::vector<SpawnResult> batch;
    for (uint32_t step = from; step < to; ++step) {
        const uint16_t type = uint16_t(step % 3);
        if (step % 50 == 0)
            for (uint32_t target = 0; target < 3; ++target)
                s.setTransform(2 + target, targetPose(target, step));
        if (step % 97 == 0) {
            ASSERT_TRUE(s.update(0.05).ok());
        }
        if (step == 5000 || step == 15000) s.removeObject(step == 5000 ? 4 : 3);
        SpawnResult r;
        if (step % 13 == 0) {
            s.spawnBatch({shot(step, 0), shot(step, 1), shot(step, 2)}, type, batch);
            r = batch.front();
        } else if (step % 11 == 0) {
            r = s.spawnAttached(step % 2, glm::vec3(float(step % 17) - 8.0f, 0.1f, -1.0f), glm::vec3(0, 1, 0),
                                type);
        } else if (step % 7 == 0) {
            r = s.spawnAt(glm::dvec3(double(step % 19) - 9.0, 0.0, 0.5), glm::dvec3(0, 1, 0), type);
        } else {
            r = s.spawn(shot(step, 0), type);
        }
        if (r.placed()) handles.push_back(r.handle);
        if (step % 23 == 0 && handles.size() > 7) s.remove(handles[handles.size() - 7]);
    }
}

std::vector<uint8_t> saved(const DecalSystem& s) {
    return saveDecals(s);
}

DecalLoadReport load(DecalSystem& s, const std::vector<uint8_t>& bytes) {
    Result<DecalLoadReport> r = loadDecals(s, bytes.data(), bytes.size());
    EXPECT_TRUE(r.ok()) << r.error();
    return r.ok() ? r.value() : DecalLoadReport{};
}

::testing::AssertionResult sameSystem(const DecalSystem& a, const DecalSystem& b) {
    if (::testing::AssertionResult r = sameDecals(a.decals(), b.decals()); !r) return r;
    for (size_t i = 0; i < a.decals().size(); ++i)
        if (!(a.craterClips(i) == b.craterClips(i)))
            return ::testing::AssertionFailure() << "decal " << i << ": crater clips differ";
    if (a.stats() != b.stats()) return ::testing::AssertionFailure() << "statistics differ";
    if (a.version() != b.version()) return ::testing::AssertionFailure() << "versions differ";
    const std::vector<uint8_t> sa = saved(a), sb = saved(b);
    if (sa != sb) {
        size_t at = 0;
        while (at < std::min(sa.size(), sb.size()) && sa[at] == sb[at])
            ++at;
        std::string section = "header";
        for (size_t s = 32; s + 12 <= sa.size() && s <= at;) {
            section.assign(reinterpret_cast<const char*>(&sa[s]), 4);
            uint64_t length = 0;
            std::memcpy(&length, &sa[s + 4], 8);
            s += 12 + size_t(length);
        }
        return ::testing::AssertionFailure() << "saves differ from byte " << at << " (section " << section
                                             << "; " << sa.size() << " and " << sb.size() << " bytes)";
    }
    return ::testing::AssertionSuccess();
}

std::vector<uint8_t> readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A reference CRC-32 (ISO-HDLC), bit by bit.
uint32_t crc32(const std::vector<uint8_t>& b, size_t begin, size_t end, uint32_t crc = 0xFFFFFFFFu) {
    for (size_t i = begin; i < end; ++i) {
        crc ^= b[i];
        for (int k = 0; k < 8; ++k)
            crc = (crc & 1u) ? (crc >> 1) ^ 0xEDB88320u : crc >> 1;
    }
    return crc;
}

// The checksum of an edited save put right, so that the edit itself is what a load meets.
void reseal(std::vector<uint8_t>& b) {
    const uint32_t crc = ~crc32(b, 28, b.size(), crc32(b, 0, 24));
    for (int i = 0; i < 4; ++i)
        b[24 + i] = uint8_t(crc >> (8 * i));
}

// The offset of the payload of section `tag`.
size_t sectionAt(const std::vector<uint8_t>& b, const char* tag) {
    for (size_t at = 32; at + 12 <= b.size();) {
        uint64_t length = 0;
        std::memcpy(&length, &b[at + 4], 8);
        if (std::memcmp(&b[at], tag, 4) == 0) return at + 12;
        at += 12 + size_t(length);
    }
    ADD_FAILURE() << "no section " << tag;
    return 0;
}

size_t decalCount(const std::vector<uint8_t>& b) {
    uint32_t n = 0;
    std::memcpy(&n, &b[sectionAt(b, "DECL")], 4);
    return n;
}

// The offset of the DECL section's type column: past the records, the opacities and the clips.
size_t integerColumnsAt(const std::vector<uint8_t>& b) {
    const size_t n = decalCount(b);
    size_t at = sectionAt(b, "DECL") + 4 + n * 44;
    for (size_t valueBytes : {1, 8, 4}) { // opacities, clips, slants: absent, dense or sparse
        const uint8_t kind = b[at++];
        if (kind == 1) at += n * valueBytes;
        if (kind != 2) continue;
        uint32_t count = 0;
        std::memcpy(&count, &b[at], 4);
        at += 4;
        at += 1 + size_t(count) * (b[at] + valueBytes);
    }
    return at;
}

void put32(std::vector<uint8_t>& b, size_t at, uint32_t v) {
    for (int i = 0; i < 4; ++i)
        b[at + i] = uint8_t(v >> (8 * i));
}

class RoundTrip : public ::testing::TestWithParam<LimitPolicy> {};

TEST_P(RoundTrip, LoadedSystemContinuesExactlyLikeOneThatNeverStopped) {
    DecalSystem reference = gameSystem(GetParam());
    play(reference, 0, kHalf);
    const std::vector<uint8_t> bytes = saved(reference);
    DecalSystem loaded = gameSystem(GetParam());
    const DecalLoadReport report = load(loaded, bytes);
    EXPECT_EQ(report.droppedDecals, 0u);
    EXPECT_EQ(report.decals, reference.decals().size());
    EXPECT_TRUE(sameSystem(loaded, reference));
    size_t clipped = 0; // craters whose clip planes the comparison covers
    for (size_t i = 0; i < loaded.decals().size(); ++i)
        clipped += loaded.craterClips(i).any() ? 1 : 0;
    EXPECT_GT(clipped, 0u);
    play(reference, kHalf, 2 * kHalf);
    play(loaded, kHalf, 2 * kHalf);
    const DecalStats& stats = reference.stats();
    EXPECT_GT(stats.evicted + stats.rejected[size_t(SpawnStatus::AreaLimit)], 0u);
    EXPECT_TRUE(sameSystem(loaded, reference));
    const DecalChanges a = reference.changesSince(reference.version() - 100);
    const DecalChanges b = loaded.changesSince(loaded.version() - 100);
    ASSERT_TRUE(a.complete && b.complete);
    ASSERT_EQ(a.changes.size(), b.changes.size());
    for (size_t i = 0; i < a.changes.size(); ++i) { // field by field: a DecalChange has padding
        EXPECT_EQ(a.changes[i].index, b.changes[i].index) << i;
        EXPECT_EQ(a.changes[i].from, b.changes[i].from) << i;
        EXPECT_EQ(a.changes[i].kind, b.changes[i].kind) << i;
    }
}

// Run by LoadedInAnotherProcess: loads the save named by the environment, plays the second half and
// saves the result.
TEST_P(RoundTrip, ChildProcessContinuesTheSave) {
    const char* job = std::getenv(kChildVariable);
    if (!job) GTEST_SKIP() << "run by LoadedInAnotherProcessContinuesExactly";
    std::istringstream args(job);
    std::string in, out;
    args >> in >> out;
    DecalSystem s = gameSystem(GetParam());
    Result<DecalLoadReport> r = loadDecalsFromFile(s, in);
    ASSERT_TRUE(r.ok()) << r.error();
    play(s, kHalf, 2 * kHalf);
    ASSERT_TRUE(saveDecalsToFile(s, out).ok());
}

TEST_P(RoundTrip, LoadedInAnotherProcessContinuesExactly) {
    if (std::getenv(kChildVariable)) GTEST_SKIP() << "in the child process";
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("spatter-persistence-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string in = (dir / "half.save").string(), out = (dir / "whole.save").string();
    DecalSystem reference = gameSystem(GetParam());
    play(reference, 0, kHalf);
    ASSERT_TRUE(saveDecalsToFile(reference, in).ok());
    play(reference, kHalf, 2 * kHalf);

    const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
    const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name();
    const std::string param = policyName(GetParam());
    const std::string command = std::string(kChildVariable) + "='" + in + " " + out + "' '" + self +
                                "' --gtest_filter='" + name + ".ChildProcessContinuesTheSave/" + param +
                                "' > '" + (dir / "child.log").string() + "' 2>&1";
    const int status = std::system(command.c_str());
    std::ifstream log(dir / "child.log");
    const std::string childLog((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    ASSERT_EQ(status, 0) << childLog;
    ASSERT_NE(childLog.find("[  PASSED  ] 1 test"), std::string::npos) << childLog;
    EXPECT_TRUE(readFile(out) == saved(reference)) << "the other process's system differs from this one's";
    std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(EveryPolicy, RoundTrip,
                         ::testing::Values(LimitPolicy::EvictOldest, LimitPolicy::FadeOldest,
                                           LimitPolicy::Reject),
                         [](const ::testing::TestParamInfo<LimitPolicy>& p) { return policyName(p.param); });

class DecalPersistence : public ::testing::Test {
protected:
    void SetUp() override {
        play(source, 0, 1500);
        bytes = saved(source);
    }
    // Loads `b` into a fresh system, expects an error containing `what`, and the system unchanged.
    void expectRefused(const std::vector<uint8_t>& b, const std::string& what) {
        DecalSystem target = gameSystem(LimitPolicy::EvictOldest);
        play(target, 0, 40);
        const std::vector<uint8_t> before = saved(target);
        Result<DecalLoadReport> r = loadDecals(target, b.data(), b.size());
        ASSERT_FALSE(r.ok()) << "expected an error with '" << what << "'";
        EXPECT_NE(r.error().find(what), std::string::npos) << r.error();
        EXPECT_EQ(r.error().rfind("decal save: ", 0), 0u) << r.error();
        EXPECT_TRUE(saved(target) == before) << "a refused load changed the system";
    }
    DecalSystem source = gameSystem(LimitPolicy::FadeOldest);
    std::vector<uint8_t> bytes;
};

TEST_F(DecalPersistence, TypesRegisteredInAnotherOrderAreMatchedByName) {
    DecalSystem loaded = gameSystem(LimitPolicy::FadeOldest, true);
    load(loaded, bytes);
    ASSERT_EQ(loaded.decals().size(), source.decals().size());
    for (size_t i = 0; i < loaded.decals().size(); ++i)
        EXPECT_EQ(loaded.type(loaded.decals()[i].type)->name, source.type(source.decals()[i].type)->name);
}

TEST_F(DecalPersistence, HandlesKeptAcrossASaveAndALoadFindTheSameDecals) {
    std::vector<DecalHandle> handles;
    for (uint32_t k = 0; k < 40; ++k)
        if (SpawnResult r = source.spawn(shot(90000 + k, 0), 0); r.placed()) handles.push_back(r.handle);
    ASSERT_GT(handles.size(), 10u);
    ASSERT_TRUE(source.remove(handles[3]));
    DecalSystem loaded = gameSystem(LimitPolicy::FadeOldest);
    load(loaded, saved(source));
    for (const DecalHandle& h : handles) {
        const Decal* a = source.get(h);
        const Decal* b = loaded.get(h);
        ASSERT_EQ(a == nullptr, b == nullptr);
        if (a) {
            EXPECT_TRUE(sameDecal(*a, *b));
        }
    }
    EXPECT_EQ(loaded.get(handles[3]), nullptr);
}

// Decals counted in cells of an object's space taken under a scale the object no longer has: the save
// names their cells, and the limits evict after the load as they would have.
TEST_F(DecalPersistence, CellsTakenUnderAnEarlierScaleComeBack) {
    DecalSettings settings = settingsFor(LimitPolicy::EvictOldest);
    settings.maxPerCell = 3;
    DecalSystem reference = makeSystem(rangeScene(3), settings);
    addType(reference, gameTypes()[0]);
    auto spawnRow = [](DecalSystem& s, float z) {
        for (int i = 0; i < 12; ++i)
            s.spawnAttached(2, glm::vec3(0.08f * float(i) - 0.45f, 0.5f, z), glm::vec3(0, 1, 0), 0);
    };
    spawnRow(reference, 0.1f);
    reference.setTransform(2, glm::scale(targetPose(0, 0), glm::dvec3(3.0)));
    const std::vector<uint8_t> b = saved(reference);
    const size_t limits = sectionAt(b, "LIMS");
    uint32_t counted = 0;
    std::memcpy(&counted, &b[limits], 4);
    uint32_t exceptions = 0;
    std::memcpy(&exceptions, &b[limits + 4 + 1 + size_t(counted) * b[limits + 4]], 4);
    EXPECT_GT(exceptions, 0u);

    DecalSystem loaded = makeSystem(rangeScene(3), settings);
    addType(loaded, gameTypes()[0]);
    load(loaded, b);
    spawnRow(reference, 0.12f);
    spawnRow(loaded, 0.12f);
    EXPECT_GT(reference.stats().evicted, 0u);
    EXPECT_TRUE(sameSystem(loaded, reference));
}

TEST_F(DecalPersistence, LoadReplacesEverythingTheSystemHeld) {
    DecalSystem target = gameSystem(LimitPolicy::EvictOldest);
    play(target, 20000, 20400); // another history: other decals, clock, limits and object places
    load(target, bytes);
    EXPECT_TRUE(sameSystem(target, source));
    play(source, 1500, 2500);
    play(target, 1500, 2500);
    EXPECT_TRUE(sameSystem(target, source));
}

TEST_F(DecalPersistence, StreamAndBufferGiveTheSameSystem) {
    std::stringstream stream;
    ASSERT_TRUE(saveDecals(source, stream).ok());
    EXPECT_TRUE(stream.str() == std::string(bytes.begin(), bytes.end()));
    DecalSystem loaded = gameSystem(LimitPolicy::FadeOldest);
    Result<DecalLoadReport> r = loadDecals(loaded, stream);
    ASSERT_TRUE(r.ok()) << r.error();
    EXPECT_TRUE(sameSystem(loaded, source));
}

TEST_F(DecalPersistence, TakesAtMostADecalRecordPerDecalPlusAFixedPart) {
    DecalSettings roomy = settingsFor(LimitPolicy::EvictOldest);
    roomy.budget = roomy.maxPerObject = 100000;
    roomy.maxPerCell = 1000;
    DecalSystem big = makeSystem(rangeScene(3), roomy);
    for (const DecalType& t : gameTypes())
        addType(big, t);
    play(big, 0, kHalf);
    const size_t n = big.decals().size();
    ASSERT_GT(n, 2000u);
    // Fixed: header, settings, objects, types and the change log's floor of 4096 entries.
    EXPECT_LE(saved(big).size(), n * sizeof(Decal) + 64 * 1024);
}

TEST_F(DecalPersistence, ObjectWithAnotherMeshDropsItsDecals) {
    Scene scene = rangeScene(3);
    scene.objects[2].mesh = shareMesh(makeBox(glm::vec3(0.5f), 2));
    DecalSystem loaded = makeSystem(scene, settingsFor(LimitPolicy::FadeOldest));
    for (const DecalType& t : gameTypes())
        addType(loaded, t);
    size_t onTarget = 0;
    for (const Decal& d : source.decals())
        onTarget += d.object == 2;
    ASSERT_GT(onTarget, 0u);
    const DecalLoadReport r = load(loaded, bytes);
    EXPECT_EQ(r.droppedDecals, onTarget);
    EXPECT_EQ(r.decals, source.decals().size() - onTarget);
    ASSERT_EQ(r.droppedObjects.size(), 1u);
    EXPECT_NE(r.droppedObjects[0].find("mesh changed"), std::string::npos) << r.droppedObjects[0];
    for (const Decal& d : loaded.decals())
        EXPECT_NE(d.object, 2u);
    const DecalStats& s = loaded.stats();
    EXPECT_EQ(s.placed, s.alive - s.fading + s.evicted + s.expired + s.removed);
}

TEST_F(DecalPersistence, MissingObjectDropsItsDecals) {
    Scene scene = rangeScene(3);
    scene.objects[3].name = "another";
    DecalSystem loaded = makeSystem(scene, settingsFor(LimitPolicy::FadeOldest));
    for (const DecalType& t : gameTypes())
        addType(loaded, t);
    const DecalLoadReport r = load(loaded, bytes);
    ASSERT_EQ(r.droppedObjects.size(), 1u);
    EXPECT_NE(r.droppedObjects[0].find("missing"), std::string::npos) << r.droppedObjects[0];
    for (const Decal& d : loaded.decals())
        EXPECT_NE(d.object, 3u);
}

// `b` with the payload of section `tag` replaced by `payload` (its length and the save's size put
// right; the checksum is left to reseal).
std::vector<uint8_t> withSection(const std::vector<uint8_t>& b, const char* tag,
                                 const std::vector<uint8_t>& payload) {
    const size_t at = sectionAt(b, tag);
    uint64_t length = 0;
    std::memcpy(&length, &b[at - 8], 8);
    std::vector<uint8_t> out(b.begin(), b.begin() + std::ptrdiff_t(at));
    out.insert(out.end(), payload.begin(), payload.end());
    out.insert(out.end(), b.begin() + std::ptrdiff_t(at + length), b.end());
    length = payload.size();
    std::memcpy(&out[at - 8], &length, 8);
    const uint64_t total = out.size();
    std::memcpy(&out[16], &total, 8);
    return out;
}

void append(std::vector<uint8_t>& out, const void* value, size_t bytes) {
    const uint8_t* p = static_cast<const uint8_t*>(value);
    out.insert(out.end(), p, p + bytes);
}

// A column of `n` values as the writer lays it out (a width byte, then little-endian values) at `at`,
// read and stepped over.
std::vector<uint32_t> column(const std::vector<uint8_t>& b, size_t& at, size_t n) {
    const unsigned width = b[at++];
    std::vector<uint32_t> v(n, 0);
    for (size_t i = 0; i < n; ++i, at += width)
        for (unsigned k = 0; k < width; ++k)
            v[i] |= uint32_t(b[at + k]) << (8 * k);
    return v;
}

// The DECL payload of `b` as version 1 wrote it: float opacities, no column of slants (every decal
// of `b` projects along its normal and has no clipped crater).
std::vector<uint8_t> declVersion1(const std::vector<uint8_t>& b) {
    const size_t decl = sectionAt(b, "DECL"), n = decalCount(b);
    uint64_t length = 0;
    std::memcpy(&length, &b[decl - 8], 8);
    size_t at = decl + 4 + n * 44;
    std::vector<uint8_t> out(b.begin() + std::ptrdiff_t(decl), b.begin() + std::ptrdiff_t(at) + 1);
    size_t values = b[at] == 1 ? n : 0; // dense: one value per decal
    ++at;
    if (b[at - 1] == 2) { // sparse: a count, a column of indices, the values
        uint32_t count = 0;
        std::memcpy(&count, &b[at], 4);
        const size_t indexBytes = 4 + 1 + size_t(count) * b[at + 4];
        out.insert(out.end(), b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(at + indexBytes));
        at += indexBytes;
        values = count;
    }
    for (size_t k = 0; k < values; ++k, ++at) {
        const float opacity = float(Opacity::fromBits(b[at]));
        append(out, &opacity, 4);
    }
    EXPECT_EQ(b[at], 0u) << "clips";
    EXPECT_EQ(b[at + 1], 0u) << "slants";
    out.push_back(b[at]);
    out.insert(out.end(), b.begin() + std::ptrdiff_t(at + 2), b.begin() + std::ptrdiff_t(decl + length));
    return out;
}

// The CHNG payload of `b` as version 1 wrote it: each change as u32 index, u32 from, u8 kind.
std::vector<uint8_t> changesVersion1(const std::vector<uint8_t>& b) {
    size_t at = sectionAt(b, "CHNG");
    std::vector<uint8_t> out(b.begin() + std::ptrdiff_t(at), b.begin() + std::ptrdiff_t(at + 12));
    uint32_t n = 0;
    std::memcpy(&n, &b[at + 8], 4);
    at += 12;
    const std::vector<uint32_t> index = column(b, at, n), from = column(b, at, n);
    for (uint32_t i = 0; i < n; ++i) {
        append(out, &index[i], 4);
        append(out, &from[i], 4);
        out.push_back(b[at + i]);
    }
    return out;
}

// `b` without its last section, SKIN, which saves before version 3 do not have.
std::vector<uint8_t> withoutAnchors(const std::vector<uint8_t>& b) {
    const size_t skin = sectionAt(b, "SKIN") - 12; // the section's tag and length
    std::vector<uint8_t> out(b.begin(), b.begin() + std::ptrdiff_t(skin));
    const uint64_t total = out.size();
    std::memcpy(&out[16], &total, 8);
    put32(out, 28, 10);
    return out;
}

// `b` as version 1 wrote it (see declVersion1).
std::vector<uint8_t> asVersion1(const std::vector<uint8_t>& b) {
    std::vector<uint8_t> out =
        withSection(withSection(withoutAnchors(b), "DECL", declVersion1(b)), "CHNG", changesVersion1(b));
    put32(out, 8, 1);
    reseal(out);
    return out;
}

// Saves of version 1 load into this build: the same decals, their float opacities kept in the steps
// a decal now holds.
TEST(DecalPersistenceVersions, Version1SavesLoadWithTheirOpacities) {
    DecalSystem source = makeSystem(rangeScene(3), settingsFor(LimitPolicy::FadeOldest));
    DecalType fading;
    fading.name = "hole";
    fading.lifetime = 2.0f;
    fading.fadeOutTime = 2.0f;
    const uint16_t type = addType(source, fading);
    for (int k = 0; k < 40; ++k) {
        ASSERT_TRUE(
            source.spawnAttached(k % 2, glm::vec3(0.3f * float(k) - 6.0f, 0.1f, -1.0f), {0, 1, 0}, type)
                .placed());
        if (k % 10 == 9) {
            ASSERT_TRUE(source.update(0.3).ok());
        }
    }
    const std::vector<uint8_t> v1 = asVersion1(saved(source));
    DecalSystem loaded = makeSystem(rangeScene(3), settingsFor(LimitPolicy::FadeOldest));
    addType(loaded, fading);
    load(loaded, v1);
    EXPECT_TRUE(sameSystem(source, loaded));
    EXPECT_LT(float(loaded.decals()[0].opacity), 1.0f);
}

// A save of decals shot onto the skinned arm, which have anchors.
std::vector<uint8_t> skinnedSave() {
    const Scene arm = makeSkinnedArm();
    DecalSettings roomy;
    roomy.maxPerCell = 1024;
    DecalSystem s = makeSystem(arm, roomy);
    DecalType hole;
    hole.name = "hole";
    hole.size = glm::vec2(0.05f);
    const uint16_t type = addType(s, hole);
    for (int i = 0; i < 20; ++i)
        s.spawn(ray({0.02 * i - 0.2, 0.1 + 0.04 * i, 2.0}, {0.0, 0.0, -1.0}), type);
    EXPECT_GT(s.decals().size(), 5u);
    return saveDecals(s);
}

// Anchors that name no decal's slot, or hold numbers that are not finite, are refused by name.
TEST(DecalPersistenceAnchors, BadAnchorsAreRefused) {
    const std::vector<uint8_t> good = skinnedSave();
    const size_t skin = sectionAt(good, "SKIN");
    const auto refusal = [](std::vector<uint8_t> b) {
        reseal(b);
        DecalSettings roomy;
        roomy.maxPerCell = 1024;
        DecalSystem s = makeSystem(makeSkinnedArm(), roomy);
        DecalType hole;
        hole.name = "hole";
        addType(s, hole);
        Result<DecalLoadReport> r = loadDecals(s, b.data(), b.size());
        if (r.ok()) return std::string();
        EXPECT_TRUE(s.decals().empty()) << "a refused load changes nothing";
        return r.error();
    };
    std::vector<uint8_t> slot = good;
    put32(slot, skin + 4, 1u << 30);
    EXPECT_NE(refusal(slot).find("anchored slot"), std::string::npos) << refusal(slot);
    std::vector<uint8_t> nan = good;
    const double notANumber = std::nan("");
    std::memcpy(&nan[skin + 4 + 8], &notANumber, 8);
    EXPECT_NE(refusal(nan).find("anchored decal"), std::string::npos) << refusal(nan);
    EXPECT_EQ(refusal(good), "");
}

// Saves of version 2 (no SKIN section) load into this build as they were.
TEST(DecalPersistenceVersions, Version2SavesLoadWithoutAnchors) {
    DecalSystem source = gameSystem(LimitPolicy::EvictOldest);
    play(source, 0, 200);
    std::vector<uint8_t> v2 = withoutAnchors(saved(source));
    put32(v2, 8, 2);
    reseal(v2);
    DecalSystem loaded = gameSystem(LimitPolicy::EvictOldest);
    load(loaded, v2);
    EXPECT_TRUE(sameSystem(source, loaded));
}

TEST_F(DecalPersistence, NewerVersionIsRefusedNamingBothVersions) {
    std::vector<uint8_t> b = bytes;
    put32(b, 8, kDecalSaveVersion + 1);
    reseal(b);
    expectRefused(b, "format version " + std::to_string(kDecalSaveVersion + 1) +
                         " is newer than this build reads (" + std::to_string(kDecalSaveVersion) + ")");
}

TEST_F(DecalPersistence, TruncatedInputIsRefused) {
    for (size_t size : {size_t(0), size_t(7), size_t(31), size_t(32), bytes.size() / 2, bytes.size() - 1})
        expectRefused(std::vector<uint8_t>(bytes.begin(), bytes.begin() + std::ptrdiff_t(size)), "truncated");
    std::stringstream stream(std::string(bytes.begin(), bytes.end() - 1));
    DecalSystem target = gameSystem(LimitPolicy::EvictOldest);
    Result<DecalLoadReport> r = loadDecals(target, stream);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().find("truncated"), std::string::npos) << r.error();
}

TEST_F(DecalPersistence, AnyChangedByteIsRefused) {
    for (size_t at = 0; at < bytes.size(); at += 1 + at / 7) {
        std::vector<uint8_t> b = bytes;
        b[at] ^= 0x10;
        expectRefused(b, "");
    }
}

TEST_F(DecalPersistence, WrongChecksumIsRefused) {
    std::vector<uint8_t> b = bytes;
    b[24] ^= 1;
    expectRefused(b, "checksum mismatch");
}

TEST_F(DecalPersistence, BadMagicAndByteOrderAreRefused) {
    std::vector<uint8_t> b = bytes;
    b[1] = 'X';
    expectRefused(b, "bad magic");
    b = bytes;
    put32(b, 12, 0x04030201);
    reseal(b);
    expectRefused(b, "big-endian");
}

TEST_F(DecalPersistence, CountsLargerThanTheDataAreRefusedBeforeAllocating) {
    for (const char* tag : {"DECL", "TYPE", "OBJS", "FADE", "CHNG"}) {
        std::vector<uint8_t> b = bytes;
        const size_t at = sectionAt(b, tag) + (std::strcmp(tag, "CHNG") == 0 ? 8 : 0);
        put32(b, at, 0xFFFFFFF0u);
        reseal(b);
        expectRefused(b, "claims 4294967280");
    }
    std::vector<uint8_t> b = bytes;
    put32(b, sectionAt(b, "SLOT"), 0xFFFFFFF0u);
    reseal(b);
    expectRefused(b, "generations need");
}

TEST_F(DecalPersistence, NonFiniteAndDenormalValuesAreRefused) {
    const size_t decals = sectionAt(bytes, "DECL") + 4;
    const std::pair<size_t, uint32_t> edits[] = {
        {decals + 12, 0x7FC00000u}, // half-depth NaN
        {decals + 24, 0x00000001u}, // width denormal
        {decals + 0, 0x7F800000u},  // centre infinite
    };
    for (const auto& [at, bits] : edits) {
        std::vector<uint8_t> b = bytes;
        put32(b, at, bits);
        reseal(b);
        expectRefused(b, "decal 0: ");
    }
    std::vector<uint8_t> b = bytes;
    put32(b, sectionAt(b, "SETT") + 8, 0x00000001u); // cellSize denormal
    reseal(b);
    expectRefused(b, "cellSize");
    b = bytes;
    put32(b, sectionAt(b, "CLCK") + 4, 0x7FF80000u); // the clock NaN (high word)
    reseal(b);
    expectRefused(b, "clock");
}

TEST_F(DecalPersistence, UnknownTypeNameIsRefused) {
    DecalSystem target = makeSystem(rangeScene(3), settingsFor(LimitPolicy::FadeOldest));
    addType(target, gameTypes()[0]);
    const std::vector<uint8_t> before = saved(target);
    Result<DecalLoadReport> r = loadDecals(target, bytes.data(), bytes.size());
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().find("decal type 'scorch' is not registered"), std::string::npos) << r.error();
    EXPECT_TRUE(saved(target) == before);
}

TEST_F(DecalPersistence, DecalOnAnObjectTheSaveDoesNotHoldIsRefused) {
    std::vector<uint8_t> b = bytes;
    size_t at = integerColumnsAt(b);
    at += 1 + decalCount(b) * b[at]; // types
    ASSERT_EQ(b[at], 1u);            // object column, one byte each
    b[at + 1] = 200;
    reseal(b);
    expectRefused(b, "decal 0 lies on object 200, which the save has not in its world");
}

// The log keeps no source of a change (a removal's is the decals' count after it), so a save whose
// sources do not follow from its decals is refused rather than replayed into other changes.
TEST_F(DecalPersistence, ChangeLogThatDoesNotLeadToTheDecalsIsRefused) {
    std::vector<uint8_t> b = bytes;
    size_t at = sectionAt(b, "CHNG");
    uint32_t n = 0;
    std::memcpy(&n, &b[at + 8], 4);
    ASSERT_GT(n, 0u);
    at += 12;
    column(b, at, n); // indices
    const size_t sources = at;
    b[sources + 1 + size_t(n - 1) * b[sources]] ^= 1; // the newest change's source, one off
    reseal(b);
    expectRefused(b, "does not lead to the");
}

TEST_F(DecalPersistence, SlotUsedTwiceIsRefused) {
    std::vector<uint8_t> b = bytes;
    const size_t n = decalCount(b);
    ASSERT_GT(n, 2u);
    size_t at = integerColumnsAt(b);
    at += 1 + n * b[at]; // types
    at += 1 + n * b[at]; // objects
    const uint8_t width = b[at];
    std::memcpy(&b[at + 1 + width], &b[at + 1], width); // decal 1 takes decal 0's slot
    reseal(b);
    expectRefused(b, "used twice");
}

} // namespace
} // namespace spatter::test

// A save over a directory fails naming why, and leaves no temporary file beside it.
TEST(DecalPersistenceFile, ASaveThatCannotReplaceItsPathSaysWhyAndLeavesNoTemporaryFile) {
    const std::filesystem::path dir = test::scratchDir("persistence-file");
    const std::filesystem::path target = dir / "taken";
    std::filesystem::create_directories(target / "inside");
    DecalSystem s = makeSystem(boxScene());
    const Status st = saveDecalsToFile(s, target.string());
    ASSERT_FALSE(st.ok());
    EXPECT_NE(st.error().find("cannot replace it"), std::string::npos) << st.error();
    EXPECT_EQ(st.error().find("Success"), std::string::npos) << st.error();
    EXPECT_FALSE(std::filesystem::exists(target.string() + ".tmp"));
    EXPECT_TRUE(std::filesystem::is_directory(target / "inside"));
}
