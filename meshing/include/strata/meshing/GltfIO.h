#pragma once
/// \file
/// Binary glTF 2.0 (.glb) files through tinygltf.

#include <strata/meshing/TriangleMesh.h>

#include <filesystem>

namespace strata::meshing {

/// Writes one mesh with POSITION and NORMAL (if present) float attributes and
/// uint32 indices — no UVs, no tangents — under one node whose translation is
/// `mesh.origin`. Written atomically (temporary file, then rename).
/// Throws strata::Error naming the path on failure.
void writeGlb(const TriangleMesh& mesh, const std::filesystem::path& path);

/// Reads the first triangle primitive of the first mesh of a .glb or .gltf
/// file. Positions stay relative to the node translation, which becomes
/// `origin`. Throws strata::Error naming the path on failure.
TriangleMesh readGltf(const std::filesystem::path& path);

} // namespace strata::meshing
