// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Texture maps: mip chains, channel remapping, loading, packing, and the CPU
// sampler against hand-computed GL filtering.

#include <strata/Error.h>
#include <strata/render/Image.h>
#include <strata/render/Texture.h>

#include "TestDir.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/type_precision.hpp>
#include <glm/vec3.hpp>

#include <cmath>

namespace {

using namespace strata::render;

/// A w×h image from a function of (x, y) in image rows (top to bottom).
template <typename F> Image makeImage(int w, int h, F&& f)
{
    Image image;
    image.width = w;
    image.height = h;
    image.pixels.resize(std::size_t(w) * std::size_t(h) * 4);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const glm::u8vec4 c = f(x, y);
            std::uint8_t* p = image.at(x, y);
            p[0] = c.r;
            p[1] = c.g;
            p[2] = c.b;
            p[3] = c.a;
        }
    }
    return image;
}

/// 2×2 linear texture, image rows top to bottom: top row 0, 100; bottom row 200, 50 (R).
TexturePtr twoByTwo(MapKind kind)
{
    const std::uint8_t values[2][2] = {{0, 100}, {200, 50}};
    return makeTexture(makeImage(2, 2,
                                 [&](int x, int y) {
                                     const std::uint8_t v = values[y][x];
                                     return glm::u8vec4(v, v, v, 255);
                                 }),
                       kind);
}

TEST(Texture, LevelsAreStoredBottomUpWithHalvingSizes)
{
    const TexturePtr t =
        makeTexture(makeImage(8, 4, [](int x, int y) { return glm::u8vec4(x * 30, y * 60, 0, 255); }), MapKind::Mask);
    ASSERT_EQ(t->levels.size(), 4u); // 8x4, 4x2, 2x1, 1x1
    EXPECT_EQ(t->levels[1].width, 4);
    EXPECT_EQ(t->levels[1].height, 2);
    EXPECT_EQ(t->levels[3].width, 1);
    EXPECT_EQ(t->levels[3].height, 1);
    // Texel (0, 0) of level 0 is the image's bottom-left pixel.
    EXPECT_EQ(t->levels[0].texels[1], 3 * 60);
    EXPECT_FALSE(t->srgb);
    EXPECT_TRUE(makeTexture(makeImage(1, 1, [](int, int) { return glm::u8vec4(0); }), MapKind::Albedo)->srgb);
}

TEST(Texture, SrgbMipsAverageInLinearSpace)
{
    // Black and white texels: the linear average 0.5 is sRGB 188, not 128.
    const TexturePtr t = makeTexture(makeImage(2, 1,
                                               [](int x, int) {
                                                   const std::uint8_t v = x == 0 ? 0 : 255;
                                                   return glm::u8vec4(v, v, v, 255);
                                               }),
                                     MapKind::Albedo);
    EXPECT_EQ(t->levels[1].texels[0], 188);
    const TexturePtr linear = makeTexture(makeImage(2, 1,
                                                    [](int x, int) {
                                                        const std::uint8_t v = x == 0 ? 0 : 255;
                                                        return glm::u8vec4(v, v, v, 255);
                                                    }),
                                          MapKind::Mask);
    EXPECT_EQ(linear->levels[1].texels[0], 128);
}

TEST(Texture, NormalMipsAreRenormalised)
{
    // Two opposite tilts average to (0, 0, 0.8): renormalised to (0, 0, 1).
    const TexturePtr t = makeTexture(
        makeImage(2, 2,
                  [](int x, int) { return x == 0 ? glm::u8vec4(51, 128, 230, 255) : glm::u8vec4(204, 128, 230, 255); }),
        MapKind::Normal);
    const std::uint8_t* n = t->levels[1].texels.data();
    const glm::vec3 v = glm::vec3(n[0], n[1], n[2]) / 255.0f * 2.0f - 1.0f;
    EXPECT_NEAR(glm::length(v), 1.0f, 0.02f);
    EXPECT_EQ(n[2], 255);
}

TEST(Texture, DetailMipsFadeToNeutralGrey)
{
    MipOptions mips;
    mips.detailFadeStart = 1.0f;
    mips.detailFadeEnd = 3.0f;
    const TexturePtr t =
        makeTexture(makeImage(16, 16, [](int, int) { return glm::u8vec4(255, 0, 255, 255); }), MapKind::Detail, mips);
    EXPECT_EQ(t->levels[0].texels[0], 255);
    EXPECT_EQ(t->levels[1].texels[0], 255); // level 1: fade 0
    EXPECT_EQ(t->levels[2].texels[0], 191); // level 2: half way to 0.5
    EXPECT_EQ(t->levels[3].texels[0], 128); // level 3 and beyond: neutral
    EXPECT_EQ(t->levels[4].texels[1], 128);
    // Other kinds do not fade.
    const TexturePtr albedo =
        makeTexture(makeImage(16, 16, [](int, int) { return glm::u8vec4(255, 0, 255, 255); }), MapKind::Mask, mips);
    EXPECT_EQ(albedo->levels[4].texels[0], 255);
}

TEST(Texture, ChannelRemappingAndGreenFlip)
{
    Image image = makeImage(1, 1, [](int, int) { return glm::u8vec4(10, 20, 30, 40); });
    ChannelMapping mapping;
    mapping.channels[0] = parseChannelSource("a", "test");
    mapping.channels[1] = parseChannelSource("1-r", "test");
    mapping.channels[2] = parseChannelSource("0", "test");
    mapping.channels[3] = parseChannelSource("1", "test");
    const Image out = remapChannels(image, mapping);
    EXPECT_EQ(out.pixels, (std::vector<std::uint8_t>{40, 245, 0, 255}));
    EXPECT_THROW(parseChannelSource("x", "material.maps.mask.channels"), strata::Error);
    flipGreen(image);
    EXPECT_EQ(image.pixels[1], 235);
}

TEST(Texture, PackMohsFromSeparateImages)
{
    const Image metallic = makeImage(2, 1, [](int x, int) { return glm::u8vec4(x * 255, 0, 0, 255); });
    const Image smooth = makeImage(2, 1, [](int, int) { return glm::u8vec4(77, 0, 0, 255); });
    const Image packed = packMohs(&metallic, nullptr, nullptr, &smooth);
    EXPECT_EQ(packed.pixels, (std::vector<std::uint8_t>{0, 255, 128, 77, 255, 255, 128, 77}));
    const Image other = makeImage(3, 1, [](int, int) { return glm::u8vec4(0); });
    EXPECT_THROW(packMohs(&metallic, &other, nullptr, nullptr), strata::Error);
}

TEST(Texture, LoadKeepsUnassociatedAlphaAndChecksChannels)
{
    const auto dir = strata::test::freshTestDir();
    // Height in the alpha of a normal map: a premultiplying loader would darken RGB.
    const Image normal = makeImage(4, 4, [](int x, int) { return glm::u8vec4(128, 128, 255, x * 60); });
    writeImage(normal, dir / "normal.png");
    const Image loaded = loadMapImage(dir / "normal.png", MapKind::Normal, 4, "material m, map normal");
    EXPECT_EQ(loaded.pixels, normal.pixels);
    // Grey file where four channels are needed.
    writeImage(makeImage(2, 2, [](int, int) { return glm::u8vec4(9, 9, 9, 255); }), dir / "grey.jpg");
    try {
        loadMapImage(dir / "grey.jpg", MapKind::Mask, 4, "material m, map mask");
        FAIL() << "no error";
    } catch (const strata::Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("material m, map mask"), std::string::npos) << what;
        EXPECT_NE(what.find("grey.jpg"), std::string::npos) << what;
        EXPECT_NE(what.find("channel"), std::string::npos) << what;
    }
    EXPECT_THROW(loadMapImage(dir / "missing.png", MapKind::Albedo, 1, "material m, map albedo"), strata::Error);
}

TEST(Texture, LoadsEveryFormatWithTheColourSpaceOfTheMap)
{
    const auto dir = strata::test::freshTestDir();
    const Image image = makeImage(8, 4, [](int x, int y) { return glm::u8vec4(x * 30, y * 60, 200, 40 + x * 20); });
    // 8-bit formats keep the stored values for every kind of map, alpha unassociated.
    for (const char* name : {"map.png", "map.tga", "map.tif"}) {
        writeImage(image, dir / name);
        EXPECT_EQ(loadMapImage(dir / name, MapKind::Albedo, 4, "m").pixels, image.pixels) << name;
        EXPECT_EQ(loadMapImage(dir / name, MapKind::Mask, 4, "m").pixels, image.pixels) << name;
    }
    // EXR is linear: an albedo map is encoded back to sRGB (the same bytes,
    // within half-float rounding); a data map keeps the linear values.
    writeImage(image, dir / "map.exr");
    const Image albedo = loadMapImage(dir / "map.exr", MapKind::Albedo, 4, "m");
    const Image mask = loadMapImage(dir / "map.exr", MapKind::Mask, 4, "m");
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        EXPECT_NEAR(int(albedo.pixels[i]), int(image.pixels[i]), 1) << i;
        if (i % 4 < 3) {
            EXPECT_NEAR(mask.pixels[i] / 255.0f, srgbByteToLinear(image.pixels[i]), 0.5f / 255.0f + 1e-3f) << i;
        }
    }
    // JPEG has no alpha: three channels.
    writeImage(image, dir / "map.jpg");
    EXPECT_NO_THROW(loadMapImage(dir / "map.jpg", MapKind::Albedo, 3, "m"));
    EXPECT_THROW(loadMapImage(dir / "map.jpg", MapKind::Mask, 4, "m"), strata::Error);
}

// --- The sampler ------------------------------------------------------------------

TEST(TextureSampler, BilinearAtTexelCentresAndBetween)
{
    const TexturePtr t = twoByTwo(MapKind::Mask);
    // GL rows bottom to top: texel (0,0) = 200, (1,0) = 50, (0,1) = 0, (1,1) = 100.
    EXPECT_NEAR(sampleBilinear(*t, 0, {0.25f, 0.25f}).r, 200.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(sampleBilinear(*t, 0, {0.75f, 0.75f}).r, 100.0f / 255.0f, 1e-6f);
    // Centre of the texture: the average of the four.
    EXPECT_NEAR(sampleBilinear(*t, 0, {0.5f, 0.5f}).r, 87.5f / 255.0f, 1e-6f);
    // u = 0.375: a quarter of the way from texel 0 to texel 1 along the bottom row.
    EXPECT_NEAR(sampleBilinear(*t, 0, {0.375f, 0.25f}).r, (0.75f * 200 + 0.25f * 50) / 255.0f, 1e-6f);
    // REPEAT: u = 0 is half way between texel 1 (wrapped) and texel 0.
    EXPECT_NEAR(sampleBilinear(*t, 0, {0.0f, 0.25f}).r, 125.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(sampleBilinear(*t, 0, {-3.0f, 5.25f}).r, 125.0f / 255.0f, 1e-5f);
}

TEST(TextureSampler, SrgbIsDecodedBeforeFiltering)
{
    const TexturePtr t = twoByTwo(MapKind::Albedo);
    const float expected =
        0.25f * (srgbByteToLinear(0) + srgbByteToLinear(100) + srgbByteToLinear(200) + srgbByteToLinear(50));
    EXPECT_NEAR(sampleBilinear(*t, 0, {0.5f, 0.5f}).r, expected, 1e-6f);
    EXPECT_NEAR(srgbByteToLinear(128), 0.2158605f, 1e-6f);
    EXPECT_EQ(srgbByteToLinear(255), 1.0f);
    // Alpha stays linear.
    EXPECT_EQ(sampleBilinear(*t, 0, {0.5f, 0.5f}).a, 1.0f);
}

TEST(TextureSampler, TrilinearLodFromDerivatives)
{
    // 4×4 with a distinct constant value per level after filtering: a
    // checker whose mips are known. Level 0 alternates 0/255 (R), level 1 is
    // the 2×2 average 128 (rounded 127.5), level 2 too.
    const TexturePtr t = makeTexture(makeImage(4, 4,
                                               [](int x, int y) {
                                                   const std::uint8_t v = ((x + y) & 1) ? 255 : 0;
                                                   return glm::u8vec4(v, v, v, 255);
                                               }),
                                     MapKind::Mask);
    ASSERT_EQ(t->levels.size(), 3u);
    EXPECT_EQ(textureLod(*t, {0.25f, 0.0f}, {0.0f, 0.25f}), 0.0f); // one texel per pixel
    EXPECT_NEAR(textureLod(*t, {0.5f, 0.0f}, {0.0f, 0.1f}), 1.0f, 1e-6f);
    EXPECT_NEAR(textureLod(*t, {0.3f, 0.4f}, {0.0f, 0.1f}), std::log2(2.0f), 1e-6f); // |(1.2, 1.6)| = 2
    // λ = 0.5 at a level-0 texel centre: half the texel, half level 1's value.
    const glm::vec2 uv{0.125f, 0.125f};
    const float l0 = sampleBilinear(*t, 0, uv).r;
    const float l1 = sampleBilinear(*t, 1, uv).r;
    const float d = std::sqrt(2.0f) / 4.0f; // ρ = √2 texels → λ = 0.5
    EXPECT_NEAR(sampleTrilinear(*t, uv, {d, 0.0f}, {0.0f, 0.0f}).r, 0.5f * (l0 + l1), 1e-6f);
    EXPECT_NEAR(l0, 1.0f, 1e-6f); // texel (0, 0) is the image's bottom-left pixel (0, 3): white
    EXPECT_NEAR(l1, 128.0f / 255.0f, 1e-6f);
    // Magnification (λ < 0) is plain bilinear on level 0; beyond the last level, the last level.
    EXPECT_EQ(sampleTrilinear(*t, uv, {0.01f, 0.0f}, {0.0f, 0.01f}), sampleBilinear(*t, 0, uv));
    EXPECT_EQ(sampleTrilinear(*t, uv, {100.0f, 0.0f}, {0.0f, 0.0f}), sampleBilinear(*t, 2, uv));
    EXPECT_EQ(sampleTrilinear(*t, uv, {0.0f, 0.0f}, {0.0f, 0.0f}), sampleBilinear(*t, 0, uv));
}

} // namespace
