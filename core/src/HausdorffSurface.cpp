#include "HausdorffSurfaceImpl.hpp"

#include "SurfaceGeometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace spatter {

namespace {

// Largest number of triangles in a leaf of the hierarchy.
constexpr uint32_t kLeafTriangles = 4;
// A node is split at the middle of its extent unless less than this fraction of its triangles would
// go to one side (buildHierarchy).
constexpr uint32_t kLeastSplit = 8;

using Impl = HausdorffSurface::Impl;
using Node = detail::HausdorffNode;

void fitBox(Impl& s, Node& n) {
    n.lo = glm::dvec3(std::numeric_limits<double>::infinity());
    n.hi = -n.lo;
    for (uint32_t i = n.first; i < n.first + n.count; ++i)
        for (uint32_t v : s.triangles[i]) {
            n.lo = glm::min(n.lo, s.positions[v]);
            n.hi = glm::max(n.hi, s.positions[v]);
        }
}

// A triangle's centroid and its index in the mesh, split by the hierarchy (in place, without
// indirection).
struct Centroid {
    glm::dvec3 c;
    uint32_t triangle;
};

// The number of the centroids in [first, last) that go to the first child: those below the middle of
// their extent along `axis`, split in place in one pass; where fewer than 1 / kLeastSplit of them lie
// on one side of it, the lower half by their order along the axis (so that the depth stays
// logarithmic whatever the spacing of the triangles).
uint32_t splitCentroids(std::vector<Centroid>::iterator first, std::vector<Centroid>::iterator last, int axis,
                        double middle) {
    const auto below = [axis, middle](const Centroid& a) { return a.c[axis] < middle; };
    const uint32_t count = uint32_t(last - first);
    const uint32_t split = uint32_t(std::partition(first, last, below) - first);
    const uint32_t least = std::max(1u, count / kLeastSplit);
    if (split >= least && count - split >= least) return split;
    std::nth_element(first, first + count / 2, last, [axis](const Centroid& a, const Centroid& b) {
        return a.c[axis] != b.c[axis] ? a.c[axis] < b.c[axis] : a.triangle < b.triangle;
    });
    return count / 2;
}

// The hierarchy over the mesh's surface triangles `surface`: split at the middle of the centroids'
// extent along its longest axis (a pass over the node, where a median costs a selection), until
// leaves of kLeafTriangles. Fills s.nodes, and s.triangles and s.meshTriangles in the hierarchy's order.
void buildHierarchy(Impl& s, const std::vector<uint32_t>& surface) {
    s.nodes.clear();
    if (surface.empty()) return;
    std::vector<Centroid> order(surface.size());
    for (size_t i = 0; i < surface.size(); ++i) {
        const uint32_t* c = &s.indices[3 * size_t(surface[i])];
        order[i] = {(s.positions[c[0]] + s.positions[c[1]] + s.positions[c[2]]) / 3.0, surface[i]};
    }
    s.nodes.reserve(2 * order.size()); // a binary tree of at most order.size() leaves
    s.nodes.push_back({glm::dvec3(0.0), glm::dvec3(0.0), 0, uint32_t(order.size()), 0});
    for (size_t i = 0; i < s.nodes.size(); ++i) {
        const Node n = s.nodes[i];
        if (n.count <= kLeafTriangles) continue;
        const auto first = order.begin() + n.first, last = first + n.count;
        glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi = -lo;
        for (auto it = first; it != last; ++it) {
            lo = glm::min(lo, it->c);
            hi = glm::max(hi, it->c);
        }
        const glm::dvec3 extent = hi - lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
        const uint32_t half = splitCentroids(first, last, axis, 0.5 * (lo[axis] + hi[axis]));
        s.nodes[i].child = uint32_t(s.nodes.size());
        s.nodes.push_back({glm::dvec3(0.0), glm::dvec3(0.0), n.first, half, 0});
        s.nodes.push_back({glm::dvec3(0.0), glm::dvec3(0.0), n.first + half, n.count - half, 0});
    }
    s.triangles.resize(order.size());
    s.meshTriangles.resize(order.size());
    for (size_t i = 0; i < order.size(); ++i) {
        const uint32_t* c = &s.indices[3 * size_t(order[i].triangle)];
        s.triangles[i] = {c[0], c[1], c[2]};
        s.meshTriangles[i] = order[i].triangle;
    }
    // Leaves from their triangles, inner nodes from their children (which come after them).
    for (size_t i = s.nodes.size(); i-- > 0;) {
        Node& n = s.nodes[i];
        if (n.child == 0) {
            fitBox(s, n);
        } else {
            n.lo = glm::min(s.nodes[n.child].lo, s.nodes[n.child + 1].lo);
            n.hi = glm::max(s.nodes[n.child].hi, s.nodes[n.child + 1].hi);
        }
    }
}

} // namespace

HausdorffSurface::HausdorffSurface(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
HausdorffSurface::HausdorffSurface(HausdorffSurface&&) noexcept = default;
HausdorffSurface& HausdorffSurface::operator=(HausdorffSurface&&) noexcept = default;
HausdorffSurface::~HausdorffSurface() = default;

Result<HausdorffSurface> HausdorffSurface::create(const Mesh& mesh) {
    Result<ClosestPointQuery> query = ClosestPointQuery::create(mesh); // validates the mesh
    if (!query) return fail(query.error());
    auto impl = std::make_unique<Impl>(std::move(query).value());
    impl->positions.reserve(mesh.positions.size());
    for (const glm::vec3& p : mesh.positions)
        impl->positions.emplace_back(p);
    impl->indices = mesh.indices;
    const std::vector<uint32_t> surface = detail::surfaceTriangles(mesh);
    for (uint32_t t : surface) {
        const uint32_t* c = &mesh.indices[3 * size_t(t)];
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k)
                impl->scale = std::max(impl->scale, std::fabs(impl->positions[c[j]][k]));
        const glm::dvec3 a = impl->positions[c[0]];
        impl->triangleArea +=
            0.5 * glm::length(glm::cross(impl->positions[c[1]] - a, impl->positions[c[2]] - a));
    }
    if (!surface.empty()) impl->triangleArea /= double(surface.size());
    buildHierarchy(*impl, surface);
    return HausdorffSurface(std::move(impl));
}

size_t HausdorffSurface::surfaceTriangleCount() const {
    return impl_->triangles.size();
}

const ClosestPointQuery& HausdorffSurface::query() const {
    return impl_->query;
}

std::vector<uint32_t> HausdorffSurface::sameTriangles(const Mesh& mesh) const {
    std::vector<uint32_t> same(mesh.triangleCount(), UINT32_MAX);
    const Impl& s = *impl_;
    if (!detail::looksForShared(s.triangles.size(), same.size())) return same;
    for (size_t t = 0; t < same.size(); ++t) {
        const uint32_t* c = &mesh.indices[3 * t];
        if (std::max({c[0], c[1], c[2]}) >= mesh.positions.size()) continue;
        s.corners().forEachSame(
            s.positions, s.triangles,
            {detail::corner(mesh, t, 0), detail::corner(mesh, t, 1), detail::corner(mesh, t, 2)},
            [&](uint32_t i) { same[t] = std::min(same[t], s.meshTriangles[i]); });
    }
    return same;
}

} // namespace spatter
