// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The project's own sin, cos, atan, exp, log, pow, hypot and tan (issue 39:
// libm's differ between C libraries and CPUs) against long double
// references, each within its stated bound over its domain, and exact where
// exactness is promised.

#include <strata/DeterministicMath.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <bit>
#include <iostream>
#include <vector>

namespace {

namespace dm = strata::dmath;

constexpr double ULP = 0x1p-52; // one ulp of 1

/// Deterministic points: an LCG's doubles in [0, 1).
struct Points
{
    std::uint64_t state = 12345;
    double next()
    {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return double(state >> 11) * 0x1p-53;
    }
};

TEST(DeterministicMath, SinAndCosOfDegreesWithinTwoUlpsOfLongDouble)
{
    // Every 1/64 degree over two turns each way, against long double libm.
    double worst = 0.0;
    for (int i = -720 * 64; i <= 720 * 64; ++i) {
        const double degrees = i / 64.0;
        double s = 0.0, c = 0.0;
        dm::sinCosDegrees(degrees, s, c);
        const long double r = (long double)degrees * 3.141592653589793238462643383279502884L / 180.0L;
        const long double rs = sinl(r), rc = cosl(r);
        const double es = double(std::abs((long double)s - rs)), ec = double(std::abs((long double)c - rc));
        worst = std::max({worst, es, ec});
        ASSERT_LE(es, 2.3e-16) << degrees;
        ASSERT_LE(ec, 2.3e-16) << degrees;
    }
    double s = 1.0, c = 0.0;
    for (const double exact : {0.0, 90.0, 180.0, 270.0, 360.0, -90.0}) {
        dm::sinCosDegrees(exact, s, c);
        EXPECT_EQ(std::abs(s) + std::abs(c), 1.0) << exact;
    }
    std::cout << "sinCosDegrees: worst absolute error " << worst << std::endl;
}

TEST(DeterministicMath, SinAndCosOfRadiansWithinTwoUlpsAbsolute)
{
    Points points;
    double worst = 0.0;
    for (int i = 0; i < 200000; ++i) {
        // Mostly the worms' range (a few turns), some far out to 1e6.
        const double x = (points.next() * 2.0 - 1.0) * (i % 10 == 0 ? 1e6 : 40.0);
        double s = 0.0, c = 0.0;
        dm::sinCos(x, s, c);
        const long double xl = x;
        worst = std::max({worst, double(std::fabs((long double)s - sinl(xl))), double(std::fabs((long double)c - cosl(xl)))});
    }
    EXPECT_LE(worst, 2.0 * ULP);
    std::cout << "sinCos: worst absolute error " << worst / ULP << " ulps of 1" << std::endl;
    double s = 1.0, c = 0.0;
    dm::sinCos(0.0, s, c);
    EXPECT_EQ(s, 0.0);
    EXPECT_EQ(c, 1.0);
}

TEST(DeterministicMath, LogAndExpWithinFourUlps)
{
    Points points;
    double worstLog = 0.0, worstExp = 0.0;
    for (int i = 0; i < 200000; ++i) {
        const double x = std::ldexp(1.0 + points.next(), int(points.next() * 2000.0) - 1000);
        const long double reference = logl((long double)x);
        if (reference != 0.0L) worstLog = std::max(worstLog, double(std::fabs((dm::log(x) - reference) / reference)));
        const double y = (points.next() * 2.0 - 1.0) * 700.0;
        const long double e = expl((long double)y);
        worstExp = std::max(worstExp, double(std::fabs((dm::exp(y) - e) / e)));
    }
    // Near 1, where log crosses 0.
    for (double x = 0.999; x < 1.001; x += 1e-6) {
        const long double reference = logl((long double)x);
        if (reference != 0.0L) worstLog = std::max(worstLog, double(std::fabs((dm::log(x) - reference) / reference)));
    }
    EXPECT_LE(worstLog, 4.0 * ULP);
    EXPECT_LE(worstExp, 4.0 * ULP);
    std::cout << "log: worst " << worstLog / ULP << " ulps, exp: " << worstExp / ULP << " ulps" << std::endl;
    EXPECT_EQ(dm::log(1.0), 0.0);
    EXPECT_EQ(dm::exp(0.0), 1.0);
    EXPECT_EQ(dm::log(0.0), -HUGE_VAL);
    EXPECT_TRUE(std::isnan(dm::log(-1.0)));
    EXPECT_EQ(dm::exp(1000.0), HUGE_VAL);
    EXPECT_EQ(dm::exp(-1000.0), 0.0);
    EXPECT_NEAR(dm::log10(1e5), 5.0, 4.0 * 5.0 * ULP);
}

TEST(DeterministicMath, PowWithinItsBoundAndExactWherePromised)
{
    // exp(y·log x): log's error (1.5 ulps) and the product's rounding become
    // an absolute error in the exponent, so the bound grows with |y·log x|.
    Points points;
    double worstRatio = 0.0;
    for (int i = 0; i < 200000; ++i) {
        const double x = std::ldexp(0.5 + points.next(), int(points.next() * 60.0) - 30);
        const double y = 0.25 + points.next() * 63.75; // the terraces' sharpness and the stream-power exponents
        const long double reference = powl((long double)x, (long double)y);
        if (reference < 1e-300L || reference > 1e300L) continue;
        const double error = double(std::fabs((dm::pow(x, y) - reference) / reference));
        const double bound = (2.0 * std::fabs(y * std::log(x)) + 4.0) * ULP;
        worstRatio = std::max(worstRatio, error / bound);
    }
    EXPECT_LE(worstRatio, 1.0);
    std::cout << "pow: worst error " << worstRatio << " of its bound" << std::endl;
    for (const double x : {0.0, 1e-300, 0.37, 1.0, 3.5, 1e300}) {
        EXPECT_EQ(dm::pow(x, 0.0), 1.0);
        EXPECT_EQ(dm::pow(x, 1.0), x);
        EXPECT_EQ(dm::pow(x, 2.0), x * x);
        EXPECT_EQ(dm::pow(x, 0.5), std::sqrt(x));
    }
    EXPECT_EQ(dm::pow(0.0, 3.0), 0.0);
    EXPECT_TRUE(std::isnan(dm::pow(-2.0, 3.0)));
    EXPECT_EQ(dm::pow(0.0, -1.5), HUGE_VAL);
}

TEST(DeterministicMath, HypotAndTanOfDegrees)
{
    Points points;
    for (int i = 0; i < 100000; ++i) {
        const double x = (points.next() - 0.5) * 1e6, y = (points.next() - 0.5) * 1e-3;
        const long double reference = sqrtl((long double)x * x + (long double)y * y);
        EXPECT_LE(std::fabs((dm::hypot(x, y) - reference) / reference), 2.0 * ULP);
        const double degrees = (points.next() * 2.0 - 1.0) * 89.0;
        const long double t = tanl((long double)degrees * 3.14159265358979323846264338327950288L / 180.0L);
        if (t != 0.0L) {
            EXPECT_LE(std::fabs((dm::tanDegrees(degrees) - t) / t), 8.0 * ULP) << degrees;
        }
    }
    EXPECT_EQ(dm::hypot(3.0, 4.0), 5.0);
    EXPECT_EQ(dm::tanDegrees(0.0), 0.0);
    EXPECT_NEAR(dm::tanDegrees(45.0), 1.0, 2.0 * ULP);
}

TEST(DeterministicMath, Log2WithinFourUlpsAndExactAtPowersOfTwo)
{
    Points points;
    double worst = 0.0;
    for (int i = 0; i < 200000; ++i) {
        // The whole range of positive doubles, subnormals included.
        const double x = std::ldexp(1.0 + points.next(), int(points.next() * 2098.0) - 1074);
        const long double reference = log2l((long double)x);
        if (reference != 0.0L) worst = std::max(worst, double(std::fabs((dm::log2(x) - reference) / reference)));
    }
    for (double x = 0.999; x < 1.001; x += 1e-6) {
        const long double reference = log2l((long double)x);
        if (reference != 0.0L) worst = std::max(worst, double(std::fabs((dm::log2(x) - reference) / reference)));
    }
    EXPECT_LE(worst, 4.0 * ULP);
    std::cout << "log2: worst " << worst / ULP << " ulps" << std::endl;
    for (int e = -1074; e <= 1023; ++e) ASSERT_EQ(dm::log2(std::ldexp(1.0, e)), double(e)) << e;
    EXPECT_EQ(dm::log2(0.0), -HUGE_VAL);
    EXPECT_EQ(dm::log2(HUGE_VAL), HUGE_VAL);
    EXPECT_TRUE(std::isnan(dm::log2(-1.0)));
    EXPECT_TRUE(std::isnan(dm::log2(NAN)));
}

TEST(DeterministicMath, AtanWithinTwoUlpsOverTheWholeLine)
{
    // Magnitudes from 1e-300 to 1e300 and, densely, the reduction's
    // breakpoints between 0 and 4; both signs.
    Points points;
    double worst = 0.0;
    auto check = [&](double x) {
        const long double reference = atanl((long double)x);
        const double error = double(std::fabs((dm::atan(x) - reference) / reference));
        worst = std::max(worst, error);
        ASSERT_LE(error, 2.0 * ULP) << x;
        ASSERT_EQ(dm::atan(-x), -dm::atan(x)) << x; // odd, exactly
    };
    for (int i = 0; i < 200000; ++i) {
        check(std::ldexp(1.0 + points.next(), int(points.next() * 2000.0) - 1000));
        check(points.next() * 4.0 + 0x1p-60);
    }
    for (int k = 1; k <= 64; ++k) check(k / 16.0); // the breakpoints k/8 and midway between
    std::cout << "atan: worst " << worst / ULP << " ulps" << std::endl;
    EXPECT_EQ(dm::atan(0.0), 0.0);
    EXPECT_TRUE(std::signbit(dm::atan(-0.0)));
    EXPECT_EQ(dm::atan(1e-300), 1e-300);
    EXPECT_EQ(dm::atan(HUGE_VAL), dm::PI_2_HI);
    EXPECT_EQ(dm::atan(-HUGE_VAL), -dm::PI_2_HI);
    EXPECT_EQ(dm::atan(1e300), dm::PI_2_HI);
    EXPECT_TRUE(std::isnan(dm::atan(NAN)));
}

TEST(DeterministicMath, Atan2WithinTwoUlpsInEveryQuadrant)
{
    Points points;
    double worst = 0.0;
    for (int i = 0; i < 400000; ++i) {
        // Angles all around, at scales from 1e-150 to 1e150 and with very
        // different magnitudes of x and y.
        const double scale = std::ldexp(1.0, int(points.next() * 1000.0) - 500);
        const double x = (points.next() * 2.0 - 1.0) * scale;
        const double y = (points.next() * 2.0 - 1.0) * (i % 4 == 0 ? scale * 1e-12 : i % 4 == 1 ? scale * 1e12 : scale);
        const long double reference = atan2l((long double)y, (long double)x);
        if (reference == 0.0L) continue;
        const double error = double(std::fabs((dm::atan2(y, x) - reference) / reference));
        worst = std::max(worst, error);
        ASSERT_LE(error, 2.0 * ULP) << y << ", " << x;
    }
    std::cout << "atan2: worst " << worst / ULP << " ulps" << std::endl;
    // Zeros, infinities and the axes: the same values as std::atan2.
    const double values[] = {0.0, -0.0, 1.0, -1.0, 3.5, -2.25, 1e-310, -1e-310, 1e300, -1e300, HUGE_VAL, -HUGE_VAL};
    for (const double y : values) {
        for (const double x : values) {
            const double expected = std::atan2(y, x), got = dm::atan2(y, x);
            const bool exactCase = y == 0.0 || x == 0.0 || std::isinf(x) || std::isinf(y);
            if (exactCase) {
                // ±0 and ±π/2, ±π, ±π/4, ±3π/4: the doubles nearest.
                EXPECT_EQ(got, expected) << y << ", " << x;
                EXPECT_EQ(std::signbit(got), std::signbit(expected)) << y << ", " << x;
            } else {
                EXPECT_NEAR(got, expected, 2.0 * ULP * std::fabs(expected)) << y << ", " << x;
            }
        }
    }
    EXPECT_TRUE(std::isnan(dm::atan2(NAN, 1.0)));
    EXPECT_TRUE(std::isnan(dm::atan2(1.0, NAN)));
}

TEST(DeterministicMath, AcosWithinThreeUlpsOnMinusOneToOne)
{
    Points points;
    double worst = 0.0;
    auto check = [&](double c) {
        const long double reference = acosl((long double)c);
        if (reference == 0.0L) {
            ASSERT_EQ(dm::acos(c), 0.0);
            return;
        }
        const double error = double(std::fabs((dm::acos(c) - reference) / reference));
        worst = std::max(worst, error);
        ASSERT_LE(error, 3.0 * ULP) << c;
    };
    for (int i = 0; i < 200000; ++i) {
        check(points.next() * 2.0 - 1.0);
        // Near ±1, where 1 − c² cancels: c = ±(1 − 2^−k·u).
        const double near = 1.0 - std::ldexp(points.next(), -int(points.next() * 52.0));
        check(near);
        check(-near);
    }
    std::cout << "acos: worst " << worst / ULP << " ulps" << std::endl;
    EXPECT_EQ(dm::acos(1.0), 0.0);
    EXPECT_EQ(dm::acos(-1.0), dm::PI_HI);
    EXPECT_EQ(dm::acos(0.0), dm::PI_2_HI);
    EXPECT_TRUE(std::isnan(dm::acos(1.0 + 0x1p-52)));
    EXPECT_TRUE(std::isnan(dm::acos(-2.0)));
    EXPECT_TRUE(std::isnan(dm::acos(NAN)));
}

} // namespace

namespace {

TEST(DeterministicMath, BitFrexpAndLdexpAreLibmsExactResults)
{
    // frexpPositive and ldexpNear1 replace libm's frexp and ldexp on pow's
    // hot path: both are exact operations, so they must give libm's bits,
    // at the normal/subnormal border and beyond it too.
    const auto sameBits = [](double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); };
    Points points;
    std::vector<double> xs = {0x1p-1074, 0x1p-1073 * 3.0, 0x1p-1023, 0x1p-1022, 0x1p-1022 * (1.0 + ULP), 0.5, 1.0,
                              0.7071067811865476, 1.0 - ULP / 2, 3.0, 0x1p1023, 1.7976931348623157e308};
    for (int i = 0; i < 100000; ++i) {
        const double u = points.next();
        xs.push_back(std::ldexp(0.5 + 0.5 * u, int(points.next() * 2098.0) - 1074));
    }
    for (const double x : xs) {
        if (!(x > 0.0) || !std::isfinite(x)) continue;
        int e = 0, eLibm = 0;
        const double m = dm::frexpPositive(x, e), mLibm = std::frexp(x, &eLibm);
        ASSERT_TRUE(sameBits(m, mLibm)) << x;
        ASSERT_EQ(e, eLibm) << x;
    }
    for (int k = -1100; k <= 1100; ++k)
        for (const double m : {0.5, 0.7071067811865476, 1.0, 1.0 + ULP, 1.4142135623730951, 2.0 - ULP}) {
            ASSERT_TRUE(sameBits(dm::ldexpNear1(m, k), std::ldexp(m, k))) << m << " · 2^" << k;
        }
}

} // namespace
