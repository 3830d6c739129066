// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/DualContouring.h>

#include "DualMesher.h"

namespace strata::meshing {

namespace {

detail::DualSettings settingsFor(const DualContouringOptions& options)
{
    detail::DualSettings settings;
    settings.options = options;
    settings.method = detail::DualMethod::DualContouring;
    settings.singularThreshold = options.singularThreshold;
    detail::validate(settings);
    return settings;
}

} // namespace

TriangleMesh dualContouring(const openvdb::FloatGrid& grid, const DualContouringOptions& options)
{
    return detail::meshChunks(grid, settingsFor(options));
}

ChunkMesh dualContouringChunk(const openvdb::FloatGrid& grid, const openvdb::Coord& chunkMin,
                              const DualContouringOptions& options)
{
    return detail::meshChunk(grid, chunkMin, settingsFor(options));
}

} // namespace strata::meshing
