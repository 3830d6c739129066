// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Small helpers shared by the terrain measurement tests (surface roughness,
// slope distribution, surface texture, height spectrum, overhang fraction,
// landform statistics): row-major grid indexing, a tilted plane, and the
// message of the strata::Error a call throws.

#include <strata/Error.h>

#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <vector>

namespace strata::test {

/// The index of cell (x, z) in a row-major grid `width` cells wide.
inline std::size_t at(int width, int x, int z)
{
    return std::size_t(z) * std::size_t(width) + std::size_t(x);
}

/// A width × height row-major grid of the plane base + perX·x + perZ·z
/// (x, z in cells).
inline std::vector<double> tiltedPlane(int width, int height, double base, double perX, double perZ)
{
    std::vector<double> heights(std::size_t(width) * std::size_t(height));
    for (int z = 0; z < height; ++z)
        for (int x = 0; x < width; ++x) heights[at(width, x, z)] = base + perX * x + perZ * z;
    return heights;
}

/// Calls f() and returns the message of the strata::Error it throws; when
/// it throws none, records a test failure and returns "".
template <class F> std::string errorOf(F f)
{
    try {
        f();
    } catch (const strata::Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "no strata::Error";
    return "";
}

} // namespace strata::test
