// libFuzzer target for the heightmap loader of the scene's image_heightfield
// node (strata::scene::readHeightImageFile, OpenImageIO underneath), on the
// bytes written to a .png file (OpenImageIO tries its other readers when
// the PNG reader refuses the bytes). It may return an image or throw
// strata::Error; anything else is a bug.

#include "FuzzTempFile.h"

#include "HeightImageFile.h" // scene/src

#include <strata/Error.h>

#include <cstdio>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static const strata::fuzz::TempFile file(".png");
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
