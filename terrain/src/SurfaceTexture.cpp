// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/SurfaceTexture.h>

#include <strata/Error.h>
#include <strata/Format.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <utility>

namespace strata::terrain {

namespace {

constexpr int MAX_FACTOR = 1 << 20;

std::string number(double v)
{
    if (!std::isfinite(v)) return "n/a";
    std::ostringstream o;
    o << std::setprecision(4) << v;
    return o.str();
}

} // namespace

HeightGrid blockAverage(const std::vector<double>& heights, int width, int height, double cellSize, int factor)
{
    const std::string what = "block average: ";
    const std::string size = std::to_string(width) + " x " + std::to_string(height);
    if (width < 1 || height < 1)
        throw Error(ErrorKind::BadInput, what + "the grid is " + size + " cells; it must hold at least one");
    if (heights.size() != std::size_t(width) * std::size_t(height))
        throw Error(ErrorKind::BadInput, what + std::to_string(heights.size()) + " heights for a " + size + " grid");
    if (!std::isfinite(cellSize) || cellSize <= 0.0)
        throw Error(ErrorKind::BadInput,
                    what + "cell size = " + formatNumber(cellSize) + " must be a finite number > 0 (metres)");
    for (std::size_t i = 0; i < heights.size(); ++i) {
        if (!std::isfinite(heights[i]))
            throw Error(ErrorKind::BadInput, what + "the height at cell (x " + std::to_string(i % std::size_t(width)) +
                                                 ", z " + std::to_string(i / std::size_t(width)) + ") is " +
                                                 formatNumber(heights[i]) + ", not a finite number");
    }
    if (factor < 1 || factor > width || factor > height)
        throw Error(ErrorKind::BadInput,
                    what + "factor = " + std::to_string(factor) + " must be >= 1 and fit the " + size + " grid");

    HeightGrid out;
    out.width = width / factor;
    out.height = height / factor;
    out.cellSize = cellSize * double(factor);
    out.heights.assign(std::size_t(out.width) * std::size_t(out.height), 0.0);
    const std::size_t W = std::size_t(width), k = std::size_t(factor);
    const double count = double(factor) * double(factor);
    for (std::size_t j = 0; j < std::size_t(out.height); ++j) {
        for (std::size_t i = 0; i < std::size_t(out.width); ++i) {
            double sum = 0.0;
            for (std::size_t z = j * k; z < (j + 1) * k; ++z)
                for (std::size_t x = i * k; x < (i + 1) * k; ++x) sum += heights[z * W + x];
            out.heights[j * std::size_t(out.width) + i] = factor == 1 ? sum : sum / count;
        }
    }
    return out;
}

int blockFactor(double gridCellSize, double cellSize)
{
    if (!std::isfinite(gridCellSize) || gridCellSize <= 0.0)
        throw Error(ErrorKind::BadInput, "surface texture: the grid's cell size = " + formatNumber(gridCellSize) +
                                             " must be a finite number > 0 (metres)");
    if (!std::isfinite(cellSize) || cellSize <= 0.0)
        throw Error(ErrorKind::BadInput, "surface texture: a cell size of " + formatNumber(cellSize) +
                                             " m is asked; it must be a finite number > 0 (metres)");
    const double ratio = cellSize / gridCellSize, rounded = std::round(ratio);
    if (!(rounded >= 1.0) || std::abs(ratio - rounded) > 1e-6 * rounded)
        throw Error(ErrorKind::BadInput, "surface texture: a cell of " + formatNumber(cellSize) +
                                             " m is not a whole multiple of the grid's " + formatNumber(gridCellSize) +
                                             " m cells");
    if (rounded > double(MAX_FACTOR))
        throw Error(ErrorKind::BadInput, "surface texture: a cell of " + formatNumber(cellSize) + " m is " +
                                             formatNumber(rounded) + " of the grid's " + formatNumber(gridCellSize) +
                                             " m cells, more than 2^20");
    return int(rounded);
}

SurfaceTexture measureSurfaceTexture(const std::vector<double>& heights, int width, int height, double cellSize,
                                     const SurfaceTextureOptions& options)
{
    SurfaceTexture t;
    t.factor = 1;
    t.width = width;
    t.height = height;
    t.cellSize = cellSize;
    t.roughness = measureSurfaceRoughness(heights, width, height, cellSize, options.roughness);
    t.spectrum = measureHeightSpectrum(heights, width, height, cellSize, options.spectrum);
    t.slopes = measureSlopeDistribution(heights, width, height, cellSize, options.slopes);
    t.measured = true;
    return t;
}

std::vector<SurfaceTexture> measureSurfaceTextureAtCells(const std::vector<double>& heights, int width, int height,
                                                         double cellSize, const std::vector<double>& cellSizes,
                                                         const SurfaceTextureOptions& options)
{
    std::vector<int> factors;
    for (double c : cellSizes) factors.push_back(blockFactor(cellSize, c)); // all refused before any work
    std::vector<SurfaceTexture> textures;
    for (const int factor : factors) {
        SurfaceTexture t;
        if (factor > width / 3 || factor > height / 3) { // fewer than 3 x 3 averaged cells
            t.factor = factor;
            t.width = width / factor;
            t.height = height / factor;
            t.cellSize = cellSize * double(factor);
        } else if (factor == 1) {
            t = measureSurfaceTexture(heights, width, height, cellSize, options);
        } else {
            const HeightGrid coarse = blockAverage(heights, width, height, cellSize, factor);
            t = measureSurfaceTexture(coarse.heights, coarse.width, coarse.height, coarse.cellSize, options);
            t.factor = factor;
        }
        textures.push_back(std::move(t));
    }
    return textures;
}

std::string formatSurfaceTexture(const std::vector<SurfaceTexture>& textures)
{
    std::ostringstream out;
    for (const SurfaceTexture& t : textures) {
        out << std::left << std::setw(24) << ("texture at " + formatNumber(t.cellSize) + " m") << t.width << " x "
            << t.height << " cells";
        if (!t.measured) {
            out << ": too small to measure (under 3 x 3)\n";
            continue;
        }
        out << ": roughness " << number(t.roughness.exponent) << ", beta fine " << number(t.spectrum.fine.beta)
            << ", coarse " << number(t.spectrum.coarse.beta) << ", slope p10 " << number(t.slopes.p10) << ", p50 "
            << number(t.slopes.median) << ", p90 " << number(t.slopes.p90) << " deg, cliffs "
            << number(100.0 * t.slopes.cliffFraction) << " %\n";
    }
    return out.str();
}

} // namespace strata::terrain
