// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The distribution of slope angles over a height grid (issue 38): the
/// 10th, 50th and 90th percentiles and the fraction of cliffs, the cells
/// steeper than 60°. Real land: a median of 13° (SRTM 84 m), 24° (30 m
/// mountains), 4° (5 m forest). See docs/landform-statistics.md.
///
/// Grids are row-major, `heights[z * width + x]`, cell size `cellSize` metres
/// on both axes, as in LandformStatistics.h. The same input gives the same
/// bits.

#include <cstddef>
#include <vector>

namespace strata::terrain {

struct SlopeDistributionOptions
{
    /// Degrees, in (0, 90): a cell steeper than this (strictly) is a cliff.
    double cliffAngle = 60.0;
};

struct SlopeDistribution
{
    std::size_t cells = 0;      ///< interior cells measured: (width − 2)·(height − 2)
    double p10 = 0.0;           ///< degrees: 10 % of the cells are at most this steep
    double median = 0.0;        ///< degrees
    double p90 = 0.0;           ///< degrees
    double mean = 0.0;          ///< degrees
    double cliffAngle = 0.0;    ///< degrees: the options' cliffAngle
    double cliffFraction = 0.0; ///< fraction of the cells steeper than cliffAngle
};

/// Slope angles of the interior cells of `heights` (width × height cells,
/// both >= 3; finite values; cellSize finite and > 0, metres): per cell,
/// atan(|∇z|) in degrees with ∇z from central differences,
/// ((z[x+1] − z[x−1]) / 2·cellSize, (z[z+1] − z[z−1]) / 2·cellSize). A
/// percentile p is interpolated linearly between the sorted angles at ranks
/// ⌊(n − 1)·p⌋ and ⌈(n − 1)·p⌉ (NumPy's default).
///
/// O(n log n) (a sort). Throws strata::Error (BadInput) for a grid smaller
/// than 3 × 3, a wrong number of heights, a non-finite height (naming the
/// cell), a bad cell size or a cliffAngle outside (0, 90).
SlopeDistribution measureSlopeDistribution(const std::vector<double>& heights, int width, int height, double cellSize,
                                           const SlopeDistributionOptions& options = {});

} // namespace strata::terrain
