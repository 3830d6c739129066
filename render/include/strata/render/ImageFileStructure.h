// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// A structural check of image files before they reach the image libraries
/// (libpng, OpenEXR, through OpenImageIO), which trust what the file says:
/// - PNG: libpng stops a read that runs past the end of the file by a
///   longjmp out of OpenImageIO's read callback, which skips C++
///   destructors (a leak found by fuzzing the heightmap loader) and prints
///   on stderr;
/// - OpenEXR: a header attribute's size is allocated before it is read (a
///   corrupt 4 KiB file asked for gigabytes).
/// A file whose chunks or attributes do not fit in it is refused here.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace strata::render {

/// The image formats Strata reads, by file extension (lower case, no dot):
/// png, jpg, jpeg, tif, tiff, exr, hdr, tga, bmp, pgm, ppm, pnm.
const std::vector<std::string>& imageExtensions();

/// Checks `path` before an image library reads it and returns the name of
/// the one OpenImageIO reader to open it with: the reader of its extension
/// (`OIIO::ImageInput::create(name)`, then `open()`), never another one
/// guessed from the bytes: a file that its extension's reader refuses is
/// refused, rather than handed to every other reader in turn (each a
/// parser of its own to trust). An extension not in imageExtensions() is
/// refused. For a file that starts with the PNG signature: every chunk's
/// length fits in the file and an IEND chunk ends it. For one that starts
/// with the OpenEXR magic number: every header attribute's size fits in the
/// file. Other files pass unchecked (their reader decides). Throws
/// strata::Error (BadInput) with the reason only ("is a truncated PNG:
/// chunk 'IDAT' at byte 33 needs 72 bytes, the file has 17 left"); the
/// caller names the key and the path. Reads only chunk and attribute
/// headers.
std::string checkImageFileStructure(const std::filesystem::path& path);

/// The most uncompressed bytes per file byte a real image reaches (zlib's
/// limit is about 1032; run-length and PIZ less), with room to spare.
constexpr std::uint64_t MAX_IMAGE_EXPANSION = 4096;

/// Refuses an image whose header claims more pixels than its file can hold
/// under any compression (`width` x `height` x `channels` bytes, at least one
/// byte per channel, over MAX_IMAGE_EXPANSION times the file's size plus
/// 64 KiB), before anything of that size is allocated. Throws strata::Error
/// (BadInput) with the reason only, as checkImageFileStructure() does.
void checkImageSizeAgainstFile(const std::filesystem::path& path, int width, int height, int channels);

} // namespace strata::render
