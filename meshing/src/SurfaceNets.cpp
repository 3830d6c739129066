// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/SurfaceNets.h>

#include "DualMesher.h"

namespace strata::meshing {

namespace {

detail::DualSettings settingsFor(const ChunkMeshOptions& options)
{
    detail::DualSettings settings;
    settings.options = options;
    settings.method = detail::DualMethod::SurfaceNets;
    detail::validate(settings);
    return settings;
}

} // namespace

TriangleMesh surfaceNets(const openvdb::FloatGrid& grid, const ChunkMeshOptions& options)
{
    return detail::meshChunks(grid, settingsFor(options));
}

ChunkMesh surfaceNetsChunk(const openvdb::FloatGrid& grid, const openvdb::Coord& chunkMin,
                           const ChunkMeshOptions& options)
{
    return detail::meshChunk(grid, chunkMin, settingsFor(options));
}

} // namespace strata::meshing
