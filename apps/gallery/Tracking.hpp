#pragma once
// What the headless run's trackers of decals share: a decal found by its ID, the pixel a world point
// projects to, and the centre of the white pixels of a coverage image.

#include "spatter/core/Image.hpp"
#include "spatter/placement/DecalSystem.hpp"
#include "spatter/render/Camera.hpp"

#include <glm/glm.hpp>
#include <optional>

namespace spatter::gallery {

// The live decal with ID `id`, or null.
const Decal* findDecal(const DecalSystem& system, uint32_t id);

// Pixel position (x right, y down) of a world point seen by `camera` in a width x height image.
glm::dvec2 project(const Camera& camera, int width, int height, const glm::dvec3& world);

// Centre of the white pixels of a coverage image, or nothing when none is white.
std::optional<glm::dvec2> coverageCentroid(const Image& image);

} // namespace spatter::gallery
