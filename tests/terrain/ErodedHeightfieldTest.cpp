// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The erode node: the same terrain for any crop, tiling and thread count,
// one evolution per process, smooth read-back, masks, the extremes and
// errors naming their key.

#include <strata/CacheMemory.h>
#include <strata/Error.h>
#include <strata/terrain/ErodedHeightfield.h>
#include <strata/terrain/NodeRegistry.h>
#include <strata/terrain/SampleLevelSet.h>
#include <strata/terrain/SimdTarget.h>

#include "TilingChecks.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <memory>

using namespace strata::terrain;
using strata::test::expectTilesMatchWhole;
using strata::test::openBox;

namespace {

HeightNodePtr hills(double offset = 0.0)
{
    NoiseHeightfieldOptions o;
    o.amplitude = 60.0;
    o.wavelength = 400.0;
    HeightNodePtr noise = std::make_shared<NoiseHeightfield>(7, o);
    if (offset == 0.0) return noise;
    // The same hills moved by (offset, offset).
    struct Moved final : HeightfieldBase
    {
        Moved(HeightNodePtr c, double d) : child(std::move(c)), by(d) { setSlopeBound(child->slopeBound()); }
        double height(double x, double z) const override { return child->height(x - by, z - by); }
        HeightNodePtr child;
        double by;
    };
    return std::make_shared<Moved>(noise, offset);
}

ErodeOptions smallDomain(double offset = 0.0, double cell = 8.0)
{
    ErodeOptions o;
    o.min = glm::dvec2(-256.0 + offset);
    o.max = glm::dvec2(256.0 + offset);
    o.evolution.cellSize = cell;
    o.evolution.years = 3e5;
    o.evolution.timeStep = 2e4;
    o.evolution.uplift = 1e-4; // 30 m: the land stays inside the tests' boxes
    return o;
}

} // namespace

TEST(ErodedHeightfield, AnyTilingAndThreadCountGivesTheSameBits)
{
    const auto field = std::make_shared<ErodedHeightfield>(hills(), nullptr, smallDomain());
    const glm::dvec3 lo(-60, -80, -60), hi(60, 80, 60);
    const auto whole = sampleLevelSet(*field, openBox(lo, hi));
    ASSERT_GT(whole->activeVoxelCount(), 10000u);
    // Evolved anew on 1, 2 and 3 threads (not taken from the cache), then
    // sampled in 2 × 2 and 3 × 3 tiles: every voxel of each tile equals the
    // whole region's.
    for (const int threads : {1, 2, 3}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
        ErodedHeightfield::clearCache();
        const auto rebuilt = std::make_shared<ErodedHeightfield>(hills(), nullptr, smallDomain());
        ASSERT_FALSE(rebuilt->cached());
        EXPECT_EQ(rebuilt->grid().heights, field->grid().heights) << threads << " threads";
        for (const int tiles : {2, 3}) {
            expectTilesMatchWhole(*rebuilt, *whole, lo, hi, tiles, "on " + std::to_string(threads) + " threads");
        }
    }
    // A node of the same key built after them takes the cached evolution.
    EXPECT_TRUE(std::make_shared<ErodedHeightfield>(hills(), nullptr, smallDomain())->cached());
}

TEST(ErodedHeightfield, EverySimdTargetGivesTheSameEvolution)
{
    // The input is sampled through the block (SIMD) noise path: each target
    // must give the same grid, so workers on different CPUs agree.
    ErodeOptions o = smallDomain();
    o.evolution.years = 1.4e5; // a key of its own (no cached grid)
    std::vector<double> first;
    for (const std::string& target : availableSimdTargets()) {
        useSimdTarget(target);
        o.riverArea += 1.0; // a new cache key per target: each evolves afresh
        const ErodedHeightfield field(hills(), nullptr, o);
        EXPECT_FALSE(field.cached()) << target;
        if (first.empty()) first = field.grid().heights;
        else EXPECT_EQ(field.grid().heights, first) << target;
    }
    useSimdTarget("");
    EXPECT_FALSE(first.empty());
}

TEST(ErodedHeightfield, EvolvesOncePerProcessAndErodesValleys)
{
    ErodeOptions o = smallDomain();
    o.evolution.years = 3.2e5; // a key no other test uses
    const ErodedHeightfield first(hills(), nullptr, o);
    const ErodedHeightfield second(hills(), nullptr, o);
    EXPECT_FALSE(first.cached());
    EXPECT_TRUE(second.cached());
    EXPECT_EQ(&first.grid(), &second.grid());
    const ErodedGrid& g = first.grid();
    EXPECT_EQ(g.width, 65);
    EXPECT_GT(g.budget.eroded, 0.0);
    EXPECT_NEAR(g.budget.eroded, g.budget.deposited + g.budget.carriedOut, 1e-9 * g.budget.eroded);
    // Masks: flow at least one cell's area, wear where rivers cut.
    double maxFlow = 0.0, maxWear = 0.0;
    for (const glm::vec4& m : g.masks) {
        EXPECT_GE(m.x, std::log10(64.0) - 1e-4);
        maxFlow = std::max(maxFlow, double(m.x));
        maxWear = std::max(maxWear, double(m.y));
    }
    EXPECT_GT(maxFlow, 3.0);
    EXPECT_GT(maxWear, 1.0);
}

// The evolutions a process keeps are bounded in bytes by the process's
// cache limit (--max-memory), keeping at least the last one: under a limit
// that holds one grid, a second evolution drops the first (issue 41: four
// grids of up to 1.6 GB each were kept whatever the budget). A grid
// evolved again is the same bits.
TEST(ErodedHeightfield, KeptEvolutionsStayWithinTheCacheLimit)
{
    ErodeOptions a = smallDomain(), b = smallDomain();
    a.evolution.years = 3.4e5; // keys no other test uses
    b.evolution.years = 3.6e5;
    const std::uint64_t before = strata::cacheMemoryLimit();
    ErodedHeightfield::clearCache();
    const std::uint64_t empty = strata::cacheMemoryUsed();
    const ErodedHeightfield firstA(hills(), nullptr, a);
    const std::uint64_t oneGrid = strata::cacheMemoryUsed() - empty;
    EXPECT_GT(oneGrid, 65u * 65u * (sizeof(double) + 16u)) << "a 65 x 65 grid's heights and masks";
    strata::setCacheMemoryLimit(empty + oneGrid + oneGrid / 2);
    const ErodedHeightfield firstB(hills(), nullptr, b);
    EXPECT_LE(strata::cacheMemoryUsed(), empty + oneGrid + oneGrid / 2);
    const ErodedHeightfield againA(hills(), nullptr, a);
    EXPECT_FALSE(againA.cached()) << "the first grid was kept over the limit";
    EXPECT_EQ(againA.grid().heights, firstA.grid().heights);
    strata::setCacheMemoryLimit(before);
    const ErodedHeightfield againB(hills(), nullptr, b);
    const ErodedHeightfield thirdA(hills(), nullptr, a);
    EXPECT_TRUE(thirdA.cached()) << "under the default limit both grids stay";
    ErodedHeightfield::clearCache();
}

TEST(ErodedHeightfield, ReadBackIsSmoothAndWithinItsBounds)
{
    const ErodedHeightfield field(hills(), nullptr, smallDomain());
    // Steps of 1 cm along a line crossing many cells: no jump at cell
    // borders beyond what the slope bound allows.
    double previous = field.height(-200.0, 13.0);
    for (double x = -199.99; x < 200.0; x += 0.01) {
        const double h = field.height(x, 13.0);
        ASSERT_LE(std::abs(h - previous), field.slopeBound() * 0.01 * (1.0 + 1e-9) + 1e-12) << x;
        previous = h;
    }
    const Interval b = field.heightBounds({-100.0, -30.0}, {-60.0, 10.0});
    for (double x = -100.0; x <= -60.0; x += 0.7) {
        for (double z = -30.0; z <= 10.0; z += 0.7) {
            const double h = field.height(x, z);
            EXPECT_GE(h, b.lo);
            EXPECT_LE(h, b.hi);
        }
    }
    // Outside the domain the edge continues.
    EXPECT_EQ(field.height(1e6, 0.0), field.height(256.0, 0.0));
    glm::vec4 m;
    const double x = 10.0, z = -20.0;
    field.landformMasks(&x, &z, 1, &m);
    EXPECT_GE(m.x, 0.0f);
    EXPECT_GE(m.w, 0.0f);
    EXPECT_LE(m.w, 1.0f);
}

TEST(ErodedHeightfield, FarFromTheOriginTheSameTerrainMoved)
{
    // 1e9 m away, the same hills over the same domain moved: the same
    // evolution bit for bit (the grid is relative to the domain).
    const double d = 1e9;
    const ErodedHeightfield here(hills(), nullptr, smallDomain());
    const ErodedHeightfield there(hills(d), nullptr, smallDomain(d));
    EXPECT_EQ(here.grid().heights, there.grid().heights);
    EXPECT_EQ(here.height(17.0, -33.0), there.height(17.0 + d, -33.0 + d));
}

TEST(ErodedHeightfield, ExtremeCellsAndDomains)
{
    // Zero years: the B-spline of the input's corners.
    ErodeOptions o = smallDomain();
    o.evolution.years = 0.0;
    const ErodedHeightfield still(hills(), nullptr, o);
    EXPECT_EQ(still.grid().heights[0], hills()->height(-256.0, -256.0));
    // One cell: 2 × 2 corners, all edge.
    o = smallDomain();
    o.max = o.min + glm::dvec2(8.0);
    EXPECT_EQ(ErodedHeightfield(hills(), nullptr, o).grid().width, 2);
    // 0.1 m cells over 12.8 m and 1 km cells over 64 km: finite.
    for (const double cell : {0.1, 1000.0}) {
        o = smallDomain(0.0, cell);
        o.max = o.min + glm::dvec2(128.0 * cell);
        const ErodedHeightfield field(hills(), nullptr, o);
        EXPECT_TRUE(std::isfinite(field.height(o.min.x + 3.3 * cell, o.min.y + 7.7 * cell))) << cell;
    }
}

TEST(ErodedHeightfield, BadKeysAreNamed)
{
    auto fails = [](ErodeOptions o, const std::string& key) {
        try {
            ErodedHeightfield field(hills(), nullptr, o);
            ADD_FAILURE() << key << " accepted";
        } catch (const strata::Error& e) {
            EXPECT_EQ(e.place().key, key) << e.what();
        }
    };
    ErodeOptions o = smallDomain();
    o.max.x = o.min.x;
    fails(o, "max");
    o = smallDomain(0.0, 0.001);
    fails(o, "cell_size"); // 512k × 512k cells
    o = smallDomain();
    o.evolution.erodibility = -1.0;
    fails(o, "erodibility");
    o = smallDomain();
    o.riverArea = 0.0;
    fails(o, "river_area");
    EXPECT_GT(ErodedHeightfield::peakBytes(smallDomain(0.0, 0.01)), std::size_t(1) << 33);
}
