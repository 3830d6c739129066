// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The talus node: cones at the foot of cliffs as high as the options say and
// never steeper than the angle of repose, nothing on flats and gentle
// slopes, the same bits for any block size, tiling and thread count,
// bounds that hold, the extremes and errors naming their key.

#include <strata/Error.h>
#include <strata/terrain/SampleLevelSet.h>
#include <strata/terrain/ScreeField.h>
#include <strata/terrain/TalusHeightfield.h>

#include "TilingChecks.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>

using namespace strata::terrain;
using strata::test::expectTilesMatchWhole;
using strata::test::openBox;

namespace {

/// A round mesa: 40 m high, radius 60 m, its wall a 1 m ramp (slope 40),
/// centred at (cx, cz).
class Mesa final : public HeightfieldBase
{
public:
    Mesa(double cx, double cz) : mCx(cx), mCz(cz) { setSlopeBound(40.0); }
    double height(double x, double z) const override
    {
        const double r = std::sqrt((x - mCx) * (x - mCx) + (z - mCz) * (z - mCz));
        return 40.0 * std::clamp(60.5 - r, 0.0, 1.0);
    }

private:
    double mCx, mCz;
};

/// The mesa as 3D rock with an alcove cut into its wall: air where r > 56 m
/// and y < 6 m (4.5 m deep under the wall).
class UndercutMesa final : public DensityField
{
public:
    double density(const glm::dvec3& p) const override
    {
        const double alcove = std::max(56.0 - std::sqrt(p.x * p.x + p.z * p.z), p.y - 6.0);
        return std::max(p.y - mMesa.height(p.x, p.z), -alcove);
    }
    double lipschitz() const override { return std::sqrt(1.0 + 40.0 * 40.0); }

private:
    Mesa mMesa{0.0, 0.0};
};

HeightNodePtr hills()
{
    NoiseHeightfieldOptions o;
    o.amplitude = 6.0;
    o.wavelength = 120.0;
    return std::make_shared<NoiseHeightfield>(3, o);
}

TalusOptions options(int block = 32)
{
    TalusOptions o;
    o.blockCells = block;
    return o;
}

double thicknessAt(const TalusHeightfield& t, double x, double z)
{
    double out;
    t.thickness(&x, &z, 1, &out);
    return out;
}

} // namespace

TEST(TalusHeightfield, ConesAtTheFootOfCliffsAsHighAsFillSays)
{
    const TalusHeightfield talus(std::make_shared<Mesa>(0.0, 0.0), options());
    // fill 0.4 of a 40 m wall: cones 16 m above the foot from the wall's
    // top, falling away at no more than tan 34° (0.6745) and no less than
    // 0.924 of it. 3.5 m out from the wall's foot (so the lattice cell holds
    // no node on the wall itself), from the last full-height node (at most
    // a cell's diagonal, 2.83 m, inside the top edge at 59.5 m): at least
    // 16 − 0.6745 · (4.5 + 2.83).
    for (const double angle : {0.0, 0.7, 2.1, 4.0}) {
        const double cx = std::cos(angle), cz = std::sin(angle);
        const double foot = thicknessAt(talus, 64.0 * cx, 64.0 * cz);
        EXPECT_GT(foot, 11.05) << angle;
        EXPECT_LE(foot, 16.0) << angle;
        // Beyond 16 / (0.924 · 0.6745) = 25.7 m from the wall, and two cells
        // of interpolation, none.
        EXPECT_EQ(thicknessAt(talus, 90.5 * cx, 90.5 * cz), 0.0) << angle;
        // The top of the mesa and the plain far off are the ground itself.
        EXPECT_EQ(talus.height(20.0 * cx, 20.0 * cz), 40.0);
        EXPECT_EQ(talus.height(120.0 * cx, 120.0 * cz), 0.0);
    }
    // max_height caps it.
    TalusOptions low = options();
    low.maxHeight = 5.0;
    const TalusHeightfield capped(std::make_shared<Mesa>(0.0, 0.0), low);
    EXPECT_LE(thicknessAt(capped, 62.5, 0.0), 5.0);
    EXPECT_GT(thicknessAt(capped, 62.5, 0.0), 1.5);
    // fill 0: no talus anywhere.
    TalusOptions none = options();
    none.fill = 0.0;
    const TalusHeightfield bare(std::make_shared<Mesa>(0.0, 0.0), none);
    for (double x = 55.0; x < 95.0; x += 0.7) EXPECT_EQ(thicknessAt(bare, x, 3.0), 0.0) << x;
}

TEST(TalusHeightfield, NeverSteeperThanItsAngleWhereItLiesOnTalus)
{
    for (const double angle : {20.0, 34.0, 55.0}) {
        TalusOptions o = options(128);
        o.angle = angle;
        o.cellSize = 1.5;
        const TalusHeightfield talus(std::make_shared<Mesa>(0.0, 0.0), o);
        const double limit = std::tan(angle * M_PI / 180.0) * (1.0 + 1e-12);
        // Every lattice node and its 8 neighbours, where both lie on talus
        // at least a cell thick (the surface there is the cones').
        int checked = 0;
        for (int j = -70; j <= 70; ++j) {
            for (int i = -70; i <= 70; ++i) {
                const double x = i * o.cellSize, z = j * o.cellSize;
                if (thicknessAt(talus, x, z) < o.cellSize) continue;
                for (const auto& [di, dj] : {std::pair{1, 0}, std::pair{0, 1}, std::pair{1, 1}, std::pair{1, -1}}) {
                    const double nx = x + di * o.cellSize, nz = z + dj * o.cellSize;
                    if (thicknessAt(talus, nx, nz) < o.cellSize) continue;
                    const double run = o.cellSize * std::sqrt(double(di * di + dj * dj));
                    EXPECT_LE(std::abs(talus.height(nx, nz) - talus.height(x, z)) / run, limit)
                        << angle << "° at " << x << ", " << z;
                    ++checked;
                }
            }
        }
        EXPECT_GT(checked, 500) << angle;
    }
}

TEST(TalusHeightfield, FlatsAndGentleSlopesAreLeftAlone)
{
    const TalusHeightfield flat(std::make_shared<ConstantHeight>(4.0), options());
    for (double x = -50.0; x < 50.0; x += 3.3) EXPECT_EQ(flat.height(x, 0.7 * x), 4.0);
    // Hills of ±6 m over 120 m are far gentler than 34°.
    const HeightNodePtr gentle = hills();
    const TalusHeightfield talus(gentle, options());
    for (double x = -80.0; x < 80.0; x += 1.9) {
        for (double z = -80.0; z < 80.0; z += 2.3) ASSERT_EQ(talus.height(x, z), gentle->height(x, z)) << x << ", " << z;
    }
}

TEST(TalusHeightfield, AnyBlockSizeTilingAndThreadCountGivesTheSameBits)
{
    // Every lattice node is a pure function of the ground within its reach:
    // blocks of 48 and 128 cells give the same surface.
    const TalusHeightfield small(std::make_shared<Mesa>(5.0, -3.0), options(48));
    const TalusHeightfield large(std::make_shared<Mesa>(5.0, -3.0), options(128));
    std::mt19937 random(7);
    std::uniform_real_distribution<double> at(-100.0, 100.0);
    int talusPoints = 0;
    for (int k = 0; k < 4000; ++k) {
        const double x = at(random), z = at(random);
        const double h = small.height(x, z);
        ASSERT_EQ(h, large.height(x, z)) << x << ", " << z;
        talusPoints += thicknessAt(small, x, z) > 0.0;
    }
    EXPECT_GT(talusPoints, 200);

    const glm::dvec3 lo(-96, -20, -96), hi(96, 60, 96);
    const auto whole = sampleLevelSet(TalusHeightfield(std::make_shared<Mesa>(5.0, -3.0), options()), openBox(lo, hi));
    ASSERT_GT(whole->activeVoxelCount(), 20000u);
    for (const int threads : {1, 2, 3}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
        const TalusHeightfield fresh(std::make_shared<Mesa>(5.0, -3.0), options()); // its own, empty cache
        for (const int tiles : {2, 3}) {
            expectTilesMatchWhole(fresh, *whole, lo, hi, tiles, std::to_string(threads) + " threads");
        }
    }
}

TEST(TalusHeightfield, BoundsAndSlopeBoundHold)
{
    const TalusHeightfield talus(std::make_shared<Mesa>(0.0, 0.0), options());
    std::mt19937 random(11);
    std::uniform_real_distribution<double> at(-100.0, 100.0), size(0.1, 30.0);
    for (int k = 0; k < 300; ++k) {
        const glm::dvec2 lo(at(random), at(random));
        const glm::dvec2 hi = lo + glm::dvec2(size(random), size(random));
        const Interval b = talus.heightBounds(lo, hi);
        for (int s = 0; s < 20; ++s) {
            const double x = lo.x + (hi.x - lo.x) * (s % 5) / 4.0, z = lo.y + (hi.y - lo.y) * (s / 5) / 3.0;
            const double h = talus.height(x, z);
            ASSERT_GE(h, b.lo) << x << ", " << z;
            ASSERT_LE(h, b.hi) << x << ", " << z;
        }
    }
    // 1 cm steps down the apron and across block borders (every 64 m).
    double previous = talus.height(40.0, 9.3), steepest = 0.0;
    for (double x = 40.01; x < 130.0; x += 0.01) {
        const double h = talus.height(x, 9.3);
        steepest = std::max(steepest, std::abs(h - previous) / 0.01);
        previous = h;
    }
    EXPECT_LE(steepest, talus.slopeBound());
}

TEST(TalusHeightfield, FarFromTheOriginTheSameCones)
{
    // The mesa at 1e9 m: the lattice holds the same cones relative to it.
    const TalusHeightfield near(std::make_shared<Mesa>(0.0, 0.0), options());
    const double far = 1e9;
    const TalusHeightfield away(std::make_shared<Mesa>(far, -far), options());
    for (double d = 58.0; d < 95.0; d += 2.0) {
        EXPECT_NEAR(thicknessAt(away, far + d, -far), thicknessAt(near, d, 0.0), 1e-4) << d;
    }
    // Beyond ±2^62 cells, or at NaN, the child's height alone.
    const auto child = hills();
    const TalusHeightfield talus(child, options());
    EXPECT_EQ(talus.height(1e300, 0.0), child->height(1e300, 0.0));
    EXPECT_TRUE(std::isnan(talus.height(std::nan(""), 0.0)) == std::isnan(child->height(std::nan(""), 0.0)));
}

TEST(TalusHeightfield, ThicknessIsTheDepositionMask)
{
    const TalusHeightfield talus(std::make_shared<Mesa>(0.0, 0.0), options());
    const double x[] = {10.0, 61.5, 70.0, 120.0}, z[] = {0.0, 0.0, 1.0, 0.0};
    glm::vec4 masks[4];
    talus.landformMasks(x, z, 4, masks);
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(masks[k].x, 0.0f);
        EXPECT_FLOAT_EQ(masks[k].z, float(thicknessAt(talus, x[k], z[k])));
    }
    EXPECT_GT(masks[1].z, 10.0f);
    EXPECT_EQ(masks[3].z, 0.0f);
}

TEST(TalusHeightfield, BadKeysAreNamed)
{
    auto fails = [](TalusOptions o, const std::string& key) {
        try {
            TalusHeightfield node(hills(), o);
            ADD_FAILURE() << key << " accepted";
        } catch (const strata::Error& e) {
            EXPECT_EQ(e.place().key, key) << e.what();
        }
    };
    TalusOptions o = options();
    o.angle = 70.0;
    fails(o, "angle");
    o = options();
    o.fill = 1.5;
    fails(o, "fill");
    o = options();
    o.maxHeight = 0.0;
    fails(o, "max_height");
    o = options();
    o.cellSize = std::nan("");
    fails(o, "cell_size");
    o = options();
    o.blockCells = 8;
    fails(o, "block");
    o = options();
    o.maxHeight = 500.0; // 500 m cones on a 2 m lattice: a window of thousands of cells
    fails(o, "max_height");
}

TEST(ScreeField, FillsTheAlcovesAtTheFootOfAWallAndKeepsItsBounds)
{
    const auto talus = std::make_shared<TalusHeightfield>(std::make_shared<Mesa>(0.0, 0.0), options(64));
    const auto rock = std::make_shared<UndercutMesa>();
    const ScreeField scree(rock, talus, 2.0);
    // In the alcove near its floor, under the cones (about 16 m against the
    // wall): air in the rock, talus with the scree. Above the cones, air.
    for (const double angle : {0.3, 1.9, 3.5}) {
        const glm::dvec3 low(58.0 * std::cos(angle), 1.0, 58.0 * std::sin(angle));
        EXPECT_GT(rock->density(low), 0.0) << angle;
        EXPECT_LT(scree.density(low), 0.0) << angle;
        const glm::dvec3 out(64.0 * std::cos(angle), 10.0, 64.0 * std::sin(angle));
        EXPECT_LT(scree.density(out), 0.0) << angle; // in the apron
        const glm::dvec3 air(64.0 * std::cos(angle), 20.0, 64.0 * std::sin(angle));
        EXPECT_GT(scree.density(air), 0.0) << angle;
        // The mesa's top and the far plain are the rock's.
        const glm::dvec3 top(10.0 * std::cos(angle), 40.5, 10.0 * std::sin(angle));
        EXPECT_EQ(scree.density(top), rock->density(top));
    }
    // Bounds hold, distance bounds are no further than the surface.
    std::mt19937 random(5);
    std::uniform_real_distribution<double> at(-100.0, 100.0), y(-10.0, 50.0), size(0.1, 12.0);
    for (int k = 0; k < 300; ++k) {
        const glm::dvec3 lo(at(random), y(random), at(random));
        const WorldBox box{lo, lo + glm::dvec3(size(random), size(random), size(random))};
        const Interval b = scree.bounds(box);
        for (int s = 0; s < 8; ++s) {
            const glm::dvec3 p(s & 1 ? box.max.x : box.min.x, s & 2 ? box.max.y : box.min.y,
                               s & 4 ? box.max.z : box.min.z);
            const double d = scree.density(p);
            ASSERT_GE(d, b.lo);
            ASSERT_LE(d, b.hi);
        }
        const glm::dvec3 c = box.centre();
        const double bound = scree.distanceBound(c), d = scree.density(c);
        ASSERT_EQ(bound < 0.0, d < 0.0);
        // No sign change within the bound along the six axes.
        for (int axis = 0; axis < 3; ++axis) {
            for (const double sign : {-1.0, 1.0}) {
                glm::dvec3 q = c;
                q[axis] += sign * std::abs(bound) * 0.999;
                ASSERT_EQ(scree.density(q) < 0.0, d < 0.0) << k;
            }
        }
    }
}

TEST(ScreeField, AnyTilingAndThreadCountGivesTheSameBits)
{
    auto make = [] {
        return ScreeField(std::make_shared<UndercutMesa>(),
                          std::make_shared<TalusHeightfield>(std::make_shared<Mesa>(0.0, 0.0), options(64)), 2.0);
    };
    const glm::dvec3 lo(-96, -10, -96), hi(96, 50, 96);
    const auto whole = sampleLevelSet(make(), openBox(lo, hi));
    ASSERT_GT(whole->activeVoxelCount(), 20000u);
    for (const int threads : {1, 3}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
        expectTilesMatchWhole(make(), *whole, lo, hi, 2, std::to_string(threads) + " threads");
    }
}
