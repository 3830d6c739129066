#pragma once
/// \file
/// Per-vertex normals from the gradient of a level set.

#include <strata/meshing/TriangleMesh.h>

#include <openvdb/openvdb.h>

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
/// normal is finite and unit length. O(vertices), multithreaded.
void computeGridNormals(const openvdb::FloatGrid& grid, TriangleMesh& mesh);

/// Sets `mesh.normals` to area-weighted averages of the adjacent face
/// normals (+Y for isolated or degenerate vertices).
void computeFaceNormals(TriangleMesh& mesh);

/// Sets `mesh.normals` to the normalised `gradient` at each vertex's world
/// position (origin added in double). Falls back like computeGridNormals
/// where the gradient vanishes or is not finite. `gradient` is called
/// concurrently and must be thread-safe; throws strata::Error if empty.
void computeGradientNormals(const GradientFunction& gradient, TriangleMesh& mesh);

} // namespace strata::meshing
