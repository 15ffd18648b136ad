#include "spatter/render/DecalTextures.hpp"

#include <gtest/gtest.h>

#include <cmath>

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
