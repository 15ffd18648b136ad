#include "DecalCutout.hpp"

#include <algorithm>
#include <cmath>

namespace spatter::render_detail {

namespace {

// A texture coordinate on the 1/255 grid, rounded down or up, in [0, 1].
float onGrid(float t, bool up) {
    const float steps = up ? std::ceil(t * 255.0f) : std::floor(t * 255.0f);
    return std::clamp(steps, 0.0f, 255.0f) / 255.0f;
}

// Min above max: nothing shows.
constexpr glm::vec4 kEmptyCutout(1.0f, 1.0f, 0.0f, 0.0f);

uint32_t byteOf(float t) {
    return uint32_t(std::lround(std::clamp(t, 0.0f, 1.0f) * 255.0f));
}

} // namespace

glm::vec4 decalCutout(const Image& albedo) {
    const int w = albedo.width, h = albedo.height;
    if (albedo.empty() || albedo.rgba.size() < size_t(w) * size_t(h) * 4) return kEmptyCutout;
    int x0 = w, x1 = -1, y0 = h, y1 = -1;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (albedo.rgba[(size_t(y) * size_t(w) + size_t(x)) * 4 + 3] != 0) {
                x0 = std::min(x0, x);
                x1 = std::max(x1, x);
                y0 = std::min(y0, y);
                y1 = std::max(y1, y);
            }
    if (x1 < 0) return kEmptyCutout;
    // Texel edges in texture coordinates (v from the bottom row), widened by the margin.
    const float m = kCutoutMargin;
    const float u0 = float(x0) / float(w) - m, u1 = float(x1 + 1) / float(w) + m;
    const float v0 = float(h - 1 - y1) / float(h) - m, v1 = float(h - y0) / float(h) + m;
    return glm::vec4(onGrid(u0, false), onGrid(v0, false), onGrid(u1, true), onGrid(v1, true));
}

uint32_t packCutout(glm::vec4 c) {
    return byteOf(c.x) | byteOf(c.y) << 8 | byteOf(c.z) << 16 | byteOf(c.w) << 24;
}

} // namespace spatter::render_detail
