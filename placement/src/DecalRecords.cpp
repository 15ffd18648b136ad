#include "spatter/placement/DecalRecords.hpp"

#include "RecordPose.hpp"

#include "spatter/placement/DecalLooks.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/placement/RayParser.hpp"
#include "spatter/placement/ScenePosing.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <utility>

namespace spatter {

namespace {

using Json = nlohmann::json;

// How far an anchor's barycentric coordinates may stray below 0, and their sum from 1 (the rounding
// of the written digits).
constexpr double kBaryRoom = 1e-6;

// One "placed" record of spatter-place.
struct PlacedRecord {
    std::string object;
    WorldDecalBox box;
    double maxAngleDeg = 80.0;
    uint8_t objectId = 0;
    std::optional<uint32_t> decalId;
    std::optional<double> time;          // when it was placed (spatter-place --time)
    std::optional<SurfaceAnchor> anchor; // the render triangle it lies on, on a deforming object
};

// The value of `v` when it is a finite number.
std::optional<double> finite(const Json& v) {
    const double x = v.is_number() ? v.get<double>() : std::nan("");
    return std::isfinite(x) ? std::optional<double>(x) : std::nullopt;
}

// The finite number `rec[key]`, or nothing when it is absent, not a number or not finite.
std::optional<double> number(const Json& rec, const char* key) {
    return rec.contains(key) ? finite(rec[key]) : std::nullopt;
}

Status readVec3(const Json& rec, const char* key, glm::dvec3& out) {
    const Json* v = rec.contains(key) ? &rec[key] : nullptr;
    bool ok = v && v->is_array() && v->size() == 3;
    for (int k = 0; ok && k < 3; ++k) {
        const std::optional<double> c = finite((*v)[size_t(k)]);
        ok = c.has_value();
        if (ok) out[k] = *c;
    }
    if (!ok) return fail(std::string("a placed record needs \"") + key + "\": three finite numbers");
    return {};
}

// Whether an axis and the normal are non-zero and far enough from parallel for the frame they span
// to be made orthonormal (Decal::setFrame).
bool spansAFrame(const glm::dvec3& axis, const glm::dvec3& normal) {
    const double lengths = glm::length(axis) * glm::length(normal);
    return lengths > 0.0 && std::isfinite(lengths) && glm::length(glm::cross(axis, normal)) > 1e-6 * lengths;
}

Status readBox(const Json& rec, WorldDecalBox& box) {
    const char* const vectors[4] = {"position", "tangent", "bitangent", "normal"};
    glm::dvec3* const targets[4] = {&box.center, &box.axes[0], &box.axes[1], &box.axes[2]};
    for (int k = 0; k < 4; ++k)
        if (Status s = readVec3(rec, vectors[k], *targets[k]); !s) return s;
    if (!spansAFrame(box.axes[0], box.axes[2]) || !spansAFrame(box.axes[1], box.axes[2]))
        return fail("a placed record's \"tangent\", \"bitangent\" and \"normal\" must be non-zero, and "
                    "neither of the first two parallel to the normal");
    const Json* size = rec.contains("size") ? &rec["size"] : nullptr;
    const std::optional<double> w =
        size && size->is_array() && size->size() == 2 ? finite((*size)[0]) : std::nullopt;
    const std::optional<double> h = w ? finite((*size)[1]) : std::nullopt;
    if (!h || !(*w > 0.0) || !(*h > 0.0))
        return fail("a placed record needs \"size\": two finite positive numbers");
    box.size = {*w, *h};
    const std::optional<double> halfDepth = number(rec, "half_depth");
    if (!halfDepth || !(*halfDepth > 0.0))
        return fail("a placed record needs \"half_depth\": a finite positive number");
    box.halfDepth = *halfDepth;
    if (!rec.contains("projection")) return {};
    if (Status s = readVec3(rec, "projection", box.projection); !s) return s;
    if (!(glm::dot(box.projection, box.axes[2]) > 0.0))
        return fail("a placed record's \"projection\" must point to the side of its \"normal\"");
    return {};
}

// The record on `line`: nothing for a record that is not placed, an error for one that cannot be used.
// The record's optional "time" and "anchor" ({"triangle": index, "bary": [b0, b1, b2]}).
Status readPose(const Json& rec, PlacedRecord& r) {
    if (rec.contains("time")) {
        r.time = finite(rec["time"]);
        if (!r.time) return fail("\"time\" must be a finite number of seconds");
    }
    if (!rec.contains("anchor")) return {};
    const Json& a = rec["anchor"];
    SurfaceAnchor anchor;
    if (!a.is_object() || !a.contains("triangle") || !a["triangle"].is_number_unsigned() ||
        a["triangle"].get<uint64_t>() > UINT32_MAX)
        return fail("\"anchor\" needs \"triangle\": a triangle index of the object's render mesh");
    anchor.triangle = a["triangle"].get<uint32_t>();
    if (Status s = readVec3(a, "bary", anchor.bary); !s) return fail("\"anchor\": " + s.error());
    const glm::dvec3& b = anchor.bary;
    if (std::min({b.x, b.y, b.z}) < -kBaryRoom || std::abs(b.x + b.y + b.z - 1.0) > kBaryRoom)
        return fail("\"anchor\": \"bary\" must be the barycentric coordinates of a point of the triangle "
                    "(each >= 0, their sum 1)");
    r.anchor = anchor;
    return {};
}

Result<std::optional<PlacedRecord>> parseRecord(const std::string& line) {
    const Json rec = Json::parse(line, nullptr, false);
    if (rec.is_discarded() || !rec.is_object()) return fail("not a JSON object");
    if (!rec.contains("status") || rec["status"] != "placed") return std::optional<PlacedRecord>();
    PlacedRecord r;
    if (!rec.contains("object") || !rec["object"].is_string())
        return fail("a placed record needs \"object\": the name of a scene object");
    r.object = rec["object"].get<std::string>();
    if (Status s = readBox(rec, r.box); !s) return fail(s.error());
    if (rec.contains("max_angle_deg")) {
        const std::optional<double> angle = number(rec, "max_angle_deg");
        if (!angle || !(*angle > 0.0 && *angle <= 90.0))
            return fail("\"max_angle_deg\" must be a number of degrees in (0, 90]");
        r.maxAngleDeg = *angle;
    }
    if (rec.contains("object_id")) {
        const std::optional<double> id = number(rec, "object_id");
        if (!id || *id < 0.0 || *id > 255.0 || std::floor(*id) != *id)
            return fail("\"object_id\" must be an integer in 0..255");
        r.objectId = uint8_t(*id);
    }
    if (rec.contains("decal_id")) {
        if (!rec["decal_id"].is_number_unsigned() || rec["decal_id"].get<uint64_t>() > UINT32_MAX)
            return fail("\"decal_id\" must be an integer in 0..4294967295");
        r.decalId = rec["decal_id"].get<uint32_t>();
    }
    if (Status s = readPose(rec, r); !s) return fail(s.error());
    return std::optional<PlacedRecord>(std::move(r));
}

// The most decal types the records may need: Decal::type is 16 bits.
constexpr size_t kMaxLoadedTypes = 65535;

// Decal types by (max angle, look), as they are first met.
class TypeTable {
public:
    TypeTable(const DecalType& base, int look) : base_(base), look_(look) {}

    Result<uint16_t> typeOf(double maxAngleDeg, size_t k, std::vector<DecalType>& types) {
        const int look = lookOf(look_, k);
        auto it = index_.find({maxAngleDeg, look});
        if (it != index_.end()) return it->second;
        if (types.size() >= kMaxLoadedTypes)
            return fail("more than " + std::to_string(kMaxLoadedTypes) +
                        " decal types (distinct \"max_angle_deg\" and look pairs)");
        DecalType t = withLook(base_, look);
        t.maxAngleDeg = float(maxAngleDeg);
        types.push_back(t);
        return index_.emplace(std::make_pair(maxAngleDeg, look), uint16_t(types.size() - 1)).first->second;
    }

private:
    DecalType base_;
    int look_;
    std::map<std::pair<double, int>, uint16_t> index_;
};

// Dynamic objects that carry no decal get an ID no decal has, so that no decal shows on them: the
// smallest one the decals do not use.
void giveSpareIds(const Scene& scene, LoadedDecals& out) {
    std::vector<bool> used(256, false), named(scene.objects.size(), false);
    for (const Decal& d : out.decals) {
        used[d.objectId] = true;
        named[d.object] = true;
    }
    int spare = 1;
    while (spare < 256 && used[size_t(spare)])
        ++spare;
    for (size_t i = 0; i < scene.objects.size(); ++i)
        if (scene.objects[i].dynamic && !named[i]) out.objectIds[i] = uint8_t(spare < 256 ? spare : 255);
}

// A look of DecalLooks.hpp: a built-in texture or kMixedLooks.
Status checkLook(int look) {
    if (look == kMixedLooks || (look >= 0 && look < int(DecalTexture::Count))) return {};
    return fail("look " + std::to_string(look) + " is not a built-in decal texture (0 to " +
                std::to_string(int(DecalTexture::Count) - 1) + ") or kMixedLooks");
}

// Whether a decal read from a record can be drawn: oriented, its size, depth and centre finite floats,
// its size and depth positive.
bool drawable(const Decal& d) {
    return hasOrientation(d.packedFrame) && std::isfinite(d.size.x) && std::isfinite(d.size.y) &&
           std::isfinite(d.halfDepth) && d.size.x > 0.0f && d.size.y > 0.0f && d.halfDepth > 0.0f &&
           std::isfinite(d.center.x) && std::isfinite(d.center.y) && std::isfinite(d.center.z);
}

// The rays of a ray file, and how many ray lines it has (parsed or not).
Result<std::pair<std::vector<Ray>, size_t>> readRays(const std::string& path) {
    std::ifstream in(path);
    if (!in) return fail("cannot read " + path);
    std::vector<Ray> rays;
    size_t lineNumber = 0, records = 0;
    for (std::string raw; std::getline(in, raw);) {
        const RayLine line = parseRayLine(raw, ++lineNumber);
        if (!line.isRay) continue;
        ++records;
        // An unparseable ray places nothing, as in spatter-place; one with values that are not finite
        // is rejected by the decal system (rayProblem) and places nothing either.
        if (line.ok) rays.push_back(line.ray);
    }
    return std::make_pair(std::move(rays), records);
}

} // namespace

int findObject(const Scene& scene, const std::string& name, const glm::dvec3& position) {
    int best = -1;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& o = scene.objects[i];
        if (o.name != name) continue;
        DBounds b;
        for (const glm::vec3& p : o.mesh->positions)
            b.extend(glm::dvec3(o.transform * glm::dvec4(glm::dvec3(p), 1.0)));
        const double d = b.empty() ? 0.0 : glm::length(glm::clamp(position, b.min, b.max) - position);
        if (d < bestDistance) {
            bestDistance = d;
            best = int(i);
        }
    }
    return best;
}

Decal toObjectSpace(const SceneObject& object, uint32_t index, const WorldDecalBox& box) {
    const glm::dmat4 inv = glm::inverse(object.transform);
    const glm::dmat3 invLinear(inv);
    const glm::dvec3 a = invLinear * (box.axes[0] * (0.5 * box.size.x));
    const glm::dvec3 b = invLinear * (box.axes[1] * (0.5 * box.size.y));
    const glm::dvec3 c = invLinear * (box.axes[2] * box.halfDepth);
    Decal d;
    d.object = index;
    d.center = glm::vec3(glm::dvec3(inv * glm::dvec4(box.center, 1.0)));
    d.setFrame(
        Frame{glm::vec3(glm::normalize(a)), glm::vec3(glm::normalize(b)), glm::vec3(glm::normalize(c))});
    d.size = glm::vec2(float(2.0 * glm::length(a)), float(2.0 * glm::length(b)));
    d.halfDepth = float(glm::length(c));
    if (box.projection != glm::dvec3(0.0)) d.setProjectionAxis(glm::vec3(invLinear * box.projection));
    return d;
}

// The record's box at the pose `drawn`: moved from its time along its anchor when it has both and
// the pose is another; as it is otherwise.
Result<WorldDecalBox> boxAt(const PlacedRecord& r, uint32_t object, const std::optional<DrawPose>& drawn,
                            std::optional<RecordPoses>& poses, const Scene& scene) {
    if (!drawn || !r.time || !r.anchor || *r.time == drawn->time) return r.box;
    if (!poses) poses.emplace(scene, drawn->offset);
    const std::optional<glm::dmat4> from = poses->frameAt(object, *r.anchor, *r.time);
    const std::optional<glm::dmat4> to = poses->frameAt(object, *r.anchor, drawn->time);
    if (!from || !to)
        return fail("\"anchor\" names triangle " + std::to_string(r.anchor->triangle) + " of '" + r.object +
                    "', which it has not or which collapses at one of the two poses");
    return moveBox(r.box, *from, *to);
}

Result<LoadedDecals> loadPlacedRecords(const std::string& path, const Scene& scene, const DecalType& base,
                                       int look, const std::optional<DrawPose>& drawn) {
    if (Status s = checkLook(look); !s) return fail(s.error());
    std::ifstream in(path);
    if (!in) return fail("cannot read " + path);
    LoadedDecals out;
    out.objectIds.assign(scene.objects.size(), 0);
    TypeTable types(base, look);
    std::optional<RecordPoses> poses;
    size_t lineNumber = 0;
    for (std::string line; std::getline(in, line);) {
        ++lineNumber;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        ++out.records;
        const std::string where = path + ":" + std::to_string(lineNumber) + ": ";
        Result<std::optional<PlacedRecord>> rec = parseRecord(line);
        if (!rec) return fail(where + rec.error());
        if (!rec.value()) continue;
        const PlacedRecord& r = *rec.value();
        const int object = findObject(scene, r.object, r.box.center);
        if (object < 0) return fail(where + "the scene has no object named '" + r.object + "'");
        Result<WorldDecalBox> box = boxAt(r, uint32_t(object), drawn, poses, scene);
        if (!box) return fail(where + box.error());
        Decal d = toObjectSpace(scene.objects[size_t(object)], uint32_t(object), box.value());
        if (!drawable(d))
            return fail(where + "the record's box, in the space of '" + r.object +
                        "', has no orientation or a size, depth or position that float does not hold");
        Result<uint16_t> type = types.typeOf(r.maxAngleDeg, out.decals.size(), out.types);
        if (!type) return fail(where + type.error());
        d.type = type.value();
        d.objectId = r.objectId;
        if (r.decalId) d.id = *r.decalId;
        out.objectIds[size_t(object)] = d.objectId;
        out.decals.push_back(d);
        ++out.placed;
    }
    giveSpareIds(scene, out);
    return out;
}

Result<LoadedDecals> placeRays(const std::string& path, const Scene& scene, const DecalType& type, int look,
                               uint64_t seed, const std::optional<DrawPose>& drawn) {
    if (Status s = checkLook(look); !s) return fail(s.error());
    Result<std::pair<std::vector<Ray>, size_t>> rays = readRays(path);
    if (!rays) return fail(rays.error());
    DecalSettings settings;
    settings.seed = seed;
    settings.maxPerCell = std::numeric_limits<uint32_t>::max();
    settings.budget = std::numeric_limits<uint32_t>::max();
    settings.maxPerObject = std::numeric_limits<uint32_t>::max();
    Result<DecalSystem> sys = DecalSystem::create(scene, settings);
    if (!sys) return fail(sys.error());
    Result<uint16_t> index = sys->registerType(type);
    if (!index) return fail(index.error());
    LoadedDecals out;
    out.warnings = sys->world().warnings();
    if (drawn)
        for (std::string& refused : poseDecalSystem(sys.value(), scene, drawn.value()))
            out.warnings.push_back(std::move(refused));
    out.records = rays->second;
    std::vector<SpawnResult> results;
    sys->spawnBatch(rays->first, index.value(), results);
    for (const SpawnResult& r : results)
        out.placed += r.placed() ? 1 : 0;
    out.decals = sys->decals();
    for (size_t k = 0; k < out.decals.size(); ++k)
        out.clips.push_back(sys->craterClips(k));
    for (int k = 0; k < int(DecalTexture::Count); ++k)
        out.types.push_back(withLook(type, k));
    for (size_t k = 0; k < out.decals.size(); ++k)
        out.decals[k].type = uint16_t(lookOf(look, k));
    for (uint32_t o = 0; o < scene.objects.size(); ++o)
        out.objectIds.push_back(sys->objectId(o));
    return out;
}

} // namespace spatter
