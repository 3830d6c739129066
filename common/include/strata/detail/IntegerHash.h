// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal (for Strata's libraries and tests): the integer hashes, one of
// each: the 64-bit mixer for noise lattices, spawn cells, task orders and
// unique file names, and the 32-bit one for the procedural textures.

#include <cstdint>

namespace strata::detail {

/// splitmix64's finaliser: a bijective 64-bit mixer with full avalanche.
/// Part of every seed's bits (the noise hashes through it): never change it.
constexpr std::uint64_t mix64(std::uint64_t h)
{
    h ^= h >> 30;
    h *= 0xbf58476d1ce4e5b9ULL;
    h ^= h >> 27;
    h *= 0x94d049bb133111ebULL;
    h ^= h >> 31;
    return h;
}

/// Chris Wellons' lowbias32: a 32-bit integer hash with low bias. Part of the
/// built-in textures' bits: never change it.
constexpr std::uint32_t lowbias32(std::uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

/// splitmix64's golden-ratio increment, the step between its outputs.
inline constexpr std::uint64_t SPLITMIX64_STEP = 0x9e3779b97f4a7c15ULL;

} // namespace strata::detail
