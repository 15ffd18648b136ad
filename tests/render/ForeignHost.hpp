#pragma once
// ForeignHost: a minimal deferred renderer whose frame layout is unlike spatter's own, to test the
// projector's host contract: standard (not reversed) Z with GL's default clip depth in a 24-bit
// depth buffer and a finite far plane, world normals in RGB10A2 as n * 0.5 + 0.5, albedo in RGBA8,
// roughness in the G channel of an RG8 texture, object decal IDs in R8UI, and an R8 coverage target.
// It draws the render meshes of a Scene's decal receivers with a flat grey albedo; like spatter's
// renderer it would draw the objects that take no decals after the projector, over the decals, which
// the tests that use it do not need. Its forward mode draws the same meshes into the same targets
// with the projector's forward path applied in the fragment shader, and its coverage.

#include "spatter/core/Image.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/DecalProjector.hpp"

#include <epoxy/gl.h>

#include <memory>
#include <vector>

namespace spatter::test {

class ForeignHost {
public:
    // Needs a current GL 4.5 context (the shared test context).
    static Result<ForeignHost> create(int width, int height);
    ForeignHost(ForeignHost&&) noexcept;
    ForeignHost& operator=(ForeignHost&&) noexcept;
    ~ForeignHost();

    // Uploads the scene's meshes (replacing any earlier scene).
    void setScene(const Scene& scene);
    // Clears the targets and draws the decal receivers with `transforms` (one per object) and `ids`.
    void draw(const std::vector<glm::dmat4>& transforms, const std::vector<uint8_t>& ids,
              const Camera& camera);
    // Forward mode: bins the projector's decals for `camera`, then draws as draw() does with the
    // decals applied per pixel, writing the coverage target too (cleared first).
    Result<ProjectorStats> drawForward(const std::vector<glm::dmat4>& transforms,
                                       const std::vector<uint8_t>& ids, const Camera& camera,
                                       DecalProjector& projector);
    // The frame as the projector's host description; `withIds`: hand it the ID texture.
    HostFrame frame(const Camera& camera, bool withIds) const;
    ForwardFrame forwardFrame(const Camera& camera) const;
    // Clears the coverage target to black.
    void clearCoverage();
    uint32_t coverageTexture() const;
    uint32_t albedoTexture() const;
    // A target read back as RGBA8, row 0 at the top.
    Image read(uint32_t texture) const;
    // The projection the host draws with: standard Z, near at camera.nearPlane, far at 1000.
    glm::dmat4 projection(const Camera& camera) const;

private:
    void drawMeshes(GLuint fbo, GLuint program, const std::vector<glm::dmat4>& transforms,
                    const std::vector<uint8_t>& ids, const Camera& camera);

    struct Impl;
    explicit ForeignHost(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

} // namespace spatter::test
