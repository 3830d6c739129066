// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The top surface of a density field as a height grid: per column (x, z),
/// the highest rock surface in a box, what an aerial survey (a digital
/// elevation model) of the terrain would record. Overhangs and caves below
/// the top surface do not show. The grid feeds measureLandforms()
/// (LandformStatistics.h) and FlowRouting.h, which take the same layout.

#include <strata/terrain/DensityField.h>

#include <glm/vec2.hpp>

#include <cstddef>
#include <functional>
#include <vector>

namespace strata::terrain {

/// A regular grid of heights over an xz rectangle, row-major:
/// heights[z·width + x] is the height (world y, metres) of the column at
/// (origin.x + x·cellSize, origin.y + z·cellSize).
struct TopSurfaceGrid
{
    int width = 0;               ///< columns along x
    int height = 0;              ///< rows along z
    double cellSize = 0.0;       ///< metres between neighbouring columns, both axes
    glm::dvec2 origin{0.0};      ///< world (x, z) of column (0, 0), metres
    std::vector<double> heights; ///< width·height values, world y in metres
    /// Columns given the region's top (rock at region.max.y: the surface may
    /// lie above the box) and its bottom (no rock in the box): clipped
    /// columns, which distort statistics measured on the grid.
    std::size_t columnsAtTop = 0, columnsAtBottom = 0;
};

/// Vertical distance (metres) within which sampleTopSurface() places each
/// height: the bisection stops once its bracket is this narrow.
inline constexpr double TOP_SURFACE_TOLERANCE = 1e-4;
/// The shortest step of sampleTopSurface()'s trace down a column, metres:
/// rock thinner than this may be stepped over. Where a field's distance
/// bound is far below the true distance (rock beds cut by differential
/// erosion: their Lipschitz constant is large), steps of the tolerance took
/// tens of thousands of evaluations per column; a centimetre is far below
/// any cell the statistics use.
inline constexpr double TOP_SURFACE_MIN_STEP = 0.01;

/// Samples the top surface of `field` over `region`.
///
/// Columns stand at (region.min.x + i·cellSize, region.min.z + j·cellSize)
/// for every i, j that keep the column inside the region's xz rectangle
/// (width = ⌊(max.x − min.x)/cellSize⌋ + 1, likewise height; a remainder
/// smaller than a cell is left out, rounding of 1e-9 cells forgiven).
/// Each column's height is the highest y in [region.min.y, region.max.y]
/// where density() changes from air (> 0) above to rock or surface (<= 0)
/// below, going down from region.max.y: found by sphere tracing down
/// with field.distanceBound() (steps of at least TOP_SURFACE_MIN_STEP, or a
/// few doubles' spacing beyond about 1e13 m from the origin, so a rock layer
/// thinner than that may be stepped over; stretches of the column that
/// field.bounds() proves to be air are skipped first), then bisection on
/// density() until the bracket is at most TOP_SURFACE_TOLERANCE high; the
/// height is the bracket's midpoint. Special columns:
///  - no rock anywhere in [min.y, max.y] (a column over a hole, or a box
///    above the terrain): region.min.y;
///  - rock at region.max.y itself (the surface lies at or above the box's
///    top, a column entirely rock included): region.max.y.
///
/// Rows are sampled in parallel (TBB); every column is independent, so the
/// result is the same bits on any thread count. `progress`, when set, is
/// called from the calling thread with the fraction done (0..1) between
/// batches of rows; returning false stops the sampling with strata::Error
/// (ErrorKind::Interrupted, "top surface sampling interrupted").
///
/// Cost: per column, the steps of the trace (a few tens for gentle slopes;
/// more where the distance bound is loose, e.g. beside cliffs) plus about
/// log2(step / tolerance) density() calls.
///
/// Throws strata::Error (BadInput) when cellSize is not finite and > 0, the
/// region is not finite with min <= max on every axis, or the grid would
/// have more than 2^31 − 1 columns on an axis or 2^28 columns in all. Throws
/// strata::Error (Internal) if the field returns NaN.
TopSurfaceGrid sampleTopSurface(const DensityField& field, const WorldBox& region, double cellSize,
                                const std::function<bool(double)>& progress = {});

} // namespace strata::terrain
