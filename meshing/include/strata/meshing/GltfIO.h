// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Binary glTF 2.0 (.glb) files through tinygltf.

#include <strata/meshing/TriangleMesh.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace strata::meshing {

/// Options for writeGlb().
struct GlbOptions
{
    /// The name of the glTF mesh and node (viewers list it); empty = the
    /// file's stem ("cave" for "out/cave.glb"), or "terrain" if that is empty.
    std::string name;
};

/// The glTF attribute names of TriangleMesh::surface (VEC2 float: cavity,
/// cover), TriangleMesh::landform (VEC4 float: flow, wear, deposition,
/// water) and TriangleMesh::rock (VEC2 float: hardness, bed). Application-specific, so they start with an underscore, as glTF
/// requires; viewers ignore them.
inline constexpr const char* SURFACE_ATTRIBUTE = "_SURFACE";
inline constexpr const char* LANDFORM_ATTRIBUTE = "_LANDFORM";
inline constexpr const char* ROCK_ATTRIBUTE = "_ROCK";

/// Writes one mesh with POSITION, NORMAL, _SURFACE, _LANDFORM and _ROCK (each when
/// present, one per position) float attributes and
/// uint32 indices — no UVs, no tangents — under one node whose translation is
/// `mesh.origin`. The primitive carries a neutral material, light grey,
/// dielectric and rough (pbrMetallicRoughness: baseColorFactor 0.8,
/// metallicFactor 0, roughnessFactor 0.9), since glTF's default material is
/// fully metallic and viewers would show the terrain as dark metal.
/// Written atomically (temporary file, then rename).
/// Throws strata::Error (ErrorKind::Io) naming the path on failure.
void writeGlb(const TriangleMesh& mesh, const std::filesystem::path& path, const GlbOptions& options = {});

/// One primitive of encodeGlb(): a mesh (positions relative to the
/// shared origin) and its material. Parts with the same material name and
/// sidedness share one material (neutral grey, as writeGlb()).
struct GlbPart
{
    const TriangleMesh* mesh = nullptr;
    std::string material = "strata-neutral";
    bool doubleSided = false;
};

/// The bytes of a .glb holding one mesh named `name` with a primitive per
/// non-empty part (POSITION; NORMAL, _SURFACE, _LANDFORM if present;
/// indices), under one node
/// translated to `origin` (double precision). `compactIndices`: uint16
/// indices for parts of at most 65535 vertices, else uint32.
/// Throws strata::Error (Internal) if tinygltf fails.
std::string encodeGlb(const std::vector<GlbPart>& parts, const glm::dvec3& origin, const std::string& name,
                      bool compactIndices = true);

/// Reads every triangle primitive of the first mesh of a .glb or .gltf
/// file, appended in order into one mesh (normals, _SURFACE and _LANDFORM
/// each kept only when every primitive has them). Positions stay relative
/// to the node translation, which becomes `origin`. Images are not decoded; a .glb reads no external files.
/// Throws strata::Error (BadInput) naming the path on failure: a missing or
/// sparse accessor, one that overruns its buffer view or its buffer, a stride
/// smaller than an element, a non-finite attribute value, an index out of
/// range, an index count that is not a multiple of 3.
TriangleMesh readGltf(const std::filesystem::path& path);

/// readGltf() of a .glb already in memory; `name` names it in messages.
TriangleMesh parseGlb(std::string_view bytes, const std::string& name);

} // namespace strata::meshing
