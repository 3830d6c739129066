// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The landform masks of erosion and the rock masks of rock beds per mesh
/// vertex (meshing::TriangleMesh::landform, rock), for terrain layer rules
/// (render::LayerRule::flow, wear, deposition, water; hardness, bed) and
/// the landform and rock debug views.

#include <strata/meshing/TriangleMesh.h>
#include <strata/terrain/LandformMasks.h>
#include <strata/terrain/RockMasks.h>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <vector>

namespace strata::world {

/// (flow, wear, deposition, water) at every vertex of `mesh`: `masks`
/// evaluated at the vertex's world column (mesh.origin + position, x and z,
/// in double), in blocks of 1024 vertices over fixed ranges on every
/// thread. Each value depends on its vertex alone, so the result is the
/// same on any thread count. O(vertices).
std::vector<glm::vec4> computeLandformAttributes(const terrain::LandformMasks& masks,
                                                 const meshing::TriangleMesh& mesh);

/// (hardness, bed) at every vertex of `mesh`: `masks` evaluated at the
/// vertex's world point (mesh.origin + position, in double), in the same
/// fixed blocks as computeLandformAttributes(): the same on any thread
/// count, and a chunk's or tile's vertex gets what the whole mesh's would.
std::vector<glm::vec2> computeRockAttributes(const terrain::RockMasks& masks, const meshing::TriangleMesh& mesh);

} // namespace strata::world
