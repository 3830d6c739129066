// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// libFuzzer target for the .vdb reader that `strata mesh` and `strata info`
// use (strata::meshing::readLevelSet), on the bytes written to a file.
// It may return a usable level set or throw strata::Error; anything else (a
// crash, a sanitizer report, another exception, a grid that breaks its
// promise) is a bug.

#include "FuzzTempFile.h"

#include <strata/Error.h>
#include <strata/meshing/GridIO.h>

#include <cstdio>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static const strata::fuzz::TempFile file(".vdb");
    try {
        const openvdb::FloatGrid::Ptr grid = strata::meshing::readLevelSet(file.write(data, size));
        if (!grid || grid->getGridClass() != openvdb::GRID_LEVEL_SET || grid->activeVoxelCount() == 0 ||
            !grid->hasUniformVoxels()) {
            std::fprintf(stderr, "readLevelSet returned a grid it promised to refuse\n");
            std::abort();
        }
    } catch (const strata::Error&) {
        // a rejected input: fine
    }
    return 0;
}
