#include "spatter/render/DecalTextures.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace spatter;

namespace {

uint8_t alphaAt(const Image& im, int x, int y) {
    return im.rgba[(size_t(y) * size_t(im.width) + size_t(x)) * 4 + 3];
}

} // namespace

TEST(DecalTextures, BuiltinDecalsAreDeterministicAndOpaqueOnlyInside) {
    for (int k = 0; k < int(DecalTexture::Count); ++k) {
        const DecalTextureImages a = makeBuiltinDecalTexture(DecalTexture(k), 64);
        const DecalTextureImages b = makeBuiltinDecalTexture(DecalTexture(k), 64);
        ASSERT_EQ(a.albedo.width, 64);
        ASSERT_EQ(a.albedo.rgba.size(), 64u * 64u * 4u);
        ASSERT_EQ(a.normal.rgba.size(), 64u * 64u * 4u);
        EXPECT_EQ(a.albedo.rgba, b.albedo.rgba) << k;
        EXPECT_EQ(a.normal.rgba, b.normal.rgba) << k;
        // Nothing along the border; something in the middle.
        for (int i = 0; i < 64; ++i) {
            EXPECT_EQ(alphaAt(a.albedo, i, 0), 0) << k;
            EXPECT_EQ(alphaAt(a.albedo, i, 63), 0) << k;
            EXPECT_EQ(alphaAt(a.albedo, 0, i), 0) << k;
            EXPECT_EQ(alphaAt(a.albedo, 63, i), 0) << k;
        }
        EXPECT_GT(alphaAt(a.albedo, 32, 32), 128) << k;
        // Normal maps point out of the surface.
        for (size_t p = 0; p < a.normal.rgba.size(); p += 4)
            EXPECT_GT(a.normal.rgba[p + 2], 128) << k;
    }
}

TEST(DecalTextures, OutOfRangeKindGivesEmptyImages) {
    EXPECT_TRUE(makeBuiltinDecalTexture(DecalTexture::Count, 64).albedo.empty());
    EXPECT_TRUE(makeBuiltinDecalTexture(DecalTexture(-3), 64).normal.empty());
    // Sizes are clamped.
    EXPECT_EQ(makeBuiltinDecalTexture(DecalTexture::Blood, 2).albedo.width, 16);
}

TEST(DecalTextures, NormalMapTiltsAwayFromRisingHeight) {
    // Height rising to the right (+x) and towards the top row (+y): the normal leans to -x and -y.
    const int n = 8;
    std::vector<float> h(size_t(n * n));
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            h[size_t(y * n + x)] = float(x) - float(y);
    const Image im = normalMapFromHeight(h, n, n, 0.5f);
    ASSERT_EQ(im.width, n);
    const uint8_t* px = &im.rgba[(size_t(4) * n + 4) * 4];
    EXPECT_LT(px[0], 128);
    EXPECT_LT(px[1], 128);
    EXPECT_GT(px[2], 128);
    EXPECT_TRUE(normalMapFromHeight(h, n + 1, n, 1.0f).empty());
}

TEST(DecalTextures, ResizeAveragesWhenShrinkingAndKeepsCorners) {
    Image im;
    im.width = 4;
    im.height = 2;
    im.name = "checker";
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) {
            const uint8_t v = (x < 2) ? 0 : 200;
            im.rgba.insert(im.rgba.end(), {v, v, v, 255});
        }
    Result<Image> small = resizeImage(im, 2, 1);
    ASSERT_TRUE(small.ok()) << small.error();
    EXPECT_EQ(small->rgba[0], 0);
    EXPECT_EQ(small->rgba[4], 200);
    Result<Image> big = resizeImage(im, 8, 4);
    ASSERT_TRUE(big.ok());
    EXPECT_EQ(big->rgba[0], 0);
    EXPECT_EQ(big->rgba[(8 * 4 - 1) * 4], 200);

    Image broken = im;
    broken.rgba.pop_back();
    EXPECT_FALSE(resizeImage(broken, 2, 2).ok());
    EXPECT_FALSE(resizeImage(im, 0, 2).ok());
}

namespace {

constexpr int kN = 256;

// Texel of decal coordinates p in [-1, 1]^2 (p.y up the image).
const uint8_t* texelAt(const Image& im, float px, float py) {
    const int x = std::clamp(int((px + 1.0f) * 0.5f * float(im.width)), 0, im.width - 1);
    const int y = std::clamp(int((1.0f - py) * 0.5f * float(im.height)), 0, im.height - 1);
    return &im.rgba[(size_t(y) * size_t(im.width) + size_t(x)) * 4];
}

// Along 36 rays from the centre, in half-texel steps: how many texels the alpha takes to fall from
// 90% to 10% at its first edge (-1 when it never does).
std::vector<float> edgeWidths(const Image& albedo) {
    std::vector<float> widths;
    for (int r = 0; r < 36; ++r) {
        const float a = float(r) * 6.2831853f / 36.0f;
        int high = -1, low = -1;
        for (int s = 0; s < 2 * albedo.width && low < 0; ++s) {
            const float t = float(s) / float(albedo.width);
            const uint8_t alpha = texelAt(albedo, t * std::cos(a), t * std::sin(a))[3];
            if (alpha >= 230) high = s;
            if (alpha <= 25 && high >= 0) low = s;
        }
        widths.push_back(low < 0 ? -1.0f : 0.5f * float(low - high));
    }
    return widths;
}

} // namespace

TEST(DecalTextures, BulletHoleIsASharpDarkHoleInALighterCraterWithARaisedRim) {
    const DecalTextureImages im = makeBuiltinDecalTexture(DecalTexture::BulletHole, kN);
    // Rings about the centre (width 0.025 in decal coordinates): mean red byte (albedo over black)
    // and mean radial component of the normal (negative: leaning towards the centre, where the
    // surface rises outward).
    double shade[20] = {}, radial[20] = {};
    int count[20] = {};
    for (int y = 0; y < kN; ++y)
        for (int x = 0; x < kN; ++x) {
            const float px = (float(x) + 0.5f) / kN * 2.0f - 1.0f, py = 1.0f - (float(y) + 0.5f) / kN * 2.0f;
            const float r = std::sqrt(px * px + py * py);
            const int ring = int(r / 0.025f);
            if (ring >= 20) continue;
            const uint8_t* a = &im.albedo.rgba[(size_t(y) * kN + size_t(x)) * 4];
            const uint8_t* n = &im.normal.rgba[(size_t(y) * kN + size_t(x)) * 4];
            shade[ring] += a[0] * a[3] / 255.0;
            radial[ring] += ((n[0] / 127.5 - 1.0) * px + (n[1] / 127.5 - 1.0) * py) / std::max(r, 1e-6f);
            ++count[ring];
        }
    for (int k = 0; k < 20; ++k) {
        shade[k] /= std::max(count[k], 1);
        radial[k] /= std::max(count[k], 1);
    }
    // A black, opaque hole; light chipped material around it; the soot fading out.
    EXPECT_LT(shade[0], 25.0);
    EXPECT_LT(shade[1], 25.0);
    EXPECT_EQ(texelAt(im.albedo, 0.0f, 0.0f)[3], 255);
    EXPECT_GT(shade[6], 100.0); // r 0.15 to 0.175
    EXPECT_LT(shade[16], 20.0); // r 0.4 to 0.425
    // The crater: its wall rises from the hole to a rim, which falls away outside.
    EXPECT_LT(radial[5], -0.2); // r 0.125 to 0.15
    EXPECT_LT(radial[6], -0.2);
    EXPECT_GT(radial[9], 0.05); // r 0.225 to 0.25
    EXPECT_GT(radial[10], 0.05);
    EXPECT_NEAR(radial[15], 0.0, 0.02); // flat away from the impact

    // The hole's edge is sharp: from dark (red < 30) to chipped material (> 90) within 3 texels.
    int sharp = 0;
    for (int r = 0; r < 36; ++r) {
        const float a = float(r) * 6.2831853f / 36.0f;
        int dark = -1, light = -1;
        for (int s = 0; s < kN && light < 0; ++s) {
            const float t = float(s) / kN;
            const uint8_t red = texelAt(im.albedo, t * std::cos(a), t * std::sin(a))[0];
            if (red < 30) dark = s;
            if (red > 90 && dark >= 0) light = s;
        }
        sharp += (light >= 0 && light - dark <= 6) ? 1 : 0;
    }
    EXPECT_GE(sharp, 30);
}

TEST(DecalTextures, SplatsHaveCrispEdgesAndScorchIsSoft) {
    for (DecalTexture kind : {DecalTexture::Blood, DecalTexture::Paint}) {
        const std::vector<float> widths = edgeWidths(makeBuiltinDecalTexture(kind, kN).albedo);
        const auto crisp =
            std::count_if(widths.begin(), widths.end(), [](float w) { return w >= 0.0f && w <= 2.5f; });
        EXPECT_GE(crisp, 20) << int(kind); // rays along a tapering tendril fade more slowly
    }
    const DecalTextureImages scorch = makeBuiltinDecalTexture(DecalTexture::Scorch, kN);
    for (float w : edgeWidths(scorch.albedo))
        EXPECT_GT(w, 20.0f);
    // Soot only: no relief.
    for (size_t p = 0; p < scorch.normal.rgba.size(); p += 4) {
        ASSERT_EQ(scorch.normal.rgba[p], 128);
        ASSERT_EQ(scorch.normal.rgba[p + 1], 128);
    }
}

TEST(DecalTextures, PaintIsNearWhiteSoItsTintColoursItAndBloodIsRed) {
    for (DecalTexture kind : {DecalTexture::Paint, DecalTexture::Blood}) {
        const Image albedo = makeBuiltinDecalTexture(kind, kN).albedo;
        double sum[3] = {};
        size_t covered = 0;
        for (size_t p = 0; p < albedo.rgba.size(); p += 4) {
            if (albedo.rgba[p + 3] < 128) continue;
            ++covered;
            for (int c = 0; c < 3; ++c)
                sum[c] += albedo.rgba[p + size_t(c)];
        }
        ASSERT_GT(covered, size_t(kN * kN) / 20) << int(kind);
        const double r = sum[0] / covered, g = sum[1] / covered, b = sum[2] / covered;
        if (kind == DecalTexture::Paint) {
            EXPECT_GT(std::min({r, g, b}), 220.0);
            EXPECT_LT(std::max({r, g, b}) - std::min({r, g, b}), 8.0);
        } else {
            EXPECT_GT(r, 3.0 * g);
            EXPECT_LT(r, 160.0);
        }
    }
}
