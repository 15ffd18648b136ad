#include "DecalMarker.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/constants.hpp>

namespace spatter::tracking {

namespace {

constexpr int kMarkerTexels = 256;
constexpr double kShownShare = 0.85;
constexpr double kLeastCosine = 0.5;

double linear(uint8_t srgb) {
    const double c = srgb / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// How much of the marker's red a pixel shows: the blend factor a of with = bare * (1 - a) + red * a,
// in linear colour, fitted over the three channels; 0 where the surface is nearly red itself.
double markerShare(const uint8_t* with, const uint8_t* bare) {
    constexpr double kRed[3] = {1.0, 0.0, 0.0};
    double num = 0.0, den = 0.0;
    for (size_t c = 0; c < 3; ++c) {
        const double b = linear(bare[c]), toRed = kRed[c] - b;
        num += (linear(with[c]) - b) * toRed;
        den += toRed * toRed;
    }
    return den > 0.05 ? std::clamp(num / den, 0.0, 1.0) : 0.0;
}

} // namespace

Image markerTexture() {
    Image im;
    im.width = im.height = kMarkerTexels;
    im.name = "centre marker";
    im.rgba.assign(size_t(kMarkerTexels) * kMarkerTexels * 4, 0);
    const double c = 0.5 * kMarkerTexels, r = kMarkerRadius * kMarkerTexels;
    for (int y = 0; y < kMarkerTexels; ++y)
        for (int x = 0; x < kMarkerTexels; ++x) {
            const double d = std::hypot(x + 0.5 - c, y + 0.5 - c);
            uint8_t* p = &im.rgba[(size_t(y) * kMarkerTexels + size_t(x)) * 4];
            p[0] = 255;
            p[3] = uint8_t(std::lround(255.0 * std::clamp(r - d + 0.5, 0.0, 1.0)));
        }
    return im;
}

Result<DecalType> markerType(Renderer& renderer, DecalType base) {
    Result<int> layer = renderer.addDecalTexture(markerTexture());
    if (!layer) return fail(layer.error());
    base.name = "centre marker";
    base.texture = layer.value();
    base.tint = glm::vec4(1.0f);
    base.normalMap = false;
    return base;
}

Marker findMarker(const Image& with, const Image& without) {
    Marker m;
    if (with.width != without.width || with.height != without.height) return m;
    glm::dvec2 sum(0.0);
    for (int y = 0; y < with.height; ++y)
        for (int x = 0; x < with.width; ++x) {
            const size_t i = (size_t(y) * size_t(with.width) + size_t(x)) * 4;
            if (std::memcmp(&with.rgba[i], &without.rgba[i], 3) == 0) continue;
            const double w = markerShare(&with.rgba[i], &without.rgba[i]);
            sum += w * glm::dvec2(x + 0.5, y + 0.5);
            m.weight += w;
        }
    if (m.weight > 0.0) m.centre = sum / m.weight;
    return m;
}

bool showsWhole(const Marker& m, double cosine, double sizePixels) {
    const double disc = glm::pi<double>() * std::pow(kMarkerRadius * sizePixels, 2.0) * cosine;
    return cosine >= kLeastCosine && m.weight > 0.0 && m.weight >= kShownShare * disc;
}

Result<Image> drawAlone(Renderer& renderer, const Camera& camera, View view, const std::vector<Decal>& decals,
                        FrameStats* stats) {
    renderer.setDecals(decals);
    Result<FrameStats> st = renderer.render(camera, view);
    if (!st) return fail(st.error());
    if (stats) *stats = st.value();
    return renderer.readback();
}

double facingCosine(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& p,
                    const glm::dvec3& eye) {
    return std::abs(glm::dot(glm::normalize(glm::cross(b - a, c - a)), glm::normalize(eye - p)));
}

glm::dvec2 pixelOf(const Camera& camera, int width, int height, const glm::dvec3& world) {
    const glm::dvec4 clip = projection(camera, double(width) / height) * viewRotation(camera) *
                            glm::dvec4(world - camera.eye, 1.0);
    const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
    return {(ndc.x * 0.5 + 0.5) * width, (0.5 - ndc.y * 0.5) * height};
}

double pixelsAcross(const Camera& camera, int height, double size, const glm::dvec3& world) {
    const double depth = glm::dot(world - camera.eye, glm::normalize(camera.target - camera.eye));
    return size * 0.5 * height / (std::tan(glm::radians(camera.fovYDeg) * 0.5) * depth);
}

} // namespace spatter::tracking
