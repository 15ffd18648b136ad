#pragma once
// Shared pieces of the render tests: one headless GL context per test process, a renderer factory,
// rendering one frame to an image, the CPU reference for decal coverage and what a mask covers.

#include "HeadlessGl.hpp"

#include "spatter/core/Decal.hpp"
#include "spatter/core/DecalType.hpp"
#include "spatter/core/Image.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/placement/CollisionWorld.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/GlContext.hpp"
#include "spatter/render/Renderer.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace spatter::test {

// The image size of most renderer tests: small, for a software rasteriser.
constexpr int kW = 128, kH = 96;
constexpr double kPi = 3.14159265358979323846;

// A camera at `eye` looking at `target`, up +Y, near plane 0.05, the default field of view.
Camera lookAt(const glm::dvec3& eye, const glm::dvec3& target);

// A renderer on the shared context.
Result<Renderer> makeRenderer(int width, int height, RendererSettings settings = {});

// One frame of `r` seen by `camera` with `options` (or the default options and `view`), read back;
// `stats` (when given) receives its stats. A failed render or readback fails the calling test and
// gives an empty image.
Image renderView(Renderer& r, const Camera& camera, const RenderOptions& options,
                 FrameStats* stats = nullptr);
Image renderView(Renderer& r, const Camera& camera, View view, FrameStats* stats = nullptr);

// Pixels of a readback that are white (> 127 in red), one byte per pixel, row 0 at the top.
std::vector<uint8_t> whiteMask(const Image& image);
// Intersection over union of two masks; NaN when both are empty, so that no bound holds for a view in
// which nothing was drawn.
double iou(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);
size_t countSet(const std::vector<uint8_t>& mask);

// What the reference needs besides the scene.
struct CoverageInputs {
    std::vector<Decal> decals;
    std::vector<DecalType> types;
    std::vector<uint8_t> objectIds; // one per object; empty: all 0
    float wrapMaxAngleDeg = 120.0f; // RendererSettings::wrapMaxAngleDeg
};

// Coverage computed on the CPU: a ray through the centre of each pixel against the render meshes
// (Embree, through CollisionWorld built on the render meshes), and the inclusion rule of the
// decal pass applied in double precision to the hit point and its interpolated shading normal:
// inside the box, same object ID (scenes with dynamic objects), normal within the type's angle of
// both the decal normal and the axis the box is projected along (wrap-around types: within
// max(maxAngleDeg, wrapMaxAngleDeg)), and for wrap-around types the wrapped footprint inside the
// decal rectangle. Returns a mask of width x height, row 0 at the top.
std::vector<uint8_t> referenceCoverage(const Scene& scene, const CoverageInputs& in, const Camera& camera,
                                       int width, int height);

// The set pixels of a kW x kH `coverage` mask of `cam` whose surface (the hit of the pixel's ray
// against the scene's meshes, if any) `counts`.
size_t coveredWhere(const Scene& scene, const std::vector<uint8_t>& coverage, const Camera& cam,
                    const std::function<bool(const std::optional<Hit>&)>& counts);

// Writes the image under the test scratch directory when SPATTER_TEST_IMAGES is set (debugging).
void dumpImage(const std::string& name, const Image& image);
void dumpMask(const std::string& name, const std::vector<uint8_t>& mask, int width, int height);

} // namespace spatter::test

// Binds `var` (GlContext&) to the shared headless context, or skips the test when no context can be
// created, except under CI=true, where that is a failure.
#define SPATTER_REQUIRE_GL(var)                                                                              \
    std::string var##Why;                                                                                    \
    ::spatter::GlContext* var##Ptr = ::spatter::test::headlessContext(var##Why);                             \
    if (!var##Ptr) {                                                                                         \
        if (::spatter::test::runningInCi()) FAIL() << "CI=true but no headless GL context: " << var##Why;    \
        GTEST_SKIP() << "no headless OpenGL 4.5 context (" << var##Why << ")";                               \
    }                                                                                                        \
    ::spatter::GlContext& var = *var##Ptr;                                                                   \
    (void)var
