// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "HeightImageFile.h"

#include <strata/Error.h>
#include <strata/StderrCapture.h>
#include <strata/render/ImageFileStructure.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <memory>
#include <string>
#include <system_error>

namespace strata::scene {

namespace {

/// OpenImageIO's message in one line (it may hold several, one per failed
/// reader or libpng complaint), or `fallback` when it has none.
std::string oneLine(std::string message, const char* fallback)
{
    std::replace(message.begin(), message.end(), '\n', ' ');
    while (!message.empty() && message.back() == ' ') message.pop_back();
    return message.empty() ? fallback : message;
}

} // namespace

terrain::HeightImage readHeightImageFile(const std::filesystem::path& path)
{
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(ErrorKind::BadInput, "no such file");
    if (!std::filesystem::is_regular_file(path, ec)) throw Error(ErrorKind::BadInput, "is not a file");
    const std::string reader = render::checkImageFileStructure(path);
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    // libpng prints its complaints on stderr; OpenImageIO's error says the same.
    StderrCapture libraryLines;
    // The extension's reader only (see checkImageFileStructure()).
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::create(reader);
    OIIO::ImageSpec opened;
    if (!in || !in->open(path.string(), opened, config)) {
        const std::string printed = libraryLines.release();
        const std::string why = in ? in->geterror() : OIIO::geterror();
        throw Error(ErrorKind::BadInput, "cannot be read as a ." + reader + " image: " +
                    oneLine(why, printed.empty() ? "unknown format" : printed.c_str()));
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width < 2 || spec.height < 2 || spec.depth != 1 || spec.nchannels < 1 ||
        double(spec.width) * double(spec.height) > MAX_HEIGHT_IMAGE_PIXELS) {
        throw Error(ErrorKind::BadInput, "is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                    (spec.depth != 1 ? "x" + std::to_string(spec.depth) : std::string()) +
                    " pixels: heightmaps need 2x2 to 16384x16384");
    }
    render::checkImageSizeAgainstFile(path, spec.width, spec.height, spec.nchannels);
    terrain::HeightImage image;
    image.width = spec.width;
    image.height = spec.height;
    image.values.resize(std::size_t(spec.width) * std::size_t(spec.height));
    // Channel 0 as float: 8- and 16-bit integers come normalised to [0, 1].
    if (!in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, image.values.data())) {
        const std::string printed = libraryLines.release();
        throw Error(ErrorKind::BadInput, "cannot be read: " + oneLine(in->geterror(), printed.empty() ? "unknown OpenImageIO error" : printed.c_str()));
    }
    in->close();
    return image;
}

} // namespace strata::scene
