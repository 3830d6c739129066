// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/SurfaceRoughness.h>

#include "HeightGridChecks.h"

#include <strata/DeterministicMath.h>
#include <strata/Error.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace strata::terrain {

namespace {

void checkWindows(const std::vector<int>& windows)
{
    const std::string what = "surface roughness: ";
    if (windows.empty() || windows.size() > 16)
        throw Error(ErrorKind::BadInput,
                    what + "windows: " + std::to_string(windows.size()) + " window widths given; give 1 to 16");
    for (std::size_t i = 0; i < windows.size(); ++i) {
        const int w = windows[i];
        if (w < 3 || w % 2 == 0 || w > 1 << 20)
            throw Error(ErrorKind::BadInput, what + "windows[" + std::to_string(i) + "] = " + std::to_string(w) +
                                                 " cells must be odd and in 3..1048575");
        if (i > 0 && w <= windows[i - 1])
            throw Error(ErrorKind::BadInput, what + "windows[" + std::to_string(i) + "] = " + std::to_string(w) +
                                                 " must be wider than the window before it (" +
                                                 std::to_string(windows[i - 1]) + ")");
    }
}

} // namespace

SurfaceRoughness measureSurfaceRoughness(const std::vector<double>& heights, int width, int height, double cellSize,
                                         const SurfaceRoughnessOptions& options)
{
    detail::checkHeightGrid("surface roughness", heights, width, height, cellSize);
    checkWindows(options.windows);

    const std::size_t W = std::size_t(width), H = std::size_t(height);
    double largest = 0.0;
    for (double h : heights) largest = std::max(largest, std::abs(h));
    const double zeroStd = std::max(1e-9, 1e-12 * largest);

    SurfaceRoughness result;
    std::vector<double> rowSums(W * H), residuals;
    std::vector<double> x, y; // the fit's points
    for (const int w : options.windows) {
        RoughnessAtScale scale;
        scale.window = w;
        scale.length = double(w) * cellSize;
        scale.residualStd = std::numeric_limits<double>::quiet_NaN();
        const std::size_t half = std::size_t(w / 2);
        if (std::size_t(w) <= W && std::size_t(w) <= H) {
            // Sums of w heights along x, for the columns whose window fits.
            for (std::size_t z = 0; z < H; ++z) {
                const double* row = heights.data() + z * W;
                for (std::size_t cx = half; cx + half < W; ++cx) {
                    double sum = 0.0;
                    for (std::size_t i = cx - half; i <= cx + half; ++i) sum += row[i];
                    rowSums[z * W + cx] = sum;
                }
            }
            // Then along z, and the residual from the window's mean.
            const double count = double(w) * double(w);
            residuals.clear();
            for (std::size_t cz = half; cz + half < H; ++cz) {
                for (std::size_t cx = half; cx + half < W; ++cx) {
                    double sum = 0.0;
                    for (std::size_t j = cz - half; j <= cz + half; ++j) sum += rowSums[j * W + cx];
                    residuals.push_back(heights[cz * W + cx] - sum / count);
                }
            }
            double mean = 0.0;
            for (double r : residuals) mean += r;
            mean /= double(residuals.size());
            double squares = 0.0;
            for (double r : residuals) squares += (r - mean) * (r - mean);
            scale.cells = residuals.size();
            scale.residualStd = std::sqrt(squares / double(residuals.size()));
            if (scale.residualStd > zeroStd) {
                x.push_back(dmath::log(scale.length));
                y.push_back(dmath::log(scale.residualStd));
            }
        }
        result.scales.push_back(scale);
    }
    result.fit = detail::fitLogLog(x, y);
    result.exponent = result.fit.exponent;
    return result;
}

} // namespace strata::terrain
