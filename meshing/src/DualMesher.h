// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: the chunk infrastructure shared by surfaceNets() and
// dualContouring(). One translation unit (DualMesher.cpp) holds the OpenVDB
// access; the meshers only pick the vertex placement.

#include <strata/meshing/ChunkMesh.h>

namespace strata::meshing::detail {

enum class DualMethod
{
    SurfaceNets,
    DualContouring,
};

struct DualSettings
{
    ChunkMeshOptions options;
    DualMethod method = DualMethod::SurfaceNets;
    double singularThreshold = 0.1; // dual contouring only
};

/// Throws strata::Error for options a user can get wrong.
void validate(const DualSettings& settings);

/// Every chunk, meshed in parallel and assembled in chunk order.
TriangleMesh meshChunks(const openvdb::FloatGrid& grid, const DualSettings& settings);

/// One chunk on its own.
ChunkMesh meshChunk(const openvdb::FloatGrid& grid, const openvdb::Coord& chunkMin, const DualSettings& settings);

} // namespace strata::meshing::detail
