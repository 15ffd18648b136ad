#include "spatter/placement/DecalPersistence.hpp"

#include "DecalSystemState.hpp"
#include "SaveBytes.hpp"
#include "SavedDecal.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <istream>
#include <limits>
#include <ostream>

namespace spatter {

using namespace save;

namespace {

// Bytes 0-7: not text (0x89), the name, a CR LF and a LF that a text-mode copy would change, and the
// end-of-file mark of DOS consoles (PNG's signature, for PNG's reasons).
constexpr uint8_t kMagic[8] = {0x89, 'S', 'P', 'D', '\r', '\n', 0x1A, '\n'};
constexpr uint32_t kByteOrderMark = 0x01020304;
constexpr size_t kHeaderBytes = 32;
constexpr size_t kChecksumAt = 24;
constexpr size_t kSectionHeaderBytes = 12;
constexpr const char* kSections[] = {"SETT", "CLCK", "STAT", "TYPE", "OBJS",
                                     "SLOT", "DECL", "LIMS", "FADE", "CHNG"};
constexpr uint32_t kSectionCount = sizeof(kSections) / sizeof(kSections[0]);
constexpr size_t kObjectMinBytes = 4 + 8 + 1 + 1 + 16 * 8;
constexpr size_t kExceptionBytes = 4 + 3 * 8 + 4;
constexpr size_t kFadingBytes = 4 + 8;
constexpr size_t kChangeBytes = 4 + 4 + 1;
constexpr uint8_t kDynamicFlag = 1, kInWorldFlag = 2;

Error corrupt(const std::string& what) {
    return fail("decal save: " + what);
}

bool denormal(double v) {
    return v != 0.0 && std::fabs(v) < std::numeric_limits<double>::min();
}
bool denormal(float v) {
    return v != 0.0f && std::fabs(v) < std::numeric_limits<float>::min();
}

// ---- writing -------------------------------------------------------------------------------------

// Unsigned values in the fewest bytes (1 to 4) that hold the largest: the width, then the values.
template <class Get> void writeColumn(ByteWriter& w, size_t n, Get get) {
    uint32_t largest = 0;
    for (size_t i = 0; i < n; ++i)
        largest = std::max(largest, uint32_t(get(i)));
    const unsigned width = largest < (1u << 8) ? 1 : largest < (1u << 16) ? 2 : largest < (1u << 24) ? 3 : 4;
    w.u8(uint8_t(width));
    uint8_t* p = w.grow(n * width);
    for (size_t i = 0; i < n; ++i, p += width) {
        const uint32_t v = uint32_t(get(i));
        for (unsigned b = 0; b < width; ++b)
            p[b] = uint8_t(v >> (8 * b));
    }
}

// Per-decal values that most decals leave at their default: the kind (u8), then for kAbsent
// nothing (every value the default), for kDense `n` values, for kSparse the count of the others
// (u32), a column of their ascending indices and their values; whichever is smallest.
enum : uint8_t { kAbsent = 0, kDense = 1, kSparse = 2 };

template <class IsDefault, class Store>
void writeSparse(ByteWriter& w, size_t n, size_t valueBytes, IsDefault isDefault, Store store) {
    std::vector<uint32_t> others;
    for (size_t i = 0; i < n; ++i)
        if (!isDefault(i)) others.push_back(uint32_t(i));
    const size_t indexBytes = n < (1u << 8) ? 1 : n < (1u << 16) ? 2 : n < (1u << 24) ? 3 : 4;
    const bool sparse = 5 + others.size() * (indexBytes + valueBytes) < n * valueBytes;
    w.u8(others.empty() ? kAbsent : sparse ? kSparse : kDense);
    if (others.empty()) return;
    if (sparse) {
        w.u32(uint32_t(others.size()));
        writeColumn(w, others.size(), [&](size_t k) { return others[k]; });
    }
    const size_t count = sparse ? others.size() : n;
    uint8_t* p = w.grow(count * valueBytes);
    for (size_t k = 0; k < count; ++k, p += valueBytes)
        store(p, sparse ? others[k] : k);
}

void writeSettings(ByteWriter& w, const DecalSystemState& st) {
    const DecalSettings& s = st.settings;
    w.u64(s.seed);
    w.f32(s.cellSize);
    w.u32(s.maxPerCell);
    w.u8(uint8_t(s.policy));
    w.u32(s.budget);
    w.u32(s.maxPerObject);
    w.f64(s.idSeparation);
    w.f32(s.depthMargin);
}

void writeClock(ByteWriter& w, const DecalSystemState& st) {
    w.f64(st.time);
    w.u64(st.rngState);
    w.u64(st.rngIncrement);
}

void writeStats(ByteWriter& w, const DecalSystemState& st) {
    const DecalStats& s = st.stats;
    w.u64(s.placed);
    w.u32(uint32_t(s.rejected.size()));
    for (uint64_t r : s.rejected)
        w.u64(r);
    w.u64(s.evicted);
    w.u64(s.expired);
    w.u64(s.removed);
    w.u64(s.alive);
    w.u64(s.fading);
    w.u32(s.sharedObjectIds);
}

void writeTypes(ByteWriter& w, const DecalSystemState& st) {
    w.u32(uint32_t(st.typeNames.size()));
    for (const std::string& name : st.typeNames)
        w.text(name);
}

void writeObjects(ByteWriter& w, const DecalSystemState& st) {
    w.u32(uint32_t(st.objects.size()));
    for (const SavedObject& o : st.objects) {
        w.text(o.name);
        w.u64(o.meshHash);
        w.u8(uint8_t((o.dynamic ? kDynamicFlag : 0) | (o.inWorld ? kInWorldFlag : 0)));
        w.u8(o.objectId);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                w.f64(o.transform[c][r]);
    }
}

void writeSlots(ByteWriter& w, const DecalSystemState& st) {
    w.u32(uint32_t(st.generations.size()));
    writeColumn(w, st.generations.size(), [&](size_t i) { return st.generations[i]; });
    w.u32(uint32_t(st.freeSlots.size()));
    writeColumn(w, st.freeSlots.size(), [&](size_t i) { return st.freeSlots[i]; });
}

bool sameClips(const Decal& a, const Decal& b) {
    for (int k = 0; k < 2; ++k)
        if (a.clips[k].octX != b.clips[k].octX || a.clips[k].octY != b.clips[k].octY ||
            a.clips[k].offset != b.clips[k].offset)
            return false;
    return true;
}

void writeDecals(ByteWriter& w, const DecalSystemState& st) {
    const std::vector<Decal>& d = st.decals;
    const size_t n = d.size();
    w.u32(uint32_t(n));
    uint8_t* p = w.grow(n * kSavedDecalBytes);
    for (size_t i = 0; i < n; ++i, p += kSavedDecalBytes)
        storeDecal(p, d[i]);
    writeSparse(
        w, n, 4, [&](size_t i) { return d[i].opacity == 1.0f; },
        [&](uint8_t* q, size_t i) { storeF32(q, d[i].opacity); });
    const Decal plain;
    writeSparse(
        w, n, 8, [&](size_t i) { return sameClips(d[i], plain); },
        [&](uint8_t* q, size_t i) {
            for (int k = 0; k < 2; ++k, q += 4) {
                q[0] = uint8_t(d[i].clips[k].octX);
                q[1] = uint8_t(d[i].clips[k].octY);
                storeU16(q + 2, uint16_t(d[i].clips[k].offset));
            }
        });
    writeColumn(w, n, [&](size_t i) { return d[i].type; });
    writeColumn(w, n, [&](size_t i) { return d[i].object; });
    writeColumn(w, n, [&](size_t i) { return st.slotOf[i]; });
}

void writeLimits(ByteWriter& w, const DecalSystemState& st) {
    w.u32(uint32_t(st.limitOrder.size()));
    writeColumn(w, st.limitOrder.size(), [&](size_t i) { return st.limitOrder[i]; });
    w.u32(uint32_t(st.cellExceptions.size()));
    for (const CellException& e : st.cellExceptions) {
        w.u32(e.position);
        w.u64(uint64_t(e.key.x));
        w.u64(uint64_t(e.key.y));
        w.u64(uint64_t(e.key.z));
        w.u32(e.key.space);
    }
}

void writeFading(ByteWriter& w, const DecalSystemState& st) {
    w.u32(uint32_t(st.fading.size()));
    for (const auto& [slot, since] : st.fading) {
        w.u32(slot);
        w.f64(since);
    }
}

void writeChanges(ByteWriter& w, const DecalSystemState& st) {
    w.u64(st.changeLogBase);
    w.u32(uint32_t(st.changeLog.size()));
    for (const DecalChange& c : st.changeLog) {
        w.u32(c.index);
        w.u32(c.from);
        w.u8(uint8_t(c.kind));
    }
}

uint32_t checksum(const uint8_t* data, size_t size) {
    Crc32 crc;
    crc.update(data, kChecksumAt);
    crc.update(data + kChecksumAt + 4, size - kChecksumAt - 4);
    return crc.value();
}

std::vector<uint8_t> encode(const DecalSystemState& st) {
    using Writer = void (*)(ByteWriter&, const DecalSystemState&);
    static const Writer kWriters[kSectionCount] = {writeSettings, writeClock,  writeStats,  writeTypes,
                                                   writeObjects,  writeSlots,  writeDecals, writeLimits,
                                                   writeFading,   writeChanges};
    std::vector<uint8_t> out;
    out.reserve(kHeaderBytes + st.decals.size() * (kSavedDecalBytes + 16) + 4096);
    ByteWriter w(out);
    std::memcpy(w.grow(8), kMagic, 8);
    w.u32(kDecalSaveVersion);
    w.u32(kByteOrderMark);
    w.grow(16); // total size, checksum, section count: below
    for (uint32_t k = 0; k < kSectionCount; ++k) {
        std::memcpy(w.grow(4), kSections[k], 4);
        const size_t lengthAt = w.size();
        w.grow(8);
        kWriters[k](w, st);
        storeU64(w.at(lengthAt), uint64_t(w.size() - lengthAt - 8));
    }
    storeU64(w.at(16), out.size());
    storeU32(w.at(28), kSectionCount);
    storeU32(w.at(kChecksumAt), checksum(out.data(), out.size()));
    return out;
}

// ---- reading -------------------------------------------------------------------------------------

std::string tagText(const uint8_t* tag) {
    std::string s;
    for (int i = 0; i < 4; ++i) {
        const uint8_t c = tag[i];
        if (c >= 0x20 && c < 0x7F) {
            s += char(c);
        } else {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02x", c);
            s += hex;
        }
    }
    return s;
}

Status truncated(const char* section, const char* what) {
    return corrupt(std::string("section ") + section + " ends inside " + what);
}

// `n` values of a column written by writeColumn; `what` names it in errors.
Status readColumn(ByteReader& r, const char* section, const char* what, size_t n,
                  std::vector<uint32_t>& out) {
    uint8_t width = 0;
    if (!r.u8(width)) return truncated(section, what);
    if (width < 1 || width > 4)
        return corrupt(std::string("section ") + section + ": " + what + " column has width " +
                       std::to_string(width) + " (1 to 4)");
    const uint8_t* p = n <= r.remaining() / width ? r.take(n * width) : nullptr;
    if (!p)
        return corrupt(std::string("section ") + section + ": " + std::to_string(n) + " " + what + " need " +
                       std::to_string(uint64_t(n) * width) + " bytes, " + std::to_string(r.remaining()) +
                       " remain");
    out.resize(n);
    for (size_t i = 0; i < n; ++i, p += width) {
        uint32_t v = 0;
        for (unsigned b = width; b-- > 0;)
            v = (v << 8) | p[b];
        out[i] = v;
    }
    return {};
}

// A count of items of at least `itemBytes` bytes each that the section's bytes must hold.
Status readCount(ByteReader& r, const char* section, const char* what, size_t itemBytes, uint32_t& n) {
    if (!r.u32(n)) return truncated(section, what);
    if (n > r.remaining() / itemBytes)
        return corrupt(std::string("section ") + section + " claims " + std::to_string(n) + " " + what +
                       ", which need at least " + std::to_string(uint64_t(n) * itemBytes) + " bytes; " +
                       std::to_string(r.remaining()) + " remain");
    return {};
}

Status readSettings(ByteReader& r, DecalSystemState& st) {
    DecalSettings& s = st.settings;
    uint8_t policy = 0;
    if (!(r.u64(s.seed) && r.f32(s.cellSize) && r.u32(s.maxPerCell) && r.u8(policy) && r.u32(s.budget) &&
          r.u32(s.maxPerObject) && r.f64(s.idSeparation) && r.f32(s.depthMargin)))
        return truncated("SETT", "the settings");
    s.policy = LimitPolicy(policy);
    if (std::string problem = DecalSystemAccess::settingsProblem(s); !problem.empty())
        return corrupt(problem);
    return {};
}

Status readClock(ByteReader& r, DecalSystemState& st) {
    if (!(r.f64(st.time) && r.u64(st.rngState) && r.u64(st.rngIncrement)))
        return truncated("CLCK", "the clock");
    if (!std::isfinite(st.time) || st.time < 0.0 || denormal(st.time))
        return corrupt("the clock is not finite, >= 0 and normal");
    if ((st.rngIncrement & 1u) == 0) return corrupt("the random generator's increment is even");
    return {};
}

Status readStats(ByteReader& r, DecalSystemState& st) {
    DecalStats& s = st.stats;
    uint32_t statuses = 0;
    if (!(r.u64(s.placed) && r.u32(statuses))) return truncated("STAT", "the statistics");
    if (statuses != s.rejected.size())
        return corrupt("the statistics count " + std::to_string(statuses) + " spawn statuses, not " +
                       std::to_string(s.rejected.size()));
    for (uint64_t& v : s.rejected)
        if (!r.u64(v)) return truncated("STAT", "the rejections");
    uint64_t alive = 0, fading = 0;
    if (!(r.u64(s.evicted) && r.u64(s.expired) && r.u64(s.removed) && r.u64(alive) && r.u64(fading) &&
          r.u32(s.sharedObjectIds)))
        return truncated("STAT", "the statistics");
    s.alive = size_t(alive);
    s.fading = size_t(fading);
    return {};
}

Status readTypes(ByteReader& r, DecalSystemState& st) {
    uint32_t n = 0;
    if (Status s = readCount(r, "TYPE", "types", 4, n); !s) return s;
    if (n > 65535) return corrupt(std::to_string(n) + " decal types (65535 at most)");
    st.typeNames.resize(n);
    for (std::string& name : st.typeNames) {
        if (!r.text(name)) return truncated("TYPE", "a type name");
        if (name.empty()) return corrupt("a decal type with an empty name");
    }
    std::vector<std::string> sorted = st.typeNames;
    std::sort(sorted.begin(), sorted.end());
    if (auto twin = std::adjacent_find(sorted.begin(), sorted.end()); twin != sorted.end())
        return corrupt("decal type '" + *twin + "' appears twice");
    return {};
}

Status readObjects(ByteReader& r, DecalSystemState& st) {
    uint32_t n = 0;
    if (Status s = readCount(r, "OBJS", "objects", kObjectMinBytes, n); !s) return s;
    st.objects.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        SavedObject& o = st.objects[i];
        uint8_t flags = 0;
        if (!(r.text(o.name) && r.u64(o.meshHash) && r.u8(flags) && r.u8(o.objectId)))
            return truncated("OBJS", "an object");
        for (int c = 0; c < 4; ++c)
            for (int k = 0; k < 4; ++k)
                if (!r.f64(o.transform[c][k])) return truncated("OBJS", "a transform");
        if (flags > (kDynamicFlag | kInWorldFlag))
            return corrupt("object " + std::to_string(i) + " has unknown flags " + std::to_string(flags));
        o.dynamic = (flags & kDynamicFlag) != 0;
        o.inWorld = (flags & kInWorldFlag) != 0;
        if (std::string problem = transformProblem(o.transform); !problem.empty())
            return corrupt("object " + std::to_string(i) + " '" + o.name + "': " + problem);
    }
    return {};
}

Status readSlots(ByteReader& r, DecalSystemState& st) {
    uint32_t slots = 0, free = 0;
    if (!r.u32(slots)) return truncated("SLOT", "the slot count");
    if (Status s = readColumn(r, "SLOT", "generations", slots, st.generations); !s) return s;
    if (!r.u32(free)) return truncated("SLOT", "the free count");
    if (free > slots) return corrupt(std::to_string(free) + " free slots of " + std::to_string(slots));
    return readColumn(r, "SLOT", "free slots", free, st.freeSlots);
}

Status checkDecal(const Decal& d, double time, size_t i) {
    auto bad = [i](const char* what) { return corrupt("decal " + std::to_string(i) + ": " + what); };
    auto extent = [](float v) { return std::isfinite(v) && v >= std::numeric_limits<float>::min(); };
    if (!std::isfinite(d.center.x) || !std::isfinite(d.center.y) || !std::isfinite(d.center.z))
        return bad("centre is not finite");
    if (!extent(d.size.x) || !extent(d.size.y) || !extent(d.halfDepth))
        return bad("size or half-depth is not finite, positive and normal");
    if (!hasOrientation(d.packedFrame)) return bad("frame has no orientation");
    if (!std::isfinite(d.spawnTime) || d.spawnTime < 0.0 || d.spawnTime > time || denormal(d.spawnTime))
        return bad("spawn time is not a normal time between 0 and the clock");
    if (!std::isfinite(d.opacity) || d.opacity < 0.0f || d.opacity > 1.0f || denormal(d.opacity))
        return bad("opacity is not a normal number in [0, 1]");
    return {};
}

// The values writeSparse wrote for `n` decals, handed to `load` with their decal's index.
template <class Load>
Status readSparse(ByteReader& r, const char* what, size_t n, size_t valueBytes, Load load) {
    uint8_t kind = 0;
    uint32_t count = uint32_t(n);
    std::vector<uint32_t> indices;
    if (!r.u8(kind)) return truncated("DECL", what);
    if (kind > kSparse)
        return corrupt(std::string("unknown kind ") + std::to_string(kind) + " of the " + what);
    if (kind == kAbsent) return {};
    if (kind == kSparse) {
        if (Status s = readCount(r, "DECL", what, valueBytes + 1, count); !s) return s;
        if (Status s = readColumn(r, "DECL", what, count, indices); !s) return s;
        for (size_t k = 0; k < count; ++k)
            if (indices[k] >= n || (k > 0 && indices[k] <= indices[k - 1]))
                return corrupt(std::string("the ") + what + " name decal " + std::to_string(indices[k]) +
                               " out of order or range");
    }
    const uint8_t* p = count <= r.remaining() / valueBytes ? r.take(count * valueBytes) : nullptr;
    if (!p) return truncated("DECL", what);
    for (size_t k = 0; k < count; ++k, p += valueBytes)
        load(p, kind == kSparse ? indices[k] : k);
    return {};
}

Status readDecalColumns(ByteReader& r, DecalSystemState& st) {
    std::vector<Decal>& d = st.decals;
    const size_t n = d.size();
    Status opacities =
        readSparse(r, "opacities", n, 4, [&](const uint8_t* p, size_t i) { d[i].opacity = loadF32(p); });
    if (!opacities) return opacities;
    Status clips = readSparse(r, "clips", n, 8, [&](const uint8_t* p, size_t i) {
        for (int k = 0; k < 2; ++k, p += 4) {
            d[i].clips[k].octX = int8_t(p[0]);
            d[i].clips[k].octY = int8_t(p[1]);
            d[i].clips[k].offset = int16_t(loadU16(p + 2));
        }
    });
    if (!clips) return clips;
    std::vector<uint32_t> column;
    if (Status s = readColumn(r, "DECL", "types", n, column); !s) return s;
    for (size_t i = 0; i < n; ++i) {
        if (column[i] >= st.typeNames.size())
            return corrupt("decal " + std::to_string(i) + " has type " + std::to_string(column[i]) + " of " +
                           std::to_string(st.typeNames.size()));
        d[i].type = uint16_t(column[i]);
    }
    if (Status s = readColumn(r, "DECL", "objects", n, column); !s) return s;
    for (size_t i = 0; i < n; ++i) {
        if (column[i] >= st.objects.size() || !st.objects[column[i]].inWorld)
            return corrupt("decal " + std::to_string(i) + " lies on object " + std::to_string(column[i]) +
                           ", which the save has not in its world (" + std::to_string(st.objects.size()) +
                           " objects)");
        d[i].object = column[i];
        d[i].objectId = st.objects[column[i]].objectId;
    }
    return readColumn(r, "DECL", "slots", n, st.slotOf);
}

Status readDecals(ByteReader& r, DecalSystemState& st) {
    uint32_t n = 0;
    if (Status s = readCount(r, "DECL", "decals", kSavedDecalBytes, n); !s) return s;
    st.decals.resize(n);
    const uint8_t* p = r.take(size_t(n) * kSavedDecalBytes);
    for (uint32_t i = 0; i < n; ++i, p += kSavedDecalBytes)
        loadDecal(p, st.decals[i]);
    if (Status s = readDecalColumns(r, st); !s) return s;
    for (uint32_t i = 0; i < n; ++i)
        if (Status s = checkDecal(st.decals[i], st.time, i); !s) return s;
    return {};
}

Status readLimits(ByteReader& r, DecalSystemState& st) {
    uint32_t n = 0, exceptions = 0;
    if (!r.u32(n)) return truncated("LIMS", "the count");
    if (Status s = readColumn(r, "LIMS", "counted slots", n, st.limitOrder); !s) return s;
    if (Status s = readCount(r, "LIMS", "cell exceptions", kExceptionBytes, exceptions); !s) return s;
    st.cellExceptions.resize(exceptions);
    for (CellException& e : st.cellExceptions) {
        uint64_t x = 0, y = 0, z = 0;
        r.u32(e.position), r.u64(x), r.u64(y), r.u64(z), r.u32(e.key.space); // counted above
        e.key.x = int64_t(x);
        e.key.y = int64_t(y);
        e.key.z = int64_t(z);
    }
    return {};
}

Status readFading(ByteReader& r, DecalSystemState& st) {
    uint32_t n = 0;
    if (Status s = readCount(r, "FADE", "fading decals", kFadingBytes, n); !s) return s;
    st.fading.resize(n);
    for (auto& [slot, since] : st.fading) {
        r.u32(slot), r.f64(since); // counted above
        if (!std::isfinite(since) || since < 0.0 || since > st.time || denormal(since))
            return corrupt("a fading decal's eviction time is not a normal time between 0 and the clock");
    }
    return {};
}

Status readChanges(ByteReader& r, DecalSystemState& st) {
    uint32_t n = 0;
    if (!r.u64(st.changeLogBase)) return truncated("CHNG", "the change log");
    if (Status s = readCount(r, "CHNG", "changes", kChangeBytes, n); !s) return s;
    st.changeLog.resize(n);
    for (DecalChange& c : st.changeLog) {
        uint8_t kind = 0;
        r.u32(c.index), r.u32(c.from), r.u8(kind); // counted above
        if (kind > uint8_t(DecalChangeKind::Removed))
            return corrupt("a change of unknown kind " + std::to_string(kind));
        c.kind = DecalChangeKind(kind);
    }
    if (st.changeLogBase > std::numeric_limits<uint64_t>::max() - n)
        return corrupt("the change log's version overflows");
    return {};
}

// Every slot is used by one decal or free once; the fading slots and the counted ones are used,
// the counted ones exactly those not fading, each once, in cells of their object's space.
Status checkSlots(const DecalSystemState& st) {
    const size_t slots = st.generations.size();
    std::vector<uint8_t> use(slots, 0); // 1 used, 2 free, 3 fading, 4 counted
    for (size_t i = 0; i < st.slotOf.size(); ++i) {
        const uint32_t slot = st.slotOf[i];
        if (slot >= slots || use[slot] != 0)
            return corrupt("decal " + std::to_string(i) + " has slot " + std::to_string(slot) +
                           (slot >= slots ? " of " + std::to_string(slots) : ", used twice"));
        use[slot] = 1;
    }
    for (uint32_t slot : st.freeSlots) {
        if (slot >= slots || use[slot] != 0)
            return corrupt("free slot " + std::to_string(slot) + " is out of range or in use");
        use[slot] = 2;
    }
    if (st.slotOf.size() + st.freeSlots.size() != slots)
        return corrupt(std::to_string(slots) + " slots, of which " + std::to_string(st.slotOf.size()) +
                       " used and " + std::to_string(st.freeSlots.size()) + " free");
    for (size_t i = 0; i < st.fading.size(); ++i) {
        const uint32_t slot = st.fading[i].first;
        if (slot >= slots || use[slot] != 1 || (i > 0 && slot <= st.fading[i - 1].first))
            return corrupt("fading slot " + std::to_string(slot) + " is not a used slot in ascending order");
        use[slot] = 3;
    }
    if (st.limitOrder.size() + st.fading.size() != st.decals.size())
        return corrupt(std::to_string(st.limitOrder.size()) + " counted and " +
                       std::to_string(st.fading.size()) + " fading decals of " +
                       std::to_string(st.decals.size()));
    for (uint32_t slot : st.limitOrder) {
        if (slot >= slots || use[slot] != 1)
            return corrupt("counted slot " + std::to_string(slot) +
                           " is not a used slot, or fading, or twice");
        use[slot] = 4;
    }
    return {};
}

Status checkCells(const DecalSystemState& st) {
    std::vector<uint32_t> denseOf(st.generations.size());
    for (uint32_t i = 0; i < st.slotOf.size(); ++i)
        denseOf[st.slotOf[i]] = i;
    for (size_t k = 0; k < st.cellExceptions.size(); ++k) {
        const CellException& e = st.cellExceptions[k];
        if (e.position >= st.limitOrder.size() || (k > 0 && e.position <= st.cellExceptions[k - 1].position))
            return corrupt("cell exception at position " + std::to_string(e.position) + " out of order");
        const uint32_t object = st.decals[denseOf[st.limitOrder[e.position]]].object;
        const uint32_t space = st.objects[object].dynamic ? object + 1 : 0;
        if (e.key.space != space)
            return corrupt("cell exception at position " + std::to_string(e.position) + " in space " +
                           std::to_string(e.key.space) + ", not its object's " + std::to_string(space));
    }
    return {};
}

Status checkStats(const DecalSystemState& st) {
    const DecalStats& s = st.stats;
    if (s.alive != st.decals.size() || s.fading != st.fading.size())
        return corrupt("the statistics count " + std::to_string(s.alive) + " alive and " +
                       std::to_string(s.fading) + " fading decals, the save holds " +
                       std::to_string(st.decals.size()) + " and " + std::to_string(st.fading.size()));
    const uint64_t accounted = uint64_t(s.alive - s.fading) + s.evicted + s.expired + s.removed;
    if (accounted < s.evicted || s.placed != accounted)
        return corrupt("the statistics do not add up (placed " + std::to_string(s.placed) +
                       " != alive - fading + evicted + expired + removed)");
    return {};
}

Result<ByteReader> openSection(ByteReader& r, const char* tag) {
    const uint8_t* h = r.take(kSectionHeaderBytes);
    if (!h) return corrupt(std::string("truncated before section ") + tag);
    if (std::memcmp(h, tag, 4) != 0)
        return corrupt(std::string("expected section ") + tag + ", found '" + tagText(h) + "'");
    const uint64_t length = loadU64(h + 4);
    if (length > r.remaining())
        return corrupt(std::string("section ") + tag + " claims " + std::to_string(length) + " bytes, " +
                       std::to_string(r.remaining()) + " remain");
    return ByteReader(r.take(size_t(length)), size_t(length));
}

// Magic, version and byte order of a header's kHeaderBytes bytes.
Status checkPreamble(const uint8_t* data) {
    if (std::memcmp(data, kMagic, 8) != 0) return corrupt("not a decal save (bad magic)");
    const uint32_t version = loadU32(data + 8);
    if (version > kDecalSaveVersion)
        return corrupt("format version " + std::to_string(version) + " is newer than this build reads (" +
                       std::to_string(kDecalSaveVersion) + ")");
    if (version == 0) return corrupt("format version 0 does not exist");
    const uint32_t mark = loadU32(data + 12);
    if (mark == 0x04030201) return corrupt("big-endian saves are not read by this version");
    if (mark != kByteOrderMark) return corrupt("bad byte-order mark");
    return {};
}

Status checkHeader(const uint8_t* data, size_t size) {
    if (size < kHeaderBytes)
        return corrupt("truncated: " + std::to_string(size) + " bytes, a save has at least " +
                       std::to_string(kHeaderBytes));
    if (Status s = checkPreamble(data); !s) return s;
    const uint64_t total = loadU64(data + 16);
    if (total != size)
        return corrupt(total > size
                           ? "truncated: " + std::to_string(size) + " of " + std::to_string(total) + " bytes"
                           : std::to_string(size - total) + " bytes past the end of the save");
    if (loadU32(data + kChecksumAt) != checksum(data, size)) return corrupt("checksum mismatch");
    if (loadU32(data + 28) != kSectionCount)
        return corrupt(std::to_string(loadU32(data + 28)) + " sections, version 1 has " +
                       std::to_string(kSectionCount));
    return {};
}

Result<DecalSystemState> decode(const uint8_t* data, size_t size) {
    if (Status s = checkHeader(data, size); !s) return fail(s.error());
    using Reader = Status (*)(ByteReader&, DecalSystemState&);
    static const Reader kReaders[kSectionCount] = {readSettings, readClock,  readStats,  readTypes,
                                                   readObjects,  readSlots,  readDecals, readLimits,
                                                   readFading,   readChanges};
    ByteReader r(data + kHeaderBytes, size - kHeaderBytes);
    DecalSystemState st;
    for (uint32_t k = 0; k < kSectionCount; ++k) {
        Result<ByteReader> section = openSection(r, kSections[k]);
        if (!section) return fail(section.error());
        if (Status s = kReaders[k](section.value(), st); !s) return fail(s.error());
        if (section->remaining() != 0)
            return corrupt(std::string("section ") + kSections[k] + " has " +
                           std::to_string(section->remaining()) + " bytes past its content");
    }
    if (r.remaining() != 0) return corrupt(std::to_string(r.remaining()) + " bytes after the last section");
    if (Status s = checkSlots(st); !s) return fail(s.error());
    if (Status s = checkCells(st); !s) return fail(s.error());
    if (Status s = checkStats(st); !s) return fail(s.error());
    return st;
}

// ---- matching against the system -----------------------------------------------------------------

Status mapTypes(const DecalSystem& system, DecalSystemState& st) {
    std::vector<uint16_t> index(st.typeNames.size());
    for (size_t i = 0; i < index.size(); ++i) {
        Result<uint16_t> t = system.typeIndex(st.typeNames[i]);
        if (!t) return corrupt("decal type '" + st.typeNames[i] + "' is not registered in this system");
        index[i] = t.value();
    }
    for (Decal& d : st.decals)
        d.type = index[d.type];
    return {};
}

// Why saved object `i` does not match the world, or empty.
std::string mismatch(const CollisionWorld& world, const SavedObject& o, uint32_t i) {
    const CollisionObject* w = world.object(i);
    if (!w) return "missing (the world has " + std::to_string(world.objectCount()) + " objects)";
    if (w->name != o.name) return "missing (object " + std::to_string(i) + " is '" + w->name + "')";
    if (w->meshHash != o.meshHash) return "its mesh changed";
    if (w->dynamic != o.dynamic) return o.dynamic ? "no longer dynamic" : "now dynamic";
    if (o.inWorld && !w->inWorld) return "not in the world";
    return {};
}

RestorePlan plan(const CollisionWorld& world, const DecalSystemState& st, DecalLoadReport& report) {
    RestorePlan p;
    p.keepObject.assign(st.objects.size(), true);
    std::vector<size_t> decalsOn(st.objects.size(), 0);
    for (const Decal& d : st.decals)
        decalsOn[d.object]++;
    for (uint32_t i = 0; i < st.objects.size(); ++i) {
        const SavedObject& o = st.objects[i];
        if (std::string why = mismatch(world, o, i); !why.empty()) {
            p.keepObject[i] = false;
            report.droppedDecals += decalsOn[i];
            report.droppedObjects.push_back("object " + std::to_string(i) + " '" + o.name + "': " + why +
                                            "; " + std::to_string(decalsOn[i]) + " decals dropped");
            continue;
        }
        // Removed objects take their last transform too: it is part of the world's state.
        if (o.dynamic && world.object(i)->inWorld) p.moves.emplace_back(i, o.transform);
        if (!o.inWorld && world.object(i)->inWorld) p.removals.push_back(i);
    }
    return p;
}

} // namespace

std::vector<uint8_t> saveDecals(const DecalSystem& system) {
    return encode(DecalSystemAccess::capture(system));
}

Status saveDecals(const DecalSystem& system, std::ostream& out) {
    const std::vector<uint8_t> bytes = saveDecals(system);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    if (!out) return fail("decal save: the stream failed after " + std::to_string(bytes.size()) + " bytes");
    return {};
}

Status saveDecalsToFile(const DecalSystem& system, const std::string& path) {
    const std::string temp = path + ".tmp";
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out) return fail("decal save " + temp + ": cannot be created");
        if (Status s = saveDecals(system, out); !s) return fail(temp + ": " + s.error());
        out.close();
        if (!out) return fail("decal save " + temp + ": cannot be written");
    }
    std::error_code ec;
    std::filesystem::rename(temp, path, ec);
    if (ec) {
        std::filesystem::remove(temp, ec);
        return fail("decal save " + path + ": cannot replace it: " + ec.message());
    }
    return {};
}

Result<DecalLoadReport> loadDecals(DecalSystem& system, const uint8_t* data, size_t size) {
    Result<DecalSystemState> st = decode(data, size);
    if (!st) return fail(st.error());
    const std::unique_lock<std::mutex> lock = DecalSystemAccess::lock(system);
    if (Status s = mapTypes(system, st.value()); !s) return fail(s.error());
    DecalLoadReport report;
    const RestorePlan p = plan(system.world(), st.value(), report);
    DecalSystemAccess::restore(system, std::move(st).value(), p);
    report.decals = system.decals().size();
    return report;
}

Result<DecalLoadReport> loadDecals(DecalSystem& system, std::istream& in) {
    std::vector<uint8_t> bytes(kHeaderBytes);
    in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(kHeaderBytes));
    if (size_t(in.gcount()) != kHeaderBytes) return corrupt("truncated: the stream ends inside the header");
    if (Status s = checkPreamble(bytes.data()); !s) return fail(s.error());
    const uint64_t total = loadU64(bytes.data() + 16);
    // Grown as the bytes arrive, so a corrupt length costs no more memory than the stream holds.
    while (bytes.size() < total) {
        const size_t at = bytes.size();
        const size_t chunk = size_t(std::min<uint64_t>(total - at, std::max<size_t>(at, 1 << 16)));
        bytes.resize(at + chunk);
        in.read(reinterpret_cast<char*>(bytes.data() + at), std::streamsize(chunk));
        if (size_t(in.gcount()) != chunk)
            return corrupt("truncated: the stream ends after " + std::to_string(at + size_t(in.gcount())) +
                           " of " + std::to_string(total) + " bytes");
    }
    return loadDecals(system, bytes.data(), bytes.size());
}

Result<DecalLoadReport> loadDecalsFromFile(DecalSystem& system, const std::string& path) {
    std::error_code ec;
    const uintmax_t size = std::filesystem::file_size(path, ec);
    std::ifstream in(path, std::ios::binary);
    if (ec || !in) return fail("decal save " + path + ": cannot be opened");
    // The file's size is known: read it whole, in one allocation.
    std::vector<uint8_t> bytes(static_cast<size_t>(size));
    in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
    if (size_t(in.gcount()) != bytes.size()) return fail("decal save " + path + ": cannot be read");
    Result<DecalLoadReport> r = loadDecals(system, bytes.data(), bytes.size());
    if (!r) return fail(path + ": " + r.error());
    return r;
}

} // namespace spatter
