// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/Error.h>
#include <strata/render/Image.h>
#include <strata/render/ProceduralTextures.h>

#include "TestDir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace {

using strata::render::Image;

struct Stats
{
    double mean[3] = {0, 0, 0};
    double lumaStdDev = 0;
};

Stats statsOf(const Image& image)
{
    Stats s;
    double sumL = 0;
    double sumL2 = 0;
    const double n = double(image.width) * image.height;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const std::uint8_t* p = image.at(x, y);
            for (int c = 0; c < 3; ++c) {
                s.mean[c] += p[c] / n;
            }
            const double l = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            sumL += l;
            sumL2 += l * l;
        }
    }
    s.lumaStdDev = std::sqrt(std::max(0.0, sumL2 / n - (sumL / n) * (sumL / n)));
    return s;
}

/// Mean absolute difference across the wrap-around seam vs between
/// neighbouring columns/rows inside the image.
void expectTileable(const Image& image)
{
    auto diff = [&](int x0, int y0, int x1, int y1) {
        const std::uint8_t* a = image.at(x0, y0);
        const std::uint8_t* b = image.at(x1, y1);
        return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
    };
    const int n = image.width;
    double seamX = 0, seamY = 0, insideX = 0, insideY = 0;
    for (int i = 0; i < n; ++i) {
        seamX += diff(n - 1, i, 0, i);
        seamY += diff(i, n - 1, i, 0);
        insideX += diff(n / 2 - 1, i, n / 2, i);
        insideY += diff(i, n / 2 - 1, i, n / 2);
    }
    EXPECT_LT(seamX, 1.5 * insideX + 3.0 * n);
    EXPECT_LT(seamY, 1.5 * insideY + 3.0 * n);
}

std::uint64_t fnv1a(const Image& image)
{
    std::uint64_t h = 1469598103934665603ULL;
    for (std::uint8_t b : image.pixels) {
        h = (h ^ b) * 1099511628211ULL;
    }
    return h;
}

TEST(ProceduralTextures, SameSeedGivesTheSameBytesOtherSeedsOthers)
{
    for (auto* make : {&strata::render::makeRockAlbedo, &strata::render::makeGrassAlbedo}) {
        const Image a = make(64, 7);
        const Image b = make(64, 7);
        const Image c = make(64, 8);
        ASSERT_EQ(a.width, 64);
        ASSERT_EQ(a.height, 64);
        ASSERT_EQ(a.pixels.size(), 64u * 64u * 4u);
        EXPECT_EQ(a.pixels, b.pixels);
        EXPECT_NE(a.pixels, c.pixels);
    }
}

TEST(ProceduralTextures, BytesAreStableAcrossBuilds)
{
    // Integer hashing and exactly rounded float operations only: these
    // checksums hold on every IEEE machine. Update them (deliberately) when
    // the look of a texture changes.
    const std::uint64_t rock = fnv1a(strata::render::makeRockAlbedo(32, 1));
    const std::uint64_t grass = fnv1a(strata::render::makeGrassAlbedo(32, 1));
    EXPECT_EQ(rock, 0xc21a606a9e9c6e76ULL) << std::hex << "rock is now 0x" << rock;
    EXPECT_EQ(grass, 0x96925f933d945de5ULL) << std::hex << "grass is now 0x" << grass;
}

TEST(ProceduralTextures, RockIsVariedGreyBrownAndTileable)
{
    const Image rock = strata::render::makeRockAlbedo(256, 1);
    const Stats s = statsOf(rock);
    EXPECT_GT(s.lumaStdDev, 8.0);
    EXPECT_GT(s.mean[0], 70.0);
    EXPECT_LT(s.mean[0], 190.0);
    // Grey-brown: red ≥ green ≥ blue, but not far apart.
    EXPECT_GE(s.mean[0], s.mean[1]);
    EXPECT_GE(s.mean[1], s.mean[2]);
    EXPECT_LT(s.mean[0] - s.mean[2], 40.0);
    for (int y = 0; y < rock.height; ++y) {
        for (int x = 0; x < rock.width; ++x) {
            ASSERT_EQ(rock.at(x, y)[3], 255);
        }
    }
    expectTileable(rock);
}

TEST(ProceduralTextures, GrassIsVariedGreenAndTileable)
{
    const Image grass = strata::render::makeGrassAlbedo(256, 1);
    const Stats s = statsOf(grass);
    EXPECT_GT(s.lumaStdDev, 6.0);
    EXPECT_GT(s.mean[1], s.mean[0]);
    EXPECT_GT(s.mean[1], s.mean[2] + 30.0);
    expectTileable(grass);
}

TEST(ProceduralTextures, RejectsSizesThatAreNotPowersOfTwo)
{
    EXPECT_THROW(strata::render::makeRockAlbedo(100, 1), strata::Error);
    EXPECT_THROW(strata::render::makeGrassAlbedo(8, 1), strata::Error);
    EXPECT_THROW(strata::render::makeGrassAlbedo(0, 1), strata::Error);
    EXPECT_NO_THROW(strata::render::makeRockAlbedo(16, 1));
}

TEST(ProceduralTextures, WritesPngsToLookAt)
{
    const auto dir = strata::test::freshTestDir();
    strata::render::writeImage(strata::render::makeRockAlbedo(512, 1), dir / "rock.png");
    strata::render::writeImage(strata::render::makeGrassAlbedo(512, 1), dir / "grass.png");
    EXPECT_TRUE(std::filesystem::exists(dir / "rock.png"));
    EXPECT_TRUE(std::filesystem::exists(dir / "grass.png"));
}

} // namespace

// --- Built-in texture sets ------------------------------------------------------

namespace {

using strata::render::BuiltinSet;
using strata::render::TextureSetImages;

double channelMean(const Image& image, int channel)
{
    double sum = 0.0;
    for (std::size_t i = std::size_t(channel); i < image.pixels.size(); i += 4) sum += image.pixels[i];
    return sum / double(image.width * image.height) / 255.0;
}

} // namespace

TEST(BuiltinSets, EverySetHasEveryMapDeterministically)
{
    for (BuiltinSet set : {BuiltinSet::Rock, BuiltinSet::Grass, BuiltinSet::Soil, BuiltinSet::Sand, BuiltinSet::Snow,
                           BuiltinSet::Circuitry}) {
        SCOPED_TRACE(strata::render::builtinSetName(set));
        EXPECT_EQ(strata::render::builtinSetFromName(strata::render::builtinSetName(set)), set);
        const TextureSetImages a = strata::render::makeBuiltinSet(set, 128, 5);
        const TextureSetImages b = strata::render::makeBuiltinSet(set, 128, 5);
        for (const Image* map : {&a.albedo, &a.mohs, &a.normal, &a.detail, &a.emission}) {
            EXPECT_EQ(map->width, 128);
            EXPECT_EQ(map->height, 128);
            EXPECT_EQ(map->pixels.size(), 128u * 128u * 4u);
        }
        EXPECT_EQ(a.albedo.pixels, b.albedo.pixels);
        EXPECT_EQ(a.mohs.pixels, b.mohs.pixels);
        EXPECT_EQ(a.normal.pixels, b.normal.pixels);
        // Normals are unit length and point out of the surface (+Z).
        for (std::size_t i = 0; i < a.normal.pixels.size(); i += 4) {
            const double x = a.normal.pixels[i] / 127.5 - 1.0, y = a.normal.pixels[i + 1] / 127.5 - 1.0,
                         z = a.normal.pixels[i + 2] / 127.5 - 1.0;
            ASSERT_NEAR(std::sqrt(x * x + y * y + z * z), 1.0, 0.02);
            ASSERT_GT(z, 0.3);
        }
        // Detail maps are centred on neutral grey; heights span the range.
        EXPECT_NEAR(channelMean(a.detail, 0), 0.5, 0.1);
        EXPECT_NEAR(channelMean(a.detail, 2), 0.5, 0.1);
        EXPECT_GT(channelMean(a.mohs, 2), 0.1);
        EXPECT_LT(channelMean(a.mohs, 2), 0.9);
        // Only the circuitry glows; only its traces are metal.
        EXPECT_EQ(channelMean(a.emission, 2) > 0.0, set == BuiltinSet::Circuitry);
        EXPECT_EQ(channelMean(a.mohs, 0) > 0.0, set == BuiltinSet::Circuitry);
    }
    EXPECT_FALSE(strata::render::builtinSetFromName("marble"));
    EXPECT_THROW(strata::render::makeBuiltinSet(BuiltinSet::Snow, 100, 1), strata::Error);
}
