// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Slope angles on surfaces whose answers are known: a plane tilted 30° in
// an oblique direction (every percentile 30°), a vertical step (the two
// columns beside it are cliffs, nothing else), a 1 m step (no cliff),
// percentiles interpolated between ranks, and bad input.

#include <strata/Error.h>
#include <strata/terrain/SlopeDistribution.h>

#include "TerrainTestHelpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace {

using namespace strata::terrain;
using strata::test::at;
using strata::test::errorOf;
using strata::test::tiltedPlane;

TEST(SlopeDistribution, PlaneTiltedThirtyDegrees)
{
    constexpr int W = 50, H = 40;
    constexpr double CELL = 4.0;
    const double gradient = std::tan(std::numbers::pi / 6.0), direction = 0.35; // radians from +x
    const std::vector<double> heights =
        tiltedPlane(W, H, 250.0, gradient * CELL * std::cos(direction), gradient * CELL * std::sin(direction));
    const SlopeDistribution s = measureSlopeDistribution(heights, W, H, CELL);
    EXPECT_EQ(s.cells, std::size_t((W - 2) * (H - 2)));
    EXPECT_NEAR(s.median, 30.0, 0.1);
    EXPECT_NEAR(s.median, 30.0, 1e-9); // central differences are exact on a plane
    EXPECT_NEAR(s.p10, 30.0, 1e-9);
    EXPECT_NEAR(s.p90, 30.0, 1e-9);
    EXPECT_NEAR(s.mean, 30.0, 1e-9);
    EXPECT_EQ(s.cliffFraction, 0.0);
    EXPECT_EQ(s.cliffAngle, 60.0);
}

TEST(SlopeDistribution, VerticalStepMakesTwoColumnsOfCliffs)
{
    constexpr int W = 30, H = 12, STEP = 10;
    for (const double rise : {50.0, 1.0}) {
        std::vector<double> heights(W * H);
        for (int z = 0; z < H; ++z)
            for (int x = 0; x < W; ++x) heights[at(W, x, z)] = x < STEP ? 100.0 : 100.0 + rise;
        const SlopeDistribution s = measureSlopeDistribution(heights, W, H, 1.0);
        // Columns STEP − 1 and STEP see the rise over 2 cells: atan(rise / 2).
        const double steep = std::atan(rise / 2.0) * 180.0 / std::numbers::pi;
        EXPECT_EQ(s.cliffFraction, rise == 50.0 ? 2.0 / double(W - 2) : 0.0) << rise;
        EXPECT_EQ(s.median, 0.0);
        EXPECT_EQ(s.p90, 0.0);                                  // 2 of 28 columns (7 %) are steep
        EXPECT_NEAR(s.mean, steep * 2.0 / double(W - 2), 1e-9); // mean over the interior
    }
    // The cliff angle is an option.
    std::vector<double> heights(W * H);
    for (int z = 0; z < H; ++z)
        for (int x = 0; x < W; ++x) heights[at(W, x, z)] = x < STEP ? 0.0 : 1.0; // 26.6° beside the step
    SlopeDistributionOptions options;
    options.cliffAngle = 25.0;
    EXPECT_EQ(measureSlopeDistribution(heights, W, H, 1.0, options).cliffFraction, 2.0 / double(W - 2));
}

TEST(SlopeDistribution, PercentilesInterpolateBetweenRanks)
{
    // A ramp whose slope grows with z: the interior rows z = 1..10 have
    // gradients g(z) = 0.1·z exactly (central differences of 0.05·z² along z
    // give 0.1·z), 8 cells each.
    constexpr int W = 10, H = 12;
    std::vector<double> heights(W * H);
    for (int z = 0; z < H; ++z)
        for (int x = 0; x < W; ++x) heights[at(W, x, z)] = 0.05 * z * z;
    const SlopeDistribution s = measureSlopeDistribution(heights, W, H, 1.0);
    std::vector<double> angles;
    for (int z = 1; z <= 10; ++z)
        for (int x = 0; x < 8; ++x) angles.push_back(std::atan(0.1 * z) * 180.0 / std::numbers::pi);
    // n = 80: p10 at rank 7.9 (rows 1 and 2), p50 at 39.5 (rows 5 and 6), p90 at 71.1 (rows 9 and 10).
    EXPECT_NEAR(s.p10, angles[7] + 0.9 * (angles[8] - angles[7]), 1e-9);
    EXPECT_NEAR(s.median, 0.5 * (angles[39] + angles[40]), 1e-9);
    EXPECT_NEAR(s.p90, angles[71] + 0.1 * (angles[72] - angles[71]), 1e-9);
}

TEST(SlopeDistribution, BadInputThrows)
{
    EXPECT_NE(errorOf([] { measureSlopeDistribution(std::vector<double>(6, 0.0), 3, 2, 1.0); }).find("3 x 3"),
              std::string::npos);
    std::vector<double> heights(9, 1.0);
    heights[at(3, 1, 2)] = NAN;
    EXPECT_NE(errorOf([&] { measureSlopeDistribution(heights, 3, 3, 1.0); }).find("(x 1, z 2)"), std::string::npos);
    heights[at(3, 1, 2)] = 1.0;
    EXPECT_NE(errorOf([&] { measureSlopeDistribution(heights, 3, 3, -2.0); }).find("cell size"), std::string::npos);
    SlopeDistributionOptions options;
    options.cliffAngle = 90.0;
    EXPECT_NE(errorOf([&] { measureSlopeDistribution(heights, 3, 3, 1.0, options); }).find("cliffAngle"),
              std::string::npos);
}

} // namespace
