// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The crests node: rounded ridges become the edge where their flanks meet;
// planes, valleys and soft rock stay as they were.

#include <strata/Error.h>
#include <strata/terrain/CrestHeightfield.h>
#include <strata/terrain/Lithology.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

using namespace strata::terrain;

namespace {

/// A ridge along z at x = centre: two planes of slope `slope` meeting at
/// `top`, rounded by a parabola within ±`round` of the crest (C1), or the
/// same valley upside down.
class RoundedRidge final : public HeightfieldBase
{
public:
    RoundedRidge(double top, double slope, double round, double centre = 0.0, bool valley = false)
        : mTop(top), mSlope(slope), mRound(round), mCentre(centre), mSign(valley ? -1.0 : 1.0)
    {
        setSlopeBound(slope);
    }
    double height(double x, double /*z*/) const override
    {
        const double u = std::abs(x - mCentre);
        const double fromTop = u >= mRound ? u : 0.5 * (u * u / mRound + mRound);
        return mSign * (mTop - mSlope * fromTop);
    }
    /// The planes without the rounding.
    double edge(double x) const { return mSign * (mTop - mSlope * std::abs(x - mCentre)); }

private:
    double mTop, mSlope, mRound, mCentre, mSign;
};

/// A constant 0..1 mask.
class ConstantMask final : public HeightfieldBase
{
public:
    explicit ConstantMask(double v) : mValue(v) { setSlopeBound(0.0); }
    double height(double, double) const override { return mValue; }

private:
    double mValue;
};

CrestOptions options(double reach = 12.0, double amount = 1.0, double maxLift = 1e3)
{
    CrestOptions o;
    o.reach = reach;
    o.amount = amount;
    o.maxLift = maxLift;
    return o;
}

} // namespace

TEST(CrestHeightfield, ARoundedRidgeBecomesTheEdgeOfItsFlanks)
{
    const auto ridge = std::make_shared<RoundedRidge>(100.0, 0.8, 6.0);
    const CrestHeightfield crest(ridge, options(12.0));
    EXPECT_LT(ridge->height(0.0, 0.0), 100.0 - 2.0); // rounded by 2.4 m before
    for (double x = -30.0; x <= 30.0; x += 0.37) {
        for (double z : {-50.0, 0.0, 13.0}) {
            // Every direction reads flank points past the rounding (reach 12 > 6).
            EXPECT_NEAR(crest.height(x, z), ridge->edge(x), 1e-9) << "x " << x;
            EXPECT_GE(crest.height(x, z), ridge->height(x, z));
        }
    }
}

TEST(CrestHeightfield, PlanesAndValleysAreLeftBitForBit)
{
    const auto valley = std::make_shared<RoundedRidge>(100.0, 0.8, 6.0, 0.0, true);
    const CrestHeightfield crest(valley, options(12.0));
    for (double x = -40.0; x <= 40.0; x += 0.53) EXPECT_EQ(crest.height(x, 3.0), valley->height(x, 3.0)) << x;
    // Far out on a flank the ridge is a plane.
    const auto ridge = std::make_shared<RoundedRidge>(100.0, 0.8, 6.0);
    const CrestHeightfield onRidge(ridge, options(12.0));
    for (double x = 30.0; x <= 80.0; x += 0.71) EXPECT_EQ(onRidge.height(x, -7.0), ridge->height(x, -7.0)) << x;
}

TEST(CrestHeightfield, AmountMaxLiftAndMaskScaleTheLift)
{
    const auto ridge = std::make_shared<RoundedRidge>(100.0, 0.8, 6.0);
    const double rounded = ridge->height(0.0, 0.0), full = 100.0 - rounded;
    EXPECT_EQ(CrestHeightfield(ridge, options(12.0, 0.0)).height(0.0, 0.0), rounded);
    EXPECT_EQ(CrestHeightfield(ridge, options(12.0, 1.0, 0.0)).height(0.0, 0.0), rounded);
    EXPECT_NEAR(CrestHeightfield(ridge, options(12.0, 0.5)).height(0.0, 0.0), rounded + 0.5 * full, 1e-9);
    EXPECT_NEAR(CrestHeightfield(ridge, options(12.0, 1.0, 1.0)).height(0.0, 0.0), rounded + 1.0, 1e-12);
    EXPECT_EQ(CrestHeightfield(ridge, options(), std::make_shared<ConstantMask>(0.0)).height(0.0, 0.0), rounded);
    EXPECT_NEAR(CrestHeightfield(ridge, options(), std::make_shared<ConstantMask>(0.25)).height(0.0, 0.0),
                rounded + 0.25 * full, 1e-9);
    EXPECT_NEAR(CrestHeightfield(ridge, options(), std::make_shared<ConstantMask>(7.0)).height(0.0, 0.0), 100.0,
                1e-9); // the mask is clamped to 1
}

TEST(CrestHeightfield, SharpOnHardBedsRoundedOnSoftOnes)
{
    LithologyOptions lo;
    lo.beds = {{50.0, 1.0}, {50.0, 0.0}}; // hard from 0 to 50 m, soft from 50 to 100 m, repeating
    lo.transition = 0.5;
    const auto rock = std::make_shared<Lithology>(7, lo);
    const auto hardRidge = std::make_shared<RoundedRidge>(30.0, 0.8, 6.0);
    const auto softRidge = std::make_shared<RoundedRidge>(80.0, 0.8, 6.0);
    EXPECT_NEAR(CrestHeightfield(hardRidge, options(), nullptr, rock).height(0.0, 0.0), 30.0, 1e-9);
    EXPECT_EQ(CrestHeightfield(softRidge, options(), nullptr, rock).height(0.0, 0.0), softRidge->height(0.0, 0.0));
}

TEST(CrestHeightfield, ColumnsInABlockGiveTheSameBitsAsOneByOne)
{
    const auto ridge = std::make_shared<RoundedRidge>(100.0, 0.8, 6.0, 3.0);
    const CrestHeightfield crest(ridge, options(9.0, 0.7, 2.0));
    std::vector<double> x, z;
    for (int i = 0; i < 300; ++i) {
        x.push_back(-20.0 + 0.137 * i);
        z.push_back(5.0 - 0.05 * i);
    }
    std::vector<double> block(x.size());
    crest.heights(x.data(), z.data(), x.size(), block.data());
    for (std::size_t i = 0; i < x.size(); ++i) EXPECT_EQ(block[i], crest.height(x[i], z[i])) << i;
}

TEST(CrestHeightfield, BoundsAndSlopeBoundHold)
{
    LithologyOptions lo;
    lo.beds = {{3.0, 0.9}, {2.0, 0.1}};
    lo.dip = 20.0;
    const auto rock = std::make_shared<Lithology>(3, lo);
    const auto ridge = std::make_shared<RoundedRidge>(100.0, 1.3, 8.0);
    const CrestHeightfield crest(ridge, options(10.0, 0.8, 5.0), std::make_shared<ConstantMask>(0.9), rock);
    std::mt19937_64 random(11);
    std::uniform_real_distribution<double> at(-40.0, 40.0);
    for (int box = 0; box < 50; ++box) {
        const double x0 = at(random), z0 = at(random), size = 0.5 + 0.2 * box;
        const Interval b = crest.heightBounds({x0, z0}, {x0 + size, z0 + size});
        for (int i = 0; i < 40; ++i) {
            const double x = x0 + size * (i % 7) / 6.0, z = z0 + size * (i / 7) / 5.0;
            const double h = crest.height(x, z);
            EXPECT_GE(h, b.lo);
            EXPECT_LE(h, b.hi);
        }
    }
    const double step = 1e-3;
    for (int i = 0; i < 4000; ++i) {
        const double x = at(random), z = at(random);
        const double dx = (crest.height(x + step, z) - crest.height(x, z)) / step;
        const double dz = (crest.height(x, z + step) - crest.height(x, z)) / step;
        EXPECT_LE(std::sqrt(dx * dx + dz * dz), crest.slopeBound() * (1.0 + 1e-6)) << x << " " << z;
    }
}

TEST(CrestHeightfield, TheSameCrestFarFromTheOrigin)
{
    const double far = 1e9;
    const auto near = std::make_shared<RoundedRidge>(100.0, 0.8, 6.0);
    const auto there = std::make_shared<RoundedRidge>(100.0, 0.8, 6.0, far);
    const CrestHeightfield a(near, options()), b(there, options());
    for (double x = -10.0; x <= 10.0; x += 0.5) EXPECT_NEAR(b.height(far + x, far), a.height(x, 0.0), 1e-6) << x;
}

TEST(CrestHeightfield, BadOptionsAreNamed)
{
    const auto ridge = std::make_shared<RoundedRidge>(100.0, 0.8, 6.0);
    auto message = [&](const CrestOptions& o) {
        try {
            CrestHeightfield crest(ridge, o);
        } catch (const strata::Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(message(options(0.0)).find("reach"), std::string::npos);
    EXPECT_NE(message(options(NAN)).find("reach"), std::string::npos);
    EXPECT_NE(message(options(12.0, 1.5)).find("amount"), std::string::npos);
    EXPECT_NE(message(options(12.0, NAN)).find("amount"), std::string::npos);
    EXPECT_NE(message(options(12.0, 1.0, -1.0)).find("max_lift"), std::string::npos);
    EXPECT_NE(message(options(12.0, 1.0, INFINITY)).find("max_lift"), std::string::npos);
}
