// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Landscape evolution: the sediment budget, the analytic steady state,
// flats, lakes, determinism and the extremes.

#include <strata/Error.h>
#include <strata/terrain/FlowRouting.h>
#include <strata/terrain/StreamPowerErosion.h>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

using namespace strata::terrain;

namespace {

/// Rough ground: a tilted plane with a hashed bump per cell (deterministic).
std::vector<double> roughGround(int w, int h, double amplitude = 5.0)
{
    std::vector<double> out(std::size_t(w) * std::size_t(h));
    for (int z = 0; z < h; ++z) {
        for (int x = 0; x < w; ++x) {
            std::uint64_t k = std::uint64_t(z) * 73856093u ^ std::uint64_t(x) * 19349663u;
            k = (k ^ (k >> 13)) * 0x9E3779B97F4A7C15ull;
            const double bump = double(k >> 40) / double(1 << 24);
            out[std::size_t(z) * std::size_t(w) + std::size_t(x)] = 0.02 * double(x + z) + amplitude * bump;
        }
    }
    return out;
}

} // namespace

TEST(StreamPowerErosion, SedimentIsConservedAndLakesFillToTheirSpillLevel)
{
    // A valley draining into a closed basin with a rim: rivers erode the
    // hills, the basin traps sediment up to its spill level, the rest
    // leaves through the edge.
    const int w = 48, h = 48;
    std::vector<double> ground = roughGround(w, h, 2.0);
    for (int z = 0; z < h; ++z) {
        for (int x = 0; x < w; ++x) {
            const double r = std::hypot(x - 24.0, z - 24.0);
            ground[std::size_t(z) * w + std::size_t(x)] += 40.0 + 2.0 * r - (r < 6.0 ? 30.0 : 0.0);
        }
    }
    StreamPowerOptions o;
    o.cellSize = 20.0;
    o.years = 2e5;
    o.timeStep = 1e4;
    o.uplift = 1e-3;
    o.erodibility = 2e-5;
    o.diffusivity = 0.0;
    const StreamPowerResult r = evolveLandscape(ground, w, h, {}, o);
    ASSERT_EQ(r.steps, 20);
    EXPECT_GT(r.eroded, 1e4);
    EXPECT_GT(r.deposited, 0.0);
    EXPECT_NEAR(r.eroded, r.deposited + r.carriedOut, 1e-9 * r.eroded);
    // Sediment thickness times the cell area never exceeds what was laid.
    double lying = 0.0;
    for (const double s : r.sediment) lying += s * o.cellSize * o.cellSize;
    EXPECT_LE(lying, r.deposited * (1.0 + 1e-9));
    // The lakes and areas are those of the final surface: routed again, it
    // fills each cell to exactly the reported depth (a depth taken before
    // the last step would differ), and the basin still holds a lake.
    const FlowRouting final = routeFlow(r.heights, w, h, o.cellSize);
    double deepest = 0.0;
    for (std::size_t i = 0; i < r.heights.size(); ++i) {
        ASSERT_EQ(r.lakeDepth[i], final.filled[i] - r.heights[i]) << "cell " << i;
        deepest = std::max(deepest, r.lakeDepth[i]);
    }
    EXPECT_GT(deepest, 0.0);
    EXPECT_EQ(r.area, drainageArea(final, o.cellSize));
}

TEST(StreamPowerErosion, UniformUpliftReachesTheAnalyticSteadyState)
{
    // At steady state uplift balances incision: S = (U/K)^(1/n)·A^(−m/n)
    // on every channel cell, for n = 1 and n = 2.
    for (const double n : {1.0, 2.0}) {
        StreamPowerOptions o;
        o.cellSize = 100.0;
        o.uplift = 1e-3;
        o.erodibility = n == 1.0 ? 1e-5 : 4e-8;
        o.areaExponent = 0.5 * n;
        o.slopeExponent = n;
        o.diffusivity = 0.0;
        o.timeStep = 2e5;
        o.years = 6e7;
        const int w = 40, h = 40;
        const StreamPowerResult r = evolveLandscape(roughGround(w, h, 1.0), w, h, {}, o);
        const FlowRouting routing = routeFlow(r.heights, w, h, o.cellSize);
        double worst = 0.0;
        int checked = 0;
        for (std::size_t i = 0; i < r.heights.size(); ++i) {
            const std::uint32_t rcv = routing.receiver[i];
            if (rcv == i || routing.receiver[rcv] == rcv) continue; // the edge and its neighbours
            const double s = (r.heights[i] - r.heights[rcv]) / receiverDistance(routing, i, o.cellSize);
            const double expected = std::pow(o.uplift / o.erodibility, 1.0 / n) * std::pow(r.area[i], -o.areaExponent / n);
            worst = std::max(worst, std::abs(s / expected - 1.0));
            ++checked;
        }
        EXPECT_GT(checked, 1000) << "n = " << n;
        EXPECT_LT(worst, 1e-3) << "n = " << n;
    }
}

TEST(StreamPowerErosion, FlatGroundWithoutUpliftStaysFlat)
{
    const int w = 32, h = 20;
    const std::vector<double> flat(std::size_t(w) * h, 12.5);
    StreamPowerOptions o;
    o.uplift = 0.0;
    const StreamPowerResult r = evolveLandscape(flat, w, h, {}, o);
    EXPECT_EQ(r.heights, flat);
    EXPECT_EQ(r.eroded, 0.0);
}

TEST(StreamPowerErosion, SameBitsOnAnyThreadCount)
{
    const int w = 64, h = 48;
    StreamPowerOptions o;
    o.years = 2e5;
    o.diffusivity = 0.5;
    auto run = [&](int threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
        return evolveLandscape(roughGround(w, h), w, h, {}, o);
    };
    const StreamPowerResult one = run(1), two = run(2), three = run(3);
    EXPECT_EQ(0, std::memcmp(one.heights.data(), two.heights.data(), one.heights.size() * sizeof(double)));
    EXPECT_EQ(0, std::memcmp(one.heights.data(), three.heights.data(), one.heights.size() * sizeof(double)));
    EXPECT_EQ(one.wear, three.wear);
}

TEST(StreamPowerErosion, Extremes)
{
    StreamPowerOptions o;
    // Zero years: the input, unchanged.
    const std::vector<double> ground = roughGround(16, 16);
    o.years = 0.0;
    EXPECT_EQ(evolveLandscape(ground, 16, 16, {}, o).heights, ground);
    // One cell, one row, 2 × 2: all edge, nothing moves.
    o.years = 1e5;
    EXPECT_EQ(evolveLandscape({3.0}, 1, 1, {}, o).heights, std::vector<double>{3.0});
    EXPECT_EQ(evolveLandscape({1.0, 2.0, 3.0, 4.0}, 2, 2, {}, o).heights, (std::vector<double>{1.0, 2.0, 3.0, 4.0}));
    // Tiny and huge cells, and heights far from zero: finite everywhere.
    for (const double cell : {0.1, 1000.0}) {
        o.cellSize = cell;
        for (const double offset : {0.0, 1e6}) {
            std::vector<double> g = ground;
            for (double& v : g) v += offset;
            const StreamPowerResult r = evolveLandscape(g, 16, 16, {}, o);
            for (const double v : r.heights) ASSERT_TRUE(std::isfinite(v)) << cell << " " << offset;
        }
    }
}

TEST(StreamPowerErosion, BadOptionsAreNamed)
{
    const std::vector<double> g(16, 0.0);
    auto fails = [&](StreamPowerOptions o, const std::string& key) {
        try {
            evolveLandscape(g, 4, 4, {}, o);
            ADD_FAILURE() << key << " accepted";
        } catch (const strata::Error& e) {
            EXPECT_EQ(e.place().key, key) << e.what();
        }
    };
    StreamPowerOptions o;
    o.cellSize = -1.0;
    fails(o, "cell_size");
    o = {};
    o.timeStep = 0.0;
    fails(o, "time_step");
    o = {};
    o.years = std::nan("");
    fails(o, "years");
    o = {};
    o.slopeExponent = 0.0;
    fails(o, "n");
    o = {};
    o.diffusivity = -1.0;
    fails(o, "diffusivity");
    // Step counts that overflowed an int (and ran 0 steps) or cannot finish
    // are refused before any work, naming both keys.
    o = {};
    o.years = 1e10;
    o.timeStep = 1.0;
    fails(o, "time_step");
    try {
        evolveLandscape(g, 4, 4, {}, o);
    } catch (const strata::Error& e) {
        EXPECT_NE(std::string(e.what()).find("years / time_step = 1e+10 / 1"), std::string::npos) << e.what();
    }
    o.timeStep = 1e4; // 1e6 steps: the most allowed
    StreamPowerOptions tiny = o;
    tiny.years = 2.0 * tiny.timeStep;
    EXPECT_EQ(evolveLandscape(g, 4, 4, {}, tiny).steps, 2);
    EXPECT_THROW(evolveLandscape(g, 5, 4, {}, StreamPowerOptions{}), strata::Error);
}
