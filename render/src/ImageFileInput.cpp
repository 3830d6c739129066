// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/ImageFileInput.h>

#include <png.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace strata::render {

namespace {

/// `message` in one line, or `fallback` when it is empty.
std::string oneLine(std::string message, const char* fallback)
{
    std::replace(message.begin(), message.end(), '\n', ' ');
    while (!message.empty() && (message.back() == ' ' || message.back() == '\r')) message.pop_back();
    return message.empty() ? fallback : message;
}

/// OpenImageIO's reader: its messages are per object (and per thread for
/// the global one), so nothing needs capturing.
class OiioInput final : public ImageFileInput
{
public:
    explicit OiioInput(std::unique_ptr<OIIO::ImageInput> input)
        : mInput(std::move(input))
    {
    }
    const OIIO::ImageSpec& spec() const override { return mInput->spec(); }
    std::string formatName() const override { return mInput->format_name(); }
    bool readFloat(int channels, float* out, std::string& error) override
    {
        if (mInput->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, out)) return true;
        std::string message = mInput->geterror();
        if (message.empty()) message = OIIO::geterror();
        error = oneLine(message, "unknown OpenImageIO error");
        return false;
    }

private:
    std::unique_ptr<OIIO::ImageInput> mInput;
};

/// Where this read's libpng messages go (one per png_struct, so per call).
struct PngMessages
{
    char error[256] = {};
};

/// libpng's error handler must not return: record the message, jump back to
/// the setjmp of the call that is reading. libpng's default handler would
/// print "libpng error: ..." on stderr first.
[[noreturn]] void onPngError(png_structp png, png_const_charp message)
{
    auto* messages = static_cast<PngMessages*>(png_get_error_ptr(png));
    std::snprintf(messages->error, sizeof(messages->error), "%s", message && *message ? message : "libpng error");
    png_longjmp(png, 1);
}

/// Warnings (an sRGB profile libpng finds odd, ...) change nothing read.
void onPngWarning(png_structp, png_const_charp) {}

/// libpng with the same transformations as OpenImageIO 2.4's PNG reader
/// (palette to RGB, grey below 8 bits to 8, tRNS to alpha, 16 bits in host
/// order), so the pixels and the header are the ones OpenImageIO gives.
/// Between each setjmp and the libpng calls it guards there are only C
/// frames (libpng's own FILE* I/O): the longjmp skips no C++ destructor.
class PngInput final : public ImageFileInput
{
public:
    ~PngInput() override
    {
        if (mPng) png_destroy_read_struct(&mPng, mInfo ? &mInfo : nullptr, nullptr);
        if (mFile) std::fclose(mFile);
    }

    /// Reads the header; false with `error` set on failure.
    bool open(const std::filesystem::path& path, std::string& error)
    {
        mFile = std::fopen(path.c_str(), "rb");
        if (!mFile) {
            error = std::string("cannot open: ") + std::strerror(errno);
            return false;
        }
        mPng = png_create_read_struct(PNG_LIBPNG_VER_STRING, &mMessages, onPngError, onPngWarning);
        if (mPng) mInfo = png_create_info_struct(mPng);
        if (!mPng || !mInfo) {
            error = "libpng could not start a read";
            return false;
        }
        if (setjmp(png_jmpbuf(mPng))) {
            error = oneLine(mMessages.error, "libpng error");
            return false;
        }
        png_init_io(mPng, mFile);
        png_read_info(mPng, mInfo);
        const int colorType = png_get_color_type(mPng, mInfo);
        const int bitDepth = png_get_bit_depth(mPng, mInfo);
        if (colorType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(mPng);
        if (colorType == PNG_COLOR_TYPE_GRAY && bitDepth < 8) png_set_expand_gray_1_2_4_to_8(mPng);
        if (png_get_valid(mPng, mInfo, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(mPng);
        if (png_get_bit_depth(mPng, mInfo) == 16) {
            const std::uint16_t one = 1;
            if (*reinterpret_cast<const unsigned char*>(&one) == 1) png_set_swap(mPng); // PNG is big-endian
        }
        png_set_interlace_handling(mPng); // png_read_image() then runs every pass
        png_read_update_info(mPng, mInfo);

        const int channels = png_get_channels(mPng, mInfo);
        mSixteen = png_get_bit_depth(mPng, mInfo) == 16;
        mSpec = OIIO::ImageSpec(int(png_get_image_width(mPng, mInfo)), int(png_get_image_height(mPng, mInfo)),
                                channels, mSixteen ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8);
        mSpec.alpha_channel = channels == 2 ? 1 : channels == 4 ? 3 : -1;
        // Named as OpenImageIO 2.4 names it: an sRGB chunk or none is sRGB;
        // a gAMA alone gives the gamma to a hundredth, "Linear" at 1.
        int intent = 0;
        double gamma = 0.0;
        std::string colorSpace = "sRGB";
        if (!png_get_sRGB(mPng, mInfo, &intent) && png_get_gAMA(mPng, mInfo, &gamma) && gamma > 0.0) {
            const float g = std::round(100.0f * float(1.0 / gamma)) / 100.0f;
            char name[48];
            std::snprintf(name, sizeof(name), "GammaCorrected%.2g", double(g));
            colorSpace = g == 1.0f ? "Linear" : name;
            mSpec.attribute("oiio:Gamma", g);
        }
        mSpec.attribute("oiio:ColorSpace", colorSpace);
        return true;
    }

    const OIIO::ImageSpec& spec() const override { return mSpec; }
    std::string formatName() const override { return "png"; }

    bool readFloat(int channels, float* out, std::string& error) override
    {
        const std::size_t width = std::size_t(mSpec.width), height = std::size_t(mSpec.height);
        const std::size_t stored = std::size_t(mSpec.nchannels);
        const std::size_t rowBytes = png_get_rowbytes(mPng, mInfo);
        // Allocated before the setjmp below, freed after it returns either way.
        std::vector<unsigned char> pixels(rowBytes * height);
        std::vector<png_bytep> rows(height);
        for (std::size_t y = 0; y < height; ++y) rows[y] = pixels.data() + y * rowBytes;
        if (setjmp(png_jmpbuf(mPng))) {
            error = oneLine(mMessages.error, "libpng error");
            return false;
        }
        png_read_image(mPng, rows.data());
        png_read_end(mPng, nullptr);

        // OpenImageIO's own conversion, so the floats are the ones its
        // read_image() would give.
        std::vector<float> row(width * stored);
        const OIIO::TypeDesc type = mSixteen ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8;
        for (std::size_t y = 0; y < height; ++y) {
            OIIO::convert_pixel_values(type, rows[y], OIIO::TypeDesc::FLOAT, row.data(), int(width * stored));
            for (std::size_t x = 0; x < width; ++x) {
                std::copy_n(row.data() + x * stored, std::size_t(channels), out + (y * width + x) * std::size_t(channels));
            }
        }
        return true;
    }

private:
    std::FILE* mFile = nullptr;
    png_structp mPng = nullptr;
    png_infop mInfo = nullptr;
    PngMessages mMessages;
    OIIO::ImageSpec mSpec;
    bool mSixteen = false;
};

} // namespace

std::unique_ptr<ImageFileInput> ImageFileInput::open(const std::string& reader, const std::filesystem::path& path,
                                                     const OIIO::ImageSpec& config, std::string& error)
{
    if (reader == "png") {
        auto input = std::make_unique<PngInput>();
        if (!input->open(path, error)) return nullptr;
        return input;
    }
    // The extension's reader only: ImageInput::open() would try every other
    // reader in turn when that one refuses the file.
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::create(reader);
    if (!input) {
        error = oneLine(OIIO::geterror(), "no OpenImageIO reader for this format");
        return nullptr;
    }
    OIIO::ImageSpec opened;
    if (!input->open(path.string(), opened, config)) {
        std::string message = input->geterror();
        if (message.empty()) message = OIIO::geterror();
        error = oneLine(message, "unknown OpenImageIO error");
        return nullptr;
    }
    return std::make_unique<OiioInput>(std::move(input));
}

} // namespace strata::render
