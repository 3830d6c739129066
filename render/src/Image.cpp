// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/Image.h>

#include "ImageOutputFile.h"

#include <strata/AtomicFile.h>
#include <strata/Error.h>
#include <strata/render/ImageFileInput.h>
#include <strata/render/ImageFileStructure.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

namespace strata::render {

namespace {

namespace fs = std::filesystem;

/// sRGB transfer functions (IEC 61966-2-1), for formats that store linear light.
float srgbToLinear(float c)
{
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float c)
{
    c = std::clamp(c, 0.0f, 1.0f);
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

std::uint8_t toByte(float v)
{
    return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

std::string oiioError(const std::string& objectError) { return detail::oiioErrorLine(objectError); }

/// True for formats whose pixels are linear light, not sRGB-encoded.
bool isLinearFormat(const std::string& formatName)
{
    return formatName == "openexr" || formatName == "hdr";
}

[[noreturn]] void throwWriteError(const fs::path& path, const std::string& reason)
{
    throw Error(ErrorKind::Io, "cannot write image '" + path.string() + "': " + reason, {.file = path.string()});
}

} // namespace

void writeImage(const Image& image, const fs::path& path)
{
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != std::size_t(image.width) * std::size_t(image.height) * 4) {
        throwWriteError(path, "invalid image " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                                  " with " + std::to_string(image.pixels.size()) + " bytes");
    }

    // Encodes into `output`, opened on `name` (the format follows its
    // extension); false with OpenImageIO's error on failure.
    auto encode = [&](OIIO::ImageOutput& output, const std::string& name) {
        const std::string formatName = output.format_name();
        const bool linear = isLinearFormat(formatName);
        const int channels = output.supports("alpha") ? 4 : 3;
        const std::size_t pixelCount = std::size_t(image.width) * std::size_t(image.height);

        OIIO::ImageSpec spec(image.width, image.height, channels,
                             linear ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
        spec.attribute("oiio:ColorSpace", linear ? "Linear" : "sRGB");
        // OpenImageIO's EXR writer stamps the time of writing unless the spec
        // has one: an empty one keeps a snapshot a function of the scene.
        if (formatName == "openexr") spec.attribute("DateTime", "");
        if (channels == 4) {
            // Our alpha is unassociated: do not let the writer un-premultiply.
            spec.attribute("oiio:UnassociatedAlpha", 1);
        }

        bool ok = output.open(name, spec);
        if (ok) {
            if (linear) {
                std::vector<float> data(pixelCount * std::size_t(channels));
                for (std::size_t i = 0; i < pixelCount; ++i) {
                    for (int c = 0; c < channels; ++c) {
                        const float v = image.pixels[i * 4 + std::size_t(c)] / 255.0f;
                        data[i * std::size_t(channels) + std::size_t(c)] = c < 3 ? srgbToLinear(v) : v;
                    }
                }
                ok = output.write_image(OIIO::TypeDesc::FLOAT, data.data());
            } else {
                // xstride 4 bytes: drops alpha when the format has none.
                ok = output.write_image(OIIO::TypeDesc::UINT8, image.pixels.data(), 4);
            }
            ok = output.close() && ok;
        }
        if (!ok) {
            throwWriteError(path, oiioError(output.geterror()));
        }
    };

    detail::writeImageFile(path, encode);
}

Image readImage(const fs::path& path)
{
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::string reader;
    try {
        reader = checkImageFileStructure(path);
    } catch (const Error& e) {
        throw Error(e.kind(), "cannot read image '" + path.string() + "': " + e.what());
    }
    std::string error;
    auto input = ImageFileInput::open(reader, path, config, error);
    if (!input) {
        throw Error(ErrorKind::BadInput, "cannot read image '" + path.string() + "' as a ." + reader + " image: " + error,
                    {.file = path.string()});
    }
    const OIIO::ImageSpec& spec = input->spec();
    const int channels = spec.nchannels;
    if (spec.width <= 0 || spec.height <= 0 || channels <= 0 || spec.depth > 1) {
        throw Error(ErrorKind::BadInput, "cannot read image '" + path.string() + "': unsupported size " + std::to_string(spec.width) +
                    "x" + std::to_string(spec.height) + "x" + std::to_string(spec.depth) + " with " +
                    std::to_string(channels) + " channels");
    }
    try {
        checkImageSizeAgainstFile(path, spec.width, spec.height, channels);
    } catch (const Error& e) {
        throw Error(e.kind(), "cannot read image '" + path.string() + "': " + e.what());
    }
    const std::string colorSpace = spec.get_string_attribute("oiio:ColorSpace");
    const bool linear = isLinearFormat(input->formatName()) || colorSpace == "Linear" ||
                        colorSpace == "lin_srgb" || colorSpace == "scene_linear";
    const int alphaChannel =
        spec.alpha_channel >= 0 ? spec.alpha_channel : (channels == 2 ? 1 : channels >= 4 ? 3 : -1);

    const std::size_t pixelCount = std::size_t(spec.width) * std::size_t(spec.height);
    std::vector<float> data(pixelCount * std::size_t(channels));
    if (!input->readFloat(channels, data.data(), error)) {
        throw Error(ErrorKind::BadInput, "cannot read image '" + path.string() + "': " + error, {.file = path.string()});
    }

    Image image;
    image.width = spec.width;
    image.height = spec.height;
    image.pixels.resize(pixelCount * 4);
    for (std::size_t i = 0; i < pixelCount; ++i) {
        const float* src = data.data() + i * std::size_t(channels);
        float rgb[3];
        if (channels >= 3) {
            rgb[0] = src[0];
            rgb[1] = src[1];
            rgb[2] = src[2];
        } else {
            rgb[0] = rgb[1] = rgb[2] = src[0]; // grey (and grey + alpha)
        }
        std::uint8_t* dst = image.pixels.data() + i * 4;
        for (int c = 0; c < 3; ++c) {
            dst[c] = toByte(linear ? linearToSrgb(rgb[c]) : rgb[c]);
        }
        dst[3] = alphaChannel >= 0 ? toByte(src[alphaChannel]) : 255;
    }
    return image;
}

namespace {

void requireSameSize(const Image& a, const Image& b, const char* what)
{
    if (a.width != b.width || a.height != b.height || a.pixels.size() != b.pixels.size()) {
        throw Error(ErrorKind::BadInput, std::string(what) + ": images differ in size (" + std::to_string(a.width) + "x" +
                    std::to_string(a.height) + " and " + std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
    }
}

} // namespace

double psnr(const Image& a, const Image& b)
{
    requireSameSize(a, b, "psnr");
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < a.pixels.size(); i += 4) {
        for (std::size_t c = 0; c < 3; ++c) {
            const double d = double(a.pixels[i + c]) - double(b.pixels[i + c]);
            sum += d * d;
        }
        count += 3;
    }
    if (count == 0 || sum == 0.0) {
        return std::numeric_limits<double>::infinity();
    }
    return 10.0 * std::log10(255.0 * 255.0 / (sum / double(count)));
}

double fractionWithin(const Image& a, const Image& b, int tolerance)
{
    requireSameSize(a, b, "fractionWithin");
    const std::size_t pixels = a.pixels.size() / 4;
    if (pixels == 0) {
        return 1.0;
    }
    std::size_t within = 0;
    for (std::size_t i = 0; i < a.pixels.size(); i += 4) {
        bool ok = true;
        for (std::size_t c = 0; c < 3; ++c) {
            ok = ok && std::abs(int(a.pixels[i + c]) - int(b.pixels[i + c])) <= tolerance;
        }
        within += ok;
    }
    return double(within) / double(pixels);
}

} // namespace strata::render
