// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// sin, cos, exp, log, pow and hypot with + − × ÷ and sqrt only (and
// frexp/ldexp, which are exact), for values that decide a world's bytes:
// libm's differ between C libraries and between glibc's builds for CPUs
// with and without FMA. Compiled with -ffp-contract=off (as the whole
// project), so the same bits on every compiler and CPU. Accurate to a few
// ulps (tests/terrain/DeterministicMathTest.cpp asserts the bounds against
// long double): the point is the same bits everywhere, not the last ulp.

#include <algorithm>
#include <cmath>

namespace strata::terrain::detail {

/// sin and cos of x, |x| <= π/4 (radians), by their Taylor series to x^17
/// and x^16: truncation below 2e-17, so within 2 ulps of the true values.
inline void sinCosReduced(double x, double& s, double& c)
{
    const double x2 = x * x;
    s = x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0 + x2 * (1.0 / 362880.0 +
        x2 * (-1.0 / 39916800.0 + x2 * (1.0 / 6227020800.0 + x2 * (-1.0 / 1307674368000.0 +
        x2 * (1.0 / 355687428096000.0)))))))));
    c = 1.0 + x2 * (-0.5 + x2 * (1.0 / 24.0 + x2 * (-1.0 / 720.0 + x2 * (1.0 / 40320.0 + x2 * (-1.0 / 3628800.0 +
        x2 * (1.0 / 479001600.0 + x2 * (-1.0 / 87178291200.0 + x2 * (1.0 / 20922789888000.0))))))));
}

/// sin and cos of r + quarter·90° from those of r: the quadrant's signs
/// and swap (quarter taken modulo 4, exactly).
inline void addQuarterTurns(double quarter, double rs, double rc, double& s, double& c)
{
    const double q = quarter - 4.0 * std::floor(quarter / 4.0); // 0, 1, 2, 3
    if (q == 0.0) {
        s = rs;
        c = rc;
    } else if (q == 1.0) {
        s = rc;
        c = -rs;
    } else if (q == 2.0) {
        s = -rs;
        c = -rc;
    } else {
        s = -rc;
        c = rs;
    }
}

/// sin and cos of an angle in degrees (finite; exact at multiples of 90°).
/// The reduction to [−45°, 45°] is exact in degrees, so large angles lose
/// nothing to a rounded π.
inline void sinCosDegrees(double degrees, double& s, double& c)
{
    const double quarter = std::floor(degrees / 90.0 + 0.5); // nearest multiple of 90°
    const double r = degrees - 90.0 * quarter;               // [−45, 45]
    double rs = 0.0, rc = 0.0;
    sinCosReduced(r * (3.14159265358979323846 / 180.0), rs, rc);
    addQuarterTurns(quarter, rs, rc, s, c);
}

/// sin and cos of x radians, |x| <= 1e6: reduced by π/2 in three parts
/// (fdlibm's split of π/2; k·P1 is exact for |k| < 2^20), then the series.
inline void sinCos(double x, double& s, double& c)
{
    constexpr double P1 = 1.57079632673412561417e+00; // the first 33 bits of π/2
    constexpr double P2 = 6.07710050630396597660e-11; // the next 33
    constexpr double P3 = 2.02226624871116645580e-21; // the rest
    const double k = std::floor(x * 0.63661977236758134308 + 0.5); // nearest multiple of π/2
    const double r = ((x - k * P1) - k * P2) - k * P3;
    double rs = 0.0, rc = 0.0;
    sinCosReduced(r, rs, rc);
    addQuarterTurns(k, rs, rc, s, c);
}

/// Natural logarithm of a finite x > 0 (NaN for x < 0 or NaN, −inf at 0):
/// x = m·2^e with m in [√½, √2), log m = 2·atanh(f), f = (m − 1)/(m + 1),
/// by its series to f^23 (|f| <= 0.172: truncation below 1e-18).
inline double log(double x)
{
    if (!(x > 0.0)) return x == 0.0 ? -HUGE_VAL : NAN;
    if (x == HUGE_VAL) return x;
    int e = 0;
    double m = std::frexp(x, &e); // [0.5, 1)
    if (m < 0.70710678118654752440) {
        m *= 2.0;
        --e;
    }
    const double f = (m - 1.0) / (m + 1.0), f2 = f * f;
    const double series = f * (2.0 + f2 * (2.0 / 3.0 + f2 * (2.0 / 5.0 + f2 * (2.0 / 7.0 + f2 * (2.0 / 9.0 + f2 * (2.0 / 11.0 +
                          f2 * (2.0 / 13.0 + f2 * (2.0 / 15.0 + f2 * (2.0 / 17.0 + f2 * (2.0 / 19.0 + f2 * (2.0 / 21.0 +
                          f2 * (2.0 / 23.0))))))))))));
    constexpr double LN2_HI = 6.93147180369123816490e-01; // ln 2 to 32 bits: e·LN2_HI is exact
    constexpr double LN2_LO = 1.90821492927058770002e-10;
    const double de = double(e);
    return de * LN2_HI + (series + de * LN2_LO);
}

/// e^x: x = k·ln 2 + r, |r| <= ln 2 / 2, e^r by its Taylor series to r^15
/// (truncation below 1e-18), then scaled by 2^k exactly. 0 below −745,
/// +inf above 709.8, NaN for NaN.
inline double exp(double x)
{
    if (x != x) return x;
    if (x > 709.782712893384) return HUGE_VAL;
    if (x < -745.2) return 0.0;
    constexpr double LN2_HI = 6.93147180369123816490e-01, LN2_LO = 1.90821492927058770002e-10;
    const double k = std::floor(x * 1.44269504088896340736 + 0.5);
    const double r = (x - k * LN2_HI) - k * LN2_LO;
    double sum = 1.0 / 1307674368000.0; // 1/15!
    const double inverseFactorials[] = {1.0 / 87178291200.0, 1.0 / 6227020800.0, 1.0 / 479001600.0, 1.0 / 39916800.0,
                                        1.0 / 3628800.0,     1.0 / 362880.0,     1.0 / 40320.0,     1.0 / 5040.0,
                                        1.0 / 720.0,         1.0 / 120.0,        1.0 / 24.0,        1.0 / 6.0,
                                        0.5,                 1.0,                1.0};
    for (const double a : inverseFactorials) sum = a + r * sum;
    return std::ldexp(sum, int(k));
}

/// x^y for x >= 0 (NaN for x < 0): exact for y = 0, 1, 2 and the square root
/// for y = 0.5, else exp(y·log x), within (2·|y·ln x| + 4) ulps.
inline double pow(double x, double y)
{
    if (y == 0.0) return 1.0;
    if (y == 1.0) return x;
    if (y == 2.0) return x * x;
    if (x < 0.0 || x != x || y != y) return NAN;
    if (y == 0.5) return std::sqrt(x);
    if (x == 0.0) return y > 0.0 ? 0.0 : HUGE_VAL;
    return exp(y * log(x));
}

/// log10 x = log x / ln 10.
inline double log10(double x) { return log(x) / 2.30258509299404568402; }

/// √(x² + y²) for values far from overflow (|x|, |y| < 1e150): sqrt is
/// correctly rounded by IEEE 754, glibc's hypot need not be elsewhere.
inline double hypot(double x, double y) { return std::sqrt(x * x + y * y); }

/// 0 at t <= 0, 1 at t >= 1, 3t² − 2t³ between (slope at most 1.5): the
/// one smoothstep of the terrain nodes.
inline double smoothstep01(double t)
{
    t = std::clamp(t, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

/// tan of an angle in degrees, |degrees| < 90.
inline double tanDegrees(double degrees)
{
    double s = 0.0, c = 1.0;
    sinCosDegrees(degrees, s, c);
    return s / c;
}

} // namespace strata::terrain::detail
