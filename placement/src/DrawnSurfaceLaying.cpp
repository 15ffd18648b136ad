// DecalSystem's calls that lay decals on the surface that is drawn, where a renderer found it: the
// line a renderer searches for a decal placed through a collision proxy (axisLine), the laying of that
// decal (layOnDrawnSurface), and the decal of a shot that the collision surface refused
// (spawnOnDrawnSurface).
#include "DecalSystemImpl.hpp"

#include "spatter/core/DecalRefit.hpp"

namespace spatter {

std::optional<DecalAxisLine> DecalSystem::axisLine(DecalHandle handle) const {
    const Decal* d = get(handle);
    if (!d) return std::nullopt;
    const CollisionObject* o = impl_->world.object(d->object);
    if (!o) return std::nullopt;
    const glm::dmat3 inv = glm::inverse(glm::dmat3(o->transform));
    if (!(finite3(inv[0]) && finite3(inv[1]) && finite3(inv[2]))) return std::nullopt; // singular
    const glm::dvec3 center(d->center), reach(d->boxToObject()[2]);
    DecalAxisLine line;
    line.from = glm::dvec3(o->transform * glm::dvec4(center + reach, 1.0));
    line.to = glm::dvec3(o->transform * glm::dvec4(center - reach, 1.0));
    line.objectId = d->objectId;
    line.alongShot = d->slant != 0;
    return line;
}

namespace {

// Why `normal` cannot be a surface's normal (not finite, zero or too small to normalise), or null.
const char* normalProblem(const glm::dvec3& normal) {
    if (!finite3(normal)) return "normal is not finite";
    const double len2 = glm::dot(normal, normal);
    if (!(len2 >= std::numeric_limits<double>::min()) || !std::isfinite(len2))
        return "normal is zero or cannot be normalised";
    return nullptr;
}

// Why a decal of type `t` on `o` cannot be laid on the drawn surface at `point` facing `normal`
// (world space), or empty.
std::string drawnSurfaceRefusal(const DecalType& t, const CollisionObject& o, bool deforms,
                                const glm::dvec3& point, const glm::dvec3& normal) {
    if (t.volumetric)
        return "a decal of volumetric type '" + t.name +
               "' keeps the proxy's hit, where its crater is clipped";
    if (deforms)
        return "object '" + o.name + "' is skinned or morphed: its decals lie on the drawn surface already";
    if (!finite3(point)) return "point is not finite";
    if (const char* problem = normalProblem(normal)) return problem;
    const glm::dmat3 inv = glm::inverse(glm::dmat3(o.transform));
    if (!(finite3(inv[0]) && finite3(inv[1]) && finite3(inv[2])))
        return "the transform of object '" + o.name + "' is singular";
    return {};
}

// Where object-space `local` lies in the box of `d`, in box units, or empty when outside it by more
// than a thousandth of its half extents.
std::string outsideBox(const Decal& d, const glm::dvec3& local) {
    const glm::dvec3 inBox(glm::inverse(glm::dmat4(d.boxToObject())) * glm::dvec4(local, 1.0));
    constexpr double kBoxTolerance = 1e-3; // of the box's half extents
    const double outside = std::max({std::fabs(inBox.x), std::fabs(inBox.y), std::fabs(inBox.z)});
    if (outside <= 1.0 + kBoxTolerance) return {};
    return "the point lies outside the decal's box (at " + formatNumber(inBox.x) + ", " +
           formatNumber(inBox.y) + ", " + formatNumber(inBox.z) + " in box units)";
}

} // namespace

Result<DrawnSurfaceLaying> DecalSystem::layOnDrawnSurface(DecalHandle handle, const glm::dvec3& point,
                                                          const glm::dvec3& normal) {
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    const Decal* found = get(handle);
    if (!found) return fail("layOnDrawnSurface: stale or invalid handle");
    const Decal& d = *found;
    const DecalType& t = s.types[d.type];
    const CollisionObject& o = s.object(d.object);
    if (std::string why = drawnSurfaceRefusal(t, o, s.world.deforms(d.object), point, normal); !why.empty())
        return fail("layOnDrawnSurface: " + why);
    // To object space (normals by the transpose of the linear part).
    const glm::dmat3 m(o.transform), inv = glm::inverse(m);
    const glm::dvec3 local = inv * (point - glm::dvec3(o.transform[3]));
    const glm::dvec3 localNormal = glm::transpose(m) * glm::normalize(normal);
    if (std::string why = outsideBox(d, local); !why.empty()) return fail("layOnDrawnSurface: " + why);
    const double localLength = glm::length(localNormal);
    if (!(localLength > 0.0) || !std::isfinite(localLength))
        return fail("layOnDrawnSurface: the normal cannot be carried to the object's space");
    std::optional<Decal> laid =
        relaidDecal(d, m, glm::vec3(local), glm::vec3(localNormal / localLength), 0.0f);
    if (!laid)
        return fail("layOnDrawnSurface: the normal is 89 degrees or more from the decal's, or the decal "
                    "cannot be laid on it");
    // The half-depth of a decal on a surface with no error bound (place with h = 0), world units, then
    // in the object's space along the laid decal's normal.
    const glm::vec2 worldSize = s.toWorld(d).size;
    const double extent = double(std::max(worldSize.x, worldSize.y));
    const float halfDepth = std::max(t.halfDepth, float(double(s.settings.depthMargin) * extent));
    laid->halfDepth =
        float(double(halfDepth) * glm::length(glm::transpose(inv) * glm::dvec3(laid->frame().normal)));
    if (!soundBox(*laid) || !(extent <= double(kMaxWorldExtent) && halfDepth <= kMaxWorldExtent))
        return fail("layOnDrawnSurface: the box of the decal laid again on '" + o.name +
                    "' is degenerate in the object's or the world's space (size " +
                    formatNumber(laid->size.x) + " x " + formatNumber(laid->size.y) + ", half-depth " +
                    formatNumber(laid->halfDepth) + ")");
    const uint32_t dense = s.slots[handle.slot].dense;
    if (const std::optional<double> angle = laidShotAngleDeg(d, *laid, m); angle && *angle > t.maxAngleDeg) {
        s.removeCounted(dense);
        return DrawnSurfaceLaying::Removed;
    }
    s.decals[dense] = *laid;
    s.logChange(dense, DecalChangeKind::Changed);
    return DrawnSurfaceLaying::Laid;
}

namespace {

// The largest error bound of `world`'s objects, world units.
double largestWorldBound(const CollisionWorld& world) {
    double h = 0.0;
    for (uint32_t i = 0; i < world.objectCount(); ++i)
        h = std::max(h, world.worldErrorBound(i));
    return h;
}

// Whether `point` (world space) lies within `margin` of object `i`'s world bounds.
bool nearBounds(const CollisionWorld& world, uint32_t i, const glm::dvec3& point, double margin) {
    const DBounds b = world.worldBounds(i);
    return !b.empty() && glm::all(glm::greaterThanEqual(point, b.min - margin)) &&
           glm::all(glm::lessThanEqual(point, b.max + margin));
}

// The object whose drawn surface `point` (world space, facing unit `normal`) can lie on, given that
// every object's drawn surface lies within its world error bound h of its collision surface: the one
// whose collision surface a probe along the normal meets within 2 h + `slack` of the point; else, where
// the probe meets none (beside an open edge of a proxy, which the drawn surface overhangs), the only
// object in the world whose bounds, grown by 2 h + `slack`, hold the point. Nothing otherwise.
std::optional<uint32_t> receiverNear(const CollisionWorld& world, const glm::dvec3& point,
                                     const glm::dvec3& normal, double slack) {
    const double reach = 2.0 * largestWorldBound(world) + slack;
    Ray probe;
    probe.origin = point + normal * reach;
    probe.direction = -normal;
    probe.tnear = 0.0;
    probe.tfar = 2.0 * reach;
    const std::optional<Hit> hit = world.intersect(probe);
    if (hit && std::fabs(hit->t - reach) <= 2.0 * world.worldErrorBound(hit->object) + slack)
        return hit->object;
    std::optional<uint32_t> only;
    for (uint32_t i = 0; i < world.objectCount(); ++i) {
        if (!world.object(i)->inWorld || !nearBounds(world, i, point, 2.0 * world.worldErrorBound(i) + slack))
            continue;
        if (only) return std::nullopt; // more than one: which one's surface it is cannot be told
        only = i;
    }
    return only;
}

} // namespace

SpawnResult DecalSystem::spawnOnDrawnSurface(const Ray& shot, const glm::dvec3& point,
                                             const glm::dvec3& normal, uint16_t type) {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->spawnOnDrawnSurface("spawnOnDrawnSurface", shot, point, normal, type);
}

SpawnResult DecalSystem::replaceOnDrawnSurface(DecalHandle handle, const Ray& shot, const glm::dvec3& point,
                                               const glm::dvec3& normal) {
    Impl& s = *impl_;
    const std::lock_guard<std::mutex> lock(s.mutex);
    const Decal* d = get(handle);
    if (!d) {
        SpawnResult stale;
        stale.status = SpawnStatus::InvalidArgument;
        stale.reason = "replaceOnDrawnSurface: stale or invalid handle";
        return stale;
    }
    const std::array<uint64_t, kSpawnStatusCount> rejected = s.stats.rejected;
    SpawnResult r = s.spawnOnDrawnSurface("replaceOnDrawnSurface", shot, point, normal, d->type);
    s.stats.rejected = rejected; // the shot was counted when it was spawned
    // The spawn may have evicted the decal under its area's limits: look its handle up again.
    if ((r.placed() || r.status == SpawnStatus::GrazingAngle) && get(handle))
        s.removeCounted(s.slots[handle.slot].dense);
    return r;
}

SpawnResult DecalSystem::Impl::spawnOnDrawnSurface(const char* caller, const Ray& shot,
                                                   const glm::dvec3& point, const glm::dvec3& normal,
                                                   uint16_t type) {
    if (type >= types.size()) return reject(SpawnStatus::InvalidType, typeError(type));
    if (const char* problem = rayProblem(shot)) return reject(SpawnStatus::InvalidRay, problem);
    const DecalType& t = types[type];
    const std::string where = std::string(caller) + ": ";
    if (t.volumetric)
        return reject(SpawnStatus::InvalidArgument, where + "a decal of volumetric type '" + t.name +
                                                        "' needs a proxy hit, where its crater is clipped");
    if (!finite3(point)) return reject(SpawnStatus::InvalidArgument, where + "point is not finite");
    if (const char* problem = normalProblem(normal))
        return reject(SpawnStatus::InvalidArgument, where + problem);
    const glm::dvec3 dir = glm::normalize(shot.direction);
    glm::dvec3 n = glm::normalize(normal);
    if (glm::dot(n, dir) > 0.0) n = -n;
    const double angle = std::acos(std::clamp(-glm::dot(dir, n), -1.0, 1.0)) * (180.0 / kPi);
    if (angle > double(t.maxAngleDeg))
        return reject(SpawnStatus::GrazingAngle, where + "the shot meets the drawn surface at " +
                                                     formatNumber(angle) +
                                                     " degrees from its normal (type '" + t.name +
                                                     "' allows " + formatNumber(t.maxAngleDeg) + ")");
    const double slack = 0.01 * double(std::max(t.size.x, t.size.y));
    const std::optional<uint32_t> owner = receiverNear(world, point, n, slack);
    if (!owner)
        return reject(SpawnStatus::Missed, where + "no one collision surface lies within twice its error "
                                                   "bound of the point");
    const CollisionObject& o = object(*owner);
    if (o.dynamic && !t.onDynamic)
        return reject(SpawnStatus::NotReceiver,
                      where + "decal type '" + t.name + "' may not land on dynamic object '" + o.name + "'");
    if (world.deforms(*owner))
        return reject(SpawnStatus::NotReceiver, where + "object '" + o.name +
                                                    "' is skinned or morphed: its proxy holds it in every "
                                                    "pose, so shots at it are placed by spawn");
    const glm::dvec3 local(glm::inverse(o.transform) * glm::dvec4(point, 1.0));
    return place(*owner, local, n, dir, type, true, false, nullptr, 0.0);
}

} // namespace spatter
