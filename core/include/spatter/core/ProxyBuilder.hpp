#pragma once
// ProxyBuilder: the collision proxy of a render mesh, with a certified error bound h.
//
// A proxy is one of
//  - the render mesh itself (ProxySource::OwnMesh, h = 0): when it has fewer triangles than
//    ProxySettings::smallMeshTriangles, when the tolerance is 0, or when simplification would not
//    remove a triangle;
//  - an authored collider (UCX_ / -col), used as given (ProxySource::AuthoredCollider), h measured;
//  - a simplification of the render mesh (ProxySource::Simplified) by OpenMesh's Decimater or
//    meshoptimizer's simplifier, h measured.
//
// The bound. h >= the true two-sided Hausdorff distance between the proxy and the render mesh,
// certified by branch and bound (HausdorffBound.hpp, where the argument is written out): exact
// closest-point distances in double at points of each surface, and convexity and Lipschitz bounds
// over the pieces between them. proxyToRenderMax and renderToProxyMax are distances measured at actual
// surface points, so the true distance is at least their maximum; h exceeds it by at most
// samplingMargin.
//
// The search. meshoptimizer (or OpenMesh, when asked for) runs at a target error, bisected between a
// candidate within the tolerance and one that is not, until the coarsest target within is known
// within 10% or maxAttempts runs are spent (a run at a larger target than the coarsest run judged
// within starts from that run's mesh where it left room under the tolerance). Runs are judged by a sampled
// lower bound of their distance (a run close to the tolerance by the certificate at once); the candidates
// judged within are then certified, coarsest first, both directions at once with the early answer to "is h <=
// tolerance?", and the first certified is the proxy, unless certified runs between it and a coarser
// candidate that failed give fewer triangles (see docs/PROXIES.md, "The search").
// Its h is at most max(largest measured distance + marginFraction * tolerance, tolerance): the search
// asks for the tolerance, not for the sharpest bound. When no candidate is certified, the finest one is
// returned with a sharp bound (within 4 * marginFraction * tolerance of the measured distance) and
// toleranceMet = false; the triangle budget is a hard limit and
// ends the search when it stops simplification.
//
// Cache: with a cache directory, a simplified proxy or a measured collider is stored on disk under a
// 64-bit hash of the render mesh, the collider and the settings (ProxyCache.hpp); a later build with
// the same input loads it (cached = true) without simplifying or measuring. A corrupt entry is
// rebuilt and overwritten.
//
// Bad input never crashes: an index past the vertex count, an index count that is not a multiple
// of 3 or a non-finite position in the render mesh or the collider, and invalid settings, give an
// error naming the mesh and the problem. Degenerate triangles (repeated index, zero area) are not
// part of the surface and are dropped from simplified proxies; non-manifold input is accepted by both
// backends.

#include "spatter/core/DrawnNormals.hpp"
#include "spatter/core/Mesh.hpp"
#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/Result.hpp"
#include "spatter/core/Threads.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace spatter {

enum class ProxyBackend : uint32_t {
    Auto = 0,     // settings: meshoptimizer (see resolveProxyBackend)
    OpenMesh = 1, // OpenMesh Decimater: quadric priority, Hausdorff and normal-deviation constraints
    MeshOpt = 2,  // meshoptimizer's meshopt_simplify: the fast path
    None = 3,     // result only: nothing was simplified (own mesh or authored collider)
};

enum class ProxySource : uint32_t {
    Simplified = 0,
    OwnMesh = 1,
    AuthoredCollider = 2,
};

// "auto", "openmesh", "meshopt", "none".
const char* proxyBackendName(ProxyBackend backend);
// "simplified", "own-mesh", "authored-collider".
const char* proxySourceName(ProxySource source);

struct ProxySettings {
    // Target for h: absolute, or (toleranceRelative) a fraction of the diagonal of the bounding box
    // of the render mesh's referenced vertices. Finite and >= 0; 0 means the render mesh itself.
    float tolerance = 0.005f;
    bool toleranceRelative = true;
    // Largest number of proxy triangles; 0 for no limit. A hard limit: met even if h exceeds the
    // tolerance; a build that can meet it only by removing every triangle fails.
    uint32_t maxTriangles = 0;
    ProxyBackend backend = ProxyBackend::Auto;
    // Keep open boundaries in place (OpenMesh: boundary vertices locked; meshopt: LockBorder).
    bool keepBoundaries = true;
    // Protect sharp edges (dihedral angle above featureAngleDegrees) during simplification: they are
    // only collapsed along themselves. Off by default: the certified bound already keeps every edge
    // within the tolerance, and protecting them all keeps far more triangles (relief on walls, CAD
    // parts). Proxy normals are split along the sharp edges of the proxy either way.
    bool keepSharpFeatures = false;
    float featureAngleDegrees = 45.0f;
    // A render mesh with fewer triangles than this is its own proxy (h = 0).
    uint32_t smallMeshTriangles = 512;
    // Certification margin, as a fraction of the absolute tolerance, in (0, 1): a bound within it
    // above the largest measured distance is not refined further; near the tolerance it shrinks to a
    // quarter of the room left under it, and a candidate measured within 1% below the tolerance may be
    // left uncertified (the search counts it as too coarse); the bound of an authored collider exceeds the
    // measured distance by at most this (that of a proxy that missed the tolerance by at most 4 times this).
    float marginFraction = 0.05f;
    // Simplification runs the search may make (>= 1).
    uint32_t maxAttempts = 8;
    // Directory of the on-disk cache; empty for no cache. Created when missing.
    std::string cacheDirectory;
    // Threads a build may use (0: the hardware's, at most kMaxThreads; 1: the calling thread alone), besides
    // the threads of Embree's own BVH builds. The proxy does not depend on it, and the cache key
    // leaves it out: a caller that builds several proxies at once can give each fewer.
    unsigned threads = 0;
};

struct Proxy {
    Mesh mesh; // positions, unit normals, indices; no UVs, tangents or submeshes
    ProxySource source = ProxySource::OwnMesh;
    ProxyBackend backend = ProxyBackend::None; // OpenMesh or MeshOpt when source == Simplified
    double tolerance = 0.0;                    // the absolute tolerance asked for
    bool toleranceMet = true;                  // errorBound <= tolerance (always true for OwnMesh)
    double errorBound = 0.0;                   // h: >= the true two-sided Hausdorff distance
    double proxyToRenderMax = 0.0;             // largest sampled proxy-to-render distance
    double renderToProxyMax = 0.0;             // largest sampled render-to-proxy distance
    // errorBound - max(proxyToRenderMax, renderToProxyMax): at most max(marginFraction * tolerance,
    // tolerance - that maximum).
    double samplingMargin = 0.0;
    // For each piece of each proxy triangle, which way the render mesh faces there (DrawnNormals.hpp);
    // empty when the render mesh is its own proxy.
    DrawnNormals drawnNormals;
    size_t samples = 0;        // closest-point queries made to certify the final proxy
    size_t inputTriangles = 0; // render mesh triangles
    size_t proxyTriangles = 0;
    uint32_t attempts = 0;          // simplification runs of the search (0 when nothing was simplified)
    double seconds = 0.0;           // wall time of this buildProxy call
    bool cached = false;            // loaded from the cache: nothing was simplified or measured
    std::vector<std::string> notes; // what happened besides the plain path (cache misses, fallbacks)
};

// The backend Auto stands for: meshoptimizer. Its runs take milliseconds where OpenMesh's take
// seconds, so the search can afford the several runs that find the coarsest certified proxy; OpenMesh
// is there for callers who ask for it (its quadric decimation with a Hausdorff constraint sometimes
// gives fewer triangles at the same tolerance, at tens of times the cost). Any backend other than Auto
// is returned unchanged; the size and tolerance arguments are not used.
ProxyBackend resolveProxyBackend(ProxyBackend requested, size_t triangles, double absoluteTolerance,
                                 double diagonal);

// Builds the proxy of `render` (see the top of this file). `authoredCollider`, when given, is used as
// the proxy instead of simplifying; it is not modified or kept. `progress` is called with the stages
// "cache", "simplify" and "measure" and the fraction of the whole build done (it never goes back;
// a simplified proxy or a measured collider ends with 1); returning false cancels the build (error
// "cancelled").
Result<Proxy> buildProxy(const Mesh& render, const ProxySettings& settings,
                         const Mesh* authoredCollider = nullptr, const ProgressCallback& progress = {});

// `proxy` held for sharing: the objects placed with one mesh take one proxy (proxySources), and the
// collision world takes an entry for each object (CollisionWorld::build).
std::shared_ptr<const Proxy> shareProxy(Proxy proxy);

} // namespace spatter
