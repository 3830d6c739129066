// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Mesh files by extension: .glb (tinygltf, origin as a node translation),
/// .ply (binary), .obj, .off (ASCII) and .stl (binary) through OpenMesh.

#include <strata/meshing/TriangleMesh.h>

#include <filesystem>
#include <string>
#include <string_view>

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

/// Throws strata::Error (BadInput) "cannot write mesh file 'PATH': unknown
/// extension ..." unless writeMeshFile() can write `path`'s extension: lets a
/// caller refuse a bad output name before doing any work.
void checkMeshFileExtension(const std::filesystem::path& path);

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

/// Reads any of those formats (and .gltf); polygons are fan-triangulated.
/// The readers are strict: a count the file is too small to hold (checked
/// before allocating), a non-numeric or non-finite coordinate, a face with an
/// index out of range or fewer than 3 vertices, a file that ends early, or a
/// path that is not a regular file throws strata::Error (BadInput) naming the
/// file and, where possible, the line and the element
/// ("m.obj:12: face 3: vertex index 9 is out of range (8 vertices so far)").
TriangleMesh readMesh(const std::filesystem::path& path);

/// readMesh() on bytes in memory; `extension` (".ply", ".obj", ".off",
/// ".stl" or ".glb", lower case) picks the format, `name` names the bytes in
/// messages. Throws strata::Error (BadInput).
TriangleMesh parseMesh(std::string_view bytes, const std::string& extension, const std::string& name);

/// OBJ: `v`, `vn` and `f` statements (v, v/t, v//n, v/t/n corners; negative
/// indices count back); normals are kept when each vertex has exactly one.
TriangleMesh parseObj(std::string_view bytes, const std::string& name);

/// OFF, NOFF, COFF, CNOFF (ASCII); extra values on a line (colours) are ignored.
TriangleMesh parseOff(std::string_view bytes, const std::string& name);

/// Binary or ASCII STL; corners with bit-identical positions become one vertex.
TriangleMesh parseStl(std::string_view bytes, const std::string& name);

} // namespace strata::meshing
