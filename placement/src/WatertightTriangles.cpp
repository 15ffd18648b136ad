#include "WatertightTriangles.hpp"

#include <algorithm>
#include <cmath>

namespace spatter {

void triangleBounds(const RTCBoundsFunctionArguments* args) {
    const auto* od = static_cast<const TracedTriangles*>(args->geometryUserPtr);
    const uint32_t* tri = &od->indices[size_t(args->primID) * 3];
    const glm::vec3 p0 = od->traced[tri[0]], p1 = od->traced[tri[1]], p2 = od->traced[tri[2]];
    // Embree 3 traverses user geometry without its robust mode: a box test is off by a few float steps
    // of |box| + |ray origin|. Every box grows by 2^-18 of that (about 32 steps), with |ray origin| at
    // most `reach`, so that no rounding culls a ray through a corner or along an edge.
    const glm::vec3 lo = glm::min(glm::min(p0, p1), p2), hi = glm::max(glm::max(p0, p1), p2);
    const glm::vec3 grow = (glm::max(glm::abs(lo), glm::abs(hi)) + float(od->reach)) * std::ldexp(1.0f, -18);
    args->bounds_o->lower_x = lo.x - grow.x;
    args->bounds_o->lower_y = lo.y - grow.y;
    args->bounds_o->lower_z = lo.z - grow.z;
    args->bounds_o->upper_x = hi.x + grow.x;
    args->bounds_o->upper_y = hi.y + grow.y;
    args->bounds_o->upper_z = hi.z + grow.z;
}

namespace {

// The rays of one call of intersectTriangle: Embree's RTCRayHitN, a structure of arrays of N lanes.
struct Lanes {
    const float* org[3];
    const float* dir[3];
    const float* tnear;
    float* tfar;
    const unsigned* id;
    unsigned* primID;
    unsigned* geomID;
    unsigned* instID;
};

Lanes lanesOf(RTCRayHitN* rayhit, unsigned n) {
    RTCRayN* ray = RTCRayHitN_RayN(rayhit, n);
    RTCHitN* hit = RTCRayHitN_HitN(rayhit, n);
    return {{&RTCRayN_org_x(ray, n, 0), &RTCRayN_org_y(ray, n, 0), &RTCRayN_org_z(ray, n, 0)},
            {&RTCRayN_dir_x(ray, n, 0), &RTCRayN_dir_y(ray, n, 0), &RTCRayN_dir_z(ray, n, 0)},
            &RTCRayN_tnear(ray, n, 0),
            &RTCRayN_tfar(ray, n, 0),
            &RTCRayN_id(ray, n, 0),
            &RTCHitN_primID(hit, n, 0),
            &RTCHitN_geomID(hit, n, 0),
            &RTCHitN_instID(hit, n, 0, 0)};
}

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define SPATTER_LANE_VARIANTS 1
// The test is compiled without contracting products and sums into fused multiply-adds: every
// variant rounds each operation as the scalar code does, so no result depends on the variant.
#define SPATTER_EXACT __attribute__((optimize("fp-contract=off")))
#define SPATTER_INLINE inline __attribute__((always_inline))
#else
#define SPATTER_LANE_VARIANTS 0
#define SPATTER_EXACT
#define SPATTER_INLINE inline
#endif

// a ? x : (b ? y : z), by selection.
SPATTER_INLINE float pick(bool a, float x, bool b, float y, float z) {
    return a ? x : (b ? y : z);
}

// The first stage of the test for a block of W lanes: each lane's sheared vertices (x, y, z of the
// three) and shear sz, and whether it may meet the triangle (`candidate`). The edge functions are
// evaluated in float first: rounding is monotonic, so each one keeps its exact sign or becomes zero,
// and a lane with one edge function below zero and another above misses exactly. The others are
// decided in double by hitDistance.
template <unsigned W> struct EdgeBlock {
    float x[3][W], y[3][W], z[3][W], sz[W];
    int candidate[W];
};

// Stage one for W lanes (ray origins o, directions d, Embree's valid flags), branch-free so that it
// vectorises. The shear space of a ray: z along the largest component of its direction (kz), x and
// y the next axes cyclically (kx, ky), swapped when the direction's z is negative so that a sheared
// triangle keeps its winding. `p`: the triangle's vertices, x, y, z of each.
template <unsigned W>
SPATTER_INLINE void edgeLanes(const float* __restrict ox, const float* __restrict oy,
                              const float* __restrict oz, const float* __restrict dxs,
                              const float* __restrict dys, const float* __restrict dzs,
                              const int* __restrict valid, const float (&p)[9], EdgeBlock<W>& __restrict e) {
    for (unsigned k = 0; k < W; ++k) {
        const float dx = dxs[k], dy = dys[k], dz = dzs[k];
        const float ax = std::fabs(dx), ay = std::fabs(dy), az = std::fabs(dz);
        const bool zIsX = (ax > ay) & (ax > az);
        const bool zIsY = !(ax > ay) & (ay > az);
        const float dkz = pick(zIsX, dx, zIsY, dy, dz);
        const bool swap = dkz < 0.0f;
        const float dcx = pick(zIsX, dy, zIsY, dz, dx), dcy = pick(zIsX, dz, zIsY, dx, dy);
        const float dkx = swap ? dcy : dcx, dky = swap ? dcx : dcy;
        const float sx = dkx / dkz, sy = dky / dkz;
        float x[3], y[3];
        for (int i = 0; i < 3; ++i) {
            const float vx = p[3 * i] - ox[k], vy = p[3 * i + 1] - oy[k], vz = p[3 * i + 2] - oz[k];
            const float vcx = pick(zIsX, vy, zIsY, vz, vx), vcy = pick(zIsX, vz, zIsY, vx, vy);
            const float vkz = pick(zIsX, vx, zIsY, vy, vz);
            const float vkx = swap ? vcy : vcx, vky = swap ? vcx : vcy;
            x[i] = vkx - sx * vkz;
            y[i] = vky - sy * vkz;
            e.x[i][k] = x[i];
            e.y[i][k] = y[i];
            e.z[i][k] = vkz;
        }
        const float u = x[2] * y[1] - y[2] * x[1];
        const float v = x[0] * y[2] - y[0] * x[2];
        const float w = x[1] * y[0] - y[1] * x[0];
        const bool mixed = ((u < 0.0f) | (v < 0.0f) | (w < 0.0f)) & ((u > 0.0f) | (v > 0.0f) | (w > 0.0f));
        e.candidate[k] = (valid[k] != 0) & !mixed;
        e.sz[k] = 1.0f / dkz;
    }
}

// Stage one for the lanes [first, first + W) of a packet; returns the candidate lanes as bits.
template <unsigned W>
SPATTER_INLINE unsigned edgeBits(const Lanes& r, const int* valid, unsigned first, const float (&p)[9],
                                 EdgeBlock<W>& e) {
    edgeLanes<W>(r.org[0] + first, r.org[1] + first, r.org[2] + first, r.dir[0] + first, r.dir[1] + first,
                 r.dir[2] + first, valid + first, p, e);
    unsigned bits = 0;
    for (unsigned k = 0; k < W; ++k)
        bits |= unsigned(e.candidate[k] != 0) << k;
    return bits;
}

template <unsigned W>
using EdgeBitsFn = unsigned (*)(const Lanes&, const int*, unsigned, const float (&)[9], EdgeBlock<W>&);

#if SPATTER_LANE_VARIANTS
// edgeBits compiled for AVX-512 and AVX2 besides the baseline. The best one the processor runs is
// picked at the first call, not at load time: a load-time resolver (GCC's target_clones) runs before
// sanitizer runtimes start.
template <unsigned W>
__attribute__((target("avx512f"), optimize("fp-contract=off"))) unsigned
edgeBitsAvx512(const Lanes& r, const int* valid, unsigned first, const float (&p)[9], EdgeBlock<W>& e) {
    return edgeBits<W>(r, valid, first, p, e);
}

template <unsigned W>
__attribute__((target("avx2"), optimize("fp-contract=off"))) unsigned
edgeBitsAvx2(const Lanes& r, const int* valid, unsigned first, const float (&p)[9], EdgeBlock<W>& e) {
    return edgeBits<W>(r, valid, first, p, e);
}
#endif

template <unsigned W>
SPATTER_EXACT unsigned edgeBitsBaseline(const Lanes& r, const int* valid, unsigned first, const float (&p)[9],
                                        EdgeBlock<W>& e) {
    return edgeBits<W>(r, valid, first, p, e);
}

template <unsigned W> EdgeBitsFn<W> edgeBitsForThisProcessor() {
#if SPATTER_LANE_VARIANTS
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx512f")) return edgeBitsAvx512<W>;
    if (__builtin_cpu_supports("avx2")) return edgeBitsAvx2<W>;
#endif
    return edgeBitsBaseline<W>;
}

template <unsigned W>
unsigned edgeFunctionsVector(const Lanes& r, const int* valid, unsigned first, const float (&p)[9],
                             EdgeBlock<W>& e) {
    static const EdgeBitsFn<W> best = edgeBitsForThisProcessor<W>();
    return best(r, valid, first, p, e);
}

// The second stage for a candidate lane k: the edge functions in double, where products of floats
// are exact, so that their signs are exact; the distance of the hit, or false when the ray misses
// the triangle (edge functions of both signs, or all zero) or the hit lies outside [tnear, tfar].
template <unsigned W>
SPATTER_INLINE bool hitDistance(const EdgeBlock<W>& e, unsigned k, float tnear, float tfar, float& t) {
    const double x0 = e.x[0][k], x1 = e.x[1][k], x2 = e.x[2][k];
    const double y0 = e.y[0][k], y1 = e.y[1][k], y2 = e.y[2][k];
    const double u = x2 * y1 - y2 * x1, v = x0 * y2 - y0 * x2, w = x1 * y0 - y1 * x0;
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0)) return false;
    const double det = u + v + w;
    if (det == 0.0) return false;
    const double sz = double(e.sz[k]);
    const double T =
        u * (sz * double(e.z[0][k])) + v * (sz * double(e.z[1][k])) + w * (sz * double(e.z[2][k]));
    const double hit = T / det;
    if (!(hit >= double(tnear) && hit <= double(tfar))) return false;
    t = float(hit);
    return true;
}

// Makes the closest hit independent of traversal order. Embree keeps the first of equally distant
// hits it meets, and the float bounds of instances can cull a surface lying exactly at the current
// tfar, so the outcome of a tie would depend on the order of traversal (single rays and packets
// differ). Each ray keeps its own best hit, ordered by (t, instance, geometry, primitive), and tfar
// a little beyond it (t + slack, slack far above the rounding of Embree's bounds), so that every
// surface at the best distance is still visited and offered here. `ids`: (instance, geometry,
// primitive) of the hit at distance t on lane i.
inline void offerHit(const TraceContext& ctx, const Lanes& r, unsigned i, float t, const unsigned (&ids)[3]) {
    float& best = ctx.bestT[r.id[i]];
    bool better = t < best || r.geomID[i] == kInvalidId;
    if (!better && t == best) {
        const unsigned kept[3] = {r.instID[i], r.geomID[i], r.primID[i]};
        better = std::lexicographical_compare(ids, ids + 3, kept, kept + 3);
    }
    if (!better) return;
    best = t;
    r.tfar[i] = t + ctx.slack;
    r.instID[i] = ids[0];
    r.geomID[i] = ids[1];
    r.primID[i] = ids[2];
}

// Intersects the lanes [first, first + W) with the triangle `p` and offers each hit to offerHit.
template <unsigned W>
SPATTER_EXACT void intersectBlock(const TraceContext& ctx, const Lanes& r, const int* valid, unsigned first,
                                  const float (&p)[9], const unsigned (&ids)[3]) {
    EdgeBlock<W> e;
    unsigned bits =
        W == 1 ? edgeBits<W>(r, valid, first, p, e) : edgeFunctionsVector<W>(r, valid, first, p, e);
    for (; bits != 0; bits &= bits - 1) {
        const auto k = unsigned(__builtin_ctz(bits));
        const unsigned i = first + k;
        float t;
        if (hitDistance<W>(e, k, r.tnear[i], r.tfar[i], t)) offerHit(ctx, r, i, t, ids);
    }
}

} // namespace

// Intersects the rays of a packet (N lanes, N = 1 for single rays) with one triangle: all lanes at
// once, or lane by lane when Embree marks few of them valid, and keeps each lane's closest hit
// (offerHit).
void intersectTriangle(const RTCIntersectFunctionNArguments* args) {
    constexpr unsigned kFewLanes = 2; // single rays, and Embree's single-ray traversal inside a packet
    const auto* od = static_cast<const TracedTriangles*>(args->geometryUserPtr);
    const uint32_t* tri = &od->indices[size_t(args->primID) * 3];
    float p[9];
    for (int i = 0; i < 3; ++i)
        for (int c = 0; c < 3; ++c)
            p[3 * i + c] = od->traced[tri[i]][c];
    const auto& ctx = *reinterpret_cast<const TraceContext*>(args->context);
    const unsigned ids[3] = {args->context->instID[0], args->geomID, args->primID};
    const unsigned n = args->N;
    const Lanes r = lanesOf(args->rayhit, n);
    const auto lanes = unsigned(std::count_if(args->valid, args->valid + n, [](int v) { return v != 0; }));
    if (lanes > kFewLanes && n == 16) {
        intersectBlock<16>(ctx, r, args->valid, 0, p, ids);
    } else if (lanes > kFewLanes && n == 8) {
        intersectBlock<8>(ctx, r, args->valid, 0, p, ids);
    } else if (lanes > kFewLanes && n == 4) {
        intersectBlock<4>(ctx, r, args->valid, 0, p, ids);
    } else {
        for (unsigned i = 0; i < n; ++i)
            if (args->valid[i] != 0) intersectBlock<1>(ctx, r, args->valid, i, p, ids);
    }
}

} // namespace spatter
