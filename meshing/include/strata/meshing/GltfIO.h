#pragma once
/// \file
/// Binary glTF 2.0 (.glb) files through tinygltf.

#include <strata/meshing/TriangleMesh.h>

#include <filesystem>
#include <string>
#include <string_view>

namespace strata::meshing {

/// Options for writeGlb().
struct GlbOptions
{
    /// The name of the glTF mesh and node (viewers list it); empty = the
    /// file's stem ("cave" for "out/cave.glb"), or "terrain" if that is empty.
    std::string name;
};

/// Writes one mesh with POSITION and NORMAL (if present) float attributes and
/// uint32 indices — no UVs, no tangents — under one node whose translation is
/// `mesh.origin`. The primitive carries a neutral material, light grey,
/// dielectric and rough (pbrMetallicRoughness: baseColorFactor 0.8,
/// metallicFactor 0, roughnessFactor 0.9), since glTF's default material is
/// fully metallic and viewers would show the terrain as dark metal.
/// Written atomically (temporary file, then rename).
/// Throws strata::Error (ErrorKind::Io) naming the path on failure.
void writeGlb(const TriangleMesh& mesh, const std::filesystem::path& path, const GlbOptions& options = {});

/// Reads the first triangle primitive of the first mesh of a .glb or .gltf
/// file. Positions stay relative to the node translation, which becomes
/// `origin`. Images are not decoded; a .glb reads no external files.
/// Throws strata::Error (BadInput) naming the path on failure: a missing or
/// sparse accessor, one that overruns its buffer view or its buffer, a stride
/// smaller than an element, a non-finite position or normal, an index out of
/// range, an index count that is not a multiple of 3.
TriangleMesh readGltf(const std::filesystem::path& path);

/// readGltf() of a .glb already in memory; `name` names it in messages.
TriangleMesh parseGlb(std::string_view bytes, const std::string& name);

} // namespace strata::meshing
