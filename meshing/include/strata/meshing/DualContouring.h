// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Dual contouring on the chunk infrastructure of the surface nets mesher
/// (see ChunkMesh.h): each cell's vertex minimises the quadric error of the
/// tangent planes at its edge crossings, so sharp edges and corners (a box
/// cut into the terrain) stay sharp.

#include <strata/meshing/ChunkMesh.h>

namespace strata::meshing {

struct DualContouringOptions : ChunkMeshOptions
{
    /// Eigenvalues of the QEF matrix below this fraction of the largest are
    /// ignored (the solve falls back to the mean crossing along those
    /// directions): 0.1 keeps flat regions smooth and edges sharp. In (0, 1).
    double singularThreshold = 0.1;
};

/// Like surfaceNets(), with each vertex at the QEF minimum clamped strictly
/// inside its cell (DUAL_CONTOURING_MARGIN, DualMesh.h), and a cell's sheets
/// at their mean crossings where their minima would coincide: no two
/// vertices share a position, so welding by position keeps the mesh manifold. Plane normals come from `options.gradient` when set, else from the
/// grid's central-difference gradient interpolated along the crossed edge.
/// Throws strata::Error for bad options (see surfaceNets(), and
/// singularThreshold outside (0, 1)).
TriangleMesh dualContouring(const openvdb::FloatGrid& grid, const DualContouringOptions& options = {});

/// One chunk on its own (see surfaceNetsChunk()).
ChunkMesh dualContouringChunk(const openvdb::FloatGrid& grid, const openvdb::Coord& chunkMin,
                              const DualContouringOptions& options = {});

} // namespace strata::meshing
