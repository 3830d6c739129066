// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// An image file opened by one reader, with every failure reported to the
/// caller of that call and nothing printed: PNG files are decoded by libpng
/// with an error handler of this call's own (libpng's default handler,
/// which OpenImageIO 2.4's PNG reader falls through to, prints
/// "libpng error: ..." on stderr); other formats by OpenImageIO, whose
/// messages come from `ImageInput::geterror()` / `OIIO::geterror()`.
/// Nothing process-wide (file descriptors, global handlers) is touched, so
/// threads may read images at the same time.

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <memory>
#include <string>

namespace strata::render {

/// An open image file: its header first, its pixels on request.
class ImageFileInput
{
public:
    /// Opens `path` with the reader named `reader` only (the name
    /// checkImageFileStructure() returns: "png", "openexr", "tiff", ...);
    /// OpenImageIO readers get `config` (e.g. `oiio:UnassociatedAlpha`).
    /// Returns null with `error` set to the library's message in one line
    /// ("IHDR: CRC error", never empty) when the file cannot be opened.
    static std::unique_ptr<ImageFileInput> open(const std::string& reader, const std::filesystem::path& path,
                                                const OIIO::ImageSpec& config, std::string& error);

    virtual ~ImageFileInput() = default;

    /// The header: width, height, depth, nchannels, alpha_channel and the
    /// `oiio:ColorSpace` attribute, as OpenImageIO's reader reports them.
    virtual const OIIO::ImageSpec& spec() const = 0;
    /// The reader's name ("png", "openexr", ...).
    virtual std::string formatName() const = 0;
    /// Channels [0, channels) of every pixel, row by row from the top, as
    /// floats (8- and 16-bit integers normalised to [0, 1] exactly as
    /// OpenImageIO converts them) into `out`, which holds width × height ×
    /// channels values. Returns false with `error` set (one line, never
    /// empty) when the pixels cannot be decoded.
    virtual bool readFloat(int channels, float* out, std::string& error) = 0;
};

} // namespace strata::render
