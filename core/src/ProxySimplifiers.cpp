#include "ProxySimplifiers.hpp"

#include "Pi.hpp"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModHausdorffT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalDeviationT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <OpenMesh/Tools/Decimater/Observer.hh>
#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace spatter::detail {

namespace {

// Full angle of the normal cone a decimated face may sweep (ModNormalDeviation): it only rules out
// fold-overs; the distance error is controlled by the Hausdorff module and the measurement.
constexpr float kNormalConeDegrees = 150.0f;

// A mesh with only the referenced vertices of `positions`.
Mesh compactMesh(const std::vector<glm::vec3>& positions, const unsigned int* indices, size_t count) {
    Mesh out;
    std::vector<uint32_t> slot(positions.size(), UINT32_MAX);
    out.indices.resize(count);
    for (size_t i = 0; i < count; ++i) {
        const uint32_t v = indices[i];
        if (slot[v] == UINT32_MAX) {
            slot[v] = uint32_t(out.positions.size());
            out.positions.push_back(positions[v]);
        }
        out.indices[i] = slot[v];
    }
    return out;
}

struct OmTraits : public OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3d Point;
    typedef OpenMesh::Vec3d Normal;
    VertexAttributes(OpenMesh::Attributes::Status);
    EdgeAttributes(OpenMesh::Attributes::Status);
    HalfedgeAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::PrevHalfedge);
    FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
};
using OmMesh = OpenMesh::TriMesh_ArrayKernelT<OmTraits>;

class DecimationObserver : public OpenMesh::Decimater::Observer {
public:
    DecimationObserver(size_t interval, size_t expected, const ProgressCallback& progress)
        : Observer(interval), expected_(std::max<size_t>(expected, 1)), progress_(progress) {}
    void notify(size_t step) override {
        const float fraction = std::min(0.99f, float(double(step) / double(expected_)));
        if (progress_ && !progress_(fraction, "simplify")) cancelled_ = true;
    }
    bool abort() const override { return cancelled_; }
    bool cancelled() const { return cancelled_; }

private:
    size_t expected_;
    const ProgressCallback& progress_;
    bool cancelled_ = false;
};

// True when add_face(a, b, c) keeps the mesh manifold: every vertex is new or on a boundary, and no
// directed edge of the face is taken already (OpenMesh's own preconditions).
bool canAddFace(const OmMesh& om, const OmMesh::VertexHandle (&v)[3]) {
    for (int k = 0; k < 3; ++k) {
        if (!om.is_isolated(v[k]) && !om.is_boundary(v[k])) return false;
        const OmMesh::HalfedgeHandle h = om.find_halfedge(v[k], v[(k + 1) % 3]);
        if (h.is_valid() && !om.is_boundary(h)) return false;
    }
    return true;
}

} // namespace

Mesh simplifyMeshopt(const Mesh& input, double tolerance, uint32_t budget, bool lockBorder,
                     double& resultError) {
    const float scale =
        meshopt_simplifyScale(&input.positions[0].x, input.positions.size(), sizeof(glm::vec3));
    const float relative = std::isfinite(tolerance) && scale > 0.0f ? float(tolerance / double(scale))
                                                                    : std::numeric_limits<float>::max();
    std::vector<unsigned int> out(input.indices.size());
    float error = 0.0f;
    const size_t count =
        meshopt_simplify(out.data(), input.indices.data(), input.indices.size(), &input.positions[0].x,
                         input.positions.size(), sizeof(glm::vec3), size_t(budget) * 3, relative,
                         lockBorder ? unsigned(meshopt_SimplifyLockBorder) : 0u, &error);
    resultError = double(error) * double(scale);
    return compactMesh(input.positions, out.data(), count);
}

Mesh simplifySloppy(const Mesh& input, uint32_t budget) {
    std::vector<unsigned int> out(input.indices.size());
    const size_t count = meshopt_simplifySloppy(
        out.data(), input.indices.data(), input.indices.size(), &input.positions[0].x, input.positions.size(),
        sizeof(glm::vec3), size_t(budget) * 3, std::numeric_limits<float>::max(), nullptr);
    return compactMesh(input.positions, out.data(), count);
}

Result<Mesh> simplifyOpenMesh(const Mesh& input, double tolerance, uint32_t budget, const ProxySettings& s,
                              const ProgressCallback& progress, size_t& detachedFaces) {
    OmMesh om;
    std::vector<OmMesh::VertexHandle> handles(input.positions.size());
    for (size_t i = 0; i < handles.size(); ++i) {
        const glm::vec3& p = input.positions[i];
        handles[i] = om.add_vertex(OmMesh::Point(p.x, p.y, p.z));
    }
    detachedFaces = 0;
    for (size_t t = 0; t < input.triangleCount(); ++t) {
        OmMesh::VertexHandle v[3] = {handles[input.indices[3 * t]], handles[input.indices[3 * t + 1]],
                                     handles[input.indices[3 * t + 2]]};
        if (canAddFace(om, v) && om.add_face(v[0], v[1], v[2]).is_valid()) continue;
        for (OmMesh::VertexHandle& h : v)
            h = om.add_vertex(om.point(h));
        om.add_face(v[0], v[1], v[2]);
        ++detachedFaces;
    }
    om.update_face_normals();

    const double cosFeature = std::cos(double(s.featureAngleDegrees) * kPi / 180.0);
    for (const OmMesh::EdgeHandle e : om.edges()) {
        if (om.is_boundary(e)) {
            if (s.keepBoundaries) {
                om.status(om.from_vertex_handle(om.halfedge_handle(e, 0))).set_locked(true);
                om.status(om.to_vertex_handle(om.halfedge_handle(e, 0))).set_locked(true);
            }
            continue;
        }
        if (!s.keepSharpFeatures) continue;
        const OmMesh::Normal n0 = om.normal(om.face_handle(om.halfedge_handle(e, 0)));
        const OmMesh::Normal n1 = om.normal(om.face_handle(om.halfedge_handle(e, 1)));
        if (OpenMesh::dot(n0, n1) < cosFeature) {
            om.status(e).set_feature(true);
            om.status(om.from_vertex_handle(om.halfedge_handle(e, 0))).set_feature(true);
            om.status(om.to_vertex_handle(om.halfedge_handle(e, 0))).set_feature(true);
        }
    }

    using Decimater = OpenMesh::Decimater::DecimaterT<OmMesh>;
    Decimater decimater(om);
    OpenMesh::Decimater::ModQuadricT<OmMesh>::Handle quadric;
    OpenMesh::Decimater::ModHausdorffT<OmMesh>::Handle hausdorff;
    OpenMesh::Decimater::ModNormalDeviationT<OmMesh>::Handle normals;
    decimater.add(quadric);
    decimater.module(quadric).unset_max_err();
    if (std::isfinite(tolerance)) {
        decimater.add(hausdorff);
        decimater.module(hausdorff).set_tolerance(tolerance);
    }
    decimater.add(normals);
    decimater.module(normals).set_normal_deviation(kNormalConeDegrees);
    if (!decimater.initialize()) return fail("OpenMesh Decimater could not be initialised");
    const size_t vertices = om.n_vertices();
    const size_t expected = budget > 0 ? vertices - std::min(vertices, size_t(budget) / 2) : vertices;
    DecimationObserver observer(std::max<size_t>(expected / 100, 64), expected, progress);
    decimater.set_observer(&observer);
    decimater.decimate_to_faces(0, budget);
    decimater.set_observer(nullptr);
    if (observer.cancelled()) return fail("cancelled");
    om.garbage_collection();

    Mesh out;
    out.positions.reserve(om.n_vertices());
    for (const OmMesh::VertexHandle v : om.vertices()) {
        const OmMesh::Point& p = om.point(v);
        out.positions.emplace_back(float(p[0]), float(p[1]), float(p[2]));
    }
    out.indices.reserve(3 * om.n_faces());
    for (const OmMesh::FaceHandle f : om.faces())
        for (const OmMesh::VertexHandle v : om.fv_range(f))
            out.indices.push_back(uint32_t(v.idx()));
    return out;
}

} // namespace spatter::detail
