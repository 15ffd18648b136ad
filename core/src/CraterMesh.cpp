#include "spatter/core/CraterMesh.hpp"
#include "Pi.hpp"

#include "spatter/core/Random.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace spatter {

namespace {

constexpr float kMaxTilt = 0.25f; // the bowl is up to this much deeper on one side

// A smooth periodic profile in [0, 1] over `segments` samples: a few random harmonics, with a
// couple of sharp notches for chips.
std::vector<float> periodicNoise(Rng& rng, int segments, int harmonics, int notches) {
    std::vector<float> v(size_t(segments), 0.0f);
    for (int h = 1; h <= harmonics; ++h) {
        const float amp = rng.uniform(0.3f, 1.0f) / float(h);
        const float phase = rng.uniform(0.0f, 2.0f * kPiF);
        for (int i = 0; i < segments; ++i)
            v[size_t(i)] += amp * std::sin(float(h) * 2.0f * kPiF * float(i) / float(segments) + phase);
    }
    for (int k = 0; k < notches; ++k) {
        const float at = rng.uniform(0.0f, 2.0f * kPiF);
        const float width = rng.uniform(0.15f, 0.4f);
        const float amp = rng.uniform(1.0f, 2.0f);
        for (int i = 0; i < segments; ++i) {
            float d = std::fabs(2.0f * kPiF * float(i) / float(segments) - at);
            d = std::min(d, 2.0f * kPiF - d);
            if (d < width) v[size_t(i)] += amp * (1.0f - d / width);
        }
    }
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    const float mn = *lo, range = *hi - *lo;
    for (float& x : v)
        x = range > 1e-6f ? (x - mn) / range : 0.0f;
    return v;
}

} // namespace

Result<Mesh> makeCraterMesh(uint32_t variant, const CraterShape& s) {
    if (!(std::isfinite(s.depth) && s.depth > 0.0f && s.depth <= 4.0f))
        return fail("crater mesh: depth " + std::to_string(s.depth) + " is outside (0, 4]");
    if (!(std::isfinite(s.chip) && s.chip >= 0.0f && s.chip < 0.9f))
        return fail("crater mesh: chip " + std::to_string(s.chip) + " is outside [0, 0.9)");
    if (!(std::isfinite(s.roughness) && s.roughness >= 0.0f && s.roughness <= 0.5f))
        return fail("crater mesh: roughness " + std::to_string(s.roughness) + " is outside [0, 0.5]");
    if (s.segments < 8 || s.segments > 1024)
        return fail("crater mesh: " + std::to_string(s.segments) + " segments is outside [8, 1024]");
    if (s.rings < 1 || s.rings > 256)
        return fail("crater mesh: " + std::to_string(s.rings) + " rings is outside [1, 256]");

    Rng rng(0x9e3779b97f4a7c15ULL ^ (uint64_t(variant) * 0xbf58476d1ce4e5b9ULL), 0x6372617465ULL);
    const int n = s.segments;
    // Rim radius 1 - chip * noise: the largest radius is exactly 1.
    const std::vector<float> rim = periodicNoise(rng, n, 5, 2);
    const float squash = rng.uniform(0.85f, 1.0f);       // slight anisotropy of the depth profile
    const float tilt = rng.uniform(-kMaxTilt, kMaxTilt); // off-centre deepest point

    Mesh m;
    // Ring 0 is the rim, rings 1..rings-1 go down, then the bottom vertex.
    for (int r = 0; r < s.rings; ++r) {
        const float t = float(r) / float(s.rings); // 0 at the rim, towards 1 at the bottom
        const float radial = 1.0f - t;
        const std::vector<float> bumps = periodicNoise(rng, n, 4, 0);
        for (int i = 0; i < n; ++i) {
            const float a = 2.0f * kPiF * float(i) / float(n);
            const float radius = (1.0f - s.chip * rim[size_t(i)]) * radial;
            const glm::vec2 xy(std::cos(a) * radius, std::sin(a) * radius);
            float z = 0.0f;
            if (r > 0) {
                // Bowl profile: 0 at the rim, -depth at the centre, always below the rim plane.
                const float bowl = 1.0f - radial * radial;
                const float skew = 1.0f + tilt * xy.x;
                z = -s.depth * squash * bowl * skew * (1.0f + s.roughness * bumps[size_t(i)]);
                z = std::min(z, -1e-4f * s.depth);
            }
            m.positions.emplace_back(xy, z);
        }
    }
    m.positions.emplace_back(0.0f, 0.0f, -s.depth * squash * (1.0f + 0.5f * s.roughness));

    auto at = [n](int ring, int i) { return uint32_t(ring * n + (i % n)); };
    for (int r = 0; r + 1 < s.rings; ++r)
        for (int i = 0; i < n; ++i) {
            // Ring r is outside ring r + 1; counter-clockwise seen from +z.
            m.indices.insert(m.indices.end(), {at(r, i), at(r, i + 1), at(r + 1, i)});
            m.indices.insert(m.indices.end(), {at(r, i + 1), at(r + 1, i + 1), at(r + 1, i)});
        }
    const uint32_t bottom = uint32_t(m.positions.size() - 1);
    for (int i = 0; i < n; ++i)
        m.indices.insert(m.indices.end(), {at(s.rings - 1, i), at(s.rings - 1, i + 1), bottom});
    computeNormals(m);
    return m;
}

float craterDepthBound(const CraterShape& s) {
    // depth * squash (<= 1) * skew (<= 1 + kMaxTilt) * (1 + roughness * bump (<= 1)); the bottom
    // vertex is shallower than that.
    return s.depth * (1.0f + kMaxTilt) * (1.0f + s.roughness);
}

} // namespace spatter
