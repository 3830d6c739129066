// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: the surface of a sampled box of the lattice, as the bake's
// tiles (TileMesher.cpp) and the engine terrain export (TerrainTile.cpp)
// both mesh it, so the two agree to the bit.

#include "ClipToBox.h"
#include "SampleArray.h"

#include <strata/meshing/TriangleMesh.h>

#include <array>

namespace strata::world::detail {

/// Positions are multiples of 1/TILE_QUANTUM cell: with at most 4096 cells
/// from the box minimum that is 24 bits, exact in float.
inline constexpr double TILE_QUANTUM = 4096.0;

/// The dual (surface nets) mesh of `samples` (filled; lattice points from
/// two cells before the box to two cells past it on every axis), clipped
/// to the box of `cells` cells: positions in cells relative to the box
/// minimum, unit normals from the cells' gradients.
ClipMesh meshSampledBox(const SampleArray& samples, const std::array<int, 3>& cells);

/// `mesh` in metres (cells of `cellMetres`) relative to `origin`.
meshing::TriangleMesh toTriangleMesh(const ClipMesh& mesh, double cellMetres, const glm::dvec3& origin);

} // namespace strata::world::detail
