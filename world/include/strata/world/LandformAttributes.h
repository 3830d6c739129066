// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The landform masks of erosion per mesh vertex (meshing::TriangleMesh::
/// landform), for terrain layer rules (render::LayerRule::flow, wear,
/// deposition, water) and the landform debug views.

#include <strata/meshing/TriangleMesh.h>
#include <strata/terrain/LandformMasks.h>

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

} // namespace strata::world
