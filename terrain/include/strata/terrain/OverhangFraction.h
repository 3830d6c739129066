// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// How much of a terrain overhangs (issue 38): the fraction of the columns
/// of a top-surface grid (TopSurface.h) that, going up through the last
/// `depth` metres below the top surface, leave rock more than once. A
/// column under a plain height field leaves rock once, at the top surface;
/// one under an arch, a ledge or a shallow cave leaves it again. Caves and
/// overhangs whose air lies deeper than `depth` below the top surface are
/// left out: this counts what shapes the visible surface, not every cave.
/// A DEM (a height grid without a volume) has no such number.

#include <strata/terrain/DensityField.h>
#include <strata/terrain/TopSurface.h>

#include <cstddef>
#include <functional>
#include <string>

namespace strata::terrain {

struct OverhangOptions
{
    /// Metres, finite and > 0: how far below the top surface each column starts.
    double depth = 20.0;
    /// Metres, finite and > 0, at most `depth`: the largest distance between
    /// the density samples along a column (the samples are spaced evenly, so
    /// the step used is depth / ⌈depth / step⌉). A rock layer or air gap
    /// thinner than the step may be missed.
    double step = 0.25;
};

struct OverhangStatistics
{
    std::size_t columns = 0;          ///< columns of the grid
    std::size_t overhangColumns = 0;  ///< columns that leave rock more than once
    double fraction = 0.0;            ///< overhangColumns / columns
    double depth = 0.0;               ///< metres: the options' depth
    double step = 0.0;                ///< metres: the step used (at most the options' step)
    std::size_t samplesPerColumn = 0; ///< density() samples per column
};

/// Counts the columns of `top` (sampled from `field` by sampleTopSurface(),
/// or any grid of the same layout) that overhang. For the column at
/// (top.origin.x + i·cellSize, top.origin.y + j·cellSize) with top height t,
/// the density is sampled at y_k = t − depth + k·s for k = 0 .. m + 1, where
/// m = ⌈depth / step⌉ and s = depth / m: from `depth` below the top surface
/// up to one step above it, so the top surface's own exit from rock counts
/// once whatever the rounding of t. The column overhangs when the samples go
/// from rock (density < 0) to air (density >= 0) more than once. A column
/// with no rock in the sampled region (t = region.min.y) leaves rock at most
/// where the field has rock in the `depth` below it, as any other.
///
/// Each column is one block (DensityField::densities()); rows run in
/// parallel (TBB) and the counts are integers summed in row order, so the
/// result is the same on any thread count. `progress`, when set, is called
/// from the calling thread with the fraction done (0..1) between batches of
/// rows; returning false stops with strata::Error (ErrorKind::Interrupted,
/// "overhang measurement interrupted").
///
/// Cost: columns · (m + 2) density evaluations (82 per column with the
/// defaults). Throws strata::Error (BadInput) for an empty grid, a wrong
/// number of heights, a non-finite height or origin, a bad cell size, or a
/// depth or step out of range (naming it); (Internal) if the field returns
/// NaN.
OverhangStatistics measureOverhangs(const DensityField& field, const TopSurfaceGrid& top,
                                    const OverhangOptions& options = {},
                                    const std::function<bool(double)>& progress = {});

/// One line (ending with a newline): the fraction, the counts, the depth and
/// the step.
std::string formatOverhangs(const OverhangStatistics& stats);

} // namespace strata::terrain
