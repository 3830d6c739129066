#pragma once
/// \file
/// Mesh files by extension: .glb (tinygltf, origin as a node translation),
/// .ply (binary), .obj, .off (ASCII) and .stl (binary) through OpenMesh.

#include <strata/meshing/TriangleMesh.h>

#include <filesystem>
#include <string>

namespace strata::meshing {

/// The extensions writeMeshFile() accepts, for messages: ".glb, .ply, .obj, .stl, .off".
std::string meshFileExtensions();

/// Writes `mesh` in the format its extension names (case-insensitive).
/// Only .glb keeps positions relative to `mesh.origin` (node translation);
/// the other formats have no transform and store world positions in float,
/// so they lose precision far from the world origin. STL has no vertex
/// normals (it stores face normals). Written atomically.
/// Throws strata::Error for an unknown extension or a failed write.
void writeMeshFile(const TriangleMesh& mesh, const std::filesystem::path& path);

/// Reads any of those formats (and .gltf); polygons are triangulated.
/// Throws strata::Error naming the path.
TriangleMesh readMesh(const std::filesystem::path& path);

} // namespace strata::meshing
