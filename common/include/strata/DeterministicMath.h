// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// sin, cos, atan, exp, log, pow and hypot with + − × ÷ and sqrt only (and
// floor, frexp and ldexp, which are exact), for values that decide a
// world's bytes or a printed statistic: libm's differ between C libraries
// and between glibc's builds for CPUs with and without FMA (issue 39).
// Compiled with -ffp-contract=off (as the whole project), so the same bits
// on every compiler and CPU. Accurate to a few ulps (the bounds below are
// checked against long double): the point is the same bits everywhere,
// not the last ulp.

#include <strata/IntegerMath.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace strata::dmath {

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

/// std::frexp for a finite x > 0: x = m·2^e with m in [½, 1). Normal x by
/// its bits (exact, as frexp is, without a call into libm on the hot path
/// of pow); subnormal x by frexp.
inline double frexpPositive(double x, int& e)
{
    if (x < 0x1p-1022) return std::frexp(x, &e);
    const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
    e = int((bits >> 52) & 0x7ff) - 1022;
    return std::bit_cast<double>((bits & ~(std::uint64_t(0x7ff) << 52)) | (std::uint64_t(1022) << 52));
}

/// std::ldexp(m, k) for m in [½, 2): by a product with 2^k built from its
/// bits where the result is normal (exact, as ldexp is), else by ldexp
/// (which rounds a subnormal result once).
inline double ldexpNear1(double m, int k)
{
    if (k < -1021 || k > 1023) return std::ldexp(m, k);
    return m * std::bit_cast<double>(std::uint64_t(k + 1023) << 52);
}

/// log x = e·ln 2 + s for a finite x > 0: x = m·2^e with m in [√½, √2),
/// s = log m = 2·atanh(f), f = (m − 1)/(m + 1), by its series to f^23
/// (|f| <= 0.172: truncation below 1e-18). The reduction of log and log2.
inline double logOfMantissa(double x, int& e)
{
    double m = frexpPositive(x, e); // [0.5, 1)
    if (m < 0.70710678118654752440) {
        m *= 2.0;
        --e;
    }
    const double f = (m - 1.0) / (m + 1.0), f2 = f * f;
    return f * (2.0 + f2 * (2.0 / 3.0 + f2 * (2.0 / 5.0 + f2 * (2.0 / 7.0 + f2 * (2.0 / 9.0 + f2 * (2.0 / 11.0 +
           f2 * (2.0 / 13.0 + f2 * (2.0 / 15.0 + f2 * (2.0 / 17.0 + f2 * (2.0 / 19.0 + f2 * (2.0 / 21.0 +
           f2 * (2.0 / 23.0))))))))))));
}

/// Natural logarithm of a finite x > 0 (NaN for x < 0 or NaN, −inf at 0,
/// +inf at +inf), by logOfMantissa.
inline double log(double x)
{
    if (!(x > 0.0)) return x == 0.0 ? -HUGE_VAL : NAN;
    if (x == HUGE_VAL) return x;
    int e = 0;
    const double series = logOfMantissa(x, e);
    constexpr double LN2_HI = 6.93147180369123816490e-01; // ln 2 to 32 bits: e·LN2_HI is exact
    constexpr double LN2_LO = 1.90821492927058770002e-10;
    const double de = double(e);
    return de * LN2_HI + (series + de * LN2_LO);
}

/// Base-2 logarithm: e + log m / ln 2 (logOfMantissa), so exact at powers
/// of two; within 4 ulps elsewhere. NaN for x < 0 or NaN, −inf at 0.
inline double log2(double x)
{
    if (!(x > 0.0)) return x == 0.0 ? -HUGE_VAL : NAN;
    if (x == HUGE_VAL) return x;
    int e = 0;
    const double series = logOfMantissa(x, e);
    constexpr double INV_LN2_HI = 1.4426950408889634, INV_LN2_LO = 2.0355273740931033e-17; // 1/ln 2
    return double(e) + (series * INV_LN2_HI + series * INV_LN2_LO);
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
    return ldexpNear1(sum, clampToInt<int>(k)); // sum = e^r in [0.7, 1.42]
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

/// atan x for |x| <= 1 as hi + lo: the nearest c = k/8 (k = 0..8), then
/// atan x = atan c + atan u, u = (x − c)/(1 + x·c), |u| <= 1/16 (x − c is
/// exact), atan u by its series to u^13: truncation below 1e-18 relative.
/// atan c is tabulated in two parts (hi: the double nearest, lo: the rest).
inline void atanReduced(double x, double& hi, double& lo)
{
    static constexpr double ATAN_HI[9] = {0.0,
                                          0.12435499454676144,
                                          0.24497866312686414,
                                          0.35877067027057225,
                                          0.4636476090008061,
                                          0.5585993153435624,
                                          0.6435011087932844,
                                          0.7188299996216245,
                                          0.7853981633974483};
    static constexpr double ATAN_LO[9] = {0.0,
                                          -3.1253241424539383e-18,
                                          1.0698755618734451e-17,
                                          -2.4623815582638635e-17,
                                          2.2698777452961687e-17,
                                          -5.4556305485916264e-18,
                                          1.5834785051444286e-17,
                                          -2.1478388444456983e-17,
                                          3.061616997868383e-17};
    const double a = std::fabs(x);
    const int k = std::min(floorToInt<int>(a * 8.0 + 0.5), 8);
    const double c = k / 8.0;
    const double u = (a - c) / (1.0 + a * c), u2 = u * u;
    const double series = u * (1.0 + u2 * (-1.0 / 3.0 + u2 * (1.0 / 5.0 + u2 * (-1.0 / 7.0 + u2 * (1.0 / 9.0 +
                          u2 * (-1.0 / 11.0 + u2 * (1.0 / 13.0)))))));
    hi = std::signbit(x) ? -ATAN_HI[k] : ATAN_HI[k];
    lo = std::signbit(x) ? -(ATAN_LO[k] + series) : ATAN_LO[k] + series;
}

/// π/2 and π in two parts each (hi: the double nearest, lo: the rest).
inline constexpr double PI_2_HI = 1.5707963267948966, PI_2_LO = 6.123233995736766e-17;
inline constexpr double PI_HI = 3.141592653589793, PI_LO = 1.2246467991473532e-16;

/// Arc tangent in radians, in [−π/2, π/2]: |x| > 1 by π/2 − atan(1/x),
/// then atanReduced. Within 2 ulps; odd (−0 gives −0); ±π/2 at ±inf, NaN
/// for NaN.
inline double atan(double x)
{
    if (x != x) return x;
    double hi = 0.0, lo = 0.0;
    if (std::fabs(x) <= 1.0) {
        atanReduced(x, hi, lo);
        return hi + lo;
    }
    atanReduced(1.0 / x, hi, lo); // 1/±inf = ±0
    const double pi2Hi = x > 0.0 ? PI_2_HI : -PI_2_HI, pi2Lo = x > 0.0 ? PI_2_LO : -PI_2_LO;
    return (pi2Hi - hi) + (pi2Lo - lo);
}

/// Angle of the point (x, y) in radians, in [−π, π], with std::atan2's
/// quadrants, signed zeros and infinities: atan(y/x) (± π for x < 0) where
/// |y| <= |x|, else ±π/2 − atan(x/y). Within 2 ulps; NaN if either is NaN.
inline double atan2(double y, double x)
{
    if (x != x || y != y) return x + y;
    if (y == 0.0) return std::signbit(x) ? std::copysign(PI_HI, y) : y; // std: (±0, −0 or x < 0) → ±π
    if (std::isinf(x) && std::isinf(y)) {
        return std::copysign(x > 0.0 ? 0.7853981633974483 : 2.356194490192345, y); // π/4, 3π/4
    }
    if (std::fabs(y) <= std::fabs(x)) {
        const double a = atan(y / x); // |y/x| <= 1
        if (x > 0.0) return a;
        return std::signbit(y) ? (a - PI_LO) - PI_HI : (a + PI_LO) + PI_HI;
    }
    const double a = atan(x / y); // |x/y| < 1 (±0 for x = ±0 or y = ±inf)
    return y > 0.0 ? (PI_2_LO - a) + PI_2_HI : (-PI_2_LO - a) - PI_2_HI;
}

/// Arc cosine in radians, in [0, π], of c in [−1, 1] (NaN outside and for
/// NaN): atan2(√((1 − c)(1 + c)), c), so accurate near ±1 too (no
/// cancellation in 1 − c²). Within 3 ulps.
inline double acos(double c) { return atan2(std::sqrt((1.0 - c) * (1.0 + c)), c); }

} // namespace strata::dmath
