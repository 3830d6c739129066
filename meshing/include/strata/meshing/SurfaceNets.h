// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Naive surface nets on leaf-aligned chunks (see ChunkMesh.h): one vertex
/// per cell that crosses the surface, at the mean of its edge crossings.

#include <strata/meshing/ChunkMesh.h>

namespace strata::meshing {

/// Meshes a level set (negative inside) chunk by chunk, in parallel over
/// chunks, and assembles the chunks in chunk order with shared border
/// vertices welded: the result is the same bytes on 1 or N threads, closed
/// wherever the surface is closed inside the grid's narrow band, and wound
/// counter-clockwise seen from outside. O(active voxels).
/// Throws strata::Error for bad options (chunk size, non-finite isovalue or
/// origin, NormalMethod::Gradient without a gradient, negative steps) or a
/// grid whose transform is not linear.
TriangleMesh surfaceNets(const openvdb::FloatGrid& grid, const ChunkMeshOptions& options = {});

/// Meshes one chunk (its minimum cell from listChunks()) on its own, e.g. to
/// stream or re-mesh after an edit. Same vertex positions as in the
/// assembled mesh. NormalMethod::Face uses only this chunk's faces.
/// `options.chunkSize` 0 means 32 here. Throws strata::Error for bad options
/// or a `chunkMin` that is not a multiple of the chunk size.
ChunkMesh surfaceNetsChunk(const openvdb::FloatGrid& grid, const openvdb::Coord& chunkMin,
                           const ChunkMeshOptions& options = {});

} // namespace strata::meshing
