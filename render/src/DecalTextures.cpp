#include "spatter/render/DecalTextures.hpp"

#include "spatter/core/Random.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/glm.hpp>

namespace spatter {

// The built-in decals are painted in decal coordinates p in [-1, 1]^2 (p.x along the tangent, p.y
// up the image, 1 = half the decal's width), so that their shapes do not depend on the texture
// size; only antialiasing widths are in texels. Everything random comes from fixed seeds, and the
// texture is built from fields that are cheap per texel: value noise from a 64 x 64 lattice,
// outlines tabulated over the angle, strokes and drops stamped into their bounding boxes, and box
// blurs. Heights are in the same units as p (1 = half the decal's width).

namespace {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kTwoPi = 2.0f * kPi;

float saturate(float x) {
    return std::clamp(x, 0.0f, 1.0f);
}

float smoothstep(float e0, float e1, float x) {
    const float t = saturate((x - e0) / (e1 - e0));
    return t * t * (3.0f - 2.0f * t);
}

float square(float x) {
    return x * x;
}

glm::vec2 direction(float angle) {
    return {std::cos(angle), std::sin(angle)};
}

// Smooth value noise over a seeded lattice of 64 x 64 values that repeats every 64 units.
class Noise {
public:
    explicit Noise(uint64_t seed) {
        Rng rng(seed);
        for (float& v : lattice_)
            v = rng.uniform(-1.0f, 1.0f);
    }

    // In [-1, 1], about one feature per unit.
    float operator()(glm::vec2 p) const {
        const float fx = std::floor(p.x), fy = std::floor(p.y);
        const float tx = p.x - fx, ty = p.y - fy;
        const float wx = tx * tx * tx * (tx * (tx * 6.0f - 15.0f) + 10.0f);
        const float wy = ty * ty * ty * (ty * (ty * 6.0f - 15.0f) + 10.0f);
        const unsigned x0 = unsigned(int(fx)) & kMask, y0 = unsigned(int(fy)) & kMask;
        const unsigned x1 = (x0 + 1) & kMask, y1 = (y0 + 1) & kMask;
        const float a = lattice_[y0 * kSize + x0], b = lattice_[y0 * kSize + x1];
        const float c = lattice_[y1 * kSize + x0], d = lattice_[y1 * kSize + x1];
        return glm::mix(glm::mix(a, b, wx), glm::mix(c, d, wx), wy);
    }

    // Sum of `octaves` octaves (frequency x2.03, amplitude x0.5), normalised to [-1, 1].
    float fbm(glm::vec2 p, int octaves) const {
        float sum = 0.0f, amp = 1.0f, total = 0.0f;
        for (int o = 0; o < octaves; ++o) {
            sum += amp * (*this)(p);
            total += amp;
            amp *= 0.5f;
            p = p * 2.03f + glm::vec2(17.31f, 9.17f);
        }
        return sum / total;
    }

private:
    static constexpr unsigned kSize = 64, kMask = kSize - 1;
    std::array<float, kSize * kSize> lattice_{};
};

// A smooth periodic function of the angle about the decal's centre (noise sampled on a circle of
// radius `frequency`, tabulated), for outlines that have no seam.
class AngularNoise {
public:
    AngularNoise(const Noise& noise, float frequency, int octaves, glm::vec2 offset) {
        for (int i = 0; i < kSamples; ++i)
            samples_[size_t(i)] =
                noise.fbm(offset + frequency * direction(kTwoPi * float(i) / kSamples), octaves);
    }

    float operator()(float angle) const {
        float t = angle * (float(kSamples) / kTwoPi);
        t -= std::floor(t / float(kSamples)) * float(kSamples);
        const int i = std::min(int(t), kSamples - 1);
        return glm::mix(samples_[size_t(i)], samples_[size_t((i + 1) % kSamples)], t - float(i));
    }

private:
    static constexpr int kSamples = 1024;
    std::array<float, kSamples> samples_{};
};

// Centre of texel (x, y) of an n x n texture in decal coordinates (row 0 at p.y = +1).
glm::vec2 texelCentre(int x, int y, int n) {
    return {(float(x) + 0.5f) / float(n) * 2.0f - 1.0f, 1.0f - (float(y) + 0.5f) / float(n) * 2.0f};
}

// An n x n field of floats over the decal, row 0 at the top.
struct Field {
    explicit Field(int size) : n(size), v(size_t(size) * size_t(size), 0.0f) {}
    float& at(int x, int y) { return v[size_t(y) * size_t(n) + size_t(x)]; }
    float at(int x, int y) const { return v[size_t(y) * size_t(n) + size_t(x)]; }
    float texel() const { return 2.0f / float(n); } // width of a texel in decal coordinates

    // Calls f(x, y, p) for every texel whose centre lies in the rectangle [lo, hi] of decal space.
    template <class F> void forEachIn(glm::vec2 lo, glm::vec2 hi, F&& f) {
        const float h = 0.5f * float(n);
        const int x0 = std::max(0, int(std::floor((lo.x + 1.0f) * h - 0.5f)));
        const int x1 = std::min(n - 1, int(std::ceil((hi.x + 1.0f) * h - 0.5f)));
        const int y0 = std::max(0, int(std::floor((1.0f - hi.y) * h - 0.5f)));
        const int y1 = std::min(n - 1, int(std::ceil((1.0f - lo.y) * h - 0.5f)));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x)
                f(x, y, texelCentre(x, y, n));
    }

    int n;
    std::vector<float> v;
};

// Coverage of a shape at signed distance d from its edge (negative inside), antialiased over one
// texel: edges stay crisp at every size.
float coverage(float d, float texel) {
    return saturate(0.5f - d / texel);
}

// Distance from p to the segment a-b, and the position t in [0, 1] of the closest point.
float segmentDistance(glm::vec2 p, glm::vec2 a, glm::vec2 b, float& t) {
    const glm::vec2 ab = b - a;
    t = std::clamp(glm::dot(p - a, ab) / std::max(glm::dot(ab, ab), 1e-12f), 0.0f, 1.0f);
    return glm::length(p - (a + t * ab));
}

// A stroke from a to b whose half-width goes from ra to rb, max-blended into the field.
void stampStroke(Field& f, glm::vec2 a, glm::vec2 b, float ra, float rb) {
    const float texel = f.texel(), reach = std::max(ra, rb) + texel;
    f.forEachIn(glm::min(a, b) - reach, glm::max(a, b) + reach, [&](int x, int y, glm::vec2 p) {
        float t = 0.0f;
        const float d = segmentDistance(p, a, b, t) - glm::mix(ra, rb, t);
        float& v = f.at(x, y);
        v = std::max(v, coverage(d, texel));
    });
}

// A drop: an ellipse of radius r across `axis` (unit) and r * stretch along it, max-blended.
void stampDrop(Field& f, glm::vec2 c, glm::vec2 axis, float r, float stretch) {
    const float texel = f.texel(), reach = r * stretch + texel;
    f.forEachIn(c - reach, c + reach, [&](int x, int y, glm::vec2 p) {
        const glm::vec2 q = p - c;
        const float along = glm::dot(q, axis) / stretch, across = q.x * -axis.y + q.y * axis.x;
        float& v = f.at(x, y);
        v = std::max(v, coverage(std::sqrt(along * along + across * across) - r, texel));
    });
}

// Two passes of a separable box blur of radius r texels (a tent of radius 2r), clamped at the border.
Field blur(const Field& in, int r) {
    const int n = in.n;
    Field a = in, b(n);
    const float scale = 1.0f / float(2 * r + 1);
    for (int pass = 0; pass < 2; ++pass) {
        for (int y = 0; y < n; ++y) { // rows: a -> b
            float sum = 0.0f;
            for (int k = -r; k <= r; ++k)
                sum += a.at(std::clamp(k, 0, n - 1), y);
            for (int x = 0; x < n; ++x) {
                b.at(x, y) = sum * scale;
                sum += a.at(std::min(x + r + 1, n - 1), y) - a.at(std::max(x - r, 0), y);
            }
        }
        for (int x = 0; x < n; ++x) { // columns: b -> a
            float sum = 0.0f;
            for (int k = -r; k <= r; ++k)
                sum += b.at(x, std::clamp(k, 0, n - 1));
            for (int y = 0; y < n; ++y) {
                a.at(x, y) = sum * scale;
                sum += b.at(x, std::min(y + r + 1, n - 1)) - b.at(x, std::max(y - r, 0));
            }
        }
    }
    return a;
}

// A decal being painted: linear colour, straight alpha and height per texel.
struct Canvas {
    explicit Canvas(int size)
        : n(size), color(size_t(size) * size_t(size), glm::vec3(0.0f)),
          alpha(size_t(size) * size_t(size), 0.0f), height(size_t(size) * size_t(size), 0.0f) {}
    int n;
    std::vector<glm::vec3> color;
    std::vector<float> alpha;
    std::vector<float> height;
};

// Porter-Duff "over" with straight alpha. Where nothing is covered yet the colour stays what it
// was, so that transparent texels carry a colour close to the mark's and filtering (bilinear,
// mipmaps) draws no dark or light fringe along its edge.
void over(glm::vec3& color, float& alpha, glm::vec3 topColor, float topAlpha) {
    const float a = topAlpha + alpha * (1.0f - topAlpha);
    if (a > 1e-6f) color = (topColor * topAlpha + color * (alpha * (1.0f - topAlpha))) / a;
    alpha = a;
}

// ---- Bullet hole -------------------------------------------------------------------------------

// Jagged cracks: a random walk outward from `start` along `heading`, tapering from `width` (half
// width) to a hairline, with at most one branch.
void crackWalk(Field& f, Rng& rng, glm::vec2 start, float heading, float length, float width, bool branch) {
    const int steps = std::max(3, int(length / 0.022f));
    const float step = length / float(steps);
    const int branchAt = branch && rng.uniform() < 0.6f ? 1 + int(rng.below(uint32_t(steps - 1))) : -1;
    const float radial = heading;
    glm::vec2 pos = start;
    float w = width;
    for (int s = 0; s < steps; ++s) {
        heading += rng.uniform(-0.5f, 0.5f) + 0.35f * (radial - heading);
        const glm::vec2 next = pos + step * direction(heading);
        if (glm::length(next) > 0.84f) break;
        const float wNext = width * (1.0f - float(s + 1) / float(steps)) + 0.0006f;
        stampStroke(f, pos, next, w, wNext);
        if (s == branchAt) {
            const float side = rng.uniform() < 0.5f ? -1.0f : 1.0f;
            crackWalk(f, rng, next, heading + side * rng.uniform(0.45f, 0.8f),
                      0.5f * length * float(steps - s) / float(steps), 0.7f * wNext, false);
        }
        pos = next;
        w = wNext;
    }
}

// Voronoi cells of a jittered grid: the fragments chipped off around the hole.
struct Chips {
    static constexpr int kGrid = 20;        // cells per side
    static constexpr float kCell = 0.05f;   // cell size in decal coordinates
    static constexpr float kOrigin = -0.5f; // the grid spans [-0.5, 0.5]^2
    struct Cell {
        glm::vec2 site;
        glm::vec2 tilt; // slope of the fragment's facet
        float shade;    // brightness
        bool chipped;
    };
    std::array<Cell, kGrid * kGrid> cells{};

    // The nearest site (a) and the second nearest (b) to p, and the distance from p to their bisector.
    void nearest(glm::vec2 p, int& a, int& b, float& edge) const {
        const int cx = int(std::floor((p.x - kOrigin) / kCell)),
                  cy = int(std::floor((p.y - kOrigin) / kCell));
        float da = 1e30f, db = 1e30f;
        a = b = -1;
        for (int j = cy - 1; j <= cy + 1; ++j)
            for (int i = cx - 1; i <= cx + 1; ++i) {
                if (i < 0 || j < 0 || i >= kGrid || j >= kGrid) continue;
                const int k = j * kGrid + i;
                const glm::vec2 q = p - cells[size_t(k)].site;
                const float d = glm::dot(q, q);
                if (d < da) {
                    db = da;
                    b = a;
                    da = d;
                    a = k;
                } else if (d < db) {
                    db = d;
                    b = k;
                }
            }
        edge = (a >= 0 && b >= 0)
                   ? (db - da) /
                         (2.0f * std::max(glm::length(cells[size_t(b)].site - cells[size_t(a)].site), 1e-6f))
                   : 1e30f;
    }
};

Canvas bulletHole(int n) {
    const uint64_t seed = 0xb011e7u;
    Noise noise(seed);
    Rng rng(seed);
    const AngularNoise holeShape(noise, 0.9f, 2, {3.1f, 7.3f}), holeJag(noise, 5.0f, 2, {11.2f, 1.7f});
    const AngularNoise chipShape(noise, 0.8f, 3, {23.5f, 5.9f}), streaks(noise, 9.0f, 2, {41.0f, 13.0f});
    auto rHole = [&](float a) { return 0.1f * (1.0f + 0.2f * holeShape(a) + 0.1f * holeJag(a)); };
    auto rChip = [&](float a) { return 0.25f * (1.0f + 0.3f * chipShape(a)); };

    Chips chips;
    for (int j = 0; j < Chips::kGrid; ++j)
        for (int i = 0; i < Chips::kGrid; ++i) {
            Chips::Cell& c = chips.cells[size_t(j * Chips::kGrid + i)];
            c.site = Chips::kOrigin + (glm::vec2(float(i), float(j)) +
                                       glm::vec2(rng.uniform(0.1f, 0.9f), rng.uniform(0.1f, 0.9f))) *
                                          Chips::kCell;
            c.tilt = glm::vec2(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f)) * 0.3f;
            c.shade = rng.uniform(0.6f, 1.2f);
            c.chipped =
                glm::length(c.site) < rChip(std::atan2(c.site.y, c.site.x)) * rng.uniform(0.85f, 1.15f);
        }

    Field cracks(n), specks(n);
    const int crackCount = 7;
    for (int k = 0; k < crackCount; ++k) {
        const float a = kTwoPi * (float(k) + rng.uniform(0.15f, 0.85f)) / float(crackCount);
        const glm::vec2 start = direction(a) * rChip(a) * rng.uniform(0.75f, 0.95f);
        crackWalk(cracks, rng, start, a, rng.uniform(0.18f, 0.46f), rng.uniform(0.0045f, 0.0075f), true);
    }
    for (int k = 0; k < 40; ++k) {
        const float a = rng.uniform(0.0f, kTwoPi);
        stampDrop(specks, direction(a) * rng.uniform(0.24f, 0.6f), direction(a), rng.uniform(0.003f, 0.009f),
                  rng.uniform(1.0f, 2.0f));
    }

    Canvas out(n);
    const float texel = 2.0f / float(n);
    const glm::vec3 sootColor(0.05f, 0.046f, 0.042f), fresh(0.52f, 0.49f, 0.45f);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const glm::vec2 p = texelCentre(x, y, n);
            const size_t i = size_t(y) * size_t(n) + size_t(x);
            const float r = glm::length(p);
            glm::vec3 c = sootColor;
            float a = 0.0f, h = 0.0f;
            if (r < 0.62f) {
                // Soot and dust thrown out of the hole, streaked radially.
                const float angle = std::atan2(p.y, p.x);
                const float reach = 0.5f + 0.1f * noise.fbm(p * 4.0f, 2);
                const float soot = 0.34f * (1.0f - smoothstep(0.12f, reach, r)) *
                                   (0.7f + 0.2f * noise.fbm(p * 11.0f, 2) + 0.1f * streaks(angle));
                over(c, a, sootColor, soot);
                over(c, a, glm::vec3(0.03f), 0.7f * specks.at(x, y));
                over(c, a, glm::vec3(0.02f), 0.92f * cracks.at(x, y));
                h -= 0.006f * cracks.at(x, y);

                // The chipped ring: whole fragments, so its outline follows their edges.
                int ca = -1, cb = -1;
                float edge = 0.0f;
                chips.nearest(p, ca, cb, edge);
                if (ca >= 0) {
                    const Chips::Cell& A = chips.cells[size_t(ca)];
                    const bool sameSide = cb < 0 || chips.cells[size_t(cb)].chipped == A.chipped;
                    const float cov = sameSide ? (A.chipped ? 1.0f : 0.0f)
                                               : (A.chipped ? saturate(0.5f + edge / texel)
                                                            : saturate(0.5f - edge / texel));
                    if (cov > 0.0f) {
                        const float rh = rHole(angle), rc = std::max(rChip(angle), rh + 0.05f);
                        const float u = saturate((r - rh) / (rc - rh));
                        // Hairline gaps between some neighbouring fragments.
                        const uint32_t pair = uint32_t(std::min(ca, cb) * 977 + std::max(ca, cb));
                        const bool gap =
                            cb >= 0 && chips.cells[size_t(cb)].chipped && (pair * 2654435761u >> 30) == 0;
                        const float line = gap ? 1.0f - smoothstep(0.25f * texel, 1.1f * texel, edge) : 0.0f;
                        const float grain = 0.88f + 0.12f * noise.fbm(p * 40.0f, 2);
                        glm::vec3 chip = fresh * A.shade * grain;
                        chip *= glm::mix(0.6f, 1.0f, smoothstep(0.0f, 0.03f, r - rh)); // the scorched bore
                        chip *= 1.0f - 0.6f * line;
                        over(c, a, chip, 0.97f * cov);
                        // A crater: a funnel down to the hole, a raised rim, each fragment a tilted facet.
                        const float crater =
                            -0.05f * square(1.0f - u) + 0.03f * std::exp(-square((u - 0.78f) / 0.2f));
                        const float facet = glm::dot(A.tilt, p - A.site);
                        h = glm::mix(h, crater + facet - 0.004f * line, cov);
                    }
                }

                // The hole: sharp-edged and irregular, the bore's wall a little lighter than its depth.
                const float rh = rHole(angle);
                const float hole = coverage(r - rh, texel);
                if (hole > 0.0f) {
                    const glm::vec3 bore = glm::mix(glm::vec3(0.004f), glm::vec3(0.02f, 0.018f, 0.017f),
                                                    smoothstep(0.75f * rh, rh, r));
                    over(c, a, bore, hole);
                    h = glm::mix(h, -0.06f - 0.03f * (1.0f - square(r / rh)), hole);
                }
            } else {
                over(c, a, glm::vec3(0.03f), 0.7f * specks.at(x, y));
                over(c, a, glm::vec3(0.02f), 0.92f * cracks.at(x, y));
                h -= 0.006f * cracks.at(x, y);
            }
            out.color[i] = c;
            out.alpha[i] = a;
            out.height[i] = h;
        }
    return out;
}

// ---- Blood and paint ---------------------------------------------------------------------------

struct SplatStyle {
    uint64_t seed = 0;
    float radius = 0.3f;        // of the main body
    float lobes = 0.2f;         // relative amplitude of its outline
    int tendrils = 0;           // streaks thrown out of the body
    float tendrilLength = 0.3f; // longest, from the body's edge
    float tendrilWidth = 0.02f; // half width at the root
    float tipDrops = 0.5f;      // chance of a drop at a tendril's end
    int drops = 0;              // satellite drops
    float dropRadius = 0.03f;   // largest
    float dropStretch = 1.5f;   // largest elongation along the direction of flight
    glm::vec3 dark{0.0f}, light{1.0f};
    float edgeDarkening = 0.0f; // how much darker the thin edge is than the pooled body
    float thickness = 0.01f;    // height of the pooled body
    float alpha = 1.0f;
};

Canvas splat(int n, const SplatStyle& s) {
    Noise noise(s.seed);
    Rng rng(s.seed);
    const AngularNoise outline(noise, 0.7f, 3, {5.3f, 2.9f}), detail(noise, 3.0f, 2, {31.7f, 17.1f});
    auto body = [&](float a) {
        return s.radius * (1.0f + s.lobes * outline(a) + 0.3f * s.lobes * detail(a));
    };

    Field cov(n);
    const float texel = cov.texel();
    const float reach = s.radius * (1.0f + 1.3f * s.lobes) + texel;
    cov.forEachIn(glm::vec2(-reach), glm::vec2(reach), [&](int x, int y, glm::vec2 p) {
        const float r = glm::length(p) * (1.0f + 0.05f * noise.fbm(p * 12.0f, 2));
        cov.at(x, y) = coverage(r - body(std::atan2(p.y, p.x)), texel);
    });

    // Tendrils: curved, tapering streaks from inside the body, many ending in a drop.
    for (int k = 0; k < s.tendrils; ++k) {
        const float a = kTwoPi * (float(k) + rng.uniform(0.0f, 1.0f)) / float(s.tendrils);
        const float rb = body(a);
        const glm::vec2 root = direction(a) * rb * 0.6f;
        float length = rb * 0.4f + s.tendrilLength * rng.uniform(0.25f, 1.0f);
        length = std::min(length, 0.8f - rb * 0.6f);
        const float bend = rng.uniform(-0.12f, 0.12f);
        const glm::vec2 mid = root + direction(a + bend) * (0.5f * length);
        const glm::vec2 tip = mid + direction(a - bend * 0.5f + rng.uniform(-0.08f, 0.08f)) * (0.5f * length);
        const float w = s.tendrilWidth * rng.uniform(0.5f, 1.2f);
        stampStroke(cov, root, mid, w, 0.55f * w);
        stampStroke(cov, mid, tip, 0.55f * w, 0.12f * w + 0.0012f);
        if (rng.uniform() < s.tipDrops) {
            const glm::vec2 axis = glm::normalize(tip - mid);
            const float r = w * rng.uniform(0.55f, 1.0f);
            const float stretch = rng.uniform(1.1f, 1.7f);
            stampDrop(cov, tip + axis * (r * stretch + rng.uniform(0.008f, 0.03f)), axis, r, stretch);
        }
    }

    // Satellite drops: fewer and smaller with distance, elongated along their flight, with a tail.
    for (int k = 0; k < s.drops; ++k) {
        const float a = rng.uniform(0.0f, kTwoPi);
        const float t = std::pow(rng.uniform(), 1.4f);
        const float dist = body(a) + 0.04f + t * (0.82f - body(a) - 0.04f);
        const float r = s.dropRadius * rng.uniform(0.25f, 1.0f) * (1.0f - 0.6f * t);
        const float stretch = rng.uniform(1.0f, s.dropStretch);
        const glm::vec2 axis = direction(a + rng.uniform(-0.15f, 0.15f));
        const glm::vec2 c = direction(a) * dist;
        stampDrop(cov, c, axis, r, stretch);
        if (stretch > 1.4f) stampStroke(cov, c, c + axis * (r * stretch * 1.9f), 0.45f * r, 0.0005f);
    }

    // Pooled liquid: thick where the mark is wide, thin along its edges and in fine streaks.
    const Field pool = blur(cov, std::max(1, int(std::lround(0.025f / texel))));
    Canvas out(n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const glm::vec2 p = texelCentre(x, y, n);
            const size_t i = size_t(y) * size_t(n) + size_t(x);
            const float m = cov.at(x, y), depth = pool.at(x, y);
            const float shade = 0.5f + 0.5f * noise.fbm(p * 6.0f, 3);
            glm::vec3 c = glm::mix(s.dark, s.light, shade);
            c *= glm::mix(1.0f - s.edgeDarkening, 1.0f, smoothstep(0.3f, 0.75f, depth));
            out.color[i] = c;
            out.alpha[i] = s.alpha * m;
            out.height[i] =
                m * (s.thickness * std::sqrt(std::max(depth, 0.0f)) + 0.002f * noise.fbm(p * 30.0f, 2));
        }
    return out;
}

SplatStyle bloodStyle() {
    SplatStyle s;
    s.seed = 0xb100du;
    s.radius = 0.3f;
    s.lobes = 0.2f;
    s.tendrils = 14;
    s.tendrilLength = 0.3f;
    s.tendrilWidth = 0.03f;
    s.tipDrops = 0.6f;
    s.drops = 45;
    s.dropRadius = 0.03f;
    s.dropStretch = 2.2f;
    s.dark = {0.12f, 0.005f, 0.004f};
    s.light = {0.3f, 0.016f, 0.012f};
    s.edgeDarkening = 0.45f;
    s.thickness = 0.014f;
    s.alpha = 0.96f;
    return s;
}

// Near white, so that DecalType::tint gives it its colour.
SplatStyle paintStyle() {
    SplatStyle s;
    s.seed = 0x9a17u;
    s.radius = 0.34f;
    s.lobes = 0.22f;
    s.tendrils = 26;
    s.tendrilLength = 0.38f;
    s.tendrilWidth = 0.024f;
    s.tipDrops = 0.8f;
    s.drops = 50;
    s.dropRadius = 0.028f;
    s.dropStretch = 1.8f;
    s.dark = {0.8f, 0.8f, 0.78f};
    s.light = {0.95f, 0.95f, 0.93f};
    s.edgeDarkening = 0.06f;
    s.thickness = 0.024f;
    s.alpha = 0.98f;
    return s;
}

// ---- Scorch ------------------------------------------------------------------------------------

Canvas scorch(int n) {
    const uint64_t seed = 0x5c07c4u;
    Noise noise(seed);
    const AngularNoise streaks(noise, 14.0f, 2, {7.7f, 3.3f}), broad(noise, 1.2f, 2, {19.1f, 29.3f});
    Canvas out(n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const glm::vec2 p = texelCentre(x, y, n);
            const size_t i = size_t(y) * size_t(n) + size_t(x);
            const float angle = std::atan2(p.y, p.x);
            const float streak = 0.5f + 0.5f * streaks(angle);
            // Radial streaks push the soot outward in rays; the outline wobbles and frays.
            const float r = glm::length(p) * (1.0f + 0.25f * noise.fbm(p * 2.5f, 3) + 0.15f * broad(angle)) *
                            (1.0f - 0.22f * streak * smoothstep(0.1f, 0.5f, glm::length(p)));
            const float grain = 0.88f + 0.12f * noise.fbm(p * 24.0f, 2);
            const float body = 1.0f - smoothstep(0.08f, 0.8f, r);
            out.alpha[i] = 0.97f * std::pow(body, 1.25f) * grain;
            const float burn = saturate(smoothstep(0.05f, 0.7f, r) * (0.7f + 0.5f * streak) * grain);
            out.color[i] = glm::mix(glm::vec3(0.012f, 0.011f, 0.01f), glm::vec3(0.11f, 0.07f, 0.038f), burn);
        }
    return out;
}

uint8_t toByte(float v) {
    return uint8_t(std::lround(saturate(v) * 255.0f));
}

// sRGB bytes of linear values in [0, 1], from a table (a pow per texel and channel is slow).
uint8_t srgbByte(float linear) {
    static const std::array<uint8_t, 4097> table = [] {
        std::array<uint8_t, 4097> t{};
        for (size_t k = 0; k < t.size(); ++k) {
            const float c = float(k) / 4096.0f;
            t[k] = toByte(c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f);
        }
        return t;
    }();
    // 4096 steps keep every value within a byte of the exact encoding, also at the steep dark end.
    return table[size_t(std::lround(saturate(linear) * 4096.0f))];
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

    Canvas canvas(0);
    switch (kind) {
    case DecalTexture::BulletHole:
        canvas = bulletHole(n);
        break;
    case DecalTexture::Blood:
        canvas = splat(n, bloodStyle());
        break;
    case DecalTexture::Paint:
        canvas = splat(n, paintStyle());
        break;
    default:
        canvas = scorch(n);
        break;
    }

    out.albedo.width = out.albedo.height = n;
    out.albedo.name = names[k];
    out.albedo.rgba.resize(size_t(n) * size_t(n) * 4);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const size_t i = size_t(y) * size_t(n) + size_t(x);
            const glm::vec2 p = texelCentre(x, y, n);
            // Fade to nothing before the border so that the square never shows.
            const float edge = std::max(std::fabs(p.x), std::fabs(p.y));
            const float alpha = canvas.alpha[i] * (1.0f - smoothstep(0.88f, 0.97f, edge));
            uint8_t* px = &out.albedo.rgba[i * 4];
            px[0] = srgbByte(canvas.color[i].x);
            px[1] = srgbByte(canvas.color[i].y);
            px[2] = srgbByte(canvas.color[i].z);
            px[3] = toByte(alpha);
        }
    // Heights are in decal coordinates, two units across the texture: slope = difference * n / 2.
    out.normal = normalMapFromHeight(canvas.height, n, n, 0.5f * float(n));
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
