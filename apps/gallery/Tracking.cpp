#include "Tracking.hpp"

#include "DecalMarker.hpp"

namespace spatter::gallery {

const Decal* findDecal(const DecalSystem& system, uint32_t id) {
    for (const Decal& d : system.decals())
        if (d.id == id) return &d;
    return nullptr;
}

Result<std::optional<glm::dvec2>> decalCentroid(Renderer& renderer, const Camera& camera,
                                                const Decal& decal) {
    Result<Image> without = tracking::drawAlone(renderer, camera, View::Coverage, {});
    if (!without) return fail(without.error());
    Result<Image> with = tracking::drawAlone(renderer, camera, View::Coverage, {decal});
    if (!with) return fail(with.error());
    glm::dvec2 sum(0.0);
    size_t count = 0;
    for (int y = 0; y < with->height; ++y)
        for (int x = 0; x < with->width; ++x) {
            const size_t i = (size_t(y) * size_t(with->width) + size_t(x)) * 4;
            if (with->rgba[i] > 127 && without->rgba[i] <= 127) {
                sum += glm::dvec2(x + 0.5, y + 0.5);
                ++count;
            }
        }
    if (count == 0) return std::optional<glm::dvec2>();
    return std::optional<glm::dvec2>(sum / double(count));
}

} // namespace spatter::gallery
