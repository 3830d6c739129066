// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// The file extension an image's first bytes ask for: the heightmap fuzzer
// writes each input under it (the loader opens a file with its extension's
// reader only), and FuzzCorpus.* replays the corpus the same way.

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace strata::fuzz {

/// PNG, OpenEXR, TIFF, JPEG, BMP, PNM and Radiance HDR by their magic
/// numbers; Targa (which has none) otherwise.
inline const char* imageExtensionFor(const std::uint8_t* data, std::size_t size)
{
    auto starts = [&](const char* magic, std::size_t n) { return size >= n && std::memcmp(data, magic, n) == 0; };
    if (starts("\x89PNG", 4)) return ".png";
    if (starts("\x76\x2f\x31\x01", 4)) return ".exr";
    if (starts("II*", 4) || starts("MM\0*", 4)) return ".tif";
    if (starts("\xff\xd8", 2)) return ".jpg";
    if (starts("BM", 2)) return ".bmp";
    if (size >= 2 && data[0] == 'P' && data[1] >= '1' && data[1] <= '6') return ".pnm";
    if (starts("#?", 2)) return ".hdr";
    return ".tga";
}

} // namespace strata::fuzz
