#pragma once
/// \file
/// A structural check of PNG files before they reach libpng (through
/// OpenImageIO). libpng stops a read that runs past the end of the file by
/// a longjmp out of OpenImageIO's read callback, which skips C++
/// destructors (a leak found by fuzzing the heightmap loader) and prints on
/// stderr; a PNG whose chunks do not fit in the file is refused here instead.

#include <filesystem>

namespace strata::render {

/// For a file that starts with the PNG signature: every chunk's length fits
/// in the file and an IEND chunk ends it. Other files pass unchecked (their
/// reader decides). Throws strata::Error (BadInput) with the reason only
/// ("is a truncated PNG: chunk 'IDAT' at byte 33 needs 72 bytes, the file
/// has 17 left"); the caller names the key and the path. Reads only the
/// chunk headers: O(number of chunks).
void checkPngStructure(const std::filesystem::path& path);

} // namespace strata::render
