// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The texture at several cell sizes: block averages of a known grid (partial
// edge blocks dropped), the factor of a cell size (whole multiples only),
// the measures at each size (the averaged grid measured as a grid of its
// own), a size too coarse for the grid, the table, and bad input.

#include <strata/Error.h>
#include <strata/terrain/SurfaceTexture.h>

#include "TerrainTestHelpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace {

using namespace strata::terrain;
using strata::test::errorOf;

/// Equal, or both NaN (a measure that could not be made).
bool same(double a, double b)
{
    return (std::isnan(a) && std::isnan(b)) || a == b;
}

TEST(SurfaceTexture, BlockAverageOfAKnownGrid)
{
    // 5 x 4 cells, value x + 10 z: blocks of 2 x 2, the fifth column dropped.
    std::vector<double> heights;
    for (int z = 0; z < 4; ++z)
        for (int x = 0; x < 5; ++x) heights.push_back(x + 10.0 * z);
    const HeightGrid two = blockAverage(heights, 5, 4, 3.0, 2);
    EXPECT_EQ(two.width, 2);
    EXPECT_EQ(two.height, 2);
    EXPECT_EQ(two.cellSize, 6.0);
    EXPECT_EQ(two.heights, (std::vector<double>{5.5, 7.5, 25.5, 27.5}));

    const HeightGrid one = blockAverage(heights, 5, 4, 3.0, 1);
    EXPECT_EQ(one.width, 5);
    EXPECT_EQ(one.cellSize, 3.0);
    EXPECT_EQ(one.heights, heights);

    // 4 x 4 blocks: one block of the 5 x 4 grid, the mean of columns 0..3.
    const HeightGrid four = blockAverage(heights, 5, 4, 3.0, 4);
    EXPECT_EQ(four.heights, (std::vector<double>{16.5}));

    EXPECT_NE(errorOf([&] { blockAverage(heights, 5, 4, 3.0, 5); }).find("factor = 5"), std::string::npos);
    EXPECT_NE(errorOf([&] { blockAverage(heights, 5, 4, 3.0, 0); }).find("factor = 0"), std::string::npos);
    EXPECT_NE(errorOf([&] { blockAverage(heights, 4, 4, 3.0, 2); }).find("20 heights"), std::string::npos);
    EXPECT_NE(errorOf([&] { blockAverage(heights, 5, 4, 0.0, 2); }).find("cell size"), std::string::npos);
    heights[7] = NAN;
    EXPECT_NE(errorOf([&] { blockAverage(heights, 5, 4, 3.0, 2); }).find("(x 2, z 1)"), std::string::npos);
}

TEST(SurfaceTexture, BlockFactorTakesWholeMultiplesOnly)
{
    EXPECT_EQ(blockFactor(4.0, 4.0), 1);
    EXPECT_EQ(blockFactor(4.0, 32.0), 8);
    EXPECT_EQ(blockFactor(83.0, 166.0), 2);
    EXPECT_EQ(blockFactor(0.1, 0.3), 3); // 0.3 / 0.1 = 2.9999999999999996
    EXPECT_NE(errorOf([] { blockFactor(4.0, 10.0); }).find("a cell of 10 m is not a whole multiple of the grid's 4 m"),
              std::string::npos);
    EXPECT_NE(errorOf([] { blockFactor(4.0, 2.0); }).find("not a whole multiple"), std::string::npos);
    EXPECT_NE(errorOf([] { blockFactor(4.0, 1.0); }).find("not a whole multiple"), std::string::npos);
    EXPECT_NE(errorOf([] { blockFactor(4.0, -8.0); }).find("finite number > 0"), std::string::npos);
    EXPECT_NE(errorOf([] { blockFactor(0.0, 8.0); }).find("the grid's cell size"), std::string::npos);
    EXPECT_NE(errorOf([] { blockFactor(1e-3, 1e4); }).find("more than 2^20"), std::string::npos);
}

TEST(SurfaceTexture, EachCellSizeMeasuresTheAveragedGrid)
{
    constexpr int W = 70, H = 52;
    std::vector<double> heights(W * H);
    for (int z = 0; z < H; ++z)
        for (int x = 0; x < W; ++x)
            heights[std::size_t(z * W + x)] =
                40.0 * std::sin(0.11 * x) * std::cos(0.07 * z) + 3.0 * std::sin(1.7 * x + 0.4 * z);
    const std::vector<SurfaceTexture> t = measureSurfaceTextureAtCells(heights, W, H, 4.0, {4.0, 8.0, 32.0, 80.0});
    ASSERT_EQ(t.size(), 4u);
    EXPECT_EQ(t[0].factor, 1);
    EXPECT_EQ(t[1].factor, 2);
    EXPECT_EQ(t[2].factor, 8);
    EXPECT_EQ(t[3].factor, 20);

    // Factor 1 is the grid itself.
    const SurfaceTexture direct = measureSurfaceTexture(heights, W, H, 4.0);
    EXPECT_TRUE(t[0].measured);
    EXPECT_EQ(t[0].slopes.median, direct.slopes.median);
    EXPECT_TRUE(same(t[0].roughness.exponent, direct.roughness.exponent));
    EXPECT_TRUE(same(t[0].spectrum.fine.beta, direct.spectrum.fine.beta));

    // Factor 2: the 35 x 26 block average, measured as a grid of 8 m cells.
    const HeightGrid coarse = blockAverage(heights, W, H, 4.0, 2);
    const SurfaceTexture two = measureSurfaceTexture(coarse.heights, coarse.width, coarse.height, 8.0);
    EXPECT_TRUE(t[1].measured);
    EXPECT_EQ(t[1].width, 35);
    EXPECT_EQ(t[1].height, 26);
    EXPECT_EQ(t[1].cellSize, 8.0);
    EXPECT_EQ(t[1].slopes.median, two.slopes.median);
    EXPECT_EQ(t[1].slopes.cliffFraction, two.slopes.cliffFraction);
    EXPECT_TRUE(same(t[1].roughness.exponent, two.roughness.exponent));
    EXPECT_TRUE(same(t[1].spectrum.coarse.beta, two.spectrum.coarse.beta));
    EXPECT_TRUE(std::isfinite(t[1].spectrum.fine.beta));
    EXPECT_EQ(t[1].spectrum.fine.beta, two.spectrum.fine.beta);
    // Averaging smooths: the gentle slopes of the big sine stay, the ripple's go.
    EXPECT_LT(t[1].slopes.p90, t[0].slopes.p90);

    // Factor 8: 8 x 6 cells, measured (no 9-cell window fits: a fit through 3 and 5 only).
    EXPECT_TRUE(t[2].measured);
    EXPECT_EQ(t[2].width, 8);
    EXPECT_EQ(t[2].height, 6);
    EXPECT_EQ(t[2].roughness.fit.points, 2u);
    // Factor 20: 3 x 2 cells, too small.
    EXPECT_FALSE(t[3].measured);
    EXPECT_EQ(t[3].width, 3);
    EXPECT_EQ(t[3].height, 2);
    EXPECT_EQ(t[3].cellSize, 80.0);

    const std::string table = formatSurfaceTexture(t);
    for (const char* text : {"texture at 4 m ", "70 x 52 cells: roughness ", ", beta fine ", ", coarse ",
                             ", slope p10 ", ", p50 ", ", p90 ", " deg, cliffs ", "texture at 32 m ",
                             "texture at 80 m ", "3 x 2 cells: too small to measure (under 3 x 3)"})
        EXPECT_NE(table.find(text), std::string::npos) << text << " in\n" << table;
    EXPECT_NE(table.find("n/a"), std::string::npos) << table; // 8 x 6 cells: no coarse band
    EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 4);

    // A cell size that is not a whole multiple: refused before anything is measured.
    EXPECT_NE(errorOf([&] {
                  measureSurfaceTextureAtCells(heights, W, H, 4.0, {8.0, 6.0});
              }).find("a cell of 6 m"),
              std::string::npos);
}

} // namespace
