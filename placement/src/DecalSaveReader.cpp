#include "ChangeLog.hpp"
#include "DecalSaveFormat.hpp"
#include "NumberChecks.hpp"
#include "SavedDecal.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

namespace spatter::save {

namespace {

// A section tag as it reads, bytes outside printable ASCII as \xNN.
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

// A section shorter than its content.
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

Status readSettings(ByteReader& r, DecalSystemState& st, uint32_t /*version*/) {
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

Status readClock(ByteReader& r, DecalSystemState& st, uint32_t /*version*/) {
    if (!(r.f64(st.time) && r.u64(st.rngState) && r.u64(st.rngIncrement)))
        return truncated("CLCK", "the clock");
    if (!std::isfinite(st.time) || st.time < 0.0 || denormal(st.time))
        return corrupt("the clock is not finite, >= 0 and normal");
    if ((st.rngIncrement & 1u) == 0) return corrupt("the random generator's increment is even");
    return {};
}

Status readStats(ByteReader& r, DecalSystemState& st, uint32_t /*version*/) {
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

Status readTypes(ByteReader& r, DecalSystemState& st, uint32_t /*version*/) {
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

Status readObjects(ByteReader& r, DecalSystemState& st, uint32_t /*version*/) {
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

Status readSlots(ByteReader& r, DecalSystemState& st, uint32_t /*version*/) {
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
    if (!validSlant(d.slant)) return bad("slant is not one a projection axis packs to");
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

// Version 1 kept opacities as floats and every decal along its normal.
Status readDecalColumns(ByteReader& r, DecalSystemState& st, uint32_t version) {
    std::vector<Decal>& d = st.decals;
    const size_t n = d.size();
    size_t badOpacity = n;
    Status opacities = version == 1 ? readSparse(r, "opacities", n, 4,
                                                 [&](const uint8_t* p, size_t i) {
                                                     const float o = loadF32(p);
                                                     if (!(o >= 0.0f && o <= 1.0f)) badOpacity = i;
                                                     d[i].opacity = o;
                                                 })
                                    : readSparse(r, "opacities", n, 1, [&](const uint8_t* p, size_t i) {
                                          d[i].opacity = Opacity::fromBits(p[0]);
                                      });
    if (!opacities) return opacities;
    if (badOpacity < n)
        return corrupt("decal " + std::to_string(badOpacity) + ": opacity is not a number in [0, 1]");
    st.clips.assign(n, CraterClips{});
    Status clips = readSparse(r, "clips", n, 8, [&](const uint8_t* p, size_t i) {
        for (CraterClip& c : st.clips[i].planes) {
            c.octX = int8_t(p[0]);
            c.octY = int8_t(p[1]);
            c.offset = int16_t(loadU16(p + 2));
            p += 4;
        }
    });
    if (!clips) return clips;
    if (version >= 2) {
        Status slants =
            readSparse(r, "slants", n, 4, [&](const uint8_t* p, size_t i) { d[i].slant = loadU32(p); });
        if (!slants) return slants;
    }
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

Status readDecals(ByteReader& r, DecalSystemState& st, uint32_t version) {
    uint32_t n = 0;
    if (Status s = readCount(r, "DECL", "decals", kSavedDecalBytes, n); !s) return s;
    st.decals.resize(n);
    const uint8_t* p = r.take(size_t(n) * kSavedDecalBytes);
    for (uint32_t i = 0; i < n; ++i, p += kSavedDecalBytes)
        loadDecal(p, st.decals[i]);
    if (Status s = readDecalColumns(r, st, version); !s) return s;
    for (uint32_t i = 0; i < n; ++i)
        if (Status s = checkDecal(st.decals[i], st.time, i); !s) return s;
    return {};
}

Status readLimits(ByteReader& r, DecalSystemState& st, uint32_t /*version*/) {
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

Status readFading(ByteReader& r, DecalSystemState& st, uint32_t /*version*/) {
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

// Version 1 kept each change as u32 index, u32 from and u8 kind; later versions keep columns.
Status readChangeEntries(ByteReader& r, uint32_t version, uint32_t n, std::vector<DecalChange>& log) {
    std::vector<uint32_t> index, from;
    std::vector<uint8_t> kind(n);
    if (version == 1) {
        index.resize(n), from.resize(n);
        for (uint32_t i = 0; i < n; ++i)
            r.u32(index[i]), r.u32(from[i]), r.u8(kind[i]); // counted by the caller
    } else {
        if (Status s = readColumn(r, "CHNG", "change indices", n, index); !s) return s;
        if (Status s = readColumn(r, "CHNG", "change sources", n, from); !s) return s;
        const uint8_t* p = r.take(n);
        if (!p && n > 0) return truncated("CHNG", "the change kinds");
        std::copy(p, p + n, kind.begin());
    }
    log.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        if (kind[i] > uint8_t(DecalChangeKind::Removed))
            return corrupt("a change of unknown kind " + std::to_string(kind[i]));
        log[i] = DecalChange{index[i], from[i], DecalChangeKind(kind[i])};
    }
    return {};
}

Status readChanges(ByteReader& r, DecalSystemState& st, uint32_t version) {
    uint32_t n = 0;
    if (!r.u64(st.changeLogBase)) return truncated("CHNG", "the change log");
    if (Status s = readCount(r, "CHNG", "changes", version == 1 ? kChangeBytes : kChangeColumnBytes, n); !s)
        return s;
    if (Status s = readChangeEntries(r, version, n, st.changeLog); !s) return s;
    if (st.changeLogBase > std::numeric_limits<uint64_t>::max() - n)
        return corrupt("the change log's version overflows");
    return {};
}

// Every slot is used by one decal or free once; the fading slots and the counted ones are used,
// the counted ones exactly those not fading, each once, in cells of their object's space.
Status readAnchors(ByteReader& r, DecalSystemState& st, uint32_t /*version*/) {
    uint32_t n = 0;
    if (Status s = readCount(r, "SKIN", "anchored decals", kAnchorBytes, n); !s) return s;
    st.anchors.resize(n);
    for (SavedAnchor& a : st.anchors) {
        r.u32(a.slot), r.u32(a.surface.triangle); // counted above
        for (glm::dvec3* v : {&a.surface.bary, &a.center, &a.tangent, &a.normal})
            for (int k = 0; k < 3; ++k) {
                double x = 0.0;
                r.f64(x);
                if (!std::isfinite(x) || denormal(x) || std::abs(x) > 1e9)
                    return corrupt("an anchored decal's coordinates are not normal numbers of sane size");
                (*v)[k] = x;
            }
    }
    return {};
}

// Anchors on used slots, each once, by ascending slot.
Status checkAnchors(const DecalSystemState& st) {
    std::vector<bool> used(st.generations.size(), false);
    for (uint32_t slot : st.slotOf)
        used[slot] = true;
    for (size_t i = 0; i < st.anchors.size(); ++i) {
        const uint32_t slot = st.anchors[i].slot;
        if (slot >= used.size() || !used[slot] || (i > 0 && slot <= st.anchors[i - 1].slot))
            return corrupt("anchored slot " + std::to_string(slot) +
                           " is not a used slot in ascending order");
    }
    return {};
}

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
    const uint32_t sections = sectionsIn(loadU32(data + 8));
    if (loadU32(data + 28) != sections)
        return corrupt(std::to_string(loadU32(data + 28)) + " sections, a save of this version has " +
                       std::to_string(sections));
    return {};
}

} // namespace

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

Result<DecalSystemState> decode(const uint8_t* data, size_t size) {
    if (Status s = checkHeader(data, size); !s) return fail(s.error());
    using Reader = Status (*)(ByteReader&, DecalSystemState&, uint32_t version);
    static const Reader kReaders[kSectionCount] = {readSettings, readClock,   readStats,  readTypes,
                                                   readObjects,  readSlots,   readDecals, readLimits,
                                                   readFading,   readChanges, readAnchors};
    ByteReader r(data + kHeaderBytes, size - kHeaderBytes);
    DecalSystemState st;
    for (uint32_t k = 0; k < sectionsIn(loadU32(data + 8)); ++k) {
        Result<ByteReader> section = openSection(r, kSections[k]);
        if (!section) return fail(section.error());
        if (Status s = kReaders[k](section.value(), st, loadU32(data + 8)); !s) return fail(s.error());
        if (section->remaining() != 0)
            return corrupt(std::string("section ") + kSections[k] + " has " +
                           std::to_string(section->remaining()) + " bytes past its content");
    }
    if (r.remaining() != 0) return corrupt(std::to_string(r.remaining()) + " bytes after the last section");
    if (Status s = checkSlots(st); !s) return fail(s.error());
    if (Status s = checkCells(st); !s) return fail(s.error());
    if (Status s = checkStats(st); !s) return fail(s.error());
    if (Status s = checkAnchors(st); !s) return fail(s.error());
    if (Status s = checkChangeLog(st.changeLog, st.decals.size()); !s) return corrupt(s.error());
    return st;
}

} // namespace spatter::save
