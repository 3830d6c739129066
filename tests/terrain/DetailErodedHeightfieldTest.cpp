// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The erode_detail node: rills and talus within their bounds, flats left
// alone, the same bits for any tiling and thread count, continuous across
// block borders, the extremes and errors naming their key.

#include <strata/Error.h>
#include <strata/terrain/DetailErodedHeightfield.h>
#include <strata/terrain/SampleLevelSet.h>

#include "TilingChecks.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <memory>
#include <utility>

using namespace strata::terrain;
using strata::test::expectTilesMatchWhole;
using strata::test::openBox;

namespace {

HeightNodePtr hills()
{
    NoiseHeightfieldOptions o;
    o.amplitude = 40.0;
    o.wavelength = 90.0;
    return std::make_shared<NoiseHeightfield>(3, o);
}

DetailErodeOptions options(int block = 32)
{
    DetailErodeOptions o;
    o.blockCells = block;
    o.erosion.dropletSteps = 12;
    return o;
}

} // namespace

TEST(DetailErodedHeightfield, CarvesWithinItsDepthAndLeavesFlatsAlone)
{
    const HeightNodePtr base = hills();
    const DetailErodedHeightfield detail(base, 5, options());
    double largest = 0.0, total = 0.0;
    for (double x = -60.0; x < 60.0; x += 0.37) {
        for (double z = -60.0; z < 60.0; z += 0.41) {
            const double change = detail.height(x, z) - base->height(x, z);
            ASSERT_LE(std::abs(change), 1.5 + 1e-6);
            largest = std::max(largest, std::abs(change));
            total += std::abs(change);
        }
    }
    EXPECT_GT(largest, 0.05); // it did something
    EXPECT_GT(total, 0.0);
    const DetailErodedHeightfield flat(std::make_shared<ConstantHeight>(4.0), 5, options());
    for (double x = -50.0; x < 50.0; x += 3.3) EXPECT_EQ(flat.height(x, 0.7 * x), 4.0);
}

TEST(DetailErodedHeightfield, AnyTilingAndThreadCountGivesTheSameBits)
{
    const glm::dvec3 lo(-48, -60, -48), hi(48, 60, 48);
    const auto whole = sampleLevelSet(DetailErodedHeightfield(hills(), 5, options()), openBox(lo, hi));
    ASSERT_GT(whole->activeVoxelCount(), 5000u);
    for (const int threads : {1, 2, 3}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
        const DetailErodedHeightfield fresh(hills(), 5, options()); // its own, empty block cache
        for (const int tiles : {2, 3}) {
            expectTilesMatchWhole(fresh, *whole, lo, hi, tiles, std::to_string(threads) + " threads");
        }
    }
}

TEST(DetailErodedHeightfield, ContinuousAcrossBlockBorders)
{
    const DetailErodedHeightfield detail(hills(), 5, options(16));
    // 1 cm steps across several block borders (every 16 m).
    double previous = detail.height(-40.0, 7.3);
    double steepest = 0.0;
    for (double x = -39.99; x < 40.0; x += 0.01) {
        const double h = detail.height(x, 7.3);
        steepest = std::max(steepest, std::abs(h - previous) / 0.01);
        previous = h;
    }
    EXPECT_LE(steepest, detail.slopeBound());
    EXPECT_LT(steepest, 5.0); // no step anywhere: the hills' own slopes plus rills
}

TEST(DetailErodedHeightfield, BeyondTheBlockLatticeTheChildsHeightIsKept)
{
    // Beyond ±2^62 cells no block index fits an int64: the old code converted
    // anyway (undefined behaviour, reported by UBSan in scripts/sanitizers.sh).
    const auto child = hills();
    const DetailErodedHeightfield detail(child, 5, options());
    for (const auto& [x, z] : {std::pair{-1e300, 0.0}, std::pair{0.0, 1e300}, std::pair{1e19, -1e19},
                               std::pair{std::nan(""), 0.0}}) {
        const double h = detail.height(x, z), expected = child->height(x, z);
        if (std::isnan(expected)) {
            EXPECT_TRUE(std::isnan(h)) << x << ", " << z;
        } else {
            EXPECT_EQ(h, expected) << x << ", " << z;
        }
    }
}

TEST(DetailErodedHeightfield, FarFromTheOriginAndBadKeys)
{
    const DetailErodedHeightfield detail(hills(), 5, options());
    const double x = 1e9 + 0.25, z = -1e9 - 0.5;
    const double h = detail.height(x, z);
    EXPECT_TRUE(std::isfinite(h));
    const Interval b = detail.heightBounds({x - 1, z - 1}, {x + 1, z + 1});
    EXPECT_GE(h, b.lo);
    EXPECT_LE(h, b.hi);
    auto fails = [](DetailErodeOptions o, const std::string& key) {
        try {
            DetailErodedHeightfield node(hills(), 1, o);
            ADD_FAILURE() << key << " accepted";
        } catch (const strata::Error& e) {
            EXPECT_EQ(e.place().key, key) << e.what();
        }
    };
    DetailErodeOptions o = options();
    o.halo = 40;
    fails(o, "halo");
    o = options();
    o.blockCells = 4;
    fails(o, "block");
    o = options();
    o.erosion.talusAngle = 90.0;
    fails(o, "talus_angle");
    o = options();
    o.erosion.dropletsPerCell = -1.0;
    fails(o, "droplets_per_cell");
}
