// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Internal: the integer hashing and interpolation helpers shared by the noise
/// sources (not installed).

#include <strata/detail/IntegerHash.h>

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
/// is in Noise.cpp).
double noise2Spread(std::uint64_t hashedSeed, const glm::dvec2& lo, const glm::dvec2& hi, double& spread);

} // namespace strata::terrain::detail
