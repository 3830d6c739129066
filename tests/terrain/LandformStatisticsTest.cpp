// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Landform statistics on surfaces whose answers are known: a tilted plane
// (no depressions, no flats), a flat (all flat, and the epsilon fill's ulps
// are no depression), a bowl with a notch (its depressions counted, deepest
// and volume exact), a 1D channel built so that S = A^-0.5 exactly
// (concavity 0.5) and whose Hack's law fit matches the fit of its known
// (A, L); determinism, the table and bad input.

#include <strata/Error.h>
#include <strata/terrain/LandformStatistics.h>

#include "TerrainTestHelpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace {

using namespace strata::terrain;
using strata::test::at;
using strata::test::errorOf;
using strata::test::tiltedPlane;

TEST(LandformStatistics, TiltedPlaneHasNoDepressionsNorFlats)
{
    constexpr int W = 30, H = 20;
    const std::vector<double> heights = tiltedPlane(W, H, 100.0, -0.2, -0.05);
    const LandformStatistics s = measureLandforms(heights, W, H, 1.0);
    EXPECT_EQ(s.interiorCells, std::size_t((W - 2) * (H - 2)));
    EXPECT_EQ(s.depressionFraction, 0.0);
    EXPECT_EQ(s.maxDepressionDepth, 0.0);
    EXPECT_EQ(s.depressionVolume, 0.0);
    EXPECT_EQ(s.flatFraction, 0.0);
    EXPECT_NEAR(s.meanSlope, 0.2, 1e-9);
    EXPECT_NEAR(s.relief, 0.2 * (W - 1) + 0.05 * (H - 1), 1e-12);
}

TEST(LandformStatistics, FlatIsFlatAndNotADepression)
{
    constexpr int W = 40, H = 25;
    const std::vector<double> heights(W * H, 312.25);
    LandformStatisticsOptions options;
    options.depressionTolerance = 0.0; // the ulps of the epsilon fill still do not count
    const LandformStatistics s = measureLandforms(heights, W, H, 5.0, options);
    EXPECT_EQ(s.flatFraction, 1.0);
    EXPECT_EQ(s.depressionFraction, 0.0);
    EXPECT_EQ(s.relief, 0.0);
    EXPECT_LT(s.meanSlope, 1e-12);
}

TEST(LandformStatistics, BowlDepressionIsMeasured)
{
    // Floor 1 + 0.1·r inside a rim (20) at Chebyshev distance 7, a notch at
    // 12, ground at 5 outside: the 13 × 13 floor cells lie in a depression
    // whose spill level is the notch.
    constexpr int N = 21, C = 10, RIM = 7;
    constexpr double CELL = 2.0;
    std::vector<double> heights(N * N);
    double volume = 0.0, deepest = 0.0;
    int floorCells = 0;
    for (int z = 0; z < N; ++z) {
        for (int x = 0; x < N; ++x) {
            const int d = std::max(std::abs(x - C), std::abs(z - C));
            const double h = d < RIM ? 1.0 + 0.1 * std::hypot(x - C, z - C) : d == RIM ? 20.0 : 5.0;
            heights[at(N, x, z)] = h;
            if (d < RIM) {
                ++floorCells;
                volume += (12.0 - h) * CELL * CELL;
                deepest = std::max(deepest, 12.0 - h);
            }
        }
    }
    heights[at(N, C + RIM, C)] = 12.0;
    const LandformStatistics s = measureLandforms(heights, N, N, CELL);
    EXPECT_EQ(floorCells, 13 * 13);
    EXPECT_DOUBLE_EQ(s.depressionFraction, double(floorCells) / double((N - 2) * (N - 2)));
    EXPECT_DOUBLE_EQ(s.maxDepressionDepth, deepest);
    EXPECT_NEAR(s.depressionVolume, volume, 1e-9 * volume);
    // The filled floor is flat (ulps apart) and so is the ground outside; the
    // rim, notch included, drains steeply outwards.
    const int rimCells = 8 * RIM;
    EXPECT_DOUBLE_EQ(s.flatFraction, double((N - 2) * (N - 2) - rimCells) / double((N - 2) * (N - 2)));
}

/// One channel along the middle row of a W × 3 grid, walls above and below
/// and at x = 0, the outlet at x = W − 1. Cell x of the channel drains x
/// cells; its heights are built so that S = A^-0.5 exactly (A in m²).
std::vector<double> channelHeights(int width, double cellSize)
{
    std::vector<double> heights(std::size_t(width) * 3, 1e4);
    heights[at(width, width - 1, 1)] = 0.0;
    for (int x = width - 2; x >= 1; --x) {
        const double area = x * cellSize * cellSize;
        heights[at(width, x, 1)] = heights[at(width, x + 1, 1)] + cellSize * std::pow(area, -0.5);
    }
    return heights;
}

TEST(LandformStatistics, ChannelWithKnownSlopeAreaLaw)
{
    constexpr int W = 1200;
    constexpr double CELL = 4.0;
    LandformStatisticsOptions options;
    options.channelMinCells = 10.0;
    const LandformStatistics s = measureLandforms(channelHeights(W, CELL), W, 3, CELL, options);
    EXPECT_EQ(s.channelCells, std::size_t(W - 2 - 10 + 1)); // x = 10 .. W − 2
    EXPECT_EQ(s.slopeAreaCells, s.channelCells);
    EXPECT_EQ(s.slopeArea.points, std::size_t(options.slopeAreaBins));
    EXPECT_NEAR(s.concavity, 0.5, 1e-9);
    EXPECT_NEAR(s.steepness, 1.0, 1e-8);
    EXPECT_NEAR(s.slopeArea.rSquared, 1.0, 1e-12);
    EXPECT_EQ(s.depressionFraction, 0.0);
}

TEST(LandformStatistics, ChannelHackFitMatchesItsPathLengths)
{
    // In the channel, cell x (and the outlet, x = W − 1) drains A = x cells
    // along a longest path of L = (x − 1) cells: the fit must be the least
    // squares line of log L on log A over x >= hackMinCells.
    constexpr int W = 500;
    constexpr double CELL = 3.0;
    const LandformStatisticsOptions options; // hackMinCells = 20
    const LandformStatistics s = measureLandforms(channelHeights(W, CELL), W, 3, CELL, options);
    std::vector<double> x, y;
    for (int i = 20; i <= W - 1; ++i) {
        x.push_back(std::log(i * CELL * CELL));
        y.push_back(std::log((i - 1) * CELL));
    }
    double mx = 0, my = 0;
    for (std::size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
    mx /= double(x.size());
    my /= double(x.size());
    double sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) sxx += (x[i] - mx) * (x[i] - mx), sxy += (x[i] - mx) * (y[i] - my);
    const double slope = sxy / sxx;
    EXPECT_EQ(s.hack.points, x.size());
    EXPECT_NEAR(s.hack.exponent, slope, 1e-12);
    EXPECT_NEAR(s.hack.coefficient, std::exp(my - slope * mx), 1e-10);
    EXPECT_GT(s.hack.rSquared, 0.999);
    EXPECT_GT(s.hack.exponent, 1.0); // a single channel: L ∝ A, not the ~0.57 of branching basins
}

std::vector<double> hills(int width, int height)
{
    std::vector<double> h(std::size_t(width) * std::size_t(height));
    std::uint64_t s = 7;
    for (int z = 0; z < height; ++z) {
        for (int x = 0; x < width; ++x) {
            s = s * 6364136223846793005ull + 1442695040888963407ull;
            h[at(width, x, z)] =
                40.0 * std::sin(x * 0.05) * std::cos(z * 0.045) + 0.02 * (x + z) + 2.0 * double(s >> 11) * 0x1p-53;
        }
    }
    return h;
}

TEST(LandformStatistics, NoisyHillsGiveSaneNumbersAndTheSameBits)
{
    constexpr int W = 150, H = 120;
    const std::vector<double> heights = hills(W, H);
    const LandformStatistics a = measureLandforms(heights, W, H, 10.0), b = measureLandforms(heights, W, H, 10.0);
    for (const double f : {a.depressionFraction, a.flatFraction}) {
        EXPECT_GE(f, 0.0);
        EXPECT_LE(f, 1.0);
    }
    EXPECT_GT(a.depressionFraction, 0.0); // the noise makes pits
    EXPECT_GT(a.hack.points, 10u);
    EXPECT_TRUE(std::isfinite(a.hack.exponent));
    EXPECT_TRUE(std::isfinite(a.concavity));
    EXPECT_GT(a.slopeArea.points, 2u);
    EXPECT_EQ(std::memcmp(&a.depressionFraction, &b.depressionFraction, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&a.hack.exponent, &b.hack.exponent, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&a.concavity, &b.concavity, sizeof(double)), 0);
    EXPECT_EQ(formatLandformStatistics(a), formatLandformStatistics(b));
}

TEST(LandformStatistics, TableNamesEachQuantityAndNaForMissingFits)
{
    const std::vector<double> heights = {3, 3, 3, 3, 1, 3, 3, 3, 3};
    const LandformStatistics s = measureLandforms(heights, 3, 3, 1.0);
    EXPECT_TRUE(std::isnan(s.hack.exponent));
    EXPECT_TRUE(std::isnan(s.concavity));
    EXPECT_EQ(s.depressionFraction, 1.0);
    EXPECT_EQ(s.maxDepressionDepth, 2.0);
    const std::string table = formatLandformStatistics(s);
    for (const char* word : {"grid", "relief", "flats", "depressions", "Hack", "slope-area", "n/a", "100 %"})
        EXPECT_NE(table.find(word), std::string::npos) << word << " in\n" << table;
}

TEST(LandformStatistics, BadInputThrows)
{
    EXPECT_NE(errorOf([] { measureLandforms(std::vector<double>(10, 0.0), 2, 5, 1.0); }).find("3 x 3"),
              std::string::npos);
    EXPECT_NE(errorOf([] { measureLandforms(std::vector<double>(8, 0.0), 3, 3, 1.0); }).find("8 heights"),
              std::string::npos);
    std::vector<double> heights(20, 1.0);
    heights[at(5, 4, 1)] = std::nan("");
    EXPECT_NE(errorOf([&] { measureLandforms(heights, 5, 4, 1.0); }).find("(x 4, z 1)"), std::string::npos);
    heights[at(5, 4, 1)] = 1.0;
    EXPECT_NE(errorOf([&] { measureLandforms(heights, 5, 4, -1.0); }).find("cell size"), std::string::npos);
    LandformStatisticsOptions options;
    options.slopeAreaBins = 1;
    EXPECT_NE(errorOf([&] { measureLandforms(heights, 5, 4, 1.0, options); }).find("slopeAreaBins"), std::string::npos);
    options = {};
    options.flatSlope = -1.0;
    EXPECT_NE(errorOf([&] { measureLandforms(heights, 5, 4, 1.0, options); }).find("flatSlope"), std::string::npos);
}

} // namespace
