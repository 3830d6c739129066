// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// render::DataImage: heightmaps, weight maps and masks written and read
// without colour transforms; and the time stamp EXR writers add.

#include <strata/Error.h>
#include <strata/render/DataImage.h>
#include <strata/render/Image.h>

#include "TestDir.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>

using namespace strata::render;

namespace {

std::string fileBytes(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream out;
    out << in.rdbuf();
    return out.str();
}

template <typename T>
DataImage ramp(int width, int height, int channels, SampleType type, T scale)
{
    DataImage image{width, height, channels, type, {}};
    image.bytes.resize(std::size_t(width) * height * channels * sizeof(T));
    auto* samples = reinterpret_cast<T*>(image.bytes.data());
    for (std::size_t i = 0; i < std::size_t(width) * height * channels; ++i) samples[i] = T(T(i % 251) * scale);
    return image;
}

} // namespace

TEST(DataImage, SamplesRoundTripExactlyInEveryTypeAndFormat)
{
    const auto dir = strata::test::freshTestDir();
    const std::vector<std::pair<DataImage, std::string>> cases = {
        {ramp<std::uint8_t>(17, 9, 1, SampleType::UInt8, 1), "grey8.png"},
        {ramp<std::uint8_t>(17, 9, 4, SampleType::UInt8, 1), "rgba8.png"},
        {ramp<std::uint16_t>(33, 5, 1, SampleType::UInt16, 261), "grey16.png"},
        {ramp<float>(8, 8, 1, SampleType::Float32, -0.37f), "height.exr"},
    };
    for (const auto& [image, name] : cases) {
        writeDataImage(image, dir / name);
        const DataImage back = readDataImage(dir / name);
        EXPECT_EQ(back.width, image.width) << name;
        EXPECT_EQ(back.height, image.height) << name;
        EXPECT_EQ(back.channels, image.channels) << name;
        EXPECT_EQ(int(back.type), int(image.type)) << name;
        EXPECT_EQ(back.bytes, image.bytes) << name << ": no gamma, no premultiplied alpha";
    }
    // A zero alpha keeps the other channels (weights, not colour).
    DataImage rgba{1, 1, 4, SampleType::UInt8, {200, 40, 15, 0}};
    writeDataImage(rgba, dir / "zero-alpha.png");
    EXPECT_EQ(readDataImage(dir / "zero-alpha.png").bytes, rgba.bytes);
}

TEST(DataImage, BadImagesAreRefusedNamingThePath)
{
    const auto dir = strata::test::freshTestDir();
    DataImage wrong{4, 4, 1, SampleType::UInt16, std::vector<std::uint8_t>(10)};
    try {
        writeDataImage(wrong, dir / "wrong.png");
        FAIL() << "a size mismatch was written";
    } catch (const strata::Error& e) {
        EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput);
        EXPECT_NE(std::string(e.what()).find("wrong.png"), std::string::npos) << e.what();
    }
    const DataImage floats = ramp<float>(2, 2, 1, SampleType::Float32, 1.0f);
    EXPECT_THROW(writeDataImage(floats, dir / "floats.png"), strata::Error);
    EXPECT_THROW(readDataImage(dir / "missing.png"), strata::Error);
    EXPECT_TRUE(std::filesystem::is_empty(dir)) << "nothing half-written";
}

TEST(DataImage, ExrFilesCarryNoTimeStamp)
{
    // OpenImageIO's EXR writer records the time of writing (capDate) unless
    // told otherwise; then the same data gives other bytes each second.
    const auto dir = strata::test::freshTestDir();
    const std::regex stamp(R"(\d{4}:\d\d:\d\d \d\d:\d\d:\d\d)");
    writeDataImage(ramp<float>(4, 4, 1, SampleType::Float32, 0.5f), dir / "data.exr");
    EXPECT_FALSE(std::regex_search(fileBytes(dir / "data.exr"), stamp));
    Image snapshot{4, 4, std::vector<std::uint8_t>(64, 128)};
    writeImage(snapshot, dir / "snapshot.exr");
    EXPECT_FALSE(std::regex_search(fileBytes(dir / "snapshot.exr"), stamp));
}
