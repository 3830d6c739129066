#pragma once
/// \file
/// Per-vertex normals from the gradient of a level set.

#include <strata/meshing/TriangleMesh.h>

#include <openvdb/openvdb.h>

namespace strata::meshing {

/// Sets `mesh.normals` to the normalised gradient of `grid` at each vertex:
/// central differences one voxel apart on the trilinearly interpolated grid.
/// Where the gradient vanishes (flat or degenerate regions) the area-weighted
/// face normal is used instead, and where that vanishes too, +Y, so every
/// normal is finite and unit length. O(vertices), multithreaded.
void computeGridNormals(const openvdb::FloatGrid& grid, TriangleMesh& mesh);

/// Sets `mesh.normals` to area-weighted averages of the adjacent face
/// normals (+Y for isolated or degenerate vertices).
void computeFaceNormals(TriangleMesh& mesh);

} // namespace strata::meshing
