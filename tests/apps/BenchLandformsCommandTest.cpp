// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata bench landforms`: a heightfield scene written here (every statistic
// and goal printed, the surface texture at each cell size, no overhangs, the
// same numbers on 1 and 2 threads, the crop and texture flags), a DEM
// written here (.asc), the real DEM Debian's python-matplotlib-data ships
// (Hack's exponent, roughness exponent, spectral slopes and median slope of
// real land), and bad input (exit 2).

#include "RunStrata.h"
#include "TestDir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

namespace {

using strata::test::CommandResult;
using strata::test::runStrata;

/// fBm hills over a 256 m region; the top surface at 8 m is 33 x 33 columns.
const char* const HILLS_SCENE = R"(seed = 3

[region]
min = [-128.0, -90.0, -128.0]
max = [128.0, 90.0, 128.0]

[terrain]
root = "hills"

[terrain.nodes.hills]
type = "heightfield"
seed = 3
base = 0.0
amplitude = 60.0
wavelength = 160.0
octaves = 5
)";

std::filesystem::path writeFile(const std::filesystem::path& path, const std::string& text)
{
    std::ofstream out(path, std::ios::binary);
    out << text;
    return path;
}

/// The output from the statistics table on (timings and thread counts left out).
std::string statistics(const std::string& output)
{
    const std::size_t start = output.find("\ngrid ");
    return start == std::string::npos ? std::string() : output.substr(start);
}

/// The number after `key` on the line that starts with `row` (NaN if absent).
double valueOf(const std::string& output, const std::string& row, const std::string& key)
{
    const std::size_t line = output.find("\n" + row);
    if (line == std::string::npos) return NAN;
    const std::size_t at = output.find(key, line);
    if (at == std::string::npos || at > output.find('\n', line + 1)) return NAN;
    return std::strtod(output.c_str() + at + key.size(), nullptr);
}

TEST(BenchLandformsCommand, SceneTopSurfacePrintsEveryStatisticAndGoal)
{
    const auto dir = strata::test::freshTestDir();
    const std::filesystem::path scene = writeFile(dir / "hills.toml", HILLS_SCENE);
    const CommandResult run = runStrata("bench landforms " + scene.string() + " --cell 8", dir);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    for (const char* text :
         {"strata bench landforms: ", "global pass", "top surface", "33 x 33 columns of 8 m",
          "x -128..128, z -128..128 m", "statistics",
          // formatLandformStatistics
          "\ngrid ", "33 x 33 cells of 8 m", "\nrelief ", "\nmean slope ", "\nflats ", "\ndepressions ",
          "\nHack L = c A^h ", "\nslope-area S = ks A^-t ",
          // the goals
          "\ngoal ", "\ndepressions ", "<= 8 %", "\nflats ", "<= 12 %", "\nHack exponent h ", "0.45 - 0.7",
          "\nconcavity theta ", "0.2 - 0.8", "\nslope-area r^2 ", ">= 0.7", " of 5 goals met",
          // the stages and lines of the texture and the overhangs
          "overhangs     ", "1,089 columns, 82 density samples each", "texture     ",
          "roughness, spectrum and slopes at 3 cell sizes",
          // the texture at the default cell sizes: the grid's cell times 1, 2 and 8
          "\ntexture at 8 m ", "33 x 33 cells: roughness ", "\ntexture at 16 m ", "16 x 16 cells: roughness ",
          "\ntexture at 64 m ", "4 x 4 cells: roughness ",
          // a height field leaves rock once per column
          "\noverhangs ", "0 % of 1,089 columns (0) leave rock more than once within 20 m below the top surface "
                          "(steps of 0.25 m)"}) {
        EXPECT_NE(run.output.find(text), std::string::npos) << "'" << text << "' in\n" << run.output;
    }
    EXPECT_TRUE(std::isfinite(valueOf(run.output, "Hack L = c A^h", "h = "))) << run.output;
    // fBm hills: moderate slopes, no cliffs, a roughness exponent between
    // white noise's 0 and a smooth surface's 2 (0.86 when written).
    const double median = valueOf(run.output, "texture at 8 m", "p50 ");
    EXPECT_GT(median, 1.0) << run.output;
    EXPECT_LT(median, 45.0) << run.output;
    EXPECT_LE(valueOf(run.output, "texture at 8 m", "p10 "), median) << run.output;
    EXPECT_GE(valueOf(run.output, "texture at 8 m", "p90 "), median) << run.output;
    EXPECT_EQ(valueOf(run.output, "texture at 8 m", "cliffs "), 0.0) << run.output;
    const double roughness = valueOf(run.output, "texture at 8 m", "roughness ");
    EXPECT_GT(roughness, 0.5) << run.output;
    EXPECT_LT(roughness, 2.1) << run.output;
    EXPECT_TRUE(std::isfinite(valueOf(run.output, "texture at 8 m", "beta fine "))) << run.output;
    EXPECT_EQ(run.output.find("note:"), std::string::npos) << run.output; // the region holds the whole surface

    // The same numbers on one thread.
    const CommandResult one = runStrata("bench landforms " + scene.string() + " --cell 8 --threads 1", dir);
    ASSERT_EQ(one.exitCode, 0) << one.output;
    EXPECT_NE(one.output.find("(1 thread)"), std::string::npos) << one.output;
    EXPECT_FALSE(statistics(run.output).empty());
    EXPECT_EQ(statistics(one.output), statistics(run.output));

    // A crop.
    const CommandResult crop =
        runStrata("bench landforms " + scene.string() + " --cell 8 --region-min 0,-64 --region-max 128,64", dir);
    ASSERT_EQ(crop.exitCode, 0) << crop.output;
    EXPECT_NE(crop.output.find("17 x 17 columns of 8 m over x 0..128, z -64..64 m"), std::string::npos) << crop.output;

    // The texture's cell sizes and the overhangs' depth and step as asked.
    const CommandResult texture = runStrata("bench landforms " + scene.string() +
                                                " --cell 8 --texture-cells 24,8 --overhang-depth 10 --overhang-step 0.5",
                                            dir);
    ASSERT_EQ(texture.exitCode, 0) << texture.output;
    for (const char* text : {"\ntexture at 24 m ", "11 x 11 cells: roughness ", "\ntexture at 8 m ",
                             "1,089 columns, 22 density samples each", "within 10 m below the top surface (steps of 0.5 m)"})
        EXPECT_NE(texture.output.find(text), std::string::npos) << "'" << text << "' in\n" << texture.output;
    EXPECT_LT(texture.output.find("\ntexture at 24 m"), texture.output.find("\ntexture at 8 m")) << texture.output;
    EXPECT_EQ(texture.output.find("\ntexture at 16 m"), std::string::npos) << texture.output;
}

TEST(BenchLandformsCommand, MeasuresAnAsciiGridDem)
{
    const auto dir = strata::test::freshTestDir();
    // 60 x 50 cells of 10 m: a valley draining south, with ripples.
    std::string text = "ncols 60\nnrows 50\nxllcorner 1000\nyllcorner 2000\ncellsize 10\nNODATA_value -9999\n";
    for (int row = 0; row < 50; ++row) {
        for (int col = 0; col < 60; ++col) {
            const double h =
                300.0 + 2.0 * row + 0.8 * std::abs(col - 30.0) + 3.0 * std::sin(0.7 * col) * std::cos(0.5 * row);
            text += std::to_string(h) + (col + 1 < 60 ? " " : "\n");
        }
    }
    const std::filesystem::path dem = writeFile(dir / "valley.asc", text);
    const CommandResult run = runStrata("bench landforms --dem " + dem.string(), dir);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    for (const char* text :
         {"DEM ", "asc, 60 x 50 cells of 10 m", "60 x 50 cells of 10 m", "Hack L = c A^h", " of 5 goals met"}) {
        EXPECT_NE(run.output.find(text), std::string::npos) << "'" << text << "' in\n" << run.output;
    }
    // --dem-cell overrides the file's cell size.
    const CommandResult cell = runStrata("bench landforms --dem " + dem.string() + " --dem-cell 30", dir);
    ASSERT_EQ(cell.exitCode, 0) << cell.output;
    EXPECT_NE(cell.output.find("60 x 50 cells of 30 m (--dem-cell)"), std::string::npos) << cell.output;

    // A hole in the data: refused, with the count.
    const std::size_t first = text.find('\n', text.find("NODATA")) + 1;
    std::string holed = text;
    holed.replace(first, holed.find(' ', first) - first, "-9999");
    const CommandResult hole = runStrata("bench landforms --dem " + writeFile(dir / "hole.asc", holed).string(), dir);
    EXPECT_EQ(hole.exitCode, 2) << hole.output;
    EXPECT_NE(hole.output.find("has 1 of 3,000 cells without data"), std::string::npos) << hole.output;
}

TEST(BenchLandformsCommand, BadInputExitsWithTwo)
{
    const auto dir = strata::test::freshTestDir();
    const std::filesystem::path scene = writeFile(dir / "hills.toml", HILLS_SCENE);
    // A .npy without a cell size: 4 x 4 zeros as int16.
    std::string npy("\x93NUMPY\x01\x00", 8);
    std::string dict = "{'descr': '<i2', 'fortran_order': False, 'shape': (4, 4), }";
    while ((10 + dict.size() + 1) % 64 != 0) dict += ' ';
    dict += '\n';
    npy += char(dict.size());
    npy += char(0);
    npy += dict + std::string(32, '\0');
    const std::filesystem::path grid = writeFile(dir / "grid.npy", npy);
    const struct
    {
        std::string arguments, expected;
    } cases[] = {
        {"--dem-cell 10", "--dem-cell is the cell size of a --dem file"},
        {"--dem " + grid.string() + " " + scene.string(), "--dem measures a DEM file"},
        {"--dem " + grid.string() + " --cell 8", "--dem measures a DEM file"},
        {"--dem " + grid.string(), "holds no cell size: give --dem-cell"},
        {"--dem " + (dir / "missing.npy").string(), "missing.npy: cannot open"},
        {"--dem " + writeFile(dir / "junk.asc", "ncols 2\nnrows x\n").string(),
         "junk.asc:2: 'nrows' needs a finite number"},
        {scene.string() + " --region-min 1,2,3", "--region-min '1,2,3' must look like X,Z"},
        {scene.string() + " --region-min 64,0 --region-max 0,64", "min < max on both axes"},
        {scene.string() + " --cell 0", "--cell"},
        {scene.string() + " --cell 200", "it must be at least 3 x 3"},
        {scene.string() + " --cell 8 --texture-cells 12", "--texture-cells: surface texture: a cell of 12 m is not a "
                                                          "whole multiple of the grid's 8 m cells"},
        {scene.string() + " --texture-cells 16,x", "--texture-cells"},
        {scene.string() + " --overhang-depth 2 --overhang-step 3", "--overhang-step = 3 m must be at most "
                                                                   "--overhang-depth = 2 m"},
        {scene.string() + " --overhang-step 0", "--overhang-step"},
        {"--dem " + grid.string() + " --dem-cell 10 --overhang-depth 5", "--overhang-depth and --overhang-step "
                                                                          "measure a scene's volume"},
        {"--dem " + grid.string() + " --dem-cell 10 --texture-cells 15", "a cell of 15 m is not a whole multiple"},
        {(dir / "missing.toml").string(), "missing.toml"},
    };
    for (const auto& c : cases) {
        const CommandResult r = runStrata("bench landforms " + c.arguments, dir);
        EXPECT_EQ(r.exitCode, 2) << c.arguments << "\n" << r.output;
        EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.arguments << "\n" << r.output;
    }
}

/// The 3 arc-second DEM of the Jacksboro fault (Tennessee) that Debian's
/// python-matplotlib-data ships (scripts/install-deps.sh installs it). Its
/// members are deflate-compressed; elevation.npy is real land, whose Hack's
/// exponent is about 0.53 with 83 m cells (about √(92.6 m × 74.4 m), the
/// cells' north-south and east-west sizes at 36.6° N), and whose texture at
/// 83 m is that of the issue's SRTM 84 m reference (roughness 1.15, β fine
/// 5.2, coarse 3.5, median slope 13°): measured 1.148, 5.22, 3.00, 13.3°.
TEST(BenchLandformsCommand, RealDemHasRealHacksExponent)
{
    const std::filesystem::path npz = "/usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz";
    // scripts/install-deps.sh installs it: missing is a failure, not a skip.
    ASSERT_TRUE(std::filesystem::exists(npz)) << npz << " is missing (apt-get install python-matplotlib-data)";
    const auto dir = strata::test::freshTestDir();

    // Its members are deflated (zip method 8): read as they are.
    const CommandResult run = runStrata("bench landforms --dem " + npz.string() + " --dem-cell 83", dir);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("npz member elevation.npy, 403 x 344 cells of 83 m (--dem-cell)"), std::string::npos) << run.output;
    const double hack = valueOf(run.output, "Hack L = c A^h", "h = ");
    EXPECT_GE(hack, 0.45) << run.output;
    EXPECT_LE(hack, 0.6) << run.output;

    // The texture at 83 m (and 166 m, 664 m: the default cell sizes), near
    // the issue's SRTM 84 m reference.
    for (const char* text : {"\ntexture at 83 m         403 x 344 cells: roughness ",
                             "\ntexture at 166 m        201 x 172 cells: roughness ",
                             "\ntexture at 664 m        50 x 43 cells: roughness ",
                             "\noverhangs               n/a (a DEM is a height grid: it has no volume)"})
        EXPECT_NE(run.output.find(text), std::string::npos) << "'" << text << "' in\n" << run.output;
    const std::string row = "texture at 83 m";
    const double roughness = valueOf(run.output, row, "roughness ");
    EXPECT_GE(roughness, 1.0) << run.output; // 1.148
    EXPECT_LE(roughness, 1.3) << run.output;
    const double fine = valueOf(run.output, row, "beta fine ");
    EXPECT_GE(fine, 4.5) << run.output; // 5.224
    EXPECT_LE(fine, 6.0) << run.output;
    const double coarse = valueOf(run.output, row, "coarse ");
    EXPECT_GE(coarse, 2.5) << run.output; // 2.998
    EXPECT_LE(coarse, 4.0) << run.output;
    const double median = valueOf(run.output, row, "p50 ");
    EXPECT_GE(median, 11.0) << run.output; // 13.34
    EXPECT_LE(median, 16.0) << run.output;
    EXPECT_LT(valueOf(run.output, row, "p10 "), median) << run.output;
    EXPECT_GT(valueOf(run.output, row, "p90 "), median) << run.output;
    EXPECT_EQ(valueOf(run.output, row, "cliffs "), 0.0) << run.output; // no 83 m cell is steeper than 60°
    // Averaging to 166 m flattens the slopes.
    EXPECT_LT(valueOf(run.output, "texture at 166 m", "p50 "), median) << run.output;
    std::cout << run.output;
}

} // namespace
