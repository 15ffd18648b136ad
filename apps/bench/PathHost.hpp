#pragma once
// PathHost: spatter-bench render's own host of the decal projector, for the rows that compare the
// projector's three paths with spatter's renderer. Its frame has the layout of spatter-example-deferred
// (standard Z in a 24-bit depth buffer with GL's default clip depth, world normals in RGB10A2 as
// n * 0.5 + 0.5, albedo RGBA8 with roughness in alpha, object IDs R8UI) and a small lighting pass; its
// forward mode shades the same meshes in one pass with the forward path's decals applied per pixel.
// Every pass is timed on the GPU (GL_TIME_ELAPSED), waiting for the result.

#include "spatter/core/Result.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/DecalProjector.hpp"

#include <memory>

namespace spatter::bench {

enum class HostPath { GBufferBlend, DBuffer, Forward };

// GPU milliseconds of one frame. `projectorMs`: the projector's pass (its draw, or its binning for
// the forward path). `hostPassMs`: the host's pass that changes with the path, and `baselineMs` the
// same pass without decals: for DBuffer the lighting pass with and without the decal buffers
// applied, for forward the forward pass with and without spatterApplyForwardDecals; 0 for G-buffer
// blend, which changes no pass of the host's.
struct PathTimes {
    double projectorMs = 0.0, hostPassMs = 0.0, baselineMs = 0.0;
    ProjectorStats stats;
    // What the decals cost the frame.
    double decalMs() const { return projectorMs + hostPassMs - baselineMs; }
};

class PathHost {
public:
    // Needs a current GL 4.5 context.
    static Result<PathHost> create(int width, int height);
    PathHost(PathHost&&) noexcept;
    PathHost& operator=(PathHost&&) noexcept;
    ~PathHost();

    // Uploads the scene's meshes; objects that take no decals are drawn like the others.
    void setScene(const Scene& scene);
    // One frame of `path` with the projector's decals (its objects set by the caller).
    Result<PathTimes> frame(HostPath path, DecalProjector& projector, const Camera& camera);

private:
    struct Impl;
    explicit PathHost(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

} // namespace spatter::bench
