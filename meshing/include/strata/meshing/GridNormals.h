// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Per-vertex normals from the gradient of a level set.

#include <strata/meshing/TriangleMesh.h>

#include <openvdb/openvdb.h>

#include <cstddef>
#include <functional>

namespace strata::meshing {

/// A world-space gradient of the field at a world position (metres); it
/// need not be unit length. Used for exact normals when the caller knows the
/// field analytically.
using GradientFunction = std::function<glm::dvec3(const glm::dvec3& world)>;

/// How a mesher fills `TriangleMesh::normals`.
enum class NormalMethod
{
    Grid,     ///< central differences on the trilinear grid (computeGridNormals)
    Gradient, ///< the caller's GradientFunction (computeGradientNormals)
    Face,     ///< area-weighted face normals (computeFaceNormals)
    None,     ///< leave `normals` empty
};

/// "grid", "gradient", "face", "none" (for CLIs and reports).
const char* toString(NormalMethod method);

/// Sets `mesh.normals` to the normalised gradient of `grid` at each vertex:
/// central differences one voxel apart on the trilinearly interpolated grid.
/// Where the gradient vanishes (flat or degenerate regions) the area-weighted
/// face normal is used instead, and where that vanishes too, +Y, so every
/// normal is finite and unit length. The result is oriented with
/// orientNormalsToFaces(): on features thinner than two voxels the
/// differences straddle both sides and can point against the faces.
/// O(vertices), multithreaded.
void computeGridNormals(const openvdb::FloatGrid& grid, TriangleMesh& mesh);

/// Replaces every normal that points against the faces around its vertex
/// (a negative dot product with the area-weighted sum of its incident face
/// normals) by that normalised sum, and returns how many were replaced.
/// The face normal is used rather than the flipped normal: a flipped normal
/// that was nearly tangent stays nearly tangent, while the face normal is
/// by construction on the faces' side. Vertices with no faces, or whose face
/// sum vanishes, are left alone. Needs `normals.size() == positions.size()`
/// (otherwise does nothing and returns 0). O(vertices + triangles).
std::size_t orientNormalsToFaces(TriangleMesh& mesh);

/// Sets `mesh.normals` to area-weighted averages of the adjacent face
/// normals (+Y for isolated or degenerate vertices).
void computeFaceNormals(TriangleMesh& mesh);

/// Sets `mesh.normals` to the normalised `gradient` at each vertex's world
/// position (origin added in double). Falls back like computeGridNormals
/// where the gradient vanishes or is not finite, and is oriented the same
/// way (orientNormalsToFaces()). `gradient` is called
/// concurrently and must be thread-safe; throws strata::Error if empty.
void computeGradientNormals(const GradientFunction& gradient, TriangleMesh& mesh);

} // namespace strata::meshing
