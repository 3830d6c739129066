// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Internal: worm caves' distanceAmong() at a block of points in SIMD lanes
/// (WormSimd.cpp, Highway), for WormCaves::densities(). Each lane runs the
/// scalar loop over the cones in the same order with the same arithmetic
/// (roundConeDistance()'s operations, unfused, exact sqrt), so the same bits.

#include <cstddef>

namespace strata::terrain::detail {

/// A round cone (segment a–b, radii ra, rb) with its bounding sphere, and
/// what roundConeDistance() derives from the segment alone.
struct LaneCone
{
    double ax, ay, az, bx, by, bz, ra, rb;
    double midX, midY, midZ, reach; ///< bounding sphere: |p − mid| − reach below the distance
    double vx, vy, vz;              ///< b − a
    double len;                     ///< |b − a|
    double slope;                   ///< (rb − ra) / len (2 when len is 0)
    double slopeRoot;               ///< √(1 − slope²), when |slope| < 1
};

/// Fills c's derived members as roundConeDistance() computes them.
void deriveLaneCone(LaneCone& c);

/// out[i] = min(cap, distance to the nearest cone) at n points, as
/// WormCaves::distanceAmong() computes it point by point.
void wormDistances(const LaneCone* cones, std::size_t count, double cap, const double* x, const double* y,
                   const double* z, std::size_t n, double* out);

} // namespace strata::terrain::detail
