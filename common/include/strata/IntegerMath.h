// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Integer helpers every library shares (lattices, tiles, blocks), and the
/// one way a double becomes an integer.

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace strata {

/// ⌊a / b⌋ for b > 0, rounding toward −∞ (C++'s `/` rounds toward zero):
/// the index of the block of size b that holds a, negative a included.
inline std::int64_t floorDiv(std::int64_t a, std::int64_t b)
{
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

/// x rounded toward zero and clamped to I's range; NaN gives 0. The one
/// float→integer conversion of the libraries (issue 39): C++ leaves the
/// conversion of NaN and of a value outside the target's range undefined,
/// and gcc and clang (and x86 and ARM) resolve it differently (x86 gives
/// the "integer indefinite" 0x80…0, ARM saturates, an optimizer may assume
/// it never happens), so an absurd user value would give different bytes,
/// or none. For x in range it is exactly `I(x)`. Constant time.
template <class I>
constexpr I clampToInt(double x) noexcept
{
    static_assert(std::is_integral_v<I> && !std::is_same_v<I, bool>, "clampToInt converts to an integer type");
    using Limits = std::numeric_limits<I>;
    // 2^digits, one above I's max: exact as a double, unlike max itself
    // (double(INT64_MAX) rounds up to 2^63, which would not fit).
    constexpr double above = [] {
        double p = 1.0;
        for (int i = 0; i < Limits::digits; ++i) p *= 2.0;
        return p;
    }();
    if (x != x) return I(0);
    if (x < double(Limits::min())) return Limits::min(); // min is 0 or −2^digits: exact
    if (x >= above) return Limits::max();
    return I(x);
}

/// ⌊x⌋ as an I, clamped to I's range (NaN gives 0): see clampToInt.
template <class I>
I floorToInt(double x) noexcept
{
    return clampToInt<I>(std::floor(x));
}

/// ⌈x⌉ as an I, clamped to I's range (NaN gives 0): see clampToInt.
template <class I>
I ceilToInt(double x) noexcept
{
    return clampToInt<I>(std::ceil(x));
}

/// x rounded to the nearest integer, halves away from zero (as std::llround),
/// as an I, clamped to I's range (NaN gives 0): see clampToInt.
template <class I>
I roundToInt(double x) noexcept
{
    return clampToInt<I>(std::round(x));
}

} // namespace strata
