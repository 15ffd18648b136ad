#pragma once
// DecalRouting: which of the decals given to spatter's renderer it draws itself rather than through
// the projector, decal by decal, kept up to date from the decal system's change list. Decals of a
// volumetric type are craters (VolumetricDecals); the other decals on an object in texture-space mode
// are splatted once into its texture (TextureSpaceDecals), recognised by a key so that a decal given
// again is not splatted twice (on a skinned or morphed object a key that the pose does not move); the rest
// are the projector's (DecalProjector::setHostDrawn). While no type is volumetric and no object texture-space
// it keeps nothing per decal; otherwise a byte, its kind.

#include "VolumetricDecals.hpp"

#include "spatter/core/CraterClip.hpp"
#include "spatter/core/Decal.hpp"
#include "spatter/core/DecalChanges.hpp"
#include "spatter/core/DecalType.hpp"
#include "spatter/render/DecalMode.hpp"

#include <cstddef>
#include <cstdint>
#include <unordered_set>
#include <vector>

namespace spatter::render_detail {

class DecalRouting {
public:
    // One object per entry of `deforming` (1: skinned or morphed), all projected; no decal, nothing
    // splatted.
    void reset(const std::vector<uint8_t>& deforming);
    // The types (their volumetric flags) and an object's mode. Either takes the decals afresh at the
    // next take or replay; a mode change forgets what was splatted on that object.
    void setTypes(const std::vector<DecalType>& types);
    void setMode(uint32_t object, DecalMode mode);
    DecalMode mode(uint32_t object) const;
    // Forgets what was splatted on `object`: its decals are splatted again when next given.
    void forgetSplats(uint32_t object);

    // For DecalProjector::setHostDrawn: the volumetric types and the texture-space objects.
    std::vector<uint8_t> hostTypes() const { return volumetricTypes_; }
    std::vector<uint8_t> hostObjects() const;

    // Every decal afresh: the volumetric ones go to `craters` with their clip planes (`clips`, may be
    // empty), the new ones on texture-space objects to the pending splats.
    void take(const std::vector<Decal>& decals, const CraterClipsOf& clips,
              const std::vector<DecalType>& types, VolumetricDecals& craters);
    // The decals after `changes` (DecalChanges.hpp), replayed on the kinds: new decals on
    // texture-space objects are splatted, and a change to a volumetric decal gives `craters` the
    // volumetric decals afresh (a scan of `decals`). False, with the kinds to be taken afresh, when
    // the changes are not complete or do not fit, and after setTypes or setMode.
    bool replay(const std::vector<Decal>& decals, const CraterClipsOf& clips, const DecalChanges& changes,
                const std::vector<DecalType>& types, VolumetricDecals& craters);

    // Decals on texture-space objects among those last given (drawn by neither the projector nor the
    // craters).
    size_t textureSpaceCount() const { return textureSpace_; }
    // Decals waiting to be splatted; the renderer takes them.
    std::vector<Decal>& pendingSplats() { return pending_; }

private:
    static constexpr uint8_t kProjected = 0, kVolumetric = 1, kTextureSpace = 2, kStale = 0x80;

    bool drawsSome() const;
    uint8_t kindOf(const Decal& d) const;
    void splat(const Decal& d);
    void setCraters(const std::vector<Decal>& decals, const CraterClipsOf& clips,
                    const std::vector<DecalType>& types, VolumetricDecals& craters) const;
    void markStale(uint32_t i, std::vector<uint32_t>& stale, bool& cratersChanged);
    bool replayChanges(const DecalChanges& changes, std::vector<uint32_t>& stale, bool& cratersChanged);

    std::vector<uint8_t> volumetricTypes_; // per type: 1 when volumetric
    std::vector<DecalMode> modes_;         // per object
    std::vector<uint8_t> deforming_;       // per object: 1 when skinned or morphed
    std::vector<uint8_t> kinds_;           // per decal, while drawsSome()
    bool current_ = false;                 // the kinds follow the types and modes as they are
    size_t textureSpace_ = 0;
    std::vector<Decal> pending_;
    std::vector<std::unordered_set<uint64_t>> splatted_; // keys of the decals splatted, per object
};

} // namespace spatter::render_detail
