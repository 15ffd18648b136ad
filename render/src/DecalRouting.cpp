#include "DecalRouting.hpp"

#include <algorithm>

namespace spatter::render_detail {

namespace {

// What identifies a decal for splatting: the same decal given again is not splatted twice. On a
// deforming object the decal system moves a decal with the pose (its skin anchor), so its centre and
// frame are not part of what identifies it there.
uint64_t decalKey(const Decal& d, bool deforming) {
    uint64_t h = 1469598103934665603ull;
    auto mix = [&h](const void* data, size_t n) {
        const unsigned char* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i)
            h = (h ^ p[i]) * 1099511628211ull;
    };
    mix(&d.id, sizeof d.id);
    mix(&d.object, sizeof d.object);
    mix(&d.type, sizeof d.type);
    if (deforming) {
        mix(&d.spawnTime, sizeof d.spawnTime);
    } else {
        mix(&d.center, sizeof d.center);
        mix(&d.packedFrame, sizeof d.packedFrame);
    }
    mix(&d.size, sizeof d.size);
    mix(&d.halfDepth, sizeof d.halfDepth);
    return h;
}

} // namespace

void DecalRouting::reset(const std::vector<uint8_t>& deforming) {
    deforming_ = deforming;
    const size_t objectCount = deforming.size();
    modes_.assign(objectCount, DecalMode::Projected);
    splatted_.assign(objectCount, {});
    pending_.clear();
    kinds_.clear();
    textureSpace_ = 0;
    current_ = false;
}

void DecalRouting::setTypes(const std::vector<DecalType>& types) {
    volumetricTypes_.assign(types.size(), 0);
    for (size_t i = 0; i < types.size(); ++i)
        volumetricTypes_[i] = types[i].volumetric ? 1 : 0;
    current_ = false;
}

void DecalRouting::setMode(uint32_t object, DecalMode mode) {
    modes_[object] = mode;
    splatted_[object].clear();
    current_ = false;
}

DecalMode DecalRouting::mode(uint32_t object) const {
    return object < modes_.size() ? modes_[object] : DecalMode::Projected;
}

void DecalRouting::forgetSplats(uint32_t object) {
    splatted_[object].clear();
}

std::vector<uint8_t> DecalRouting::hostObjects() const {
    std::vector<uint8_t> host(modes_.size());
    for (size_t i = 0; i < modes_.size(); ++i)
        host[i] = modes_[i] == DecalMode::TextureSpace ? 1 : 0;
    return host;
}

bool DecalRouting::drawsSome() const {
    return std::find(volumetricTypes_.begin(), volumetricTypes_.end(), 1) != volumetricTypes_.end() ||
           std::find(modes_.begin(), modes_.end(), DecalMode::TextureSpace) != modes_.end();
}

uint8_t DecalRouting::kindOf(const Decal& d) const {
    if (d.type < volumetricTypes_.size() && volumetricTypes_[d.type]) return kVolumetric; // wherever it lies
    if (d.object < modes_.size() && modes_[d.object] == DecalMode::TextureSpace) return kTextureSpace;
    return kProjected;
}

void DecalRouting::splat(const Decal& d) {
    ++textureSpace_;
    if (splatted_[d.object].insert(decalKey(d, deforming_[d.object] != 0)).second) pending_.push_back(d);
}

void DecalRouting::setCraters(const std::vector<Decal>& decals, const CraterClipsOf& clips,
                              const std::vector<DecalType>& types, VolumetricDecals& craters) const {
    std::vector<Decal> volumetric;
    std::vector<CraterClips> planes;
    for (size_t i = 0; i < kinds_.size(); ++i)
        if (kinds_[i] == kVolumetric) {
            volumetric.push_back(decals[i]);
            planes.push_back(clips ? clips(i) : CraterClips{});
        }
    craters.setDecals(volumetric, planes, types, modes_.size());
}

void DecalRouting::take(const std::vector<Decal>& decals, const CraterClipsOf& clips,
                        const std::vector<DecalType>& types, VolumetricDecals& craters) {
    kinds_.clear();
    textureSpace_ = 0;
    if (drawsSome()) kinds_.resize(decals.size());
    for (size_t i = 0; i < kinds_.size(); ++i) {
        kinds_[i] = kindOf(decals[i]);
        if (kinds_[i] == kTextureSpace) splat(decals[i]);
    }
    std::vector<uint8_t>(kinds_).swap(kinds_); // no room kept past the decals
    setCraters(decals, clips, types, craters);
    current_ = true;
}

// Marks the kind at `i` stale (its decal is read again at the end), taking the old decal out.
void DecalRouting::markStale(uint32_t i, std::vector<uint32_t>& stale, bool& cratersChanged) {
    const uint8_t k = kinds_[i];
    if (k & kStale) return;
    cratersChanged = cratersChanged || k == kVolumetric;
    textureSpace_ -= k == kTextureSpace ? 1 : 0;
    kinds_[i] = kStale;
    stale.push_back(i);
}

// Replays the changes on the kinds as DecalChanges.hpp describes; false when they do not fit.
bool DecalRouting::replayChanges(const DecalChanges& changes, std::vector<uint32_t>& stale,
                                 bool& cratersChanged) {
    for (const DecalChange& c : changes.changes) {
        const size_t n = kinds_.size();
        if (c.kind == DecalChangeKind::Added) {
            if (c.index != n) return false;
            kinds_.push_back(kStale);
            stale.push_back(c.index);
        } else if (c.kind == DecalChangeKind::Changed) {
            if (c.index >= n) return false;
            markStale(c.index, stale, cratersChanged);
        } else {
            if (c.index >= n || c.from != n - 1) return false;
            markStale(c.index, stale, cratersChanged); // takes the removed decal out
            kinds_[c.index] = kinds_[c.from];
            kinds_.pop_back();
            if (c.index != c.from && (kinds_[c.index] & kStale)) stale.push_back(c.index);
        }
    }
    return true;
}

bool DecalRouting::replay(const std::vector<Decal>& decals, const CraterClipsOf& clips,
                          const DecalChanges& changes, const std::vector<DecalType>& types,
                          VolumetricDecals& craters) {
    if (!current_ || !changes.complete) return false;
    if (kinds_.empty() && !drawsSome()) return true; // nothing is the renderer's
    std::vector<uint32_t> stale;
    bool cratersChanged = false;
    if (!replayChanges(changes, stale, cratersChanged) || kinds_.size() != decals.size()) return false;
    std::sort(stale.begin(), stale.end()); // splatted in the order of decals(), as take() splats
    for (const uint32_t i : stale) {
        if (i >= kinds_.size() || !(kinds_[i] & kStale)) continue;
        kinds_[i] = kindOf(decals[i]);
        cratersChanged = cratersChanged || kinds_[i] == kVolumetric;
        if (kinds_[i] == kTextureSpace) splat(decals[i]);
    }
    if (cratersChanged) setCraters(decals, clips, types, craters);
    return true;
}

} // namespace spatter::render_detail
