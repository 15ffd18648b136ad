#pragma once
// DecalSaveFormat: the layout of a decal save (docs/PLACEMENT.md, "The save format") shared by its
// writer (DecalSaveWriter.cpp) and its reader (DecalSaveReader.cpp): the header's constants, the
// sections in their order, and the checksum.

#include "DecalSystemState.hpp"
#include "SaveBytes.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/placement/DecalPersistence.hpp"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace spatter::save {

// Bytes 0-7: not text (0x89), the name, a CR LF and a LF that a text-mode copy would change, and the
// end-of-file mark of DOS consoles (PNG's signature, for PNG's reasons).
constexpr uint8_t kMagic[8] = {0x89, 'S', 'P', 'D', '\r', '\n', 0x1A, '\n'};
constexpr uint32_t kByteOrderMark = 0x01020304;
constexpr size_t kHeaderBytes = 32;
constexpr size_t kChecksumAt = 24;
constexpr size_t kSectionHeaderBytes = 12;
constexpr const char* kSections[] = {"SETT", "CLCK", "STAT", "TYPE", "OBJS", "SLOT",
                                     "DECL", "LIMS", "FADE", "CHNG", "SKIN"};
constexpr uint32_t kSectionCount = sizeof(kSections) / sizeof(kSections[0]);
// The sections a save of `version` has: versions 1 and 2 end with CHNG, later ones have SKIN too.
constexpr uint32_t sectionsIn(uint32_t version) {
    return version <= 2 ? kSectionCount - 1 : kSectionCount;
}
constexpr size_t kObjectMinBytes = 4 + 8 + 1 + 1 + 16 * 8;
constexpr size_t kExceptionBytes = 4 + 3 * 8 + 4;
constexpr size_t kFadingBytes = 4 + 8;
constexpr size_t kChangeBytes = 4 + 4 + 1;       // version 1: index, from and kind of a change
constexpr size_t kChangeColumnBytes = 1 + 1 + 1; // later versions: a change's least in the columns
constexpr size_t kAnchorBytes = 4 + 4 + 12 * 8;  // slot, triangle, barycentric coordinates, frame
constexpr uint8_t kDynamicFlag = 1, kInWorldFlag = 2;
// Kinds of an optional column (writeSparse): every value the default, all values, or the others.
enum : uint8_t { kAbsent = 0, kDense = 1, kSparse = 2 };

// Every error of a load starts so.
inline Error corrupt(const std::string& what) {
    return fail("decal save: " + what);
}

// CRC-32 of every byte of the save but the checksum's own four.
inline uint32_t checksum(const uint8_t* data, size_t size) {
    Crc32 crc;
    crc.update(data, kChecksumAt);
    crc.update(data + kChecksumAt + 4, size - kChecksumAt - 4);
    return crc.value();
}

// The save of `state`.
std::vector<uint8_t> encode(const DecalSystemState& state);

// Magic, version and byte order of a header's kHeaderBytes bytes.
Status checkPreamble(const uint8_t* data);
// The state in the save [data, data + size), every field and cross-reference checked; its type and
// object indices are the save's own.
Result<DecalSystemState> decode(const uint8_t* data, size_t size);

} // namespace spatter::save
