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

/// Options for writeMeshFile().
struct MeshFileOptions
{
    /// .glb only: the name of the mesh and node (GlbOptions::name); empty =
    /// the file's stem.
    std::string name;
};

/// Writes `mesh` in the format its extension names (case-insensitive).
/// Text formats (.obj, .off) write max_digits10 (9) significant digits, so
/// every position and normal reads back bit-identical.
/// Only .glb keeps positions relative to `mesh.origin` (node translation);
/// the other formats have no transform and store world positions in float,
/// so they lose precision far from the world origin. STL has no vertex
/// normals (it stores face normals) and no shared vertices (read it back
/// and check it with analyzeTopology(), which welds by position). Written
/// atomically. Throws strata::Error for an unknown extension (BadInput) or
/// a failed write (Io).
void writeMeshFile(const TriangleMesh& mesh, const std::filesystem::path& path, const MeshFileOptions& options = {});

/// Reads any of those formats (and .gltf); polygons are triangulated.
/// Throws strata::Error naming the path.
TriangleMesh readMesh(const std::filesystem::path& path);

} // namespace strata::meshing
