#pragma once
// DecalMarker: where a decal's centre is drawn, found in rendered images. The decal is drawn alone
// with a centre marker for texture (an opaque red disc a fifth of the decal's width across at the
// texture's centre, clear elsewhere) in the albedo view, and once without it; the drawn centre is the
// centroid of the pixels the marker changes, each weighted by how much of the marker it shows, so
// that neither the surface's colours nor a curved surface clipping the decal's edges move it. The
// gallery's headless tracker and spatter-bench skinned measure drift with it.

#include "spatter/core/Image.hpp"
#include "spatter/render/Camera.hpp"
#include "spatter/render/Renderer.hpp"

#include <vector>

#include <glm/glm.hpp>

namespace spatter::tracking {

constexpr double kMarkerRadius = 0.1; // of the decal's width

// The marker texture (RGBA8, straight alpha), for Renderer::addDecalTexture.
Image markerTexture();

// `base` drawn with the marker: the marker texture added to `renderer`, untinted, no normal map.
Result<DecalType> markerType(Renderer& renderer, DecalType base);

struct Marker {
    glm::dvec2 centre{0.0}; // pixel position, x right, y down
    double weight = 0.0;    // pixels' worth of marker
};

// The marker in the albedo image `with` against the same frame `without` it.
Marker findMarker(const Image& with, const Image& without);

// Whether `m` shows whole: at least 85% of the pixels a flat disc would cover, where the surface
// under it faces the view at `cosine` (at least 0.5: nearly edge-on, an image cannot place a centre)
// and the decal is `sizePixels` wide.
bool showsWhole(const Marker& m, double cosine, double sizePixels);

// The view `view` of `renderer` from `camera` with `decals` alone (its FrameStats into `stats`, when
// given). Leaves the renderer drawing them.
Result<Image> drawAlone(Renderer& renderer, const Camera& camera, View view, const std::vector<Decal>& decals,
                        FrameStats* stats = nullptr);

// How squarely the triangle (a, b, c) faces `eye` at its point `p`: the cosine between its normal
// (either side) and the direction to the eye.
double facingCosine(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& p,
                    const glm::dvec3& eye);

// Pixel position (x right, y down) of a world point seen by `camera` in a width x height image.
glm::dvec2 pixelOf(const Camera& camera, int width, int height, const glm::dvec3& world);

// The width in pixels of something `size` wide at `world`, facing the camera, in an image `height`
// pixels high.
double pixelsAcross(const Camera& camera, int height, double size, const glm::dvec3& world);

} // namespace spatter::tracking
