#pragma once
// DecalPersistence: a DecalSystem's state saved to bytes and loaded back, in this run of the program
// or a later one, so that a game's saved world keeps every decal. After a load the system carries on
// as if it had never stopped: the same later calls give bit-identical decals, handles, IDs,
// evictions, statistics and change versions.
//
//   std::vector<uint8_t> bytes = saveDecals(system);                // or saveDecalsToFile
//   ...
//   Result<DecalSystem> sys = DecalSystem::create(scene);           // the same scene
//   sys->registerType(hole); sys->registerType(scorch);             // in any order: matched by name
//   Result<DecalLoadReport> r = loadDecals(*sys, bytes.data(), bytes.size());
//   if (!r) std::fprintf(stderr, "%s\n", r.error().c_str());         // the system is as it was
//
// A save holds the settings (batchThreads excepted: it changes no result and is the host's), the
// names of the registered types, the world's objects (each by its index, name and mesh hash, with
// its object ID and transform), the clock, the random generator, the statistics, every live decal
// with its handle and age, the fading decals, the area limits' order and cells, the handle free
// list and the change log. The format is documented field by field in docs/PLACEMENT.md.
//
// Loading checks everything before it changes anything: any error leaves the system as it was. It
// replaces the system's decals and state with the save's; the system keeps its own types, which
// must include every type the save names (matched by name: the indices may differ), and its world,
// which the save's objects are matched against by index, name and CollisionObject::meshHash. An
// object of the save that the world lacks, calls otherwise, has out of the world, or holds with
// another mesh or another dynamic flag is dropped with its decals (counted in stats().removed and
// in the report); a dynamic object takes the transform it had when saved; an object the save had
// removed is removed. Memory: a load allocates in proportion to the input (about three times its
// size for a real save, about ten for one made of nothing but handle slots); counts that the
// input's bytes cannot hold are errors before anything is allocated.
//
// After a load, a renderer that follows changesSince() takes decals() whole: the versions go on from
// the saved system's, which its copy of the decals never saw.
//
// Threading: saving is a const call (like decals(): never during a mutation); loading is a mutation
// (it takes the system's lock).

#include "spatter/core/Result.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace spatter {

// The format version this build writes; it reads every version up to it.
constexpr uint32_t kDecalSaveVersion = 3;

struct DecalLoadReport {
    size_t decals = 0;                       // live decals after the load
    size_t droppedDecals = 0;                // decals dropped with objects the world does not match
    std::vector<std::string> droppedObjects; // one line per saved object not matched, and why
};

// The save of `system`: a new byte vector, owned by the caller.
std::vector<uint8_t> saveDecals(const DecalSystem& system);
// Writes the save to `out`. Fails, naming what failed, when the stream does.
Status saveDecals(const DecalSystem& system, std::ostream& out);
// Writes the save to `path` through a temporary file in the same directory renamed over it, so a
// reader never sees half a save. Fails with a message naming the file and the problem, leaving the
// file at `path` as it was and no temporary file.
Status saveDecalsToFile(const DecalSystem& system, const std::string& path);

// Loads the save in [data, data + size) (exactly one save) into `system`. Fails, changing nothing,
// with a message that starts "decal save: " and says what is wrong: truncated or oversized input, a
// bad magic, byte order, checksum or section, a format version newer than kDecalSaveVersion (naming
// both), counts larger than the input holds, values out of range (NaN, infinite or denormal sizes,
// depths, times, opacities and settings; indices out of range; a slot used twice), a type name
// the system has not registered, or a decal on an object the save itself has out of the world.
Result<DecalLoadReport> loadDecals(DecalSystem& system, const uint8_t* data, size_t size);
// Reads one save from `in` (its header says how long it is; the stream is read no further) and
// loads it. Fails as above, and when the stream ends early or fails.
Result<DecalLoadReport> loadDecals(DecalSystem& system, std::istream& in);
// Reads the file at `path` and loads it; errors name the file.
Result<DecalLoadReport> loadDecalsFromFile(DecalSystem& system, const std::string& path);

} // namespace spatter
