// libFuzzer target: loading a decal save (DecalPersistence.hpp). Each input is a save, loaded into a
// fresh decal system over a small scene. A refused load must leave the system as it was (its own save
// unchanged); an accepted one must give a system whose statistics add up, whose save loads again into
// the same state, and that spawns, ages and reports changes like any other.
//
// Each input is loaded as it is and again with its checksum put right, so that mutations reach past it.
// Seeds: with SPATTER_FUZZ_LOAD_SEEDS set to a directory, the target writes real saves there when it
// starts (./spatter fuzz points it at the corpus).

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/core/SceneEvaluator.hpp"
#include "spatter/core/SkinnedDummy.hpp"
#include "spatter/placement/DecalPersistence.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using namespace spatter;

[[noreturn]] void violated(const char* what) {
    std::fprintf(stderr, "FuzzLoad: %s\n", what);
    std::abort();
}

constexpr uint32_t kDummy = 4; // the skinned dummy's object index

// A static floor and pillar, a dynamic crate and a dynamic ball, and the skinned dummy, whose decals
// carry anchors (the save's SKIN section).
Scene makeScene() {
    Scene s;
    s.source = "fuzz:load";
    const glm::dmat4 id(1.0);
    s.objects.push_back(makeSceneObject("floor", makeBox(glm::vec3(10.0f, 0.1f, 10.0f), 2),
                                        glm::translate(id, glm::dvec3(0.0, -0.1, 0.0)), false));
    s.objects.push_back(
        makeSceneObject("pillar", makeSphere(1.0f, 8, 12), glm::translate(id, glm::dvec3(3, 1, 0)), false));
    s.objects.push_back(
        makeSceneObject("crate", makeBox(glm::vec3(0.5f), 1), glm::translate(id, glm::dvec3(0, 1, 0)), true));
    s.objects.push_back(
        makeSceneObject("ball", makeSphere(0.5f, 6, 8), glm::translate(id, glm::dvec3(0, 1, 3)), true));
    addSkinnedDummy(s, glm::translate(id, glm::dvec3(-4, 0, 0)));
    return s;
}

const Scene& scene() {
    static const Scene s = makeScene();
    return s;
}

// Poses the dummy at time t of its animation.
void poseDummy(DecalSystem& s, double t) {
    SceneEvaluator evaluator(scene());
    evaluator.evaluate(0, t);
    if (!s.setPose(kDummy, evaluator.objectTransform(kDummy), evaluator.jointMatrices(0), {}))
        violated("the dummy cannot be posed");
}

DecalSystem freshSystem(const DecalSettings& settings = {}) {
    Result<DecalSystem> s = DecalSystem::create(scene(), settings);
    if (!s) violated("the scene does not build");
    DecalType hole;
    hole.name = "hole";
    DecalType scorch;
    scorch.name = "scorch";
    scorch.lifetime = 2.0f;
    scorch.sizeJitter = 0.25f;
    DecalType crater;
    crater.name = "crater";
    crater.volumetric = true;
    for (const DecalType& t : {scorch, hole, crater})
        if (!s->registerType(t)) violated("a type is refused");
    return std::move(s).value();
}

// A few decals of every type on every object, with the clock, a move, an eviction and a removal.
std::vector<uint8_t> seedSave(LimitPolicy policy, int shots) {
    DecalSettings settings;
    settings.policy = policy;
    settings.maxPerCell = 3;
    settings.budget = 12;
    DecalSystem s = freshSystem(settings);
    poseDummy(s, 0.5);
    for (int i = 0; i < shots / 3; ++i) { // at the dummy's chest and arms
        Ray r;
        r.origin = glm::dvec3(-4.3 + 0.1 * i, 0.9 + 0.07 * i, 3.0);
        r.direction = glm::dvec3(0.0, 0.0, -1.0);
        s.spawn(r, uint16_t(i % 2));
    }
    for (int i = 0; i < shots; ++i) {
        Ray r;
        r.origin = glm::dvec3(0.3 * (i % 7) - 1.0, 4.0, 0.25 * (i % 5) + 0.1 * i);
        r.direction = glm::dvec3(0.05 * (i % 3), -1.0, -0.1);
        const SpawnResult placed = s.spawn(r, uint16_t(i % 3));
        if (i % 4 == 0) s.update(0.3);
        if (i == 5) s.setTransform(2, glm::translate(glm::dmat4(1.0), glm::dvec3(0.5, 1.2, 0.1)));
        if (i % 6 == 5 && placed.placed()) s.remove(placed.handle);
    }
    return saveDecals(s);
}

void writeSeeds(const std::string& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    const std::pair<const char*, std::vector<uint8_t>> seeds[] = {
        {"empty.save", seedSave(LimitPolicy::EvictOldest, 0)},
        {"evict.save", seedSave(LimitPolicy::EvictOldest, 24)},
        {"fade.save", seedSave(LimitPolicy::FadeOldest, 24)},
        {"reject.save", seedSave(LimitPolicy::Reject, 16)},
    };
    for (const auto& [name, bytes] : seeds) {
        std::FILE* f = std::fopen((dir + "/" + name).c_str(), "wb");
        if (!f || std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size() || std::fclose(f) != 0)
            violated("cannot write a seed");
    }
}

void checkLoaded(DecalSystem& s) {
    const DecalStats& st = s.stats();
    if (st.alive != s.decals().size() ||
        st.placed != st.alive - st.fading + st.evicted + st.expired + st.removed)
        violated("the statistics of a loaded system do not add up");
    const std::vector<uint8_t> again = saveDecals(s);
    DecalSystem twin = freshSystem();
    if (!loadDecals(twin, again.data(), again.size())) violated("a loaded system's save is refused");
    if (saveDecals(twin) != again) violated("a save does not load into the same state");
    Ray r;
    r.origin = glm::dvec3(0.2, 3.0, 0.2);
    r.direction = glm::dvec3(0.0, -1.0, 0.0);
    for (uint16_t t = 0; t < 3; ++t)
        s.spawn(r, t);
    poseDummy(s, 1.0); // the loaded anchors ride the skin
    if (!s.update(0.5)) violated("update fails after a load");
    (void)s.changesSince(0);
}

// CRC-32 (ISO-HDLC) of bytes [begin, end), bit by bit, continuing from `crc`.
uint32_t crc32(const std::vector<uint8_t>& b, size_t begin, size_t end, uint32_t crc = 0xFFFFFFFFu) {
    for (size_t i = begin; i < end; ++i) {
        crc ^= b[i];
        for (int k = 0; k < 8; ++k)
            crc = (crc & 1u) ? (crc >> 1) ^ 0xEDB88320u : crc >> 1;
    }
    return crc;
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    if (const char* dir = std::getenv("SPATTER_FUZZ_LOAD_SEEDS")) writeSeeds(dir);
    return 0;
}

void loadOne(const uint8_t* data, size_t size) {
    DecalSystem s = freshSystem();
    const std::vector<uint8_t> before = saveDecals(s);
    Result<DecalLoadReport> r = loadDecals(s, data, size);
    if (!r) {
        if (r.error().rfind("decal save: ", 0) != 0) violated("an error without its prefix");
        if (saveDecals(s) != before) violated("a refused load changed the system");
        return;
    }
    checkLoaded(s);
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    loadOne(data, size);
    // Again with the checksum put right, so that mutations reach the sections behind it.
    if (size >= 32) {
        std::vector<uint8_t> sealed(data, data + size);
        const uint32_t crc = ~crc32(sealed, 28, size, crc32(sealed, 0, 24));
        for (int i = 0; i < 4; ++i)
            sealed[24 + i] = uint8_t(crc >> (8 * i));
        if (!std::equal(sealed.begin(), sealed.end(), data)) loadOne(sealed.data(), size);
    }
    return 0;
}
