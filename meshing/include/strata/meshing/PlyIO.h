// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// PLY files: written binary through OpenMesh, read (ASCII or binary) by a
/// strict reader of our own.

#include <strata/meshing/TriangleMesh.h>

#include <filesystem>
#include <string>
#include <string_view>

namespace strata::meshing {

/// Writes binary little-endian PLY with vertex positions (world metres,
/// float: `origin` is added, since PLY has no transform) and normals.
/// Triangles OpenMesh cannot attach to its half-edge structure (non-manifold
/// configurations) are written with their own copies of their vertices, so no
/// face is lost. Written atomically. Throws strata::Error naming the path.
void writePly(const TriangleMesh& mesh, const std::filesystem::path& path);

/// Reads a mesh file of any format readMesh() reads (kept for callers that
/// used it for PLY, OBJ, OFF and STL). Throws strata::Error naming the path.
TriangleMesh readMeshFile(const std::filesystem::path& path);

/// Reads an ASCII or binary (either endianness) PLY file: the `vertex`
/// element's x, y, z (and nx, ny, nz when all three are present) and the
/// `face` element's `vertex_indices` lists, fan-triangulated; other elements
/// and properties are skipped. Origin zero. Throws strata::Error (BadInput)
/// naming the file and the element for anything it cannot read exactly: a
/// count the file is too small to hold (checked before allocating), a
/// non-numeric or non-finite coordinate, a face with fewer than 3 vertices or
/// an index out of range, a file that ends early.
TriangleMesh readPly(const std::filesystem::path& path);

/// readPly() on bytes already in memory; `name` names them in messages.
TriangleMesh parsePly(std::string_view bytes, const std::string& name);

} // namespace strata::meshing
