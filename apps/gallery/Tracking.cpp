#include "Tracking.hpp"

namespace spatter::gallery {

const Decal* findDecal(const DecalSystem& system, uint32_t id) {
    for (const Decal& d : system.decals())
        if (d.id == id) return &d;
    return nullptr;
}

glm::dvec2 project(const Camera& camera, int width, int height, const glm::dvec3& world) {
    const glm::dvec4 clip = projection(camera, double(width) / height) * viewRotation(camera) *
                            glm::dvec4(world - camera.eye, 1.0);
    const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
    return {(ndc.x * 0.5 + 0.5) * width, (0.5 - ndc.y * 0.5) * height};
}

std::optional<glm::dvec2> coverageCentroid(const Image& image) {
    glm::dvec2 sum(0.0);
    size_t count = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (image.rgba[(size_t(y) * image.width + x) * 4] > 127) {
                sum += glm::dvec2(x + 0.5, y + 0.5);
                ++count;
            }
    if (count == 0) return std::nullopt;
    return sum / double(count);
}

} // namespace spatter::gallery
