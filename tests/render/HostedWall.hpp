#pragma once
// HostedWall: the projector inside ForeignHost over a small scene, as the projector's tests use it: a
// wall (z = 0, facing +Z) and a dynamic crate in front of it, seen from the front, with one decal on
// each; the crate's decal is deep enough to reach the wall, so only object IDs keep it off the wall.

#include "ForeignHost.hpp"

#include "spatter/core/Decal.hpp"
#include "spatter/core/DecalType.hpp"
#include "spatter/core/Image.hpp"
#include "spatter/core/Scene.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/DecalProjector.hpp"

#include <optional>
#include <vector>

namespace spatter::test {

struct WallScene {
    Scene scene;
    std::vector<glm::dmat4> transforms;
    std::vector<uint8_t> ids = {0, 7};
    std::vector<DecalType> types;
    std::vector<Decal> decals;
    Camera camera;

    WallScene();
    // A 0.6 x 0.6 decal facing +Z at `center` in the object's space.
    static Decal decalAt(uint32_t object, const glm::vec3& center);
};

struct HostedWall {
    static constexpr int kWidth = 96;
    static constexpr int kHeight = 64;

    WallScene wall;
    ForeignHost host;
    DecalProjector projector;

    // The host has drawn the wall scene and the projector (made with `settings`) holds its objects,
    // types and decals; nothing when the host or the projector cannot be made (a test failure is
    // recorded).
    static std::optional<HostedWall> make(const ProjectorSettings& settings = {});
};
constexpr int kWallWidth = HostedWall::kWidth, kWallHeight = HostedWall::kHeight;

// Pixels whose RGBA differ.
size_t differingPixels(const Image& a, const Image& b);

} // namespace spatter::test
