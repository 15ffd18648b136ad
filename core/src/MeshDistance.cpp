#include "spatter/core/MeshDistance.hpp"

#include "spatter/core/Random.hpp"

#include "SurfaceGeometry.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace spatter {

namespace {

using detail::checkTriangles;
using detail::closestOnTriangle;
using detail::corner;
using detail::enclosingRadius;
using detail::kRoundingAllowance;
using detail::parallelChunks;
using detail::surfaceTriangles;
using detail::workerCount;

} // namespace

// ---------------------------------------------------------------------------------------------
// ClosestPointQuery

struct ClosestPointQuery::Impl {
    RTCDevice device = nullptr; // the shared one (sharedDevice), retained
    RTCScene scene = nullptr;
    // Three per surface triangle, as the mesh holds them (in float: each converts to double exactly).
    std::vector<glm::vec3> corners;
    std::vector<uint32_t> triangleIds; // surface triangle -> mesh triangle

    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

namespace {

// The Embree device of every closest-point structure, made at the first: a device costs more to
// make than a small mesh's structure, and a proxy build makes several. Null when Embree cannot make
// one. Each structure retains it; this reference lasts as long as the process.
RTCDevice sharedDevice() {
    static const RTCDevice device = rtcNewDevice(nullptr);
    return device;
}

// How far p lies from the float point an Embree query is made at.
double pointRounding(const glm::dvec3& p) {
    return glm::length(p - glm::dvec3(glm::vec3(p)));
}

// A float radius at least `radius`.
float roundedRadius(double radius) {
    return std::nextafter(float(radius), std::numeric_limits<float>::infinity());
}

struct PointQueryState {
    const glm::vec3* corners;
    glm::dvec3 p;
    double rounding = 0.0; // pointRounding(p)
    double best2 = std::numeric_limits<double>::infinity();
    double reach2 = std::numeric_limits<double>::infinity(); // farther triangles are not taken
    glm::dvec3 bestPoint{0.0};
    uint32_t bestTriangle = 0;
};

bool closestPointCallback(RTCPointQueryFunctionArguments* args) {
    auto* s = static_cast<PointQueryState*>(args->userPtr);
    const glm::vec3* t = s->corners + 3 * size_t(args->primID);
    const glm::dvec3 q = closestOnTriangle(s->p, glm::dvec3(t[0]), glm::dvec3(t[1]), glm::dvec3(t[2]));
    const double d2 = glm::dot(q - s->p, q - s->p);
    // Of triangles at the same distance, the first (the smallest index): the answer does not depend on
    // the order Embree visits them in, which its BVH's width, and so the processor, decides.
    const bool nearer = d2 < s->best2 || (d2 == s->best2 && args->primID < s->bestTriangle);
    if (!nearer || d2 > s->reach2) return false;
    s->best2 = d2;
    s->bestPoint = q;
    s->bestTriangle = args->primID;
    // Widened so that no triangle at the current best distance is culled by the float radius.
    const float r = roundedRadius(std::sqrt(d2) + s->rounding);
    if (r < args->query->radius) {
        args->query->radius = r;
        return true;
    }
    return false;
}

// Whether some triangle lies within sqrt(radius2) of p: found at the first, after which the query's
// radius is 0 so that Embree visits little more.
struct WithinState {
    const glm::vec3* corners;
    glm::dvec3 p;
    double radius2;
    bool found = false;
};

bool withinCallback(RTCPointQueryFunctionArguments* args) {
    auto* s = static_cast<WithinState*>(args->userPtr);
    if (s->found) return false;
    const glm::vec3* t = s->corners + 3 * size_t(args->primID);
    const glm::dvec3 q = closestOnTriangle(s->p, glm::dvec3(t[0]), glm::dvec3(t[1]), glm::dvec3(t[2]));
    if (!(glm::dot(q - s->p, q - s->p) <= s->radius2)) return false;
    s->found = true;
    args->query->radius = 0.0f;
    return true;
}

bool finitePoint(const glm::dvec3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// An Embree point query at p (rounded to float) whose radius holds every point within `radius` of p
// itself: widened by the rounding of p and rounded up (infinity stays infinity).
RTCPointQuery pointQuery(const glm::dvec3& p, double radius) {
    RTCPointQuery query;
    query.x = float(p.x);
    query.y = float(p.y);
    query.z = float(p.z);
    query.time = 0.0f;
    query.radius = roundedRadius(radius + pointRounding(p));
    return query;
}

} // namespace

ClosestPointQuery::ClosestPointQuery(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ClosestPointQuery::ClosestPointQuery(ClosestPointQuery&&) noexcept = default;
ClosestPointQuery& ClosestPointQuery::operator=(ClosestPointQuery&&) noexcept = default;
ClosestPointQuery::~ClosestPointQuery() = default;

Result<ClosestPointQuery> ClosestPointQuery::create(const Mesh& mesh) {
    if (Status s = checkTriangles(mesh); !s) return fail(s.error());
    auto impl = std::make_unique<Impl>();
    const std::vector<uint32_t> surface = surfaceTriangles(mesh);
    impl->triangleIds = surface;
    impl->corners.reserve(3 * surface.size());
    for (uint32_t t : surface)
        for (int k = 0; k < 3; ++k)
            impl->corners.push_back(mesh.positions[mesh.indices[3 * size_t(t) + size_t(k)]]);
    if (surface.empty()) return ClosestPointQuery(std::move(impl));

    impl->device = sharedDevice();
    if (!impl->device) return fail("Embree could not create a device");
    rtcRetainDevice(impl->device);
    rtcGetDeviceError(impl->device); // this thread's earlier error, if any, is not this build's
    impl->scene = rtcNewScene(impl->device);
    // Built once per mesh and queried a few times per triangle: a quick build pays.
    rtcSetSceneBuildQuality(impl->scene, RTC_BUILD_QUALITY_LOW);
    RTCGeometry geom = rtcNewGeometry(impl->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
    auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), surface.size()));
    if (!vertices || !indices) {
        rtcReleaseGeometry(geom);
        return fail("Embree could not allocate buffers for " + std::to_string(surface.size()) + " triangles");
    }
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        vertices[3 * i] = mesh.positions[i].x;
        vertices[3 * i + 1] = mesh.positions[i].y;
        vertices[3 * i + 2] = mesh.positions[i].z;
    }
    for (size_t i = 0; i < surface.size(); ++i)
        for (int k = 0; k < 3; ++k)
            indices[3 * i + size_t(k)] = mesh.indices[3 * size_t(surface[i]) + size_t(k)];
    rtcCommitGeometry(geom);
    rtcAttachGeometry(impl->scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(impl->scene);
    if (const RTCError err = rtcGetDeviceError(impl->device); err != RTC_ERROR_NONE)
        return fail("Embree failed to build the closest-point structure (error " + std::to_string(int(err)) +
                    ")");
    return ClosestPointQuery(std::move(impl));
}

std::optional<ClosestPoint> ClosestPointQuery::closest(const glm::dvec3& p) const {
    return closest(p, std::numeric_limits<double>::infinity());
}

std::optional<ClosestPoint> ClosestPointQuery::closest(const glm::dvec3& p, double reach) const {
    if (!impl_->scene || !finitePoint(p) || !(reach >= 0.0)) return std::nullopt;
    PointQueryState state;
    state.corners = impl_->corners.data();
    state.p = p;
    state.rounding = pointRounding(p);
    state.reach2 = reach * reach * (1.0 + 1e-12); // a point at the reach, up to double rounding
    RTCPointQuery query = pointQuery(p, reach);
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(impl_->scene, &query, &context, closestPointCallback, &state);
    if (!std::isfinite(state.best2)) return std::nullopt;
    ClosestPoint out;
    out.point = state.bestPoint;
    out.distance = std::sqrt(state.best2);
    out.triangle = impl_->triangleIds[state.bestTriangle];
    return out;
}

bool ClosestPointQuery::within(const glm::dvec3& p, double radius) const {
    if (!impl_->scene || !finitePoint(p) || !std::isfinite(radius) || radius < 0.0) return false;
    WithinState state{impl_->corners.data(), p, radius * radius};
    RTCPointQuery query = pointQuery(p, radius);
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(impl_->scene, &query, &context, withinCallback, &state);
    return state.found;
}

std::optional<ClosestPointQuery::RayMeet>
ClosestPointQuery::firstMeet(const glm::dvec3& origin, const glm::dvec3& direction, double reach) const {
    if (!impl_->scene || !std::isfinite(reach) || !(reach > 0.0)) return std::nullopt;
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(origin[k]) || !std::isfinite(direction[k])) return std::nullopt;
    RTCRayHit rh{};
    rh.ray.org_x = float(origin.x);
    rh.ray.org_y = float(origin.y);
    rh.ray.org_z = float(origin.z);
    rh.ray.dir_x = float(direction.x);
    rh.ray.dir_y = float(direction.y);
    rh.ray.dir_z = float(direction.z);
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = float(reach);
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(impl_->scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    return RayMeet{impl_->triangleIds[rh.hit.primID], double(rh.ray.tfar)};
}

size_t ClosestPointQuery::surfaceTriangleCount() const {
    return impl_->triangleIds.size();
}

// ---------------------------------------------------------------------------------------------
// One-sided distance

namespace {

// A piece of a triangle being cut: its corners and the distances measured at them.
struct DistancePiece {
    glm::dvec3 p[3];
    double d[3];
};

// The four pieces of a triangle cut at its edge midpoints m[k] (on the edge from corner k to k + 1).
void quarter(const DistancePiece& t, const glm::dvec3 (&m)[3], const double (&dm)[3],
             DistancePiece (&out)[4]) {
    out[0] = {{t.p[0], m[0], m[2]}, {t.d[0], dm[0], dm[2]}};
    out[1] = {{m[0], t.p[1], m[1]}, {dm[0], t.d[1], dm[1]}};
    out[2] = {{m[2], m[1], t.p[2]}, {dm[2], dm[1], t.d[2]}};
    out[3] = {{m[0], m[1], m[2]}, {dm[0], dm[1], dm[2]}};
}

double largestOf(const double (&d)[3]) {
    return std::max({d[0], d[1], d[2]});
}

} // namespace

Result<OneSidedDistance> measureOneSidedDistance(const Mesh& from, const ClosestPointQuery& to,
                                                 const SurfaceSampling& sampling,
                                                 const ProgressCallback& progress) {
    if (Status s = checkTriangles(from); !s) return fail(s.error());
    const std::vector<uint32_t> surface = surfaceTriangles(from);
    OneSidedDistance out;
    if (surface.empty()) return out;
    if (to.surfaceTriangleCount() == 0)
        return fail("the target mesh has no surface (no triangle of non-zero area)");

    // Vertices of the surface triangles, each measured once.
    std::vector<uint32_t> vertexSlot(from.positions.size(), UINT32_MAX);
    std::vector<uint32_t> vertices;
    for (uint32_t t : surface)
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = from.indices[3 * size_t(t) + size_t(k)];
            if (vertexSlot[v] == UINT32_MAX) {
                vertexSlot[v] = uint32_t(vertices.size());
                vertices.push_back(v);
            }
        }

    const unsigned workers = workerCount();
    struct Accumulator {
        double measured = 0.0;
        double bound = 0.0;
        size_t samples = 0;
    };
    std::vector<Accumulator> acc(workers);
    auto distanceTo = [&](const glm::dvec3& p) {
        const std::optional<ClosestPoint> c = to.closest(p);
        return c ? c->distance : std::numeric_limits<double>::infinity();
    };
    // Progress: vertices, midpoints and random samples are known amounts of work; the cutting is
    // reported per triangle done.
    // A restart of the cutting reports no less than before, so the fraction never goes back.
    const double stages = 4.0;
    double reported = 0.0;
    auto reporter = [&](double stage) {
        return [&progress, &reported, stage, stages](double fraction) {
            reported = std::max(reported, (stage + fraction) / stages);
            return !progress || progress(float(reported), "measure");
        };
    };

    // 1. Vertices and edge midpoints: M1, the level every piece is compared with.
    std::vector<double> vertexDistance(vertices.size());
    bool ok = parallelChunks(
        vertices.size(), 1024, workers,
        [&](size_t begin, size_t end, unsigned w) {
            for (size_t i = begin; i < end; ++i) {
                vertexDistance[i] = distanceTo(glm::dvec3(from.positions[vertices[i]]));
                acc[w].measured = std::max(acc[w].measured, vertexDistance[i]);
                ++acc[w].samples;
            }
        },
        reporter(0.0));
    if (!ok) return fail("cancelled");
    auto piece = [&](size_t i) {
        DistancePiece t;
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = from.indices[3 * size_t(surface[i]) + size_t(k)];
            t.p[k] = glm::dvec3(from.positions[v]);
            t.d[k] = vertexDistance[vertexSlot[v]];
        }
        return t;
    };
    std::vector<std::array<double, 3>> midpointDistance(surface.size());
    ok = parallelChunks(
        surface.size(), 256, workers,
        [&](size_t begin, size_t end, unsigned w) {
            for (size_t i = begin; i < end; ++i) {
                const DistancePiece t = piece(i);
                for (int k = 0; k < 3; ++k) {
                    midpointDistance[i][size_t(k)] = distanceTo(0.5 * (t.p[k] + t.p[(k + 1) % 3]));
                    acc[w].measured = std::max(acc[w].measured, midpointDistance[i][size_t(k)]);
                }
                acc[w].samples += 3;
            }
        },
        reporter(1.0));
    if (!ok) return fail("cancelled");
    double level = 0.0; // M1
    for (const Accumulator& a : acc)
        level = std::max(level, a.measured);

    // 2. Cutting, with r doubled until it fits the sample budget.
    double radius = sampling.radius > 0.0 ? sampling.radius : 0.0;
    const size_t firstSamples = vertices.size() + 3 * surface.size();
    const size_t budget = sampling.maxSamples > firstSamples ? sampling.maxSamples - firstSamples : 0;
    for (;;) {
        std::atomic<size_t> cutSamples{0};
        std::atomic<bool> overBudget{false};
        std::vector<Accumulator> cut(workers);
        ok = parallelChunks(
            surface.size(), 64, workers,
            [&](size_t begin, size_t end, unsigned w) {
                std::vector<DistancePiece> stack;
                for (size_t i = begin; i < end && !overBudget.load(std::memory_order_relaxed); ++i) {
                    const DistancePiece t = piece(i);
                    glm::dvec3 m[3];
                    double dm[3];
                    for (int k = 0; k < 3; ++k) {
                        m[k] = 0.5 * (t.p[k] + t.p[(k + 1) % 3]);
                        dm[k] = midpointDistance[i][size_t(k)];
                    }
                    DistancePiece quarters[4];
                    quarter(t, m, dm, quarters);
                    stack.assign(quarters, quarters + 4);
                    size_t local = 0;
                    while (!stack.empty()) {
                        const DistancePiece q = stack.back();
                        stack.pop_back();
                        const double c = enclosingRadius(q.p[0], q.p[1], q.p[2]);
                        const double sum = largestOf(q.d) + c;
                        if (radius <= 0.0 || c <= radius || sum <= level + radius) {
                            cut[w].bound = std::max(cut[w].bound, sum);
                            continue;
                        }
                        // Halve the longest edge (from corner k to k + 1).
                        const int k = detail::longestEdge(q.p), k1 = (k + 1) % 3;
                        const glm::dvec3 mid = 0.5 * (q.p[k] + q.p[k1]);
                        const double dmid = distanceTo(mid);
                        cut[w].measured = std::max(cut[w].measured, dmid);
                        ++local;
                        DistancePiece a = q, b = q;
                        a.p[k1] = mid;
                        a.d[k1] = dmid;
                        b.p[k] = mid;
                        b.d[k] = dmid;
                        stack.push_back(a);
                        stack.push_back(b);
                    }
                    cut[w].samples += local;
                    if (cutSamples.fetch_add(local) + local > budget) overBudget = true;
                }
            },
            reporter(2.0));
        if (!ok) return fail("cancelled");
        if (!overBudget.load() || radius <= 0.0) {
            for (unsigned w = 0; w < workers; ++w) {
                acc[w].measured = std::max(acc[w].measured, cut[w].measured);
                acc[w].bound = std::max(acc[w].bound, cut[w].bound);
                acc[w].samples += cut[w].samples;
            }
            break;
        }
        radius *= 2.0;
    }

    // 3. Random area-weighted samples (seeded, so the result is reproducible).
    const size_t randomTotal = sampling.randomSamples;
    if (randomTotal > 0) {
        std::vector<double> cumulative(surface.size());
        double total = 0.0;
        for (size_t i = 0; i < surface.size(); ++i) {
            const uint32_t t = surface[i];
            const glm::dvec3 a = corner(from, t, 0);
            total += glm::length(glm::cross(corner(from, t, 1) - a, corner(from, t, 2) - a));
            cumulative[i] = total;
        }
        std::vector<glm::dvec3> points(randomTotal);
        Rng rng(sampling.seed);
        for (glm::dvec3& p : points) {
            const double pick = double(rng.uniform()) * total;
            const size_t i = std::min(
                size_t(std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin()),
                surface.size() - 1);
            const double su = std::sqrt(double(rng.uniform())), v = double(rng.uniform());
            const uint32_t t = surface[i];
            p = corner(from, t, 0) * (1.0 - su) + corner(from, t, 1) * (su * (1.0 - v)) +
                corner(from, t, 2) * (su * v);
        }
        ok = parallelChunks(
            points.size(), 1024, workers,
            [&](size_t begin, size_t end, unsigned w) {
                for (size_t i = begin; i < end; ++i) {
                    acc[w].measured = std::max(acc[w].measured, distanceTo(points[i]));
                    ++acc[w].samples;
                }
            },
            reporter(3.0));
        if (!ok) return fail("cancelled");
    }

    if (progress && !progress(1.0f, "measure")) return fail("cancelled");
    double scale = 0.0;
    for (uint32_t v : vertices) {
        const glm::vec3& p = from.positions[v];
        scale = std::max({scale, double(std::fabs(p.x)), double(std::fabs(p.y)), double(std::fabs(p.z))});
    }
    for (const Accumulator& a : acc) {
        out.measuredMax = std::max(out.measuredMax, a.measured);
        out.bound = std::max(out.bound, a.bound);
        out.samples += a.samples;
    }
    out.bound =
        std::max(out.bound, out.measuredMax) * (1.0 + kRoundingAllowance) + kRoundingAllowance * scale;
    out.margin = out.bound - out.measuredMax;
    return out;
}

Result<MeshDistance> measureMeshDistance(const Mesh& a, const Mesh& b, const SurfaceSampling& sampling,
                                         const ProgressCallback& progress) {
    Result<ClosestPointQuery> qa = ClosestPointQuery::create(a);
    if (!qa) return fail("mesh A: " + qa.error());
    Result<ClosestPointQuery> qb = ClosestPointQuery::create(b);
    if (!qb) return fail("mesh B: " + qb.error());
    if ((qa->surfaceTriangleCount() == 0) != (qb->surfaceTriangleCount() == 0))
        return fail(std::string("mesh ") + (qa->surfaceTriangleCount() == 0 ? "A" : "B") +
                    " has no surface (no triangle of non-zero area) but the other has one");
    auto half = [&](float offset) -> ProgressCallback {
        if (!progress) return {};
        return [&progress, offset](float f, const char* stage) { return progress(offset + 0.5f * f, stage); };
    };
    MeshDistance out;
    Result<OneSidedDistance> ab = measureOneSidedDistance(a, qb.value(), sampling, half(0.0f));
    if (!ab) return fail(ab.error());
    Result<OneSidedDistance> ba = measureOneSidedDistance(b, qa.value(), sampling, half(0.5f));
    if (!ba) return fail(ba.error());
    out.aToB = ab.value();
    out.bToA = ba.value();
    return out;
}

} // namespace spatter
