// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/DataImage.h>

#include "ImageOutputFile.h"

#include <strata/Error.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <string>

namespace strata::render {

namespace {

namespace fs = std::filesystem;

OIIO::TypeDesc typeOf(SampleType type)
{
    switch (type) {
    case SampleType::UInt8: return OIIO::TypeDesc::UINT8;
    case SampleType::UInt16: return OIIO::TypeDesc::UINT16;
    case SampleType::Float32: return OIIO::TypeDesc::FLOAT;
    }
    return OIIO::TypeDesc::UINT8;
}

} // namespace

void writeDataImage(const DataImage& image, const fs::path& path)
{
    const std::size_t samples = std::size_t(std::max(image.width, 0)) * std::max(image.height, 0) * image.channels;
    if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
        image.bytes.size() != samples * image.sampleBytes())
        throw Error(ErrorKind::BadInput, "cannot write image '" + path.string() + "': " + std::to_string(image.width) +
                                             "x" + std::to_string(image.height) + "x" + std::to_string(image.channels) +
                                             " samples do not match its " + std::to_string(image.bytes.size()) + " bytes",
                    {.file = path.string()});
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    const OIIO::TypeDesc type = typeOf(image.type);
    if (extension == ".png" && image.type == SampleType::Float32)
        throw Error(ErrorKind::BadInput, "cannot write image '" + path.string() + "': PNG holds no float samples",
                    {.file = path.string()});
    detail::writeImageFile(path, [&](OIIO::ImageOutput& out, const std::string& name) {
        const std::string writer = out.format_name();
        // EXR stores float (or half): integers are written as their values.
        OIIO::ImageSpec spec(image.width, image.height, image.channels,
                             writer == "openexr" ? OIIO::TypeDesc::FLOAT : type);
        spec.attribute("oiio:ColorSpace", "Linear");
        if (image.channels == 4) spec.attribute("oiio:UnassociatedAlpha", 1);
        if (writer == "png") spec.attribute("png:compressionLevel", 9);
        // OpenImageIO's EXR writer stamps the time of writing (capDate) unless
        // the spec has one: an empty one keeps the file a function of the data.
        if (writer == "openexr") spec.attribute("DateTime", "");
        bool ok = out.open(name, spec) && out.write_image(type, image.bytes.data());
        ok = out.close() && ok;
        if (!ok)
            throw Error(ErrorKind::Io, "cannot write image '" + path.string() + "': " + detail::oiioErrorLine(out.geterror()),
                        {.file = path.string()});
    });
}

DataImage readDataImage(const fs::path& path)
{
    // Alpha is data here: never premultiplied into the other channels.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto input = OIIO::ImageInput::open(path.string(), &config);
    if (!input)
        throw Error(ErrorKind::BadInput, "cannot read image '" + path.string() + "': " + detail::oiioErrorLine({}),
                    {.file = path.string()});
    const OIIO::ImageSpec& spec = input->spec();
    DataImage image;
    image.width = spec.width;
    image.height = spec.height;
    image.channels = spec.nchannels;
    image.type = spec.format == OIIO::TypeDesc::UINT8    ? SampleType::UInt8
                 : spec.format == OIIO::TypeDesc::UINT16 ? SampleType::UInt16
                                                         : SampleType::Float32;
    if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4)
        throw Error(ErrorKind::BadInput, "cannot read image '" + path.string() + "': unsupported size or channels",
                    {.file = path.string()});
    image.bytes.resize(std::size_t(image.width) * image.height * image.channels * image.sampleBytes());
    if (!input->read_image(0, 0, 0, image.channels, typeOf(image.type), image.bytes.data()))
        throw Error(ErrorKind::BadInput, "cannot read image '" + path.string() + "': " + detail::oiioErrorLine(input->geterror()),
                    {.file = path.string()});
    return image;
}

} // namespace strata::render
