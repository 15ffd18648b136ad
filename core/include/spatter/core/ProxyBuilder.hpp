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
// The bound. h = max(bound(proxy -> render), bound(render -> proxy)), each one-sided bound computed by
// measureOneSidedDistance (MeshDistance.hpp, where the derivation is written out): exact closest-point
// distances (Embree rtcPointQuery) at every vertex, every edge midpoint, the corners of an adaptive
// cutting of every triangle, and random area-weighted samples; plus, per piece of the cutting, the
// radius of its smallest enclosing circle. Because the distance to a surface is 1-Lipschitz and every
// point of a piece lies within that radius of one of the piece's corners, h >= the true two-sided
// Hausdorff distance between the proxy and the render mesh; and max(proxyToRenderMax,
// renderToProxyMax), being attained at actual surface points, is <= it. The cutting goes on until
// h <= max(proxyToRenderMax, renderToProxyMax) + marginFraction * tolerance, unless maxSamples
// forces it to stop earlier (samplingMargin reports the margin reached).
//
// The tolerance is the target for h; the triangle budget is a hard limit. A backend is run with an
// internal tolerance below the target; if the measured h exceeds the target, it is run again with a
// smaller internal tolerance (up to maxAttempts runs). When the budget stops simplification first,
// or no run meets the target, the proxy with the smallest h is returned with toleranceMet = false.
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

#include "spatter/core/Mesh.hpp"
#include "spatter/core/MeshDistance.hpp"
#include "spatter/core/Result.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace spatter {

enum class ProxyBackend : uint32_t {
    Auto = 0,     // settings: pick by size and tolerance (see resolveProxyBackend)
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
    // tolerance.
    uint32_t maxTriangles = 0;
    ProxyBackend backend = ProxyBackend::Auto;
    // Keep open boundaries in place (OpenMesh: boundary vertices locked; meshopt: LockBorder).
    bool keepBoundaries = true;
    // Keep sharp edges (dihedral angle above featureAngleDegrees): they are only collapsed along
    // themselves, and proxy normals are split along them.
    bool keepSharpFeatures = true;
    float featureAngleDegrees = 45.0f;
    // A render mesh with fewer triangles than this is its own proxy (h = 0).
    uint32_t smallMeshTriangles = 512;
    // Error measurement: the sampling margin allowed (h minus the largest sampled distance) as a
    // fraction of the absolute tolerance, in (0, 1); the sample budget and the random samples per
    // direction, and their seed.
    float marginFraction = 0.2f;
    uint32_t maxSamples = 2'000'000;
    uint32_t randomSamples = 16384;
    uint64_t seed = 1;
    // Simplification runs allowed to bring h under the tolerance (>= 1).
    uint32_t maxAttempts = 4;
    // Directory of the on-disk cache; empty for no cache. Created when missing.
    std::string cacheDirectory;
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
    // errorBound <= max(proxyToRenderMax, renderToProxyMax) + samplingMargin; the margin is at most
    // marginFraction * tolerance unless maxSamples forced coarser sampling.
    double samplingMargin = 0.0;
    size_t samples = 0;        // closest-point queries made for the final proxy
    size_t inputTriangles = 0; // render mesh triangles
    size_t proxyTriangles = 0;
    uint32_t attempts = 0;          // simplification runs (0 when nothing was simplified)
    double seconds = 0.0;           // wall time of this buildProxy call
    bool cached = false;            // loaded from the cache: nothing was simplified or measured
    std::vector<std::string> notes; // what happened besides the plain path (cache misses, fallbacks)
};

// The backend Auto starts with. For meshes of at most 8,000 triangles whose tolerance is at most 2%
// of the diagonal it is OpenMesh, and buildProxy then runs meshoptimizer as well and keeps the better
// proxy (within the tolerance first, then fewer triangles, then the smaller h): there both cost well
// under a second and each wins on some meshes. Otherwise it is meshoptimizer alone: tens of times
// faster on large meshes, and OpenMesh's cost grows with the tolerance (each remaining face re-tests
// every vertex removed under it). Any backend other than Auto is returned unchanged.
ProxyBackend resolveProxyBackend(ProxyBackend requested, size_t triangles, double absoluteTolerance,
                                 double diagonal);

// Builds the proxy of `render` (see the top of this file). `authoredCollider`, when given, is used as
// the proxy instead of simplifying; it is not modified or kept. `progress` is called with the stages
// "cache", "simplify" and "measure"; returning false cancels the build (error "cancelled").
Result<Proxy> buildProxy(const Mesh& render, const ProxySettings& settings,
                         const Mesh* authoredCollider = nullptr, const ProgressCallback& progress = {});

} // namespace spatter
