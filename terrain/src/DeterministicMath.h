// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Trigonometry with + − × ÷ only, for values that decide a world's bytes:
// libm's sin and cos differ between C libraries and between glibc's builds
// for CPUs with and without FMA. Compiled with -ffp-contract=off (as all of
// terrain/), so the same bits on every compiler and CPU.

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

/// sin and cos of an angle in degrees (finite; exact at multiples of 90°).
/// The reduction to [−45°, 45°] is exact in degrees, so large angles lose
/// nothing to a rounded π.
inline void sinCosDegrees(double degrees, double& s, double& c)
{
    const double quarter = std::floor(degrees / 90.0 + 0.5); // nearest multiple of 90°
    const double r = degrees - 90.0 * quarter;               // [−45, 45]
    double rs = 0.0, rc = 0.0;
    sinCosReduced(r * (3.14159265358979323846 / 180.0), rs, rc);
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

} // namespace strata::terrain::detail
