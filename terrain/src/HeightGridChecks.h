// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: what the landform and surface-texture measures (LandformStatistics, SurfaceRoughness,
// SlopeDistribution, HeightSpectrum, SurfaceTexture) share: the check of a
// height grid given by the user, and a least-squares line in log–log space.

#include <strata/DeterministicMath.h>
#include <strata/Error.h>
#include <strata/Format.h>
#include <strata/terrain/LandformStatistics.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace strata::terrain::detail {

/// Throws strata::Error (BadInput), its message starting with `what`, for a
/// grid under 3 x 3 cells, a wrong number of heights, a cell size that is not
/// finite and > 0, or a non-finite height (naming the cell).
inline void checkHeightGrid(const std::string& what, const std::vector<double>& heights, int width, int height,
                            double cellSize)
{
    const std::string size = std::to_string(width) + " x " + std::to_string(height);
    if (width < 3 || height < 3)
        throw Error(ErrorKind::BadInput, what + ": the grid is " + size + " cells; it must be at least 3 x 3");
    if (heights.size() != std::size_t(width) * std::size_t(height))
        throw Error(ErrorKind::BadInput, what + ": " + std::to_string(heights.size()) + " heights for a " + size +
                                             " grid (" + std::to_string(std::size_t(width) * std::size_t(height)) +
                                             " cells)");
    if (!std::isfinite(cellSize) || cellSize <= 0.0)
        throw Error(ErrorKind::BadInput,
                    what + ": cell size = " + formatNumber(cellSize) + " must be a finite number > 0 (metres)");
    for (std::size_t i = 0; i < heights.size(); ++i) {
        if (!std::isfinite(heights[i]))
            throw Error(ErrorKind::BadInput, what + ": the height at cell (x " +
                                                 std::to_string(i % std::size_t(width)) + ", z " +
                                                 std::to_string(i / std::size_t(width)) + ") is " +
                                                 formatNumber(heights[i]) + ", not a finite number");
    }
}

/// Least squares y = a + b·x through the points (means first, two passes):
/// exponent b, coefficient e^a, r² in the fitted space; all NaN without two
/// distinct x. The caller passes logs. Same arithmetic in the same order on
/// every call: the same bits.
inline LogLogFit fitLogLog(const std::vector<double>& x, const std::vector<double>& y)
{
    constexpr double NOT_A_NUMBER = std::numeric_limits<double>::quiet_NaN();
    LogLogFit fit;
    fit.points = x.size();
    fit.exponent = fit.coefficient = fit.rSquared = NOT_A_NUMBER;
    if (x.size() < 2) return fit;
    double mx = 0.0, my = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        mx += x[i];
        my += y[i];
    }
    mx /= double(x.size());
    my /= double(x.size());
    double sxx = 0.0, sxy = 0.0, syy = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double dx = x[i] - mx, dy = y[i] - my;
        sxx += dx * dx;
        sxy += dx * dy;
        syy += dy * dy;
    }
    if (!(sxx > 0.0)) return fit;
    const double b = sxy / sxx, a = my - b * mx;
    double residual = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double e = y[i] - (a + b * x[i]);
        residual += e * e;
    }
    fit.exponent = b;
    fit.coefficient = dmath::exp(a);
    fit.rSquared = syy > 0.0 ? std::max(0.0, 1.0 - residual / syy) : 1.0;
    return fit;
}

} // namespace strata::terrain::detail
