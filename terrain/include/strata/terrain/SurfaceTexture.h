// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The surface texture of a height grid at several cell sizes (issue 38):
/// the grid as sampled (e.g. at 4 m) is block-averaged to coarser cells
/// (e.g. 8 m, 32 m: whole multiples), and each is measured for its
/// roughness-vs-scale exponent (SurfaceRoughness.h), its spectral slopes
/// (HeightSpectrum.h) and its slope angles (SlopeDistribution.h), so a
/// terrain can be compared with real DEMs of those resolutions. See
/// docs/landform-statistics.md.
///
/// Grids are row-major, `heights[z * width + x]`, cell size `cellSize` metres
/// on both axes, as in LandformStatistics.h. The same input gives the same
/// bits on any thread count.

#include <strata/terrain/HeightSpectrum.h>
#include <strata/terrain/SlopeDistribution.h>
#include <strata/terrain/SurfaceRoughness.h>

#include <string>
#include <vector>

namespace strata::terrain {

/// A height grid of the same layout as the measures take.
struct HeightGrid
{
    int width = 0, height = 0;
    double cellSize = 0.0;       ///< metres
    std::vector<double> heights; ///< width·height values, row-major, metres
};

/// The grid averaged over blocks of `factor` × `factor` cells: cell (i, j)
/// of the result is the mean of the input cells (i·factor .. i·factor +
/// factor − 1, j·factor .. j·factor + factor − 1), summed row by row; a
/// partial block at the right or bottom edge is dropped, so the result is
/// ⌊width / factor⌋ × ⌊height / factor⌋ cells of factor · cellSize metres
/// (its cell (0, 0) is centred (factor − 1)/2 input cells from the input's).
/// factor 1 copies the grid. O(width · height).
///
/// Throws strata::Error (BadInput) for an empty grid, a wrong number of
/// heights, a non-finite height (naming the cell), a bad cell size, a factor
/// below 1, or a factor larger than the grid's width or height (naming it).
HeightGrid blockAverage(const std::vector<double>& heights, int width, int height, double cellSize, int factor);

/// The block-averaging factor that turns cells of `gridCellSize` metres into
/// cells of `cellSize` metres: cellSize / gridCellSize rounded to an integer,
/// which must be >= 1 and match the ratio within 1e-6 relative. Throws
/// strata::Error (BadInput) otherwise ("... is not a whole multiple ..."), or
/// when either size is not finite and > 0, or the factor is over 2^20.
int blockFactor(double gridCellSize, double cellSize);

struct SurfaceTextureOptions
{
    SurfaceRoughnessOptions roughness;
    HeightSpectrumOptions spectrum;
    SlopeDistributionOptions slopes;
};

/// The three texture measures of one grid.
struct SurfaceTexture
{
    int factor = 1; ///< the block-averaging factor from the grid given
    int width = 0, height = 0;
    double cellSize = 0.0; ///< metres
    /// False when the averaged grid is smaller than 3 × 3 cells: nothing is
    /// measured (the measures below keep their defaults).
    bool measured = false;
    SurfaceRoughness roughness;
    HeightSpectrum spectrum;
    SlopeDistribution slopes;
};

/// measureSurfaceRoughness(), measureHeightSpectrum() and
/// measureSlopeDistribution() of one grid (factor 1). Throws what they throw.
SurfaceTexture measureSurfaceTexture(const std::vector<double>& heights, int width, int height, double cellSize,
                                     const SurfaceTextureOptions& options = {});

/// The texture of `heights` (cells of `cellSize` metres) at each of
/// `cellSizes` (metres, each a whole multiple of cellSize: blockFactor()),
/// in the order given: the grid block-averaged (blockAverage()) and measured.
/// A cell size whose averaged grid would be smaller than 3 × 3 cells (or
/// whose factor exceeds the grid) gives an entry with `measured` false.
/// Throws what blockFactor() and the measures throw.
std::vector<SurfaceTexture> measureSurfaceTextureAtCells(const std::vector<double>& heights, int width, int height,
                                                         double cellSize, const std::vector<double>& cellSizes,
                                                         const SurfaceTextureOptions& options = {});

/// One line per entry, ending with a newline: "texture at 8 m" then the grid,
/// the roughness exponent, β fine and coarse, the slope percentiles and the
/// cliff fraction; "n/a" for a number that could not be measured.
std::string formatSurfaceTexture(const std::vector<SurfaceTexture>& textures);

} // namespace strata::terrain
