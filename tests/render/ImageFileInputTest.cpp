// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// render::ImageFileInput: PNG files decoded by libpng with a per-read error
// handler give the same header and floats as OpenImageIO's reader, and a
// corrupt one fails with libpng's reason in the error, nothing on stderr
// and stderr never redirected (file descriptor 2 stays the same file).

#include <strata/Error.h>
#include <strata/render/Image.h>
#include <strata/render/ImageFileInput.h>

#include "TestDir.h"

#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using strata::render::ImageFileInput;

/// A width x height image with `channels` channels of `type`, written by OpenImageIO.
fs::path writePng(const fs::path& path, int width, int height, int channels, OIIO::TypeDesc type,
                  const std::string& colorSpace = {})
{
    OIIO::ImageSpec spec(width, height, channels, type);
    if (!colorSpace.empty()) spec.attribute("oiio:ColorSpace", colorSpace);
    if (channels == 2 || channels == 4) spec.alpha_channel = channels - 1;
    std::vector<float> values(std::size_t(width) * std::size_t(height) * std::size_t(channels));
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = float((i * 2654435761u) % 65536u) / 65535.0f;
    auto out = OIIO::ImageOutput::create(path.string());
    EXPECT_TRUE(out && out->open(path.string(), spec));
    EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, values.data()));
    out->close();
    return path;
}

std::string readBytes(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// What this process writes on file descriptor 2 while `run` runs (the
/// test's own capture; the library must not need one).
template<typename Run>
std::string stderrDuring(Run run)
{
    std::fflush(stderr);
    char name[] = "/tmp/strata-test-stderr-XXXXXX";
    const int capture = ::mkstemp(name);
    ::unlink(name);
    const int saved = ::dup(2);
    ::dup2(capture, 2);
    run();
    std::fflush(stderr);
    ::dup2(saved, 2);
    ::close(saved);
    std::string text(4096, '\0');
    const ssize_t n = ::pread(capture, text.data(), text.size(), 0);
    ::close(capture);
    text.resize(n > 0 ? std::size_t(n) : 0);
    return text;
}

} // namespace

TEST(ImageFileInput, PngGivesTheHeaderAndFloatsOpenImageIoGives)
{
    const fs::path dir = strata::test::freshTestDir();
    struct Case
    {
        int channels;
        OIIO::TypeDesc type;
        std::string colorSpace; // written as a gAMA chunk (or none)
    };
    for (const Case& c : {Case{1, OIIO::TypeDesc::UINT8, ""}, Case{3, OIIO::TypeDesc::UINT8, "Linear"},
                          Case{4, OIIO::TypeDesc::UINT8, ""}, Case{1, OIIO::TypeDesc::UINT16, "Linear"},
                          Case{2, OIIO::TypeDesc::UINT16, "GammaCorrected2.2"}, Case{4, OIIO::TypeDesc::UINT16, ""}}) {
        const std::string what = std::to_string(c.channels) + " x " + c.type.c_str() + " " + c.colorSpace;
        const fs::path path = writePng(dir / ("c" + std::to_string(c.channels) + c.type.c_str() + c.colorSpace + ".png"),
                                       37, 23, c.channels, c.type, c.colorSpace);
        OIIO::ImageSpec config;
        config.attribute("oiio:UnassociatedAlpha", 1);
        std::string error;
        auto mine = ImageFileInput::open("png", path, config, error);
        ASSERT_TRUE(mine) << what << ": " << error;
        auto theirs = OIIO::ImageInput::open(path.string(), &config);
        ASSERT_TRUE(theirs) << what;
        const OIIO::ImageSpec a = mine->spec(); // a copy: `mine` is reopened below
        const OIIO::ImageSpec& b = theirs->spec();
        EXPECT_EQ(a.width, b.width) << what;
        EXPECT_EQ(a.height, b.height) << what;
        EXPECT_EQ(a.depth, b.depth) << what;
        EXPECT_EQ(a.nchannels, b.nchannels) << what;
        EXPECT_EQ(a.alpha_channel, b.alpha_channel) << what;
        EXPECT_EQ(a.get_string_attribute("oiio:ColorSpace"), b.get_string_attribute("oiio:ColorSpace")) << what;
        EXPECT_EQ(a.get_float_attribute("oiio:Gamma"), b.get_float_attribute("oiio:Gamma")) << what;
        EXPECT_EQ(mine->formatName(), theirs->format_name()) << what;
        for (int channels = 1; channels <= c.channels; ++channels) {
            std::vector<float> x(std::size_t(a.width) * std::size_t(a.height) * std::size_t(channels), -1.0f);
            std::vector<float> y(x.size(), -2.0f);
            ASSERT_TRUE(mine->readFloat(channels, x.data(), error)) << what << ": " << error;
            mine = ImageFileInput::open("png", path, config, error); // a read consumes the file
            ASSERT_TRUE(theirs->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, y.data())) << what;
            EXPECT_EQ(x, y) << what << ", first " << channels << " channel(s)";
        }
    }
}

TEST(ImageFileInput, ACorruptPngFailsWithLibpngsReasonAndPrintsNothing)
{
    const fs::path dir = strata::test::freshTestDir();
    const std::string good = readBytes(writePng(dir / "good.png", 16, 16, 3, OIIO::TypeDesc::UINT8));
    const std::size_t idat = good.find("IDAT");
    ASSERT_NE(idat, std::string::npos);
    const std::size_t length = (std::size_t(std::uint8_t(good[idat - 4])) << 24) | (std::size_t(std::uint8_t(good[idat - 3])) << 16) |
                               (std::size_t(std::uint8_t(good[idat - 2])) << 8) | std::size_t(std::uint8_t(good[idat - 1]));
    std::string badCrc = good;
    badCrc[idat + 4 + length] = char(badCrc[idat + 4 + length] ^ 0x5a);
    std::ofstream(dir / "badcrc.png", std::ios::binary) << badCrc;

    std::string message;
    std::atomic<bool> redirected{false};
    const std::string printed = stderrDuring([&] {
        struct stat before{};
        ASSERT_EQ(::fstat(2, &before), 0);
        std::atomic<bool> done{false};
        // Another thread watches fd 2 throughout the reads: it must stay the same file.
        std::thread watcher([&] {
            while (!done) {
                struct stat now{};
                if (::fstat(2, &now) != 0 || now.st_ino != before.st_ino || now.st_dev != before.st_dev) redirected = true;
            }
        });
        for (int i = 0; i < 50; ++i) {
            try {
                strata::render::readImage(dir / "badcrc.png");
            } catch (const strata::Error& e) {
                message = e.what();
            }
        }
        done = true;
        watcher.join();
    });
    EXPECT_NE(message.find("badcrc.png"), std::string::npos) << message;
    EXPECT_NE(message.find("CRC error"), std::string::npos) << message;
    EXPECT_EQ(printed, "") << "the read printed on stderr";
    EXPECT_FALSE(redirected) << "file descriptor 2 was pointed elsewhere during the read";
}
