// DecalBatch::cull: frustum culling of the mirrored records on the CPU, in draw order. A box far
// outside the view is ruled out by its bounding sphere (SphereCull.hpp); the others are tested corner
// by corner in clip space, and those kept are told whether they may hold the eye.

#include "DecalBatch.hpp"

#include "SphereCull.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/matrix_access.hpp>
#include <optional>

namespace spatter::render_detail {

namespace {

// The view's six planes as functions of clip coordinates, each negative beyond its plane: the four
// sides (clipSidePlanes), then the near and the far plane in the view's depth convention.
std::array<glm::dvec4, 6> clipPlanes(const CullView& view) {
    const glm::dvec4 low = view.clipMinusOne ? glm::dvec4(0, 0, 1, 1) : glm::dvec4(0, 0, 1, 0); // z >= low
    const glm::dvec4 high(0, 0, -1, 1);                                                         // z <= w
    const std::array<glm::dvec4, 4> sides = clipSidePlanes();
    return {sides[0], sides[1], sides[2], sides[3], view.reversedZ ? high : low, view.reversedZ ? low : high};
}

// A box in clip space: a corner is the centre's image plus or minus the images of its three axes.
struct ClipBox {
    glm::dvec4 centre;
    glm::dvec4 axis[3];

    ClipBox(const glm::dmat4& boxToWorld, const CullView& view)
        : centre(view.viewProj * glm::dvec4(glm::dvec3(boxToWorld[3]) - view.eye, 1.0)),
          axis{view.viewProj * glm::dvec4(glm::dvec3(boxToWorld[0]), 0.0),
               view.viewProj * glm::dvec4(glm::dvec3(boxToWorld[1]), 0.0),
               view.viewProj * glm::dvec4(glm::dvec3(boxToWorld[2]), 0.0)} {}

    // The largest value over the corners of a function linear in clip coordinates.
    double largest(const glm::dvec4& f) const {
        return glm::dot(f, centre) + std::fabs(glm::dot(f, axis[0])) + std::fabs(glm::dot(f, axis[1])) +
               std::fabs(glm::dot(f, axis[2]));
    }
    // Whether all eight corners lie beyond one of `planes`.
    bool outside(const std::array<glm::dvec4, 6>& planes) const {
        return std::any_of(planes.begin(), planes.end(),
                           [&](const glm::dvec4& f) { return largest(f) < 0.0; });
    }
    // Whether a corner lies at clip w <= 0 (on or behind the eye's plane).
    bool behind() const { return !(-largest(glm::dvec4(0.0, 0.0, 0.0, -1.0)) > 0.0); }
    // The normalised device x, y bounds (min x, min y, max x, max y) of the corners, all in front of
    // the eye.
    glm::dvec4 screenRect() const {
        glm::dvec4 rect(1.0, 1.0, -1.0, -1.0);
        for (int c = 0; c < 8; ++c) {
            const glm::dvec4 clip = centre + ((c & 1) ? axis[0] : -axis[0]) + ((c & 2) ? axis[1] : -axis[1]) +
                                    ((c & 4) ? axis[2] : -axis[2]);
            const glm::dvec2 ndc = glm::dvec2(clip) * (1.0 / clip.w);
            rect = glm::dvec4(glm::min(glm::dvec2(rect), ndc), glm::max(glm::dvec2(rect.z, rect.w), ndc));
        }
        return rect;
    }
};

// Whether the eye's sphere of `radius` (holding the near plane's rectangle) may reach into the box:
// row r of the inverse maps world offsets to box coordinate r, so the sphere reaches |u_r| <= 1 only
// if |u_r| <= 1 + radius * |row r|. Empty for a box that collapsed in double after all.
std::optional<bool> mayHoldEye(const glm::dmat4& boxToWorld, const glm::dvec3& eye, double radius) {
    const glm::dmat3 worldToBox = glm::inverse(glm::dmat3(boxToWorld));
    const glm::dvec3 u = worldToBox * (eye - glm::dvec3(boxToWorld[3]));
    if (!std::isfinite(u.x + u.y + u.z)) return std::nullopt;
    for (int r = 0; r < 3; ++r)
        if (!(std::fabs(u[r]) <= 1.0 + radius * glm::length(glm::row(worldToBox, r)))) return false;
    return true;
}

} // namespace

DecalVisibility DecalBatch::cull(const std::vector<glm::dmat4>& objectTransforms,
                                 const CullView& view) const {
    DecalVisibility vis;
    const double radius = view.nearRadius * 1.01;
    // On an object with a singular transform (a scale of 0) the boxes collapse: nothing to draw.
    std::vector<uint8_t> collapsed(objectTransforms.size());
    std::vector<SidePlanes> sides; // the view's side planes in each object's space
    sides.reserve(objectTransforms.size());
    for (size_t o = 0; o < objectTransforms.size(); ++o) {
        const double det = glm::determinant(glm::dmat3(objectTransforms[o]));
        collapsed[o] = !(std::fabs(det) > 0.0) || !std::isfinite(det) ? 1 : 0;
        sides.emplace_back(view.viewProj, view.eye, objectTransforms[o]);
    }
    const std::array<glm::dvec4, 6> planes = clipPlanes(view);
    for (const uint32_t i : order_.entries()) {
        if (i == DrawOrder::kEmpty) continue;
        const DecalRecordGpu& r = records_[i];
        if (hostDrawn(r)) { // the host's, valid or not
            ++vis.hostDrawn;
            continue;
        }
        if (!valid(i)) {
            ++vis.invalid;
            continue;
        }
        const uint32_t object = r.info.x;
        // Most of a large world goes by its sphere, before the corners.
        if (object >= objectTransforms.size() || collapsed[object] ||
            sides[object].outside(glm::dvec3(glm::vec3(r.centerDepth)), recordRadius(r))) {
            ++vis.culled;
            continue;
        }
        const glm::dmat4 boxToWorld = objectTransforms[object] * recordBoxToObject(r);
        const ClipBox box(boxToWorld, view);
        if (box.outside(planes)) {
            ++vis.culled;
            continue;
        }
        const std::optional<bool> inside = mayHoldEye(boxToWorld, view.eye, radius);
        if (!inside) continue;
        vis.visible.push_back(i);
        vis.inside += *inside ? 1 : 0;
        vis.flags |= flags(r);
        if (view.rects)
            vis.rects.push_back(box.behind() || *inside ? glm::vec4(-1.0f, -1.0f, 1.0f, 1.0f)
                                                        : glm::vec4(glm::clamp(box.screenRect(), -1.0, 1.0)));
    }
    return vis;
}

} // namespace spatter::render_detail
