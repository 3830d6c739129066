// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// A non-owning view of an indexed triangle mesh, so the renderer needs no
/// mesh type of its own and no dependency on the meshing library.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>

namespace strata::render {

struct MeshView
{
    const glm::vec3* positions = nullptr; ///< world metres, relative to `origin`
    const glm::vec3* normals = nullptr;   ///< unit, per vertex
    /// Optional, per vertex: x the cavity (0 open .. 1 a deep crevice), y
    /// the cover (0 open sky .. 1 rock overhead), as layer rules read them
    /// (LayerRule::cavity, cover). Null reads (0, 0).
    const glm::vec2* surface = nullptr;
    /// Optional, per vertex: the landform masks of erosion as layer rules
    /// read them (LayerRule::flow, wear, deposition, water): x flow (log10
    /// of the drainage area in m²), y wear (metres eroded), z deposition
    /// (metres of sediment), w water (0 dry .. 1 river or lake); see
    /// terrain::LandformMasks. Null reads (0, 0, 0, 0).
    const glm::vec4* landform = nullptr;
    /// Optional, per vertex: the rock masks of rock beds as layer rules
    /// read them (LayerRule::hardness, bed): x hardness (0 soft .. 1 hard),
    /// y the bed's index; see terrain::RockMasks. Null reads (0, 0).
    const glm::vec2* rock = nullptr;
    std::size_t vertexCount = 0;
    const std::uint32_t* indices = nullptr; ///< counter-clockwise seen from outside
    std::size_t indexCount = 0;             ///< multiple of 3
    glm::dvec3 origin{0.0};                 ///< world position of the mesh's local (0,0,0)
};

} // namespace strata::render
