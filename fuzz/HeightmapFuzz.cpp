// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// libFuzzer target for the heightmap loader of the scene's image_heightfield
// node (strata::scene::readHeightImageFile, OpenImageIO underneath). The
// loader opens a file with its extension's reader only, so the bytes are
// written under the extension their first bytes ask for
// (imageExtensionFor()): every reader Strata lets OpenImageIO use gets
// fuzzed. It may return an image or throw strata::Error; anything else is
// a bug.

#include "FuzzTempFile.h"
#include "ImageExtension.h"

#include "HeightImageFile.h" // scene/src

#include <strata/Error.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    // One file per extension, kept for the process (TempFile removes it at exit).
    static std::map<std::string, strata::fuzz::TempFile> files;
    const std::string extension = strata::fuzz::imageExtensionFor(data, size);
    const strata::fuzz::TempFile& file = files.try_emplace(extension, extension).first->second;
    try {
        const strata::terrain::HeightImage image = strata::scene::readHeightImageFile(file.write(data, size));
        if (image.width < 2 || image.height < 2 ||
            image.values.size() != std::size_t(image.width) * std::size_t(image.height)) {
            std::fprintf(stderr, "readHeightImageFile returned a broken image\n");
            std::abort();
        }
    } catch (const strata::Error&) {
        // a rejected input: fine
    }
    return 0;
}
