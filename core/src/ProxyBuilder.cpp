#include "spatter/core/ProxyBuilder.hpp"
#include "ProxyMeshes.hpp"
#include "ProxySearch.hpp"
#include "SurfaceGeometry.hpp"

#include "spatter/core/HausdorffBound.hpp"
#include "spatter/core/ProxyCache.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace spatter {

std::shared_ptr<const Proxy> shareProxy(Proxy proxy) {
    return std::make_shared<const Proxy>(std::move(proxy));
}

const char* proxyBackendName(ProxyBackend backend) {
    switch (backend) {
    case ProxyBackend::Auto:
        return "auto";
    case ProxyBackend::OpenMesh:
        return "openmesh";
    case ProxyBackend::MeshOpt:
        return "meshopt";
    case ProxyBackend::None:
        return "none";
    }
    return "unknown";
}

const char* proxySourceName(ProxySource source) {
    switch (source) {
    case ProxySource::Simplified:
        return "simplified";
    case ProxySource::OwnMesh:
        return "own-mesh";
    case ProxySource::AuthoredCollider:
        return "authored-collider";
    }
    return "unknown";
}

ProxyBackend resolveProxyBackend(ProxyBackend requested, size_t, double, double) {
    return requested == ProxyBackend::Auto ? ProxyBackend::MeshOpt : requested;
}

namespace {

using detail::Candidate;
using detail::CoarseInput;
using detail::PendingSurface;
using detail::SearchContext;
using detail::SearchOutcome;
using detail::surfaceTriangleCount;
using Clock = std::chrono::steady_clock;

Status checkMesh(const Mesh& mesh, const char* what) {
    const size_t n = mesh.positions.size();
    const std::string prefix = std::string(what) + ": ";
    if (mesh.indices.size() % 3 != 0)
        return fail(prefix + "index count " + std::to_string(mesh.indices.size()) +
                    " is not a multiple of 3");
    if (n > size_t(UINT32_MAX)) return fail(prefix + "too many vertices (" + std::to_string(n) + ")");
    for (size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= n)
            return fail(prefix + "index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) +
                        ", past the vertex count " + std::to_string(n));
    for (size_t i = 0; i < n; ++i) {
        const glm::vec3& p = mesh.positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return fail(prefix + "position " + std::to_string(i) + " is not finite (NaN or Inf)");
    }
    return {};
}

Status checkSettings(const ProxySettings& s) {
    if (!std::isfinite(s.tolerance) || s.tolerance < 0.0f)
        return fail("proxy settings: tolerance " + std::to_string(s.tolerance) + " is not finite and >= 0");
    if (s.backend == ProxyBackend::None) return fail("proxy settings: backend 'none' cannot simplify");
    if (uint32_t(s.backend) > uint32_t(ProxyBackend::None)) return fail("proxy settings: unknown backend");
    if (!(s.featureAngleDegrees >= 0.0f && s.featureAngleDegrees <= 180.0f))
        return fail("proxy settings: feature angle " + std::to_string(s.featureAngleDegrees) +
                    " is not in [0, 180]");
    if (!(s.marginFraction > 0.0f && s.marginFraction < 1.0f))
        return fail("proxy settings: margin fraction " + std::to_string(s.marginFraction) +
                    " is not in (0, 1)");
    if (s.maxAttempts < 1) return fail("proxy settings: maxAttempts must be at least 1");
    if (const std::string p = detail::threadsProblem(s.threads); !p.empty())
        return fail("proxy settings: " + p);
    return {};
}

double referencedDiagonal(const Mesh& m) {
    Bounds b;
    for (uint32_t i : m.indices)
        b.extend(m.positions[i]);
    return double(b.diagonal());
}

// The render mesh's own positions, indices and normals.
Mesh ownMesh(const Mesh& m) {
    Mesh out;
    out.positions = m.positions;
    out.indices = m.indices;
    out.normals = m.normals;
    repairNormals(out);
    return out;
}

void finishResult(Proxy& p, const Clock::time_point& start) {
    p.proxyTriangles = p.mesh.triangleCount();
    p.seconds = std::chrono::duration<double>(Clock::now() - start).count();
}

// The cache key, where there is a cache (the key hashes the whole render mesh).
uint64_t cacheKey(const Mesh& render, const ProxySettings& s, const Mesh* authoredCollider) {
    return s.cacheDirectory.empty() ? 0 : proxyCacheKey(render, s, authoredCollider);
}

// Cache lookup: the proxy on a hit; nothing on a miss (a corrupt entry adds a note).
std::optional<Proxy> lookUp(const ProxySettings& s, uint64_t key, const ProgressCallback& progress,
                            std::vector<std::string>& notes) {
    if (s.cacheDirectory.empty()) return std::nullopt;
    Result<Proxy> hit = loadCachedProxy(s.cacheDirectory, key);
    if (hit) {
        if (progress) progress(1.0f, "cache");
        return std::move(hit).value();
    }
    if (hit.error().rfind("no cache entry", 0) != 0) notes.push_back(hit.error() + "; rebuilt");
    return std::nullopt;
}

void store(const ProxySettings& s, uint64_t key, Proxy& p) {
    if (s.cacheDirectory.empty()) return;
    if (Status st = storeCachedProxy(s.cacheDirectory, key, p); !st) p.notes.push_back(st.error());
}

// The report fields of a certified candidate.
void takeBound(Proxy& p, const Candidate& c, double tolerance) {
    p.errorBound = c.bound();
    p.proxyToRenderMax = c.proxyToRender.lower;
    p.renderToProxyMax = c.renderToProxy.lower;
    p.samplingMargin = p.errorBound - c.lower();
    p.samples = c.proxyToRender.queries + c.renderToProxy.queries;
    p.toleranceMet = c.within(tolerance);
}

} // namespace

Result<Proxy> buildProxy(const Mesh& render, const ProxySettings& s, const Mesh* authoredCollider,
                         const ProgressCallback& progress) {
    const Clock::time_point start = Clock::now();
    if (Status st = checkSettings(s); !st) return fail(st.error());
    if (Status st = checkMesh(render, "render mesh"); !st) return fail(st.error());
    if (authoredCollider)
        if (Status st = checkMesh(*authoredCollider, "authored collider"); !st) return fail(st.error());

    const double diagonal = referencedDiagonal(render);
    const double tolerance = s.toleranceRelative ? double(s.tolerance) * diagonal : double(s.tolerance);
    const size_t inputTriangles = render.triangleCount();
    const size_t surfaceTriangles = surfaceTriangleCount(render);
    const HausdorffSettings certifying =
        detail::certifyingSettings(tolerance, diagonal, s.marginFraction, s.threads);

    Proxy proxy;
    proxy.tolerance = tolerance;
    proxy.inputTriangles = inputTriangles;

    if (authoredCollider) {
        const uint64_t key = cacheKey(render, s, authoredCollider);
        if (std::optional<Proxy> hit = lookUp(s, key, progress, proxy.notes)) {
            hit->notes = std::move(proxy.notes);
            finishResult(*hit, start);
            return std::move(*hit);
        }
        proxy.mesh = ownMesh(*authoredCollider);
        proxy.source = ProxySource::AuthoredCollider;
        proxy.backend = ProxyBackend::None;
        Result<HausdorffSurface> renderSurface = HausdorffSurface::create(render);
        if (!renderSurface) return fail("render mesh: " + renderSurface.error());
        if ((renderSurface->surfaceTriangleCount() == 0) != (surfaceTriangleCount(proxy.mesh) == 0))
            return fail("authored collider: exactly one of the collider and the render mesh has a surface");
        Candidate c;
        c.mesh = proxy.mesh;
        HausdorffSettings sharp = certifying;
        sharp.tolerance = std::numeric_limits<double>::infinity();
        auto measure = [&](float f, const char* stage) { return !progress || progress(f, stage); };
        if (Status st = certify(c, renderSurface.value(), sharp, measure); !st)
            return fail(st.error() == "cancelled" ? st.error() : "authored collider: " + st.error());
        takeBound(proxy, c, tolerance);
        proxy.drawnNormals =
            DrawnNormals::build(render, renderSurface.value(), proxy.mesh, proxy.errorBound, s.threads);
        finishResult(proxy, start);
        store(s, key, proxy);
        return proxy;
    }

    const bool withinBudget = s.maxTriangles == 0 || inputTriangles <= s.maxTriangles;
    if (surfaceTriangles == 0 ||
        (withinBudget && (inputTriangles < s.smallMeshTriangles || tolerance == 0.0))) {
        if (surfaceTriangles == 0)
            proxy.notes.push_back("the render mesh has no surface: the proxy is empty");
        else
            proxy.mesh = ownMesh(render);
        proxy.source = ProxySource::OwnMesh;
        finishResult(proxy, start);
        return proxy;
    }

    const uint64_t key = cacheKey(render, s, nullptr);
    if (std::optional<Proxy> hit = lookUp(s, key, progress, proxy.notes)) {
        hit->notes = std::move(proxy.notes);
        finishResult(*hit, start);
        return std::move(*hit);
    }

    const ProxyBackend backend = resolveProxyBackend(s.backend, inputTriangles, tolerance, diagonal);
    PendingSurface renderSurface(render, s.threads);
    const Mesh welded = detail::weldedSurface(render);
    detail::SearchProgress searchProgress(progress);
    const Mesh meshoptInput = backend == ProxyBackend::MeshOpt ? detail::meshoptInputOf(welded, s) : Mesh();
    // The certificate still measures every candidate against the render mesh.
    const std::vector<CoarseInput> coarse =
        backend == ProxyBackend::MeshOpt && s.maxTriangles == 0
            ? detail::coarseInputs(meshoptInput, welded.triangleCount(), tolerance, s.keepBoundaries)
            : std::vector<CoarseInput>();
    SampleMemory judged;
    const SearchContext context{backend,          welded,       meshoptInput,  coarse,     tolerance,
                                surfaceTriangles, withinBudget, renderSurface, certifying, s,
                                searchProgress,   proxy.notes,  judged};
    Result<SearchOutcome> outcome = searchBackend(context, s.maxAttempts);
    if (!outcome) return fail(outcome.error());
    proxy.attempts = outcome->runs;
    if (!outcome->best) {
        proxy.notes.push_back("the render mesh is its own proxy");
        proxy.mesh = ownMesh(render);
        proxy.source = ProxySource::OwnMesh;
    } else {
        Candidate& best = outcome->best.value();
        proxy.mesh = detail::finishProxy(std::move(best.mesh), s);
        proxy.source = ProxySource::Simplified;
        proxy.backend = best.backend;
        takeBound(proxy, best, tolerance);
        Result<const HausdorffSurface*> drawn = renderSurface.get(); // ready: the search certified `best`
        if (!drawn) return fail(drawn.error());
        proxy.drawnNormals =
            DrawnNormals::build(render, *drawn.value(), proxy.mesh, proxy.errorBound, s.threads);
        if (!proxy.toleranceMet)
            proxy.notes.push_back(
                std::string("h = ") + std::to_string(proxy.errorBound) + " is above the tolerance " +
                std::to_string(tolerance) +
                (best.budgetLimited ? " (the triangle budget stopped simplification)" : ""));
    }
    if (progress && !progress(1.0f, "measure")) return fail("cancelled");
    finishResult(proxy, start);
    store(s, key, proxy);
    return proxy;
}

} // namespace spatter
