#include "DecalSystemImpl.hpp"

#include "DecalSystemState.hpp"
#include "DecalTypeCheck.hpp"
#include "spatter/placement/ObjectIds.hpp"

namespace spatter {

uint64_t DecalStats::rejectedTotal() const {
    uint64_t n = 0;
    for (uint64_t r : rejected)
        n += r;
    return n;
}

bool DecalStats::operator==(const DecalStats& o) const {
    return placed == o.placed && rejected == o.rejected && evicted == o.evicted && expired == o.expired &&
           removed == o.removed && alive == o.alive && fading == o.fading &&
           sharedObjectIds == o.sharedObjectIds;
}

DecalSystem::DecalSystem(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
DecalSystem::DecalSystem(DecalSystem&&) noexcept = default;
DecalSystem& DecalSystem::operator=(DecalSystem&&) noexcept = default;
DecalSystem::~DecalSystem() = default;

Result<DecalSystem> DecalSystem::create(CollisionWorld world, const DecalSettings& s) {
    if (std::string problem = DecalSystemAccess::settingsProblem(s); !problem.empty()) return fail(problem);
    auto impl = std::make_unique<Impl>(std::move(world), s);
    const size_t n = impl->world.objectCount();
    std::vector<DBounds> bounds(n);
    std::vector<bool> dynamic(n);
    for (uint32_t i = 0; i < n; ++i) {
        bounds[i] = impl->world.worldBounds(i);
        dynamic[i] = impl->world.object(i)->dynamic;
    }
    ObjectIdAssignment ids = assignObjectIds(bounds, dynamic, s.idSeparation, s.seed);
    impl->objectIds = std::move(ids.ids);
    impl->stats.sharedObjectIds = ids.sharedPairs;
    return DecalSystem(std::move(impl));
}

Result<DecalSystem> DecalSystem::create(const Scene& scene, const DecalSettings& settings) {
    Result<CollisionWorld> world = CollisionWorld::build(scene);
    if (!world) return fail(world.error());
    return create(std::move(world).value(), settings);
}

Result<uint16_t> DecalSystem::registerType(const DecalType& t) {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    const std::string where = "decal type '" + t.name + "': ";
    if (t.name.empty()) return fail("decal type: empty name");
    for (const DecalType& other : impl_->types)
        if (other.name == t.name) return fail(where + "a type of that name is already registered");
    if (impl_->types.size() >= 65535) return fail(where + "65535 types are registered already");
    if (const std::string p = decalTypeProblem(t); !p.empty()) return fail(where + p);
    impl_->types.push_back(t);
    return uint16_t(impl_->types.size() - 1);
}

Result<uint16_t> DecalSystem::typeIndex(const std::string& name) const {
    for (size_t i = 0; i < impl_->types.size(); ++i)
        if (impl_->types[i].name == name) return uint16_t(i);
    return fail("no decal type named '" + name + "'");
}

const DecalType* DecalSystem::type(uint16_t index) const {
    return index < impl_->types.size() ? &impl_->types[index] : nullptr;
}

size_t DecalSystem::typeCount() const {
    return impl_->types.size();
}

SpawnResult DecalSystem::spawn(const Ray& ray, uint16_t type) {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    if (type >= impl_->types.size()) return impl_->reject(SpawnStatus::InvalidType, impl_->typeError(type));
    if (const char* problem = rayProblem(ray)) return impl_->reject(SpawnStatus::InvalidRay, problem);
    return impl_->fromHit(ray, impl_->world.intersect(ray), type);
}

SpawnResult DecalSystem::spawnAt(const glm::dvec3& position, const glm::dvec3& normal, uint16_t type) {
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    if (type >= s.types.size()) return s.reject(SpawnStatus::InvalidType, s.typeError(type));
    if (!finite3(position)) return s.reject(SpawnStatus::InvalidArgument, "spawnAt: position is not finite");
    if (!finite3(normal)) return s.reject(SpawnStatus::InvalidArgument, "spawnAt: normal is not finite");
    const double len2 = glm::dot(normal, normal);
    if (!(len2 >= std::numeric_limits<double>::min()) || !std::isfinite(len2))
        return s.reject(SpawnStatus::InvalidArgument, "spawnAt: normal is zero or cannot be normalised");
    const DecalType& t = s.types[type];
    const glm::dvec3 n = normal / std::sqrt(len2);
    const double r = double(std::max(t.size.x, t.size.y));
    Ray probe;
    probe.origin = position + n * r;
    probe.direction = -n;
    probe.tnear = 0.0;
    probe.tfar = 2.0 * r;
    const std::optional<Hit> hit = s.world.intersect(probe);
    if (!hit)
        return s.reject(SpawnStatus::Missed, "spawnAt: no decal receiver within " + formatNumber(r) +
                                                 " of the position along the normal");
    const CollisionObject& o = s.object(hit->object);
    if (o.dynamic && !t.onDynamic)
        return s.reject(SpawnStatus::NotReceiver,
                        "decal type '" + t.name + "' may not land on dynamic object '" + o.name + "'");
    const double angle = std::acos(std::clamp(glm::dot(n, hit->normal), -1.0, 1.0)) * (180.0 / kPi);
    if (angle > double(t.maxAngleDeg))
        return s.reject(SpawnStatus::GrazingAngle, "spawnAt: the surface of '" + o.name + "' is " +
                                                       formatNumber(angle) +
                                                       " degrees from the normal (type '" + t.name +
                                                       "' allows " + formatNumber(t.maxAngleDeg) + ")");
    return s.placeAtHit(*hit, probe.direction, n, glm::dvec3(1.0, 0.0, 0.0), type, false);
}

SpawnResult DecalSystem::spawnAttached(uint32_t objectIndex, const glm::vec3& localPosition,
                                       const glm::vec3& localNormal, uint16_t type) {
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    if (type >= s.types.size()) return s.reject(SpawnStatus::InvalidType, s.typeError(type));
    const CollisionObject* o = s.world.object(objectIndex);
    if (!o)
        return s.reject(SpawnStatus::InvalidArgument,
                        "spawnAttached: object " + std::to_string(objectIndex) + " out of range (" +
                            std::to_string(s.world.objectCount()) + " objects)");
    const glm::dvec3 p(localPosition), ln(localNormal);
    if (!finite3(p))
        return s.reject(SpawnStatus::InvalidArgument, "spawnAttached: local position is not finite");
    if (!finite3(ln))
        return s.reject(SpawnStatus::InvalidArgument, "spawnAttached: local normal is not finite");
    if (std::max({std::fabs(localNormal.x), std::fabs(localNormal.y), std::fabs(localNormal.z)}) <
        std::numeric_limits<float>::min())
        return s.reject(SpawnStatus::InvalidArgument, "spawnAttached: local normal is zero or denormal");
    if (!o->inWorld)
        return s.reject(SpawnStatus::NotReceiver, "object '" + o->name + "' is not in the collision world");
    if (!o->traced) return s.reject(SpawnStatus::NotReceiver, "object '" + o->name + "': " + o->untraced);
    const glm::dmat3 m(o->transform);
    const glm::dvec3 wn = glm::transpose(glm::inverse(m)) * ln;
    const double len2 = glm::dot(wn, wn);
    if (!(len2 >= std::numeric_limits<double>::min()) || !std::isfinite(len2))
        return s.reject(SpawnStatus::InvalidArgument,
                        "spawnAttached: local normal is zero or cannot be normalised");
    const DecalType& t = s.types[type];
    if (o->dynamic && !t.onDynamic)
        return s.reject(SpawnStatus::NotReceiver,
                        "decal type '" + t.name + "' may not land on dynamic object '" + o->name + "'");
    const glm::dvec3 facing = wn / std::sqrt(len2), hint = m * glm::dvec3(1.0, 0.0, 0.0);
    // On a skinned or morphed object the decal lands on the drawn surface under the point, found by a
    // short probe along the normal (probeOwnSurface), and follows the pose from there.
    if (const std::optional<Hit> hit = s.probeOwnSurface(objectIndex, p, facing, t); hit)
        return s.placeAtHit(*hit, -facing, facing, hint, type, false);
    return s.place(objectIndex, p, facing, hint, type);
}

void DecalSystem::spawnBatch(const std::vector<Ray>& rays, uint16_t type, std::vector<SpawnResult>& results) {
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    results.clear();
    results.reserve(rays.size());
    if (type >= s.types.size()) {
        for (size_t i = 0; i < rays.size(); ++i)
            results.push_back(s.reject(SpawnStatus::InvalidType, s.typeError(type)));
        return;
    }
    const std::vector<std::optional<Hit>> hits = s.traceBatch(rays);
    for (size_t i = 0; i < rays.size(); ++i) {
        if (const char* problem = rayProblem(rays[i]))
            results.push_back(s.reject(SpawnStatus::InvalidRay, problem));
        else
            results.push_back(s.fromHit(rays[i], hits[i], type));
    }
}

Status DecalSystem::update(double dt) {
    if (!std::isfinite(dt) || dt < 0.0 || denormal(dt))
        return fail("update: dt must be finite, >= 0 and not denormal");
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    if (!std::isfinite(s.time + dt)) return fail("update: the clock would pass the largest finite time");
    s.time += dt;
    // Only the timed decals can change: the others are opaque (1) from their placement on and stay.
    // They are visited from the highest dense index down, as a walk over every decal would meet them,
    // and a removal moves the last decal (visited already) into the hole: the indices below the one
    // visited, and the members of `timed` among them, do not move.
    for (uint32_t i = s.timed.highestBelow(uint32_t(s.decals.size())); i != DenseIndexSet::kNone;
         i = s.timed.highestBelow(i)) {
        Decal& d = s.decals[i];
        const auto fade = s.fadingSince.empty() ? s.fadingSince.end() : s.fadingSince.find(s.slotOf[i]);
        const bool fading = fade != s.fadingSince.end();
        const DecalType& t = s.types[d.type];
        float opacity = 1.0f;
        bool remove = false;
        if (t.lifetime > 0.0f) {
            const double age = s.time - d.spawnTime;
            if (age >= double(t.lifetime)) {
                remove = true;
                if (!fading) s.stats.expired++;
            } else {
                const double fadeStart = std::max(0.0, double(t.lifetime) - double(t.fadeOutTime));
                if (age > fadeStart)
                    opacity = float((double(t.lifetime) - age) / (double(t.lifetime) - fadeStart));
            }
        }
        if (!remove && fading) {
            const double since = s.time - fade->second;
            if (since >= double(t.fadeOutTime))
                remove = true;
            else
                opacity = std::min(opacity, float(1.0 - since / double(t.fadeOutTime)));
        }
        if (remove) {
            s.removeDense(i);
        } else if (const Opacity stored(opacity); stored.bits() != d.opacity.bits()) {
            d.opacity = stored; // a change only when the stored step does
            s.logChange(i, DecalChangeKind::Changed);
        }
    }
    return {};
}

bool DecalSystem::remove(DecalHandle handle) {
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    if (!get(handle)) return false;
    s.removeCounted(s.slots[handle.slot].dense);
    return true;
}

const Decal* DecalSystem::get(DecalHandle handle) const {
    const Impl& s = *impl_;
    if (handle.slot >= s.slots.size()) return nullptr;
    const Slot& slot = s.slots[handle.slot];
    if (slot.generation != handle.generation || slot.dense == kNone) return nullptr;
    return &s.decals[slot.dense];
}

std::optional<WorldDecal> DecalSystem::worldBox(DecalHandle handle) const {
    const Decal* d = get(handle);
    if (!d) return std::nullopt;
    return impl_->toWorld(*d);
}

WorldDecal DecalSystem::worldBox(const Decal& decal) const {
    return impl_->toWorld(decal);
}

const std::vector<Decal>& DecalSystem::decals() const {
    return impl_->decals;
}

CraterClips DecalSystem::craterClips(size_t index) const {
    const Impl& s = *impl_;
    if (index >= s.decals.size()) return {};
    const uint32_t slot = s.slotOf[index];
    return slot < s.clipsBySlot.size() ? s.clipsBySlot[slot] : CraterClips{};
}

uint64_t DecalSystem::version() const {
    return impl_->version();
}

void DecalSystem::changesSince(uint64_t version, DecalChanges& out) const {
    const Impl& s = *impl_;
    out.version = s.version();
    out.complete = s.changeLog.since(version, s.decals.size(), out.changes);
}

DecalChanges DecalSystem::changesSince(uint64_t version) const {
    DecalChanges out;
    changesSince(version, out);
    return out;
}

Result<TransformUpdate> DecalSystem::setTransform(uint32_t object, const glm::dmat4& transform) {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->world.setTransform(object, transform);
}

Result<TransformUpdate> DecalSystem::setPose(uint32_t object, const glm::dmat4& transform,
                                             const std::vector<glm::dmat4>& joints,
                                             const std::vector<double>& morphWeights) {
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    Result<TransformUpdate> update = s.world.setPose(object, transform, joints, morphWeights);
    if (!update) return update;
    s.anchors.repose(
        object, s.world, s.decals, [&s](uint32_t slot) { return s.slots[slot].dense; },
        [&s](uint32_t dense) { s.logChange(dense, DecalChangeKind::Changed); });
    return update;
}

Status DecalSystem::removeObject(uint32_t object) {
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    if (Status st = s.world.removeObject(object); !st) return st;
    for (size_t i = s.decals.size(); i-- > 0;) {
        if (s.decals[i].object != object) continue;
        s.removeCounted(uint32_t(i));
    }
    return {};
}

uint8_t DecalSystem::objectId(uint32_t object) const {
    return object < impl_->objectIds.size() ? impl_->objectIds[object] : 0;
}

std::vector<uint8_t> DecalSystem::objectIds() const {
    std::vector<uint8_t> ids(impl_->world.objectCount());
    for (uint32_t o = 0; o < ids.size(); ++o)
        ids[o] = objectId(o);
    return ids;
}

const DecalStats& DecalSystem::stats() const {
    return impl_->stats;
}

DecalSystemMemory DecalSystem::memory() const {
    const Impl& s = *impl_;
    DecalSystemMemory m;
    m.records = s.decals.capacity() * sizeof(Decal);
    m.handles = s.slotOf.capacity() * sizeof(uint32_t) + s.slots.capacity() * sizeof(Slot) +
                s.freeSlots.capacity() * sizeof(uint32_t);
    m.areaLimits = s.limits.bytes();
    m.changeLog = s.changeLog.bytes();
    // A node of the fading table holds its entry and a link; the table a pointer per bucket.
    const size_t fadingNode = sizeof(std::pair<const uint32_t, double>) + sizeof(void*);
    m.other = s.timed.bytes() + s.fadingSince.size() * fadingNode +
              s.fadingSince.bucket_count() * sizeof(void*) + s.clipsBySlot.capacity() * sizeof(CraterClips) +
              s.anchors.bytes();
    return m;
}
const DecalSettings& DecalSystem::settings() const {
    return impl_->settings;
}
const CollisionWorld& DecalSystem::world() const {
    return impl_->world;
}
double DecalSystem::time() const {
    return impl_->time;
}

} // namespace spatter
