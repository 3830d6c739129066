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

#include <filesystem>

namespace strata::render {

/// For a file that starts with the PNG signature: every chunk's length fits
/// in the file and an IEND chunk ends it. For one that starts with the
/// OpenEXR magic number: every header attribute's size fits in the file.
/// Other files pass unchecked (their reader decides). Throws strata::Error
/// (BadInput) with the reason only ("is a truncated PNG: chunk 'IDAT' at
/// byte 33 needs 72 bytes, the file has 17 left"); the caller names the key
/// and the path. Reads only chunk and attribute headers.
void checkImageFileStructure(const std::filesystem::path& path);

} // namespace strata::render
