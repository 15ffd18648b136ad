#pragma once
// SavedDecal: the fixed fields of one Decal in a save, field by field (never the struct's bytes:
// its padding and its layout are the compiler's), little-endian:
//   center x, y, z (f32 each), halfDepth (f32), packedFrame (u64, PackedFrame.hpp),
//   size x, y (f32 each), spawnTime (f64), id (u32).
// The other fields go in columns of their own (DecalSaveWriter.cpp): opacity and the crater clips
// kept beside the decals (DecalSystem::craterClips), which most decals share or lack, and type, object
// and objectId, which the save stores narrower or derives.

#include "SaveBytes.hpp"
#include "spatter/core/Decal.hpp"

namespace spatter::save {

constexpr size_t kSavedDecalBytes = 44;

inline void storeDecal(uint8_t* p, const Decal& d) {
    storeF32(p, d.center.x);
    storeF32(p + 4, d.center.y);
    storeF32(p + 8, d.center.z);
    storeF32(p + 12, d.halfDepth);
    storeU64(p + 16, d.packedFrame);
    storeF32(p + 24, d.size.x);
    storeF32(p + 28, d.size.y);
    storeF64(p + 32, d.spawnTime);
    storeU32(p + 40, d.id);
}

inline void loadDecal(const uint8_t* p, Decal& d) {
    d.center = glm::vec3(loadF32(p), loadF32(p + 4), loadF32(p + 8));
    d.halfDepth = loadF32(p + 12);
    d.packedFrame = loadU64(p + 16);
    d.size = glm::vec2(loadF32(p + 24), loadF32(p + 28));
    d.spawnTime = loadF64(p + 32);
    d.id = loadU32(p + 40);
}

} // namespace spatter::save
