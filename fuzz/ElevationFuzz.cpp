// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// libFuzzer target for the DEM reader of `strata bench landforms --dem`
// (strata::terrain::parseElevationFile: NumPy .npy, .npz stored or deflated,
// ESRI ASCII grid), on the bytes as they are. It may return a grid or throw
// strata::Error; anything else (a crash, a sanitizer report, another
// exception, a grid that breaks its promise) is a bug.

#include <strata/Error.h>
#include <strata/terrain/ElevationFile.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    try {
        const strata::terrain::ElevationGrid grid =
            strata::terrain::parseElevationFile(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz");
        std::size_t missing = 0;
        for (const double h : grid.heights) missing += std::isnan(h) ? 1 : 0;
        if (grid.width < 1 || grid.height < 1 ||
            grid.heights.size() != std::size_t(grid.width) * std::size_t(grid.height) || missing != grid.noDataCells) {
            std::fprintf(stderr, "parseElevationFile returned a grid that breaks its promise\n");
            std::abort();
        }
    } catch (const strata::Error&) {
        // a rejected input: fine
    }
    return 0;
}
