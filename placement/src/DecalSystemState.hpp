#pragma once
// DecalSystemState: everything a DecalSystem needs to carry on exactly where it stood, as plain
// values, and the door through which a save takes it out and a load puts it back
// (DecalPersistence.hpp). capture() copies it; restore() replaces the system's state with it.

#include "AreaLimits.hpp"
#include "SkinAnchors.hpp"
#include "spatter/core/Decal.hpp"
#include "spatter/core/DecalChanges.hpp"
#include "spatter/placement/DecalSystem.hpp"

#include <cstdint>
#include <glm/glm.hpp>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace spatter {

// An object of the saving system's world, by its key (index in the table, name, mesh hash).
struct SavedObject {
    std::string name;
    uint64_t meshHash = 0;
    bool dynamic = false;
    bool inWorld = false;
    uint8_t objectId = 0;
    glm::dmat4 transform{1.0};
};

// A decal the area limits count, in the cell it was counted in when that cell is not the one its
// centre gives under its object's transform now (DecalSystemAccess::cellKey).
struct CellException {
    uint32_t position = 0; // in DecalSystemState::limitOrder
    CellKey key;
};

struct DecalSystemState {
    DecalSettings settings;
    std::vector<std::string> typeNames; // by type index
    std::vector<SavedObject> objects;   // by object index
    uint64_t rngState = 0, rngIncrement = 1;
    double time = 0.0;
    DecalStats stats;
    std::vector<Decal> decals;                       // dense, as decals() gives them
    std::vector<uint32_t> slotOf;                    // parallel to decals: each one's handle slot
    std::vector<CraterClips> clips;                  // parallel to decals: their craters' clip planes
    std::vector<uint32_t> generations;               // by slot
    std::vector<uint32_t> freeSlots;                 // the last is the next one used
    std::vector<std::pair<uint32_t, double>> fading; // (slot, clock time of its eviction), by slot
    std::vector<uint32_t> limitOrder;                // the slots the limits count, oldest first
    std::vector<CellException> cellExceptions;       // by position
    uint64_t changeLogBase = 0;
    std::vector<DecalChange> changeLog;
    std::vector<SavedAnchor> anchors; // decals on deforming objects' drawn surfaces, by ascending slot
};

// What a load does to the world and the decals beside the state (DecalSystemAccess::restore).
struct RestorePlan {
    std::vector<bool> keepObject;                       // by saved object: its decals stay
    std::vector<std::pair<uint32_t, glm::dmat4>> moves; // dynamic objects in the world and their transform
    std::vector<uint32_t> removals;                     // objects the save has removed from the world
};

struct DecalSystemAccess {
    // The system's lock, held by every mutation.
    static std::unique_lock<std::mutex> lock(DecalSystem& system);
    // A copy of the system's state (a const call: never during a mutation).
    static DecalSystemState capture(const DecalSystem& system);
    // Empty when `settings` may create a system, else what is wrong (DecalSystem::create's checks).
    static std::string settingsProblem(const DecalSettings& settings);
    // Replaces the system's state with `state` (its batchThreads kept), applies `plan` to the world
    // and removes the decals of the objects it does not keep (counted in stats().removed, logged).
    // The caller holds lock(system) and has checked everything: the state is consistent (every slot
    // used once or free once, the order a permutation of the slots not fading), its type indices
    // are the system's, every kept decal's object is in the world, and every move and removal
    // is one the world accepts.
    static void restore(DecalSystem& system, DecalSystemState&& state, const RestorePlan& plan);

private:
    // The decals, their slots, the free list, the fading decals and the decals update() visits.
    static void restoreDecals(DecalSystem::Impl& s, DecalSystemState& state);
    // The area limits: the counted decals of the kept objects linked oldest first, each in its cell.
    static void relink(DecalSystem::Impl& s, const DecalSystemState& state, const std::vector<bool>& keep);
};

} // namespace spatter
