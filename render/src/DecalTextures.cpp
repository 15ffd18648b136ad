#include "spatter/render/DecalTextures.hpp"

#include "spatter/core/Random.hpp"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

namespace spatter {

namespace {

constexpr float kPi = 3.14159265358979323846f;

uint32_t mixBits(uint32_t h) {
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

float hash2(int x, int y, uint32_t seed) {
    uint32_t h = mixBits(seed ^ 0x9e3779b9u);
    h = mixBits(h ^ uint32_t(x));
    h = mixBits(h ^ (uint32_t(y) * 0x85ebca6bu));
    return float(h >> 8) * (1.0f / 16777216.0f);
}

// Smooth value noise in [-1, 1].
float noise(glm::vec2 p, uint32_t seed) {
    const glm::vec2 f = glm::floor(p);
    const glm::vec2 t = p - f;
    const glm::vec2 w = t * t * (3.0f - 2.0f * t);
    const int x = int(f.x), y = int(f.y);
    const float a = hash2(x, y, seed), b = hash2(x + 1, y, seed);
    const float c = hash2(x, y + 1, seed), d = hash2(x + 1, y + 1, seed);
    return 2.0f * glm::mix(glm::mix(a, b, w.x), glm::mix(c, d, w.x), w.y) - 1.0f;
}

float fbm(glm::vec2 p, uint32_t seed, int octaves) {
    float sum = 0.0f, amp = 1.0f, total = 0.0f;
    for (int o = 0; o < octaves; ++o) {
        sum += amp * noise(p, seed + uint32_t(o) * 0x632be5abu);
        total += amp;
        amp *= 0.5f;
        p *= 2.07f;
    }
    return sum / total;
}

float smoothstep(float e0, float e1, float x) {
    const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// Distance from p to the segment a-b, and the position t in [0, 1] of the closest point.
float segmentDistance(glm::vec2 p, glm::vec2 a, glm::vec2 b, float& t) {
    const glm::vec2 ab = b - a;
    t = std::clamp(glm::dot(p - a, ab) / std::max(glm::dot(ab, ab), 1e-12f), 0.0f, 1.0f);
    return glm::length(p - (a + t * ab));
}

// Noise sampled on the unit circle at the direction of p, so that it has no seam at +-pi.
float angularNoise(glm::vec2 p, float frequency, uint32_t seed, int octaves) {
    const float r = glm::length(p);
    const glm::vec2 dir = r > 1e-6f ? p / r : glm::vec2(1.0f, 0.0f);
    return fbm(dir * frequency + glm::vec2(3.7f, 1.3f), seed, octaves);
}

// One texel of a procedural decal: linear colour, alpha and height.
struct Texel {
    glm::vec3 color{0.0f};
    float alpha = 0.0f;
    float height = 0.0f;
};

struct Droplet {
    glm::vec2 center;
    glm::vec2 axis; // unit, the direction it was thrown in
    float radius;
    float stretch; // >= 1: elongation along axis
};

std::vector<Droplet> makeDroplets(uint64_t seed, int count, float minDist, float maxDist, float maxRadius,
                                  float maxStretch) {
    Rng rng(seed);
    std::vector<Droplet> drops;
    for (int i = 0; i < count; ++i) {
        const float a = rng.uniform(0.0f, 2.0f * kPi);
        const float d = rng.uniform(minDist, maxDist);
        const glm::vec2 axis(std::cos(a), std::sin(a));
        const float shrink = 1.0f - 0.6f * (d - minDist) / std::max(maxDist - minDist, 1e-3f);
        drops.push_back(
            {axis * d, axis, maxRadius * rng.uniform(0.35f, 1.0f) * shrink, rng.uniform(1.0f, maxStretch)});
    }
    return drops;
}

// Signed-ish coverage of the droplets at p: 1 inside, falling to 0 over `edge`.
float dropletMask(const std::vector<Droplet>& drops, glm::vec2 p, float edge) {
    float m = 0.0f;
    for (const Droplet& d : drops) {
        const glm::vec2 q = p - d.center;
        const float along = glm::dot(q, d.axis) / d.stretch;
        const float across = q.x * -d.axis.y + q.y * d.axis.x;
        const float dist = std::sqrt(along * along + across * across) - d.radius;
        m = std::max(m, 1.0f - smoothstep(-edge, edge, dist));
    }
    return m;
}

Texel bulletHole(glm::vec2 p) {
    const uint32_t seed = 0xb011e7u;
    const float r = glm::length(p);
    const float rHole = 0.11f * (1.0f + 0.18f * angularNoise(p, 2.5f, seed, 3));
    const float rRing = 0.34f * (1.0f + 0.25f * angularNoise(p, 3.0f, seed + 7, 3));

    Texel t;
    // Soot and dust around the impact.
    const float soot =
        0.45f * (1.0f - smoothstep(0.05f, 0.62f, r)) * (0.75f + 0.25f * fbm(p * 9.0f, seed + 3, 3));
    // Crushed ring.
    const float ring = 0.9f * std::pow(1.0f - smoothstep(rHole, rRing, r), 0.6f);
    // Radial cracks.
    Rng rng(seed);
    float crack = 0.0f;
    for (int k = 0; k < 7; ++k) {
        const float a = rng.uniform(0.0f, 2.0f * kPi);
        const float len = rng.uniform(0.4f, 0.78f);
        const glm::vec2 dir(std::cos(a), std::sin(a));
        const glm::vec2 bend(-dir.y, dir.x);
        const glm::vec2 mid = dir * (0.5f * len) + bend * rng.uniform(-0.05f, 0.05f);
        float s = 0.0f;
        const float d1 = segmentDistance(p, dir * rHole, mid, s);
        float s2 = 0.0f;
        const float d2 = segmentDistance(p, mid, dir * len, s2);
        const float along = d1 < d2 ? 0.5f * s : 0.5f + 0.5f * s2;
        const float width = 0.014f * (1.0f - along) + 0.002f;
        crack = std::max(crack, 1.0f - smoothstep(0.6f * width, width, std::min(d1, d2)));
    }
    const float hole = 1.0f - smoothstep(rHole - 0.012f, rHole + 0.004f, r);

    t.alpha = std::max({soot, ring, 0.85f * crack, hole});
    const glm::vec3 sootColor(0.09f, 0.085f, 0.08f), ringColor(0.2f, 0.19f, 0.18f), holeColor(0.01f);
    const float g = 0.8f + 0.2f * fbm(p * 14.0f, seed + 5, 3);
    t.color = glm::mix(sootColor, ringColor * g, std::clamp(ring / 0.9f, 0.0f, 1.0f));
    t.color = glm::mix(t.color, glm::vec3(0.05f), crack);
    t.color = glm::mix(t.color, holeColor, hole);
    t.height = -1.0f * hole + 0.35f * std::exp(-std::pow((r - rHole * 1.4f) / 0.045f, 2.0f)) - 0.25f * crack +
               0.04f * fbm(p * 20.0f, seed + 9, 2) * ring;
    return t;
}

Texel splat(glm::vec2 p, uint32_t seed, const std::vector<Droplet>& drops, glm::vec3 dark, glm::vec3 light,
            float baseRadius, float thickness) {
    const float r = glm::length(p);
    const float rBlob = baseRadius * (1.0f + 0.28f * angularNoise(p, 2.2f, seed, 4)) *
                        (1.0f + 0.05f * fbm(p * 6.0f, seed + 1, 3));
    const float blob = 1.0f - smoothstep(rBlob - 0.012f, rBlob + 0.012f, r);
    const float drop = dropletMask(drops, p, 0.01f);
    const float m = std::max(blob, drop);
    Texel t;
    t.alpha = 0.95f * m;
    const float n = 0.5f + 0.5f * fbm(p * 7.0f, seed + 2, 4);
    t.color = glm::mix(dark, light, n);
    // Thicker at the rim where the liquid pooled, thin inside.
    const float rim = std::exp(-std::pow((r - rBlob + 0.03f) / 0.03f, 2.0f));
    t.height = thickness * (0.6f * m + 0.4f * rim * blob) + 0.05f * fbm(p * 16.0f, seed + 4, 2) * m;
    return t;
}

Texel scorch(glm::vec2 p) {
    const uint32_t seed = 0x5c07c4u;
    const float r = glm::length(p) * (1.0f + 0.3f * fbm(p * 2.5f, seed, 4));
    Texel t;
    t.alpha = 0.96f * (1.0f - smoothstep(0.12f, 0.92f, r));
    const float streaks = 0.5f + 0.5f * angularNoise(p, 9.0f, seed + 3, 2);
    t.color = glm::mix(glm::vec3(0.02f, 0.018f, 0.016f), glm::vec3(0.16f, 0.12f, 0.08f),
                       std::clamp(smoothstep(0.1f, 0.9f, r) * (0.6f + 0.4f * streaks), 0.0f, 1.0f));
    t.height = 0.12f * fbm(p * 14.0f, seed + 5, 3) * t.alpha;
    return t;
}

uint8_t toByte(float v) {
    return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

float linearToSrgb(float c) {
    c = std::clamp(c, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

} // namespace

Image normalMapFromHeight(const std::vector<float>& heights, int width, int height, float strength) {
    Image out;
    if (width <= 0 || height <= 0 || heights.size() != size_t(width) * size_t(height)) return out;
    out.width = width;
    out.height = height;
    out.name = "normal map";
    out.rgba.resize(size_t(width) * size_t(height) * 4);
    auto h = [&](int x, int y) {
        x = std::clamp(x, 0, width - 1);
        y = std::clamp(y, 0, height - 1);
        return heights[size_t(y) * size_t(width) + size_t(x)];
    };
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float dx = 0.5f * (h(x + 1, y) - h(x - 1, y)) * strength;
            const float dy = 0.5f * (h(x, y - 1) - h(x, y + 1)) * strength; // +y is up the image
            const glm::vec3 n = glm::normalize(glm::vec3(-dx, -dy, 1.0f));
            uint8_t* px = &out.rgba[(size_t(y) * size_t(width) + size_t(x)) * 4];
            px[0] = toByte(n.x * 0.5f + 0.5f);
            px[1] = toByte(n.y * 0.5f + 0.5f);
            px[2] = toByte(n.z * 0.5f + 0.5f);
            px[3] = 255;
        }
    return out;
}

DecalTextureImages makeBuiltinDecalTexture(DecalTexture kind, int size) {
    DecalTextureImages out;
    const int k = int(kind);
    if (k < 0 || k >= int(DecalTexture::Count)) return out;
    const int n = std::clamp(size, 16, 2048);
    const char* names[] = {"builtin:bullet_hole", "builtin:blood", "builtin:paint", "builtin:scorch"};

    std::vector<Droplet> drops;
    if (kind == DecalTexture::Blood) drops = makeDroplets(0xb100d, 26, 0.42f, 0.86f, 0.06f, 2.2f);
    if (kind == DecalTexture::Paint) drops = makeDroplets(0x9a17, 40, 0.38f, 0.9f, 0.07f, 3.0f);

    out.albedo.width = out.albedo.height = n;
    out.albedo.name = names[k];
    out.albedo.rgba.resize(size_t(n) * size_t(n) * 4);
    std::vector<float> heights(size_t(n) * size_t(n));
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const glm::vec2 p((float(x) + 0.5f) / float(n) * 2.0f - 1.0f,
                              1.0f - (float(y) + 0.5f) / float(n) * 2.0f);
            Texel t;
            switch (kind) {
            case DecalTexture::BulletHole:
                t = bulletHole(p);
                break;
            case DecalTexture::Blood:
                t = splat(p, 0xb100du, drops, {0.16f, 0.005f, 0.004f}, {0.38f, 0.02f, 0.015f}, 0.4f, 0.5f);
                break;
            case DecalTexture::Paint:
                t = splat(p, 0x9a17u, drops, {0.78f, 0.78f, 0.76f}, {0.95f, 0.95f, 0.93f}, 0.36f, 0.8f);
                break;
            default:
                t = scorch(p);
                break;
            }
            // Fade to nothing before the border so that the square never shows.
            const float edge = std::max(std::fabs(p.x), std::fabs(p.y));
            t.alpha *= 1.0f - smoothstep(0.86f, 0.97f, edge);
            uint8_t* px = &out.albedo.rgba[(size_t(y) * size_t(n) + size_t(x)) * 4];
            px[0] = toByte(linearToSrgb(t.color.x));
            px[1] = toByte(linearToSrgb(t.color.y));
            px[2] = toByte(linearToSrgb(t.color.z));
            px[3] = toByte(t.alpha);
            heights[size_t(y) * size_t(n) + size_t(x)] = t.height;
        }
    // Heights are in units of about a tenth of the decal: scale the slope to the texel size.
    out.normal = normalMapFromHeight(heights, n, n, 0.1f * float(n) / 16.0f);
    out.normal.name = std::string(names[k]) + " normal";
    return out;
}

Result<Image> resizeImage(const Image& image, int width, int height) {
    if (image.empty() || image.rgba.size() != size_t(image.width) * size_t(image.height) * 4)
        return fail("image '" + image.name + "' has no valid pixels");
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
        return fail("image '" + image.name + "': target size out of range");
    Image out;
    out.width = width;
    out.height = height;
    out.name = image.name;
    out.rgba.resize(size_t(width) * size_t(height) * 4);
    if (width == image.width && height == image.height) {
        out.rgba = image.rgba;
        return out;
    }
    const float sx = float(image.width) / float(width), sy = float(image.height) / float(height);
    auto src = [&](int x, int y, int c) {
        x = std::clamp(x, 0, image.width - 1);
        y = std::clamp(y, 0, image.height - 1);
        return float(image.rgba[(size_t(y) * size_t(image.width) + size_t(x)) * 4 + size_t(c)]);
    };
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 4; ++c) {
                float v = 0.0f;
                if (sx > 1.0f || sy > 1.0f) {
                    // Average of the source texels whose centres fall in this texel's footprint.
                    const int x0 = int(std::floor(float(x) * sx)),
                              x1 = std::max(x0 + 1, int(std::floor(float(x + 1) * sx)));
                    const int y0 = int(std::floor(float(y) * sy)),
                              y1 = std::max(y0 + 1, int(std::floor(float(y + 1) * sy)));
                    float sum = 0.0f;
                    for (int yy = y0; yy < y1; ++yy)
                        for (int xx = x0; xx < x1; ++xx)
                            sum += src(xx, yy, c);
                    v = sum / float((x1 - x0) * (y1 - y0));
                } else {
                    const float fx = (float(x) + 0.5f) * sx - 0.5f, fy = (float(y) + 0.5f) * sy - 0.5f;
                    const int ix = int(std::floor(fx)), iy = int(std::floor(fy));
                    const float tx = fx - float(ix), ty = fy - float(iy);
                    v = glm::mix(glm::mix(src(ix, iy, c), src(ix + 1, iy, c), tx),
                                 glm::mix(src(ix, iy + 1, c), src(ix + 1, iy + 1, c), tx), ty);
                }
                out.rgba[(size_t(y) * size_t(width) + size_t(x)) * 4 + size_t(c)] =
                    uint8_t(std::lround(std::clamp(v, 0.0f, 255.0f)));
            }
    return out;
}

} // namespace spatter
