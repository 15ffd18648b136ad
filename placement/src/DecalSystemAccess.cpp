// DecalSystemAccess: the decal system's state as saves take it and loads give it back
// (DecalSystemState.hpp).
#include "DecalSystemImpl.hpp"

#include "DecalSystemState.hpp"

namespace spatter {

std::string DecalSystemAccess::settingsProblem(const DecalSettings& s) {
    if (!std::isfinite(s.cellSize) || !(s.cellSize > 0.0f) || denormal(s.cellSize))
        return "decal settings: cellSize must be finite, > 0 and not denormal";
    if (s.maxPerCell < 1) return "decal settings: maxPerCell must be >= 1";
    if (s.budget < 1) return "decal settings: budget must be >= 1";
    if (s.maxPerObject < 1) return "decal settings: maxPerObject must be >= 1";
    if (uint8_t(s.policy) > uint8_t(LimitPolicy::Reject)) return "decal settings: unknown limit policy";
    if (!std::isfinite(s.idSeparation) || s.idSeparation < 0.0 || denormal(s.idSeparation))
        return "decal settings: idSeparation must be finite, >= 0 and not denormal";
    if (!std::isfinite(s.depthMargin) || s.depthMargin < 0.0f || denormal(s.depthMargin))
        return "decal settings: depthMargin must be finite, >= 0 and not denormal";
    return {};
}

std::unique_lock<std::mutex> DecalSystemAccess::lock(DecalSystem& system) {
    return std::unique_lock<std::mutex>(system.impl_->mutex);
}

DecalSystemState DecalSystemAccess::capture(const DecalSystem& system) {
    const DecalSystem::Impl& s = *system.impl_;
    DecalSystemState st;
    st.settings = s.settings;
    for (const DecalType& t : s.types)
        st.typeNames.push_back(t.name);
    for (uint32_t i = 0; i < s.world.objectCount(); ++i) {
        const CollisionObject& o = s.object(i);
        st.objects.push_back({o.name, o.meshHash, o.dynamic, o.inWorld, s.objectIds[i], o.transform});
    }
    st.rngState = s.rng.state();
    st.rngIncrement = s.rng.increment();
    st.time = s.time;
    st.stats = s.stats;
    st.decals = s.decals;
    st.slotOf = s.slotOf;
    st.clips.reserve(s.decals.size());
    for (size_t i = 0; i < s.decals.size(); ++i)
        st.clips.push_back(system.craterClips(i));
    st.generations.reserve(s.slots.size());
    for (const Slot& slot : s.slots)
        st.generations.push_back(slot.generation);
    st.freeSlots = s.freeSlots;
    st.fading.assign(s.fadingSince.begin(), s.fadingSince.end());
    std::sort(st.fading.begin(), st.fading.end());
    st.limitOrder.reserve(s.limits.total());
    for (uint32_t slot = s.limits.oldest(); slot != AreaLimits::kNone; slot = s.limits.newer(slot)) {
        const Decal& d = s.decals[s.slots[slot].dense];
        const CellKey key = s.limits.cellOf(slot);
        if (!(key == s.cellKey(d.object, glm::dvec3(d.center))))
            st.cellExceptions.push_back({uint32_t(st.limitOrder.size()), key});
        st.limitOrder.push_back(slot);
    }
    st.changeLogBase = s.changeLog.base();
    s.changeLog.since(st.changeLogBase, s.decals.size(), st.changeLog);
    st.anchors = s.anchors.saved();
    return st;
}

void DecalSystemAccess::restore(DecalSystem& system, DecalSystemState&& st, const RestorePlan& plan) {
    DecalSystem::Impl& s = *system.impl_;
    for (const auto& [object, transform] : plan.moves)
        s.world.setTransform(object, transform);
    for (uint32_t object : plan.removals)
        s.world.removeObject(object);
    for (size_t i = 0; i < st.objects.size() && i < s.objectIds.size(); ++i)
        if (plan.keepObject[i]) s.objectIds[i] = st.objects[i].objectId;
    st.settings.batchThreads = s.settings.batchThreads;
    s.settings = st.settings;
    s.rng = Rng::fromState(st.rngState, st.rngIncrement);
    s.time = st.time;
    s.stats = st.stats;
    s.changeLog.assign(st.changeLogBase, st.changeLog);
    restoreDecals(s, st);
    relink(s, st, plan.keepObject);
    for (size_t i = s.decals.size(); i-- > 0;) { // as removeObject does
        if (plan.keepObject[s.decals[i].object]) continue;
        s.removeCounted(uint32_t(i));
    }
}

void DecalSystemAccess::restoreDecals(DecalSystem::Impl& s, DecalSystemState& st) {
    s.decals = std::move(st.decals);
    s.slotOf = std::move(st.slotOf);
    s.slots.assign(st.generations.size(), Slot());
    for (size_t i = 0; i < st.generations.size(); ++i)
        s.slots[i].generation = st.generations[i];
    for (uint32_t i = 0; i < s.slotOf.size(); ++i)
        s.slots[s.slotOf[i]].dense = i;
    s.freeSlots = std::move(st.freeSlots);
    s.anchors.restore(st.anchors, [&s](uint32_t slot) { return s.decals[s.slots[slot].dense].object; });
    s.fadingSince = std::unordered_map<uint32_t, double>(st.fading.begin(), st.fading.end());
    s.clipsBySlot = {};
    for (uint32_t i = 0; i < st.clips.size(); ++i)
        if (st.clips[i].any()) s.setClips(s.slotOf[i], st.clips[i]);
    s.timed = DenseIndexSet();
    for (uint32_t i = 0; i < s.decals.size(); ++i)
        if (s.types[s.decals[i].type].lifetime > 0.0f || s.fading(i)) s.timed.set(i);
}

void DecalSystemAccess::relink(DecalSystem::Impl& s, const DecalSystemState& st,
                               const std::vector<bool>& keep) {
    const DecalSettings& set = s.settings;
    s.limits = AreaLimits(s.world.objectCount(), set.budget, set.maxPerCell, set.maxPerObject);
    size_t exception = 0;
    for (uint32_t k = 0; k < st.limitOrder.size(); ++k) {
        const uint32_t slot = st.limitOrder[k];
        const Decal& d = s.decals[s.slots[slot].dense];
        const bool given = exception < st.cellExceptions.size() && st.cellExceptions[exception].position == k;
        const CellKey key = given ? st.cellExceptions[exception++].key : CellKey();
        if (keep[d.object])
            s.limits.link(slot, given ? key : s.cellKey(d.object, glm::dvec3(d.center)), d.object);
    }
}

} // namespace spatter
