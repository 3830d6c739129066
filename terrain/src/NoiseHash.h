// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Internal: the integer hashing and interpolation helpers shared by the noise
/// sources (not installed).

#include <strata/detail/IntegerHash.h>
#include <strata/terrain/DensityField.h> // Interval

#include <cmath>
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace strata::terrain::detail {

using strata::detail::mix64; // common/include/strata/detail/IntegerHash.h

/// Folds one lattice coordinate into a running hash. Mixing after every
/// coordinate (rather than summing multiples of the coordinates) leaves no
/// linear relation between distant cells, so the pattern does not repeat.
inline std::uint64_t hashCombine(std::uint64_t h, std::int64_t v)
{
    return mix64(h ^ (std::uint64_t(v) + 0x9e3779b97f4a7c15ULL));
}

/// The seed's own hash, so that seeds 0, 1, 2... start far apart.
inline std::uint64_t seedHash(std::uint64_t seed)
{
    return mix64(seed + 0x632be59bd9b4e019ULL);
}

/// floor(x) as a lattice index. Coordinates beyond ±2^62 saturate (the
/// pattern is then constant there) instead of overflowing the conversion.
inline std::int64_t latticeIndex(double floorX)
{
    constexpr double LIMIT = 4611686018427387904.0; // 2^62
    if (std::abs(floorX) < LIMIT) return std::int64_t(floorX);
    return floorX > 0.0 ? std::int64_t(LIMIT) : -std::int64_t(LIMIT); // also NaN: no UB
}

/// Perlin's quintic fade 6t^5 - 15t^4 + 10t^3: C2, zero slope at 0 and 1.
inline double fade(double t)
{
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

inline double lerp(double a, double b, double t)
{
    return a + t * (b - a);
}

/// Uniform index in [0, n) from the top 32 bits of a hash (multiply-shift,
/// no modulo bias worth speaking of and no division).
inline unsigned pick(std::uint64_t h, unsigned n)
{
    return unsigned(((h >> 32) * std::uint64_t(n)) >> 32);
}

/// Gradient noise from an already hashed seed (see gradientNoise()).
double noise3(std::uint64_t hashedSeed, const glm::dvec3& p);
double noise2(std::uint64_t hashedSeed, const glm::dvec2& p);

/// noise2 over the rectangle [lo, hi], which must lie in one lattice cell
/// (floor(lo) == floor(hi) per axis): returns noise2 at its centre c and
/// sets `spread` to a bound of |noise2(p) − noise2(c)| for every p in it
/// (mean value form with an interval enclosure of the gradient; the proof
/// is in Noise.cpp). With `gradient`, the enclosure itself too: gradient[a]
/// holds ∂noise2/∂a at every point of the rectangle.
double noise2Spread(std::uint64_t hashedSeed, const glm::dvec2& lo, const glm::dvec2& hi, double& spread,
                    Interval* gradient = nullptr);
/// noise2Spread for version 2's 2D gradient noise with the 32-bit seed
/// (NoiseLanes32.cpp; the fractions rounded to float are held too).
double noise2SpreadVersion2(std::uint32_t seed, const glm::dvec2& lo, const glm::dvec2& hi, double& spread,
                            Interval* gradient = nullptr);

/// noise3 over the box [lo, hi] in one lattice cell, as noise2Spread (the
/// 3D mean value form; proof in Noise.cpp), and its version-2 form.
double noise3Spread(std::uint64_t hashedSeed, const glm::dvec3& lo, const glm::dvec3& hi, double& spread,
                    Interval* gradient = nullptr);
double noise3SpreadVersion2(std::uint32_t seed, const glm::dvec3& lo, const glm::dvec3& hi, double& spread,
                            Interval* gradient = nullptr);

/// Version 2's lattice hash, one corner at a time (NoiseLanes32.cpp does it
/// in lanes, with these constants): the term of cell index i on axis a is
/// T(i) = lo·P_a ^ hi·Q_a of its 32-bit words, a corner's hash
/// lowbias32(seed ^ T(i) ^ T(j) ^ T(k)).
namespace hash32 {

inline constexpr std::uint32_t LOW_PRIME[3] = {0x9E3779B1u, 0x85EBCA77u, 0xC2B2AE3Du};
inline constexpr std::uint32_t HIGH_PRIME[3] = {0x27D4EB2Fu, 0x165667B1u, 0xD3A2646Du};

inline std::uint32_t term(std::int64_t i, int axis)
{
    const std::uint64_t u = std::uint64_t(i);
    return (std::uint32_t(u) * LOW_PRIME[axis]) ^ (std::uint32_t(u >> 32) * HIGH_PRIME[axis]);
}

inline std::uint32_t corner(std::uint32_t seed, std::uint32_t tx, std::uint32_t ty, std::uint32_t tz)
{
    return strata::detail::lowbias32(seed ^ tx ^ ty ^ tz);
}

/// The 2D gradient the top 3 bits of a corner's hash pick: bit 31 a
/// diagonal (±√½, ±√½; bit 29 the sign of x, bit 30 of y), else an axis
/// (bit 30: y, else x; bit 29 its sign).
inline void gradient2(std::uint32_t h, double* g)
{
    constexpr double DIAG = 0.70710678118654752440;
    const double sx = (h & 0x20000000u) ? -1.0 : 1.0, sy = (h & 0x40000000u) ? -1.0 : 1.0;
    if (h & 0x80000000u) {
        g[0] = sx * DIAG;
        g[1] = sy * DIAG;
    } else if (h & 0x40000000u) {
        g[0] = 0.0;
        g[1] = sx;
    } else {
        g[0] = sx;
        g[1] = 0.0;
    }
}

/// The 3D gradient the top 4 bits of a corner's hash pick, as the lanes'
/// gradientDot3 (improved Perlin noise's 12 edge directions, 4 repeated):
/// g·p = ±u ± v with u = x below 8, else y; v = y below 4, z from 4 (x at
/// 12 and 14); bit 28 the sign of u, bit 29 of v.
inline void gradient3(std::uint32_t h, double* g)
{
    const unsigned index = h >> 28;
    const int u = index < 8 ? 0 : 1;
    const int v = index < 4 ? 1 : ((index | 2u) == 14u ? 0 : 2);
    g[0] = g[1] = g[2] = 0.0;
    g[u] += (h & 0x10000000u) ? -1.0 : 1.0;
    g[v] += (h & 0x20000000u) ? -1.0 : 1.0;
}

} // namespace hash32

} // namespace strata::terrain::detail
