// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Moving mesh vertices onto the isosurface of a grid: an accuracy knob for
/// any mesher (the chunk meshers also do it per cell, see ChunkMesh.h).

#include <strata/meshing/TriangleMesh.h>

#include <openvdb/openvdb.h>

namespace strata::meshing {

struct ProjectOptions
{
    int steps = 1;         ///< Newton steps, each p -= f(p) ∇f / |∇f|²
    double isovalue = 0.0; ///< world units
    /// A vertex moves at most this many voxels in total (keeps thin
    /// features and far-from-surface vertices in place).
    double maxMoveVoxels = 0.5;
};

/// Moves each vertex of `mesh` (positions relative to mesh.origin) towards
/// the trilinear isosurface of `grid` along the central-difference
/// gradient. Normals are left as they are. O(vertices), multithreaded,
/// deterministic. Throws strata::Error for bad options.
void projectToSurface(const openvdb::FloatGrid& grid, TriangleMesh& mesh, const ProjectOptions& options = {});

} // namespace strata::meshing
