// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// How a height grid's roughness grows with the scale it is looked at: the
/// roughness-vs-scale exponent of issue 38. For each window of w × w cells,
/// the residual of every height from the mean of the window centred on it,
/// r = z − mean(z over the window), has a standard deviation σ(w); the
/// exponent is the slope of log σ against log(w · cellSize). A surface that
/// is smooth at the window's scale (a curved hill: residuals grow like w²)
/// gives about 2; a self-affine rough surface gives its Hurst exponent, real
/// land about 1.0–1.2 (issue 38: SRTM 84 m 1.15, 30 m mountains 1.06, 5 m
/// forest 1.04). See docs/landform-statistics.md.
///
/// Grids are row-major, `heights[z * width + x]`, cell size `cellSize` metres
/// on both axes, as in LandformStatistics.h. The same input gives the same
/// bits.

#include <strata/terrain/LandformStatistics.h>

#include <cstddef>
#include <vector>

namespace strata::terrain {

struct SurfaceRoughnessOptions
{
    /// Window widths in cells: odd, >= 3, increasing, at most 16 of them.
    std::vector<int> windows{3, 5, 9, 17};
};

/// The residual spread at one window width.
struct RoughnessAtScale
{
    int window = 0;           ///< w, cells
    double length = 0.0;      ///< w · cellSize, metres
    double residualStd = 0.0; ///< σ of the residuals, metres (NaN when no window fits the grid)
    std::size_t cells = 0;    ///< cells whose whole window lies inside the grid: those σ is over
};

struct SurfaceRoughness
{
    std::vector<RoughnessAtScale> scales; ///< one per window, in the options' order
    /// The least-squares line through (log length, log σ) of the scales that
    /// enter it (a window inside the grid, σ above zero: see
    /// measureSurfaceRoughness()); `fit.points` counts them.
    LogLogFit fit;
    /// fit.exponent: NaN when fewer than 2 scales enter the fit, e.g. a
    /// plane (every σ is zero) or a grid narrower than 5 cells.
    double exponent = 0.0;
};

/// Measures the roughness-vs-scale exponent of `heights` (width × height
/// cells, both >= 3; finite values; cellSize finite and > 0, metres).
///
/// Per window width w (the options' windows): the window's mean is a box
/// filter (separable sums of w values along x then z, no running sums, so a
/// plane's residuals are zero up to rounding); σ is the population standard
/// deviation (about the residuals' own mean) over the cells whose whole window
/// lies inside the grid. A window wider than the grid has no such cell: its σ
/// is NaN and it is left out of the fit. A σ at or below max(1e-9 m, 1e-12 ·
/// the largest |height|) is zero up to rounding (a plane, a tilted plane):
/// log 0 is not defined, so that scale is left out of the fit too.
///
/// O(width · height · Σw). Throws strata::Error (BadInput) for a grid smaller
/// than 3 × 3, a wrong number of heights, a non-finite height (naming the
/// cell), a bad cell size, or bad windows (naming the window).
SurfaceRoughness measureSurfaceRoughness(const std::vector<double>& heights, int width, int height, double cellSize,
                                         const SurfaceRoughnessOptions& options = {});

} // namespace strata::terrain
