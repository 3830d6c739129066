// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Internal: the distinct (x, z) columns of a block of points. A field that
/// depends on x and z only for part of its work (a heightfield) computes it
/// once per column: an 8³ block of voxels has 64, not 512.

#include <strata/terrain/DensityField.h>

#include <cstdint>
#include <vector>

namespace strata::terrain::detail {

struct BlockColumns
{
    std::vector<std::uint32_t> of; ///< of[i]: point i's column
    std::vector<double> x, z;      ///< each column's coordinates, in first-seen order
};

/// Columns by their bits (−0 and +0 are distinct: a field may tell them apart).
/// Where the first 16 points are all in distinct columns (points moved by a
/// warp), every point is taken as its own column without looking further.
void findColumns(const PointBlock& points, BlockColumns& columns);

} // namespace strata::terrain::detail
