#pragma once
/// \file
/// Binary PLY files through OpenMesh.

#include <strata/meshing/TriangleMesh.h>

#include <filesystem>

namespace strata::meshing {

/// Writes binary little-endian PLY with vertex positions (world metres,
/// float: `origin` is added, since PLY has no transform) and normals.
/// Triangles OpenMesh cannot attach to its half-edge structure (non-manifold
/// configurations) are written with their own copies of their vertices, so no
/// face is lost. Written atomically. Throws strata::Error naming the path.
void writePly(const TriangleMesh& mesh, const std::filesystem::path& path);

/// Reads a PLY (or any format OpenMesh reads: OBJ, OFF, STL) into a
/// triangle mesh with origin zero; polygons are fan-triangulated.
/// Throws strata::Error naming the path.
TriangleMesh readMeshFile(const std::filesystem::path& path);

} // namespace strata::meshing
