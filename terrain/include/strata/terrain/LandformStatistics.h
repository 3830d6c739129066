// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Landform statistics of a height grid, the numbers geomorphologists use to
/// compare a landscape with real land: how much of it lies in closed
/// depressions or on flats, Hack's law (the longest flow path against
/// drainage area) and the slope–area relation (Flint's law, the channels'
/// concavity). Flow is D8 steepest descent over the priority-flood-filled
/// surface (routeFlow()).
///
/// Grids are row-major, `values[z * width + x]`, cell size `cellSize` metres
/// on both axes, as in FlowRouting.h. The same input gives the same bits.

#include <cstddef>
#include <string>
#include <vector>

namespace strata::terrain {

struct LandformStatisticsOptions
{
    /// Metres, >= 0: a cell is in a closed depression when its spill level
    /// (the highest original height on its flow path to the grid's edge, the
    /// level a plain priority-flood fills it to) is more than this above its
    /// own height. The epsilon fill's steps (ulps) never count, whatever the
    /// tolerance.
    double depressionTolerance = 1e-6;
    /// Metres per metre, >= 0: a cell whose D8 steepest downhill slope on the
    /// filled surface is below this is flat.
    double flatSlope = 1e-3;
    /// Cells (drainage area / cellSize²), >= 2: the cells whose drainage area
    /// is at least this enter the Hack's law fit.
    double hackMinCells = 20.0;
    /// Cells, >= 1: the cells whose drainage area is at least this are
    /// channels and enter the slope–area fit.
    double channelMinCells = 100.0;
    /// Metres per metre, >= 0: channel slopes at or below this are taken as
    /// zero and left out of the slope–area fit (log 0 is not defined).
    double minChannelSlope = 1e-9;
    /// Bins of log drainage area for the slope–area fit, 2..1000.
    int slopeAreaBins = 20;
    /// Cells a bin needs to enter the slope–area fit, >= 1.
    int minCellsPerBin = 3;
};

/// A least-squares line y = intercept + slope·x through `points` points.
struct LogLogFit
{
    double exponent = 0.0;    ///< slope of log y against log x (NaN without 2 distinct x)
    double coefficient = 0.0; ///< e^intercept: y = coefficient · x^exponent (NaN likewise)
    double rSquared = 0.0;    ///< coefficient of determination of the fit in log space (NaN likewise)
    std::size_t points = 0;   ///< points fitted (cells, or bins for the binned fit)
};

struct LandformStatistics
{
    int width = 0, height = 0;
    double cellSize = 0.0;         ///< metres
    std::size_t interiorCells = 0; ///< (width − 2)·(height − 2): the cells the fractions are of
    /// Fraction of the interior cells lying in closed depressions (see
    /// LandformStatisticsOptions::depressionTolerance); edge cells drain off
    /// the grid and never do.
    double depressionFraction = 0.0;
    double maxDepressionDepth = 0.0; ///< metres: the deepest cell below its spill level
    double depressionVolume = 0.0;   ///< cubic metres a plain fill adds
    /// Fraction of the interior cells whose D8 steepest slope on the filled
    /// surface is below LandformStatisticsOptions::flatSlope.
    double flatFraction = 0.0;
    double meanSlope = 0.0; ///< mean D8 steepest slope of the interior cells on the filled surface, m/m
    double relief = 0.0;    ///< highest minus lowest height, metres
    /// Hack's law L = c·A^h over the cells with at least hackMinCells of
    /// drainage area, fitted cell by cell in log space: L the longest flow
    /// path from a divide to the cell (metres, D8 steps of cellSize or
    /// cellSize·√2), A its drainage area (square metres). Real basins give
    /// h ≈ 0.5–0.6. Edge cells count (they collect whole basins).
    LogLogFit hack;
    /// The slope–area relation S = ks·A^(−θ) of the channel cells (at least
    /// channelMinCells of drainage area): S the D8 slope to the receiver on
    /// the original surface where positive, else on the filled surface,
    /// slopes at or below minChannelSlope skipped. Binned: log A is split
    /// into slopeAreaBins equal bins between the channel cells' extremes,
    /// each bin with at least minCellsPerBin cells gives one point (mean
    /// log A, mean log S), and the line is fitted through those points, so
    /// the many small channels do not outweigh the few large ones.
    /// `slopeArea.exponent` is −θ; `slopeArea.points` counts bins.
    LogLogFit slopeArea;
    double concavity = 0.0;         ///< θ = −slopeArea.exponent: 0.2–0.8 for real rivers (NaN without a fit)
    double steepness = 0.0;         ///< ks = slopeArea.coefficient (m^(2θ))
    std::size_t channelCells = 0;   ///< interior cells with at least channelMinCells of drainage area
    std::size_t slopeAreaCells = 0; ///< channel cells with a slope above minChannelSlope: those binned
};

/// Measures `heights` (width × height cells, both >= 3; finite values;
/// cellSize finite and > 0, metres). O(n log n) (routeFlow()), then O(n).
/// Throws strata::Error for a grid smaller than 3 × 3, a wrong number of
/// heights, a non-finite height (naming the cell), a bad cell size or an
/// option out of range (naming it).
LandformStatistics measureLandforms(const std::vector<double>& heights, int width, int height, double cellSize,
                                    const LandformStatisticsOptions& options = {});

/// A readable multi-line table of `stats`, one quantity a line, ending with
/// a newline; "n/a" for a fit that could not be made.
std::string formatLandformStatistics(const LandformStatistics& stats);

} // namespace strata::terrain
