// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/Error.h>
#include <strata/render/Image.h>

#include "TestDir.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

namespace fs = std::filesystem;
using strata::render::Image;

Image makePattern(int width, int height)
{
    Image image;
    image.width = width;
    image.height = height;
    image.pixels.resize(std::size_t(width) * height * 4);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            std::uint8_t* p = image.at(x, y);
            p[0] = std::uint8_t(x * 7 + y);
            p[1] = std::uint8_t(y * 13);
            p[2] = std::uint8_t((x ^ y) * 5);
            p[3] = std::uint8_t(255 - ((x + y) % 4) * 60); // unassociated alpha, not premultiplied
        }
    }
    return image;
}

std::size_t countEntries(const fs::path& dir)
{
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) {
        ++n;
    }
    return n;
}

TEST(Image, PngAndTiffRoundTripExactly)
{
    const auto dir = strata::test::freshTestDir();
    const Image image = makePattern(37, 21);
    for (const char* name : {"pattern.png", "pattern.tif", "pattern.tga"}) {
        SCOPED_TRACE(name);
        strata::render::writeImage(image, dir / name);
        const Image back = strata::render::readImage(dir / name);
        EXPECT_EQ(back.width, image.width);
        EXPECT_EQ(back.height, image.height);
        EXPECT_EQ(back.pixels, image.pixels);
    }
    EXPECT_EQ(countEntries(dir), 3u); // no temporary files left behind
}

TEST(Image, ExrStoresLinearLightAndReadsBackSrgb)
{
    const auto dir = strata::test::freshTestDir();
    Image image = makePattern(16, 16);
    for (std::size_t i = 3; i < image.pixels.size(); i += 4) {
        image.pixels[i] = 255;
    }
    strata::render::writeImage(image, dir / "pattern.exr");
    const Image back = strata::render::readImage(dir / "pattern.exr");
    ASSERT_EQ(back.pixels.size(), image.pixels.size());
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        EXPECT_LE(std::abs(int(back.pixels[i]) - int(image.pixels[i])), 1) << "byte " << i;
    }
}

TEST(Image, JpegHasNoAlphaAndReadsBackOpaque)
{
    const auto dir = strata::test::freshTestDir();
    strata::render::writeImage(makePattern(32, 32), dir / "pattern.jpg");
    const Image back = strata::render::readImage(dir / "pattern.jpg");
    ASSERT_EQ(back.width, 32);
    for (std::size_t i = 3; i < back.pixels.size(); i += 4) {
        ASSERT_EQ(back.pixels[i], 255);
    }
}

TEST(Image, OverwritesAnExistingFile)
{
    const auto dir = strata::test::freshTestDir();
    strata::render::writeImage(makePattern(8, 8), dir / "a.png");
    const Image second = makePattern(9, 5);
    strata::render::writeImage(second, dir / "a.png");
    EXPECT_EQ(strata::render::readImage(dir / "a.png").pixels, second.pixels);
    EXPECT_EQ(countEntries(dir), 1u);
}

TEST(Image, WritingIntoAMissingDirectoryThrowsAndLeavesNothing)
{
    const auto dir = strata::test::freshTestDir();
    const fs::path target = dir / "missing" / "out.png";
    try {
        strata::render::writeImage(makePattern(4, 4), target);
        FAIL() << "expected strata::Error";
    } catch (const strata::Error& e) {
        EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir / "missing"));
    EXPECT_EQ(countEntries(dir), 0u);
}

TEST(Image, UnknownExtensionAndInvalidImagesThrow)
{
    const auto dir = strata::test::freshTestDir();
    EXPECT_THROW(strata::render::writeImage(makePattern(4, 4), dir / "out.unknownformat"), strata::Error);
    Image broken;
    broken.width = 4;
    broken.height = 4;
    EXPECT_THROW(strata::render::writeImage(broken, dir / "broken.png"), strata::Error);
    EXPECT_EQ(countEntries(dir), 0u);
}

TEST(Image, ReadingAMissingFileThrowsNamingIt)
{
    const auto dir = strata::test::freshTestDir();
    try {
        strata::render::readImage(dir / "nope.png");
        FAIL() << "expected strata::Error";
    } catch (const strata::Error& e) {
        EXPECT_NE(std::string(e.what()).find("nope.png"), std::string::npos) << e.what();
    }
}

} // namespace
