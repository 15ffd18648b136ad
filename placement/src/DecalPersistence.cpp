#include "spatter/placement/DecalPersistence.hpp"

#include "DecalSaveFormat.hpp"
#include "DecalSystemState.hpp"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <istream>
#include <ostream>

namespace spatter {

using namespace save;

namespace {

// The save's type indices turned into the system's, by name.
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
    std::error_code ec;
    // A failure leaves no temporary file behind (the file at `path` is as it was).
    auto failWith = [&](const std::string& message) {
        std::error_code ignored;
        std::filesystem::remove(temp, ignored);
        return fail(message);
    };
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out) return failWith("decal save " + temp + ": cannot be created");
        if (Status s = saveDecals(system, out); !s) return failWith(temp + ": " + s.error());
        out.close();
        if (!out) return failWith("decal save " + temp + ": cannot be written");
    }
    std::filesystem::rename(temp, path, ec);
    if (ec) return failWith("decal save " + path + ": cannot replace it: " + ec.message());
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
