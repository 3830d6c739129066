// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// floorDiv, and clampToInt / floorToInt / ceilToInt / roundToInt: the one float→integer
// conversion (issue 39), defined for NaN, infinities and values out of the
// target's range, and the plain conversion for values in it.

#include <strata/IntegerMath.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace {

using strata::ceilToInt;
using strata::clampToInt;
using strata::floorToInt;
using strata::roundToInt;

template <class I>
constexpr I lowest()
{
    return std::numeric_limits<I>::min();
}
template <class I>
constexpr I highest()
{
    return std::numeric_limits<I>::max();
}

TEST(IntegerMath, FloorDivRoundsTowardMinusInfinity)
{
    EXPECT_EQ(strata::floorDiv(7, 2), 3);
    EXPECT_EQ(strata::floorDiv(-7, 2), -4);
    EXPECT_EQ(strata::floorDiv(-8, 2), -4);
    EXPECT_EQ(strata::floorDiv(0, 5), 0);
    EXPECT_EQ(strata::floorDiv(-1, 5), -1);
}

TEST(IntegerMath, ClampToIntGivesZeroForNaNAndTheBoundsForInfinities)
{
    EXPECT_EQ(clampToInt<int>(NAN), 0);
    EXPECT_EQ(clampToInt<std::int64_t>(-NAN), 0);
    EXPECT_EQ(clampToInt<std::uint64_t>(NAN), 0u);
    EXPECT_EQ(clampToInt<int>(HUGE_VAL), highest<int>());
    EXPECT_EQ(clampToInt<int>(-HUGE_VAL), lowest<int>());
    EXPECT_EQ(clampToInt<std::int64_t>(HUGE_VAL), highest<std::int64_t>());
    EXPECT_EQ(clampToInt<std::int64_t>(-HUGE_VAL), lowest<std::int64_t>());
    EXPECT_EQ(clampToInt<std::size_t>(HUGE_VAL), highest<std::size_t>());
    EXPECT_EQ(clampToInt<std::size_t>(-HUGE_VAL), 0u);
    EXPECT_EQ(clampToInt<int>(1e300), highest<int>());
    EXPECT_EQ(clampToInt<int>(-1e300), lowest<int>());
    EXPECT_EQ(clampToInt<std::int64_t>(1e300), highest<std::int64_t>());
    EXPECT_EQ(clampToInt<std::int64_t>(-1e300), lowest<std::int64_t>());
    EXPECT_EQ(clampToInt<std::uint64_t>(1e300), highest<std::uint64_t>());
    EXPECT_EQ(floorToInt<int>(NAN), 0);
    EXPECT_EQ(ceilToInt<std::int64_t>(-HUGE_VAL), lowest<std::int64_t>());
    EXPECT_EQ(roundToInt<std::int64_t>(NAN), 0);
    EXPECT_EQ(roundToInt<std::size_t>(1e300), highest<std::size_t>());
    EXPECT_EQ(roundToInt<std::size_t>(-0.5), 0u);
}

TEST(IntegerMath, ClampToIntAtTheEdgesOfInt32)
{
    EXPECT_EQ(clampToInt<std::int32_t>(2147483647.0), 2147483647);
    EXPECT_EQ(clampToInt<std::int32_t>(2147483647.75), 2147483647); // toward zero, inside
    EXPECT_EQ(clampToInt<std::int32_t>(2147483648.0), 2147483647);  // just outside
    EXPECT_EQ(clampToInt<std::int32_t>(-2147483648.0), lowest<std::int32_t>());
    EXPECT_EQ(clampToInt<std::int32_t>(-2147483648.75), lowest<std::int32_t>());
    EXPECT_EQ(clampToInt<std::int32_t>(-2147483649.0), lowest<std::int32_t>());
    EXPECT_EQ(floorToInt<std::int32_t>(2147483646.5), 2147483646);
    EXPECT_EQ(ceilToInt<std::int32_t>(2147483646.5), 2147483647);
    EXPECT_EQ(ceilToInt<std::int32_t>(2147483647.5), 2147483647); // ⌈⌉ = 2^31: clamped
    EXPECT_EQ(floorToInt<std::int32_t>(-2147483648.5), lowest<std::int32_t>());
}

TEST(IntegerMath, ClampToIntAtTheEdgesOfInt64AndUint64)
{
    // double(INT64_MAX) rounds up to 2^63, which does not fit.
    constexpr double TWO_63 = 9223372036854775808.0, TWO_64 = 18446744073709551616.0;
    EXPECT_EQ(clampToInt<std::int64_t>(TWO_63), highest<std::int64_t>());
    EXPECT_EQ(clampToInt<std::int64_t>(double(highest<std::int64_t>())), highest<std::int64_t>());
    EXPECT_EQ(clampToInt<std::int64_t>(std::nextafter(TWO_63, 0.0)), std::int64_t(9223372036854774784)); // 2^63 − 1024
    EXPECT_EQ(clampToInt<std::int64_t>(-TWO_63), lowest<std::int64_t>());
    EXPECT_EQ(clampToInt<std::int64_t>(std::nextafter(-TWO_63, -HUGE_VAL)), lowest<std::int64_t>());
    EXPECT_EQ(clampToInt<std::uint64_t>(TWO_64), highest<std::uint64_t>());
    EXPECT_EQ(clampToInt<std::uint64_t>(TWO_63), std::uint64_t(1) << 63);
    // The largest double below 2^64 is 2^64 − 2048.
    EXPECT_EQ(clampToInt<std::uint64_t>(std::nextafter(TWO_64, 0.0)), std::uint64_t(18446744073709549568u));
    EXPECT_EQ(clampToInt<std::size_t>(TWO_64), highest<std::size_t>());
    EXPECT_EQ(ceilToInt<std::size_t>(std::nextafter(TWO_64, 0.0)), std::size_t(18446744073709549568u));
}

TEST(IntegerMath, NegativeValuesToUnsignedGiveZero)
{
    EXPECT_EQ(clampToInt<std::size_t>(-1.0), 0u);
    EXPECT_EQ(clampToInt<std::size_t>(-0.75), 0u); // toward zero: 0, as the plain conversion
    EXPECT_EQ(clampToInt<std::uint64_t>(-1e300), 0u);
    EXPECT_EQ(clampToInt<unsigned>(-5.0), 0u);
    EXPECT_EQ(floorToInt<std::size_t>(-0.25), 0u);
    EXPECT_EQ(ceilToInt<std::size_t>(-0.25), 0u);
    EXPECT_EQ(clampToInt<unsigned>(4294967296.0), highest<unsigned>());
    EXPECT_EQ(clampToInt<unsigned>(4294967295.5), highest<unsigned>());
}

TEST(IntegerMath, OrdinaryValuesConvertAsThePlainConversion)
{
    for (const double x : {0.0, -0.0, 0.25, -0.25, 0.5, -0.5, 0.999, -0.999, 1.0, -1.0, 2.5, -2.5, 1e6 + 0.5,
                           -1e6 - 0.5, 123456789.9, -123456789.9}) {
        EXPECT_EQ(clampToInt<int>(x), int(x)) << x;
        EXPECT_EQ(clampToInt<std::int64_t>(x), std::int64_t(x)) << x;
        EXPECT_EQ(floorToInt<int>(x), int(std::floor(x))) << x;
        EXPECT_EQ(ceilToInt<int>(x), int(std::ceil(x))) << x;
        EXPECT_EQ(floorToInt<std::int64_t>(x), std::int64_t(std::floor(x))) << x;
        EXPECT_EQ(ceilToInt<std::int64_t>(x), std::int64_t(std::ceil(x))) << x;
        EXPECT_EQ(roundToInt<std::int64_t>(x), std::llround(x)) << x; // halves away from zero
        if (x > -1.0) {
            EXPECT_EQ(clampToInt<std::size_t>(x), std::size_t(x)) << x;
        }
    }
    EXPECT_EQ(clampToInt<std::int64_t>(4503599627370497.0), 4503599627370497); // 2^52 + 1: exact
    EXPECT_EQ(clampToInt<std::int64_t>(-4503599627370497.0), -4503599627370497);
    static_assert(clampToInt<int>(-3.75) == -3, "a constant expression");
    static_assert(clampToInt<std::uint8_t>(300.0) == 255 && clampToInt<std::int8_t>(-300.0) == -128);
}

} // namespace
