// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Reading a material map from its file (Texture.h's loadMapImage()), apart
// from the texture code so programs that build textures in memory link no
// image file libraries.

#include <strata/render/Texture.h>

#include "SrgbEncoding.h"

#include <strata/Error.h>
#include <strata/render/ImageFileInput.h>
#include <strata/render/ImageFileStructure.h>

#include <OpenImageIO/imageio.h>

namespace strata::render {

using detail::linearToSrgbValue;
using detail::toByte;

Image loadMapImage(const std::filesystem::path& path, MapKind kind, int minChannels, const std::string& what)
{
    auto fail = [&](const std::string& why) -> Error { return Error(ErrorKind::BadInput, what + ": '" + path.string() + "': " + why); };
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw fail("no such file");
    if (!std::filesystem::is_regular_file(path, ec)) throw fail("is not a file");
    std::string reader;
    try {
        reader = checkImageFileStructure(path);
    } catch (const Error& e) {
        throw fail(e.what());
    }
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::string error;
    auto input = ImageFileInput::open(reader, path, config, error);
    if (!input) {
        throw fail("cannot read as a ." + reader + " image: " + error);
    }
    const OIIO::ImageSpec& spec = input->spec();
    const int channels = spec.nchannels;
    if (spec.width <= 0 || spec.height <= 0 || spec.depth > 1 || channels <= 0) {
        throw fail("unsupported image size");
    }
    if (spec.width > MAX_MAP_SIZE || spec.height > MAX_MAP_SIZE) {
        throw fail("is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                   " pixels: maps may be at most " + std::to_string(MAX_MAP_SIZE) + " on a side");
    }
    if (channels < minChannels) {
        throw fail("has " + std::to_string(channels) + " channel(s), the map needs " + std::to_string(minChannels));
    }
    try {
        checkImageSizeAgainstFile(path, spec.width, spec.height, channels);
    } catch (const Error& e) {
        throw fail(e.what());
    }
    const std::string format = input->formatName();
    const std::string colorSpace = spec.get_string_attribute("oiio:ColorSpace");
    const bool fileLinear = format == "openexr" || format == "hdr" || colorSpace == "Linear" ||
                            colorSpace == "lin_srgb" || colorSpace == "scene_linear";
    std::vector<float> data(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(channels));
    if (!input->readFloat(channels, data.data(), error)) {
        throw fail("cannot read: " + error);
    }
    Image image;
    image.width = spec.width;
    image.height = spec.height;
    image.pixels.resize(std::size_t(spec.width) * std::size_t(spec.height) * 4);
    const bool srgb = isSrgb(kind);
    const int alpha = spec.alpha_channel >= 0 ? spec.alpha_channel : (channels == 2 ? 1 : channels >= 4 ? 3 : -1);
    for (std::size_t i = 0; i < std::size_t(spec.width) * std::size_t(spec.height); ++i) {
        const float* s = data.data() + i * std::size_t(channels);
        std::uint8_t* d = image.pixels.data() + i * 4;
        for (int c = 0; c < 3; ++c) {
            float v = channels >= 3 ? s[c] : s[0];
            // Colour maps from linear files are encoded; data maps keep their values.
            if (srgb && fileLinear) v = linearToSrgbValue(v);
            d[c] = toByte(v);
        }
        d[3] = alpha >= 0 ? toByte(s[alpha]) : 255;
    }
    return image;
}

} // namespace strata::render
