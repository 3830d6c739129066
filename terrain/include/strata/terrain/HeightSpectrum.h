// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The spectral slope of a height grid (issue 38): how fast the power of
/// its relief falls with the wavenumber, P(k) ∝ k^−β, in two bands of
/// wavelengths, fine (2.5–8 cells) and coarse (8 cells to a third of the
/// map's smaller extent). A surface smoothed at a scale has a steep β at
/// wavelengths below it; real land gives β fine 5.2 and coarse 3.5 (SRTM
/// 84 m), 3.6 and 4.6 (30 m mountains), 5.5 and 4.6 (5 m forest). See
/// docs/landform-statistics.md.
///
/// Grids are row-major, `heights[z * width + x]`, cell size `cellSize` metres
/// on both axes, as in LandformStatistics.h. The same input gives the same
/// bits on any thread count.

#include <strata/terrain/LandformStatistics.h>

#include <cstddef>
#include <vector>

namespace strata::terrain {

struct HeightSpectrumOptions
{
    /// Cells, >= 2 (the Nyquist wavelength): the fine band's shortest wavelength.
    double fineMinWavelength = 2.5;
    /// Cells, > fineMinWavelength: the fine band's longest wavelength and the
    /// coarse band's shortest.
    double fineMaxWavelength = 8.0;
    /// In (0, 1]: the coarse band's longest wavelength as a fraction of the
    /// grid's smaller extent (min(width, height) · cellSize).
    double coarseMaxFraction = 1.0 / 3.0;
    /// Log-spaced bins of the radial wavenumber per decade, in [1, 100]: a
    /// band of d decades gets ⌈d · binsPerDecade⌉ bins of equal width in log k.
    double binsPerDecade = 10.0;
};

/// The power-law fit over one band of wavelengths.
struct SpectralBand
{
    double minWavelength = 0.0; ///< metres (the band's highest wavenumber is 1 / this)
    double maxWavelength = 0.0; ///< metres
    /// The least-squares line through (mean log k, log mean |F|²) of the
    /// band's bins that hold a wavenumber of the padded grid; `fit.points`
    /// counts those bins. k in cycles per metre.
    LogLogFit fit;
    /// β = −fit.exponent: NaN where the band has fewer than 2 such bins (a
    /// grid too small for the band) or the surface is a plane.
    double beta = 0.0;
};

struct HeightSpectrum
{
    int paddedWidth = 0, paddedHeight = 0; ///< the FFT's grid: powers of two >= width, height
    SpectralBand fine, coarse;
};

/// Measures the spectral slopes of `heights` (width × height cells, both
/// >= 3; finite values; cellSize finite and > 0, metres):
///  1. the least-squares plane through the heights is subtracted (a tilt
///     would otherwise put its ramp's k^−2 leakage over everything);
///  2. a separable Hann window, w(i) = sin²(π(i + ½)/n) per axis, tapers the
///     edges to zero (the grid is not periodic);
///  3. the grid is zero-padded to powers of two and transformed with a 2D
///     radix-2 FFT (own code: a bench-only measure of small grids, not worth
///     a package dependency such as FFTW);
///  4. |F|² is binned by radial wavenumber k = |(kx, kz)| (cycles per metre,
///     k = 0 left out) into log-spaced bins per band (both ends of a band
///     included); each bin gives the point (mean log k, log of its mean
///     |F|²), and β is minus the slope of the line through them.
/// A detrended surface whose RMS is at most max(1e-9 m, 1e-12 · the largest
/// |height|) is a plane: both bands are NaN.
///
/// Cost O(P log P) for P padded cells, memory 16·P bytes; rows and columns
/// transform in parallel (TBB), each independently, so the result is the
/// same bits on any thread count. Throws strata::Error (BadInput) for a grid
/// smaller than 3 × 3, a wrong number of heights, a non-finite height (naming
/// the cell), a bad cell size, an option out of range (naming it), or a
/// padded grid over 2^26 cells (1 GiB: use a coarser cell).
HeightSpectrum measureHeightSpectrum(const std::vector<double>& heights, int width, int height, double cellSize,
                                     const HeightSpectrumOptions& options = {});

} // namespace strata::terrain
