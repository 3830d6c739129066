// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The `cave` camera preset: a view from inside the largest cave, looking out.

#include <strata/render/Camera.h>

#include <openvdb/openvdb.h>

#include <glm/vec3.hpp>

#include <cstddef>

namespace strata::scene {

struct CaveViewOptions
{
    /// Coarse cell size in metres; 0 = twice the grid's voxel size, grown
    /// as needed so the region holds at most maxCells cells.
    double cellSize = 0.0;
    std::size_t maxCells = std::size_t(8) << 20;
    double fovYDegrees = 75.0;
};

/// What findCaveView() found, for reports.
struct CaveView
{
    render::Camera camera;
    std::size_t caveCells = 0; ///< cells of the chosen cave
    std::size_t caveCount = 0; ///< enclosed air regions found
    double clearance = 0.0;    ///< metres from the camera to the nearest rock (cell-distance estimate)
    bool looksOut = false;     ///< true: towards an opening; false: along the cave's longest axis
    double cellSize = 0.0;     ///< metres
};

/// A camera inside the largest cave of the level set `grid` (negative in
/// rock) within the world box [regionMin, regionMax]:
///  1. the box is sampled on a coarse grid of cells (air = grid value > 0);
///  2. air cells with rock somewhere above them in their column are cave
///     air; air open to the sky straight above is outside;
///  3. the cave air is split into 6-connected regions; the largest (most
///     cells, the first in x-y-z order on ties) is the cave;
///  4. the camera goes to its most interior cell: the largest breadth-first
///     (26-neighbour) distance from the region's walls;
///  5. it looks towards the region's nearest opening (a cave cell next to
///     outside air or the box's side) along the shortest path through the
///     cave, aiming at the farthest point of that path it can see (the
///     opening itself, and the sky beyond, when in sight); a cave with no
///     opening is looked along its longest axis (principal axis of its cells).
/// Deterministic. Throws strata::Error when the terrain has no cave.
/// Complexity O(cells).
CaveView findCaveView(const openvdb::FloatGrid& grid, const glm::dvec3& regionMin, const glm::dvec3& regionMax,
                      const CaveViewOptions& options = {});

} // namespace strata::scene
