#pragma once
// SphereCull: the cheap first test of the CPU's frustum culling (DecalBatch::cull), as the GPU's
// first culling pass makes it (cull.comp): a box's bounding sphere against the view's four side
// planes, with no frame to unpack and no corners. A sphere wholly outside one side plane, by a margin
// for rounding, holds a box whose eight corners all lie beyond that plane, which the corner test
// culls too, so the visible list stays the same; the test only saves the corner test's work on the
// boxes far outside the view, most of a large world. The planes are taken into each object's space
// once per cull, so that a box's centre is tested where its record keeps it.

#include "GpuLayouts.hpp"

#include <array>
#include <glm/glm.hpp>

namespace spatter::render_detail {

// The four side planes of every view as functions of clip coordinates, each negative beyond its
// plane: x + w, w - x, y + w, w - y (x and y within [-w, w]). The corner test (DecalBatch::cull) adds
// the near and the far plane of the view's depth convention.
std::array<glm::dvec4, 4> clipSidePlanes();

// The radius of a sphere around the centre of record `r`'s box that holds the box, in object space:
// the corners lie within |(hx + hz |sx|, hy + hz |sy|, hz)| of it (half extents h, slant s: the
// depth axis is normal + sx tangent + sy bitangent).
double recordRadius(const DecalRecordGpu& r);

// The four side planes of a view (x and y within [-w, w] in clip space) in one object's space.
class SidePlanes {
public:
    // `viewProj`: camera-relative world -> clip; `eye` in the world; `toWorld`: the object's transform.
    SidePlanes(const glm::dmat4& viewProj, const glm::dvec3& eye, const glm::dmat4& toWorld);
    // Whether the sphere of `radius` around `centre` (both in object space) lies wholly outside one
    // plane in the world, by a margin for rounding.
    bool outside(const glm::dvec3& centre, double radius) const;

private:
    glm::dvec4 plane_[4];                    // object space; inside: dot(plane.xyz, centre) + plane.w >= 0
    double length_[4]{};                     // of the world plane's normal
    double stretch_ = 0.0, magnitude_ = 0.0; // largestStretch (LinearStretch.hpp); |translation| + |eye|
};

} // namespace spatter::render_detail
