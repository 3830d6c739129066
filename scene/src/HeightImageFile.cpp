// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "HeightImageFile.h"

#include <strata/Error.h>
#include <strata/render/ImageFileInput.h>
#include <strata/render/ImageFileStructure.h>

#include <OpenImageIO/imageio.h>

#include <memory>
#include <string>
#include <system_error>

namespace strata::scene {

terrain::HeightImage readHeightImageFile(const std::filesystem::path& path)
{
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error(ErrorKind::BadInput, "no such file");
    if (!std::filesystem::is_regular_file(path, ec)) throw Error(ErrorKind::BadInput, "is not a file");
    const std::string reader = render::checkImageFileStructure(path);
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    // The extension's reader only (see checkImageFileStructure()).
    std::string error;
    std::unique_ptr<render::ImageFileInput> in = render::ImageFileInput::open(reader, path, config, error);
    if (!in) throw Error(ErrorKind::BadInput, "cannot be read as a ." + reader + " image: " + error);
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
    if (!in->readFloat(1, image.values.data(), error)) throw Error(ErrorKind::BadInput, "cannot be read: " + error);
    return image;
}

} // namespace strata::scene
