#include "PersistenceBench.hpp"

#include "BenchSupport.hpp"
#include "DecalField.hpp"

#include "spatter/core/MeshBuilder.hpp"
#include "spatter/placement/DecalPersistence.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <cstdio>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

namespace spatter::bench {

namespace {

const char* kPersistenceCommand = "persistence";

const char* kPersistenceUsage =
    R"(usage: spatter-bench persistence [--decals N] [--repeat R] [--worst] [--quick] [--json FILE]

Saving and loading a decal system (DecalPersistence.hpp), single-threaded, wall clock, the median
of R runs each:

  save          saveDecals: the system's state to a new byte vector
  load          loadDecals: that vector into a second system over the same scene (replacing its state)
  save file     saveDecalsToFile: to a temporary file (page cache; the disk's speed is not measured)
  load file     loadDecalsFromFile: from that file

N decals lie on a floor as in `memory` (spawnAttached, about 8 to a cell of the area grid), with
random rotations and sizes, under a budget of N. With --worst every decal takes every optional
column a save has room for: the floor is a slab 1 cm thick and the type volumetric, so each crater
is clipped at its back, and the type's lifetime has every decal fading (its opacity differs from 1
and its change fills the change log). The loaded system is checked: its own save equals
the one it was loaded from, byte for byte. MB/s are of the save's size.

Target: saving and loading 1,000,000 decals each within 0.5 s (0.5 s a million decals placed); a
save at most what a decal holds in memory (sizeof(Decal), and the crater clips kept beside every
record once a crater has them) plus a fixed part, which the save's bytes a decal include.

--decals N  decals (default 1000000)     --repeat R  runs per row (default 5)
--worst     the largest save a decal can take (above)
--quick     20,000 decals, 3 runs (smoke test)
--json FILE {"decals", "save_bytes", "bytes_per_decal", "decal_record_bytes", "memory_bytes_per_decal",
            "rows": [...], "targets": {"times_met", "save_bytes_met"}}
)";

// The floor of the worst case: a slab 1 cm thick, as wide as the field's floor, its top at y = 0.
Scene slabFloor(const Scene& field) {
    Scene s = field;
    const Bounds b = s.objects[0].mesh->bounds();
    const glm::vec3 half(0.5f * (b.max.x - b.min.x), 0.005f, 0.5f * (b.max.z - b.min.z));
    s.objects[0].mesh = shareMesh(makeBox(half, 1));
    s.objects[0].transform =
        glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, -0.005, 0.0)) * s.objects[0].transform;
    return s;
}

// The decal system of the benchmark: `n` decals spawned, or none; `worst`: craters that fade.
Result<DecalSystem> makeSystem(const Scene& field, size_t n, size_t spawned, bool worst) {
    DecalSettings ds;
    ds.budget = uint32_t(n);
    ds.maxPerObject = uint32_t(n);
    Result<DecalSystem> sys = DecalSystem::create(field, ds);
    if (!sys) return sys;
    DecalType type;
    type.name = "hole";
    type.sizeJitter = 0.2f;
    type.volumetric = worst;
    type.lifetime = worst ? 100.0f : 0.0f;
    type.fadeOutTime = 100.0f;
    const uint16_t ti = sys->registerType(type).value();
    const double side = std::sqrt(double(n) / 8.0) * double(ds.cellSize);
    Rng rng(1);
    for (size_t i = 0; i < spawned; ++i) {
        const glm::vec3 p(float(side) * rng.uniform(-0.5f, 0.5f), worst ? 0.005f : 0.0f, // on the slab's top
                          float(side) * rng.uniform(-0.5f, 0.5f));
        sys->spawnAttached(0, p, glm::vec3(0.0f, 1.0f, 0.0f), ti);
    }
    if (worst && spawned > 0)
        if (Status s = sys->update(1.0); !s) return fail(s.error());
    return sys;
}

// Median wall time of `runs` calls of `f`, seconds; false from `f` stops with an error.
Result<double> timed(size_t runs, const std::function<Status()>& f) {
    std::vector<double> times;
    for (size_t r = 0; r < runs; ++r) {
        const double t0 = now();
        if (Status s = f(); !s) return fail(s.error());
        times.push_back(now() - t0);
    }
    return median(times);
}

Status loaded(Result<DecalLoadReport> r) {
    if (!r) return fail(r.error());
    return {};
}

} // namespace

int runPersistenceCommand(int argc, char** argv) {
    int exitCode = 0;
    const std::optional<Args> parsed =
        commandArgs(argc, argv, kPersistenceCommand, kPersistenceUsage, {"--decals", "--repeat", "--json"},
                    {"--quick", "--worst"}, exitCode);
    if (!parsed) return exitCode;
    const Args& args = *parsed;
    if (!args.positional.empty()) return usageError(kPersistenceCommand, "no positional arguments");
    const bool quick = args.has("--quick");
    Result<uint64_t> count = parseCount(args.value("--decals", quick ? "20000" : "1000000"), "--decals");
    if (!count) return usageError(kPersistenceCommand, count.error());
    Result<uint64_t> repeat = parseCount(args.value("--repeat", quick ? "3" : "5"), "--repeat");
    if (!repeat) return usageError(kPersistenceCommand, repeat.error());
    const size_t n = count.value(), runs = repeat.value();
    if (n == 0 || n > (1u << 30)) return usageError(kPersistenceCommand, "--decals must be in [1, 2^30]");
    if (runs == 0) return usageError(kPersistenceCommand, "--repeat must be positive");

    const MachineInfo machine = machineInfo();
    std::printf("spatter-bench persistence: %zu decals, %zu runs a row\nmachine: %s\n", n, runs,
                describe(machine).c_str());
    const bool worst = args.has("--worst");
    const Scene flat = decalFieldScene(decalFieldView(16.0 / 9.0), false);
    const Scene field = worst ? slabFloor(flat) : flat;
    Result<DecalSystem> source = makeSystem(field, n, n, worst);
    Result<DecalSystem> target = makeSystem(field, n, 0, worst);
    if (!source || !target) {
        std::fprintf(stderr, "spatter-bench persistence: %s\n", (source ? target : source).error().c_str());
        return 1;
    }
    DecalSystem& src = source.value();
    DecalSystem& dst = target.value();
    std::vector<uint8_t> bytes;
    const ScratchDirectory scratch("persistence");
    const std::string path = scratch.path() + "/decals.save";
    std::vector<std::pair<std::string, Result<double>>> rows;
    rows.emplace_back("save", timed(runs, [&] {
                          bytes = saveDecals(src);
                          return Status();
                      }));
    rows.emplace_back("load",
                      timed(runs, [&] { return loaded(loadDecals(dst, bytes.data(), bytes.size())); }));
    rows.emplace_back("save file", timed(runs, [&] { return saveDecalsToFile(src, path); }));
    rows.emplace_back("load file", timed(runs, [&] { return loaded(loadDecalsFromFile(dst, path)); }));
    for (const auto& [name, t] : rows)
        if (!t) {
            std::fprintf(stderr, "spatter-bench persistence: %s: %s\n", name.c_str(), t.error().c_str());
            return 1;
        }
    if (saveDecals(dst) != bytes) {
        std::fprintf(stderr, "spatter-bench persistence: the loaded system saves differently\n");
        return 1;
    }

    const size_t placed = src.decals().size();
    const double perDecal = double(bytes.size()) / double(placed);
    size_t clipped = 0, fading = 0;
    for (size_t i = 0; i < placed; ++i) {
        clipped += src.craterClips(i).any() ? 1 : 0;
        fading += float(src.decals()[i].opacity) < 1.0f ? 1 : 0;
    }
    std::printf(
        "\n%zu decals placed (%zu with clipped craters, %zu fading); save %zu bytes: %.2f B per decal "
        "(sizeof(Decal) %zu)\n\n",
        placed, clipped, fading, bytes.size(), perDecal, sizeof(Decal));
    // What a decal holds in memory: its record, and the crater clips the system keeps beside every
    // record once a crater has them.
    const double memoryPerDecal = double(sizeof(Decal)) + (clipped > 0 ? double(sizeof(CraterClips)) : 0.0);
    Json j;
    j["command"] = kPersistenceCommand;
    j["machine"] = toJson(machine);
    j["decals"] = placed;
    j["worst"] = worst;
    j["clipped"] = clipped;
    j["fading"] = fading;
    j["save_bytes"] = bytes.size();
    j["bytes_per_decal"] = number(perDecal);
    j["decal_record_bytes"] = sizeof(Decal);
    j["memory_bytes_per_decal"] = memoryPerDecal;
    j["runs"] = runs;
    std::vector<std::vector<std::string>> table;
    Json jrows = Json::array();
    bool timesMet = true;
    for (const auto& [name, t] : rows) {
        const double mbs = double(bytes.size()) / 1e6 / t.value();
        const bool within = t.value() <= 0.5 * double(placed) / 1e6;
        timesMet = timesMet && within;
        table.push_back({name, fixed(t.value() * 1e3, 1), fmt(mbs, 4), within ? "yes" : "no"});
        Json row;
        row["operation"] = name;
        row["seconds"] = number(t.value());
        row["mb_per_s"] = number(mbs);
        jrows.push_back(row);
    }
    j["rows"] = jrows;
    printTable({"operation", "ms", "MB/s", "within 0.5 s per million"}, table);
    const bool compact = perDecal <= memoryPerDecal;
    std::printf(
        "\nsave %.2f B a decal against the %.0f B a decal holds in memory (target: at most that plus a "
        "fixed part): %s\n",
        perDecal, memoryPerDecal, compact ? "met" : "missed");
    j["targets"] = {{"times_met", timesMet}, {"save_bytes_met", compact}};
    if (args.has("--json"))
        if (Status s = writeJson(j, args.value("--json")); !s) {
            std::fprintf(stderr, "spatter-bench persistence: %s\n", s.error().c_str());
            return 1;
        }
    return 0;
}

} // namespace spatter::bench
