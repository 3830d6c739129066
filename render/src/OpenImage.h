// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Opening an image file with one OpenImageIO reader, chosen by the caller
// (checkImageFileStructure() names the reader of the file's extension).

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <memory>
#include <string>

namespace strata::render {

/// `path` opened by OpenImageIO's reader named `reader` only
/// (ImageInput::open() would try every other reader in turn when that one
/// refuses the file). Returns the open input, or null with `error` set to
/// OpenImageIO's message (possibly empty).
inline std::unique_ptr<OIIO::ImageInput> openImageWith(const std::string& reader, const std::filesystem::path& path,
                                                       const OIIO::ImageSpec& config, std::string& error)
{
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::create(reader);
    OIIO::ImageSpec opened;
    if (!input) {
        error = OIIO::geterror();
        return nullptr;
    }
    if (!input->open(path.string(), opened, config)) {
        error = input->geterror();
        return nullptr;
    }
    return input;
}

} // namespace strata::render
