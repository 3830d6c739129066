// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/LandformStatistics.h>

#include "HeightGridChecks.h"

#include <strata/DeterministicMath.h>
#include <strata/Error.h>
#include <strata/Format.h>
#include <strata/terrain/FlowRouting.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace strata::terrain {

namespace {

void checkOptions(const LandformStatisticsOptions& o)
{
    const auto bad = [](const std::string& name, double value, const std::string& range) {
        throw Error(ErrorKind::BadInput, "landform statistics: " + name + " = " + formatNumber(value) + " must be " + range);
    };
    if (!(o.depressionTolerance >= 0.0) || !std::isfinite(o.depressionTolerance))
        bad("depressionTolerance", o.depressionTolerance, "a finite number >= 0");
    if (!(o.flatSlope >= 0.0) || !std::isfinite(o.flatSlope)) bad("flatSlope", o.flatSlope, "a finite number >= 0");
    if (!(o.hackMinCells >= 2.0) || !std::isfinite(o.hackMinCells))
        bad("hackMinCells", o.hackMinCells, "a finite number >= 2");
    if (!(o.channelMinCells >= 1.0) || !std::isfinite(o.channelMinCells))
        bad("channelMinCells", o.channelMinCells, "a finite number >= 1");
    if (!(o.minChannelSlope >= 0.0) || !std::isfinite(o.minChannelSlope))
        bad("minChannelSlope", o.minChannelSlope, "a finite number >= 0");
    if (o.slopeAreaBins < 2 || o.slopeAreaBins > 1000) bad("slopeAreaBins", o.slopeAreaBins, "in 2..1000");
    if (o.minCellsPerBin < 1) bad("minCellsPerBin", o.minCellsPerBin, ">= 1");
}

} // namespace

LandformStatistics measureLandforms(const std::vector<double>& heights, int width, int height, double cellSize,
                                    const LandformStatisticsOptions& options)
{
    if (width < 3 || height < 3)
        throw Error(ErrorKind::BadInput, "landform statistics: the grid is " + std::to_string(width) + " x " + std::to_string(height) +
                    " cells; it must be at least 3 x 3");
    checkOptions(options);
    const FlowRouting routing = routeFlow(heights, width, height, cellSize); // checks the rest of the input
    const std::vector<double> area = drainageArea(routing, cellSize);
    const std::size_t n = heights.size(), w = std::size_t(width);
    const double cellArea = cellSize * cellSize;

    LandformStatistics s;
    s.width = width;
    s.height = height;
    s.cellSize = cellSize;
    s.interiorCells = (w - 2) * std::size_t(height - 2);
    const auto [lowest, highest] = std::minmax_element(heights.begin(), heights.end());
    s.relief = *highest - *lowest;

    // Receivers first: the spill level is the highest original height on the
    // flow path to the edge (a plain fill's level, up to the epsilon steps).
    std::vector<double> spill(n);
    for (const std::uint32_t c : routing.order) {
        const std::uint32_t to = routing.receiver[c];
        spill[c] = to == c ? heights[c] : std::max(heights[c], spill[to]);
    }
    // Donors first: the longest flow path from a divide to each cell.
    std::vector<double> longest(n, 0.0);
    for (std::size_t i = n; i-- > 0;) {
        const std::uint32_t c = routing.order[i], to = routing.receiver[c];
        if (to != c) longest[to] = std::max(longest[to], longest[c] + receiverDistance(routing, c, cellSize));
    }

    std::size_t depressed = 0, flat = 0;
    double slopeSum = 0.0;
    std::vector<double> logA, logS; // slope–area cells
    for (std::size_t c = 0; c < n; ++c) {
        const std::uint32_t to = routing.receiver[c];
        if (to == c) continue; // edge cell
        const double depth = spill[c] - heights[c];
        if (depth > options.depressionTolerance) {
            ++depressed;
            s.maxDepressionDepth = std::max(s.maxDepressionDepth, depth);
            s.depressionVolume += depth * cellArea;
        }
        const double distance = receiverDistance(routing, c, cellSize);
        const double filledSlope = (routing.filled[c] - routing.filled[to]) / distance;
        slopeSum += filledSlope;
        if (filledSlope < options.flatSlope) ++flat;
        if (area[c] >= options.channelMinCells * cellArea) {
            ++s.channelCells;
            const double drop = heights[c] - heights[to];
            const double slope = drop > 0.0 ? drop / distance : filledSlope;
            if (slope > options.minChannelSlope) {
                logA.push_back(dmath::log(area[c]));
                logS.push_back(dmath::log(slope));
            }
        }
    }
    s.depressionFraction = double(depressed) / double(s.interiorCells);
    s.flatFraction = double(flat) / double(s.interiorCells);
    s.meanSlope = slopeSum / double(s.interiorCells);

    // Hack's law, cell by cell (edge cells included: they collect whole basins).
    {
        std::vector<double> x, y;
        for (std::size_t c = 0; c < n; ++c) {
            if (area[c] < options.hackMinCells * cellArea || !(longest[c] > 0.0)) continue;
            x.push_back(dmath::log(area[c]));
            y.push_back(dmath::log(longest[c]));
        }
        s.hack = detail::fitLogLog(x, y);
    }

    // Slope–area, binned by log A.
    s.slopeAreaCells = logA.size();
    {
        std::vector<double> x, y;
        if (!logA.empty()) {
            const auto [lo, hi] = std::minmax_element(logA.begin(), logA.end());
            const double lowA = *lo, span = *hi - *lo;
            const int bins = options.slopeAreaBins;
            std::vector<double> sumA(std::size_t(bins), 0.0), sumS(std::size_t(bins), 0.0);
            std::vector<std::size_t> count(std::size_t(bins), 0);
            for (std::size_t i = 0; i < logA.size(); ++i) {
                int b = span > 0.0 ? int((logA[i] - lowA) / span * bins) : 0;
                b = std::clamp(b, 0, bins - 1);
                sumA[std::size_t(b)] += logA[i];
                sumS[std::size_t(b)] += logS[i];
                ++count[std::size_t(b)];
            }
            for (std::size_t b = 0; b < std::size_t(bins); ++b) {
                if (count[b] < std::size_t(options.minCellsPerBin)) continue;
                x.push_back(sumA[b] / double(count[b]));
                y.push_back(sumS[b] / double(count[b]));
            }
        }
        s.slopeArea = detail::fitLogLog(x, y);
        s.concavity = -s.slopeArea.exponent;
        s.steepness = s.slopeArea.coefficient;
    }
    return s;
}

std::string formatLandformStatistics(const LandformStatistics& s)
{
    std::ostringstream out;
    out << std::setprecision(4);
    const auto number = [](double v) {
        if (!std::isfinite(v)) return std::string("n/a");
        std::ostringstream o;
        o << std::setprecision(4) << v;
        return o.str();
    };
    const auto percent = [&](double f) { return number(100.0 * f) + " %"; };
    const auto row = [&](const std::string& name, const std::string& value) {
        out << std::left << std::setw(24) << name << value << '\n';
    };
    row("grid", std::to_string(s.width) + " x " + std::to_string(s.height) + " cells of " + number(s.cellSize) +
                    " m (" + withThousands(s.interiorCells) + " interior)");
    row("relief", number(s.relief) + " m");
    row("mean slope", number(s.meanSlope) + " m/m (filled surface)");
    row("flats", percent(s.flatFraction) + " of interior cells");
    row("depressions", percent(s.depressionFraction) + " of interior cells, deepest " + number(s.maxDepressionDepth) +
                           " m, volume " + number(s.depressionVolume) + " m^3");
    row("Hack L = c A^h", "h = " + number(s.hack.exponent) + ", c = " + number(s.hack.coefficient) +
                              ", r^2 = " + number(s.hack.rSquared) + " (" + withThousands(s.hack.points) + " cells)");
    row("slope-area S = ks A^-t",
        "theta = " + number(s.concavity) + ", ks = " + number(s.steepness) + ", r^2 = " + number(s.slopeArea.rSquared) +
            " (" + withThousands(s.slopeArea.points) + " bins of " + withThousands(s.slopeAreaCells) +
            " sloping channel cells, " + withThousands(s.channelCells) + " channel cells)");
    return out.str();
}

} // namespace strata::terrain
