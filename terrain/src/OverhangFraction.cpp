// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/OverhangFraction.h>

#include <strata/Error.h>
#include <strata/Format.h>
#include <strata/IntegerMath.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <vector>

namespace strata::terrain {

namespace {

/// Samples per column at most: a finer step is refused, not run for hours.
constexpr double MAX_STEPS = 1e6;

void checkInput(const TopSurfaceGrid& top, const OverhangOptions& o)
{
    const std::string what = "overhang measurement: ";
    if (top.width < 1 || top.height < 1)
        throw Error(ErrorKind::BadInput, what + "the grid is " + std::to_string(top.width) + " x " +
                                             std::to_string(top.height) + " columns; it must hold at least one");
    if (top.heights.size() != std::size_t(top.width) * std::size_t(top.height))
        throw Error(ErrorKind::BadInput, what + std::to_string(top.heights.size()) + " heights for a " +
                                             std::to_string(top.width) + " x " + std::to_string(top.height) + " grid");
    if (!std::isfinite(top.cellSize) || top.cellSize <= 0.0)
        throw Error(ErrorKind::BadInput,
                    what + "cell size = " + formatNumber(top.cellSize) + " must be a finite number > 0 (metres)");
    if (!std::isfinite(top.origin.x) || !std::isfinite(top.origin.y))
        throw Error(ErrorKind::BadInput, what + "the grid's origin (" + formatNumber(top.origin.x) + ", " +
                                             formatNumber(top.origin.y) + ") must be finite");
    for (std::size_t i = 0; i < top.heights.size(); ++i) {
        if (!std::isfinite(top.heights[i]))
            throw Error(ErrorKind::BadInput, what + "the height at column (x " +
                                                 std::to_string(i % std::size_t(top.width)) + ", z " +
                                                 std::to_string(i / std::size_t(top.width)) + ") is " +
                                                 formatNumber(top.heights[i]) + ", not a finite number");
    }
    if (!std::isfinite(o.depth) || o.depth <= 0.0)
        throw Error(ErrorKind::BadInput,
                    what + "depth = " + formatNumber(o.depth) + " must be a finite number > 0 (metres)");
    if (!std::isfinite(o.step) || o.step <= 0.0 || o.step > o.depth)
        throw Error(ErrorKind::BadInput,
                    what + "step = " + formatNumber(o.step) +
                        " must be a finite number > 0 and at most depth = " + formatNumber(o.depth) + " (metres)");
    if (o.depth / o.step > MAX_STEPS)
        throw Error(ErrorKind::BadInput,
                    what + "step = " + formatNumber(o.step) + " takes more than " + formatNumber(MAX_STEPS) +
                        " samples over depth = " + formatNumber(o.depth) + " m: use a larger step");
}

} // namespace

OverhangStatistics measureOverhangs(const DensityField& field, const TopSurfaceGrid& top,
                                    const OverhangOptions& options, const std::function<bool(double)>& progress)
{
    checkInput(top, options);
    const std::size_t steps = ceilToInt<std::size_t>(options.depth / options.step);
    const double step = options.depth / double(steps);
    const std::size_t samples = steps + 2; // from depth below the top to one step above it

    OverhangStatistics s;
    s.columns = top.heights.size();
    s.depth = options.depth;
    s.step = step;
    s.samplesPerColumn = samples;

    const auto report = [&progress](double fraction) {
        if (progress && !progress(fraction)) throw Error(ErrorKind::Interrupted, "overhang measurement interrupted");
    };
    report(0.0);
    std::vector<std::size_t> rowCounts(std::size_t(top.height), 0);
    const int batch = std::max(1, top.height / 32);
    for (int begin = 0; begin < top.height; begin += batch) {
        const int end = std::min(top.height, begin + batch);
        tbb::parallel_for(tbb::blocked_range<int>(begin, end), [&](const tbb::blocked_range<int>& range) {
            std::vector<double> xs(samples), ys(samples), zs(samples), density(samples);
            for (int row = range.begin(); row != range.end(); ++row) {
                const double z = top.origin.y + double(row) * top.cellSize;
                std::size_t count = 0;
                for (int column = 0; column < top.width; ++column) {
                    const double x = top.origin.x + double(column) * top.cellSize;
                    const double bottom =
                        top.heights[std::size_t(row) * std::size_t(top.width) + std::size_t(column)] - options.depth;
                    for (std::size_t k = 0; k < samples; ++k) {
                        xs[k] = x;
                        ys[k] = bottom + double(k) * step;
                        zs[k] = z;
                    }
                    PointBlock block;
                    block.x = xs.data();
                    block.y = ys.data();
                    block.z = zs.data();
                    block.count = samples;
                    block.box = {{x, ys.front(), z}, {x, ys.back(), z}};
                    field.densities(block, density.data());
                    int exits = 0;
                    for (std::size_t k = 0; k < samples; ++k) {
                        if (std::isnan(density[k]))
                            throw Error(ErrorKind::Internal, "overhang measurement: the density field is NaN at (" +
                                                                 formatNumber(x) + ", " + formatNumber(ys[k]) + ", " +
                                                                 formatNumber(z) + ")");
                        if (k > 0 && density[k - 1] < 0.0 && density[k] >= 0.0) ++exits;
                    }
                    count += exits > 1 ? 1 : 0;
                }
                rowCounts[std::size_t(row)] = count;
            }
        });
        report(double(end) / double(top.height));
    }
    for (std::size_t count : rowCounts) s.overhangColumns += count;
    s.fraction = double(s.overhangColumns) / double(s.columns);
    return s;
}

std::string formatOverhangs(const OverhangStatistics& s)
{
    std::ostringstream out, percent;
    percent << std::setprecision(4) << 100.0 * s.fraction;
    out << std::left << std::setw(24) << "overhangs" << percent.str() << " % of " << withThousands(s.columns)
        << " columns (" << withThousands(s.overhangColumns) << ") leave rock more than once within "
        << formatNumber(s.depth) << " m below the top surface (steps of " << formatNumber(s.step) << " m)\n";
    return out.str();
}

} // namespace strata::terrain
