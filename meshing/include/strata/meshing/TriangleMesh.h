// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The plain, engine-ready mesh buffers every mesher returns.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace strata::meshing {

/// An indexed triangle mesh. Positions are in metres relative to `origin`
/// (kept in double), so float precision holds far from the world origin.
/// Triangles are counter-clockwise seen from outside (outward normals).
struct TriangleMesh
{
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals; ///< unit, one per position, or empty
    std::vector<std::uint32_t> indices;
    glm::dvec3 origin{0.0};
    /// Optional (cavity, cover) per vertex for terrain layer rules
    /// (computeSurfaceAttributes()), or empty. Mesh operations do not carry
    /// it: compute it on the final mesh.
    std::vector<glm::vec2> surface;
    /// Optional landform masks per vertex for terrain layer rules: x flow
    /// (log10 of the drainage area in m²), y wear (metres eroded), z
    /// deposition (metres of sediment), w water (0 dry .. 1 river or lake),
    /// as terrain::LandformMasks defines them; or empty. Like `surface`,
    /// mesh operations do not carry it.
    std::vector<glm::vec4> landform;
    /// Optional rock masks per vertex for terrain layer rules: x hardness
    /// (0 soft .. 1 hard), y the bed's index, as terrain::RockMasks defines
    /// them; or empty. Like `surface`, mesh operations do not carry it.
    std::vector<glm::vec2> rock;

    std::size_t vertexCount() const { return positions.size(); }
    std::size_t triangleCount() const { return indices.size() / 3; }
};

} // namespace strata::meshing
