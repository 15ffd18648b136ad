#include "DecalSaveFormat.hpp"
#include "SavedDecal.hpp"

#include <algorithm>
#include <cstring>

namespace spatter::save {

namespace {

// The fewest bytes (1 to 4) that hold `largest`.
unsigned widthFor(uint64_t largest) {
    return largest < (1u << 8) ? 1 : largest < (1u << 16) ? 2 : largest < (1u << 24) ? 3 : 4;
}

// Unsigned values in the fewest bytes that hold the largest: the width, then the values.
template <class Get> void writeColumn(ByteWriter& w, size_t n, Get get) {
    uint32_t largest = 0;
    for (size_t i = 0; i < n; ++i)
        largest = std::max(largest, uint32_t(get(i)));
    const unsigned width = widthFor(largest);
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
template <class IsDefault, class Store>
void writeSparse(ByteWriter& w, size_t n, size_t valueBytes, IsDefault isDefault, Store store) {
    std::vector<uint32_t> others;
    for (size_t i = 0; i < n; ++i)
        if (!isDefault(i)) others.push_back(uint32_t(i));
    const bool sparse = 5 + others.size() * (widthFor(n) + valueBytes) < n * valueBytes;
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

void writeDecals(ByteWriter& w, const DecalSystemState& st) {
    const std::vector<Decal>& d = st.decals;
    const size_t n = d.size();
    w.u32(uint32_t(n));
    uint8_t* p = w.grow(n * kSavedDecalBytes);
    for (size_t i = 0; i < n; ++i, p += kSavedDecalBytes)
        storeDecal(p, d[i]);
    writeSparse(
        w, n, 1, [&](size_t i) { return d[i].opacity.bits() == 255; },
        [&](uint8_t* q, size_t i) { q[0] = d[i].opacity.bits(); });
    writeSparse(
        w, n, 8, [&](size_t i) { return st.clips[i] == CraterClips{}; },
        [&](uint8_t* q, size_t i) {
            for (const CraterClip& c : st.clips[i].planes) {
                q[0] = uint8_t(c.octX);
                q[1] = uint8_t(c.octY);
                storeU16(q + 2, uint16_t(c.offset));
                q += 4;
            }
        });
    writeSparse(
        w, n, 4, [&](size_t i) { return d[i].slant == 0; },
        [&](uint8_t* q, size_t i) { storeU32(q, d[i].slant); });
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
    const std::vector<DecalChange>& log = st.changeLog;
    w.u32(uint32_t(log.size()));
    writeColumn(w, log.size(), [&](size_t i) { return log[i].index; });
    writeColumn(w, log.size(), [&](size_t i) { return log[i].from; });
    uint8_t* kinds = w.grow(log.size());
    for (size_t i = 0; i < log.size(); ++i)
        kinds[i] = uint8_t(log[i].kind);
}

void writeAnchors(ByteWriter& w, const DecalSystemState& st) {
    w.u32(uint32_t(st.anchors.size()));
    for (const SavedAnchor& a : st.anchors) {
        w.u32(a.slot);
        w.u32(a.surface.triangle);
        for (const glm::dvec3* v : {&a.surface.bary, &a.center, &a.tangent, &a.normal})
            for (int k = 0; k < 3; ++k)
                w.f64((*v)[k]);
    }
}

} // namespace

std::vector<uint8_t> encode(const DecalSystemState& st) {
    using Writer = void (*)(ByteWriter&, const DecalSystemState&);
    static const Writer kWriters[kSectionCount] = {writeSettings, writeClock,   writeStats,  writeTypes,
                                                   writeObjects,  writeSlots,   writeDecals, writeLimits,
                                                   writeFading,   writeChanges, writeAnchors};
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

} // namespace spatter::save
