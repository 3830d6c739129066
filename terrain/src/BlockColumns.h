// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Internal: the distinct (x, z) columns of a block of points. A field that
/// depends on x and z only for part of its work (a heightfield) computes it
/// once per column: an 8³ block of voxels has 64, not 512.

#include "BlockScratch.h"

#include <strata/terrain/DensityField.h>

#include <cstdint>

namespace strata::terrain::detail {

/// Arrays taken from a ScratchFrame (valid while it lives).
struct BlockColumns
{
    std::uint32_t* of = nullptr; ///< of[i]: point i's column
    double* x = nullptr;         ///< each column's coordinates, in first-seen order
    double* z = nullptr;
    std::size_t count = 0;       ///< columns found
};

/// Columns by their bits (−0 and +0 are distinct: a field may tell them apart).
/// Where the first 16 points are all in distinct columns (points moved by a
/// warp), every point is taken as its own column without looking further.
/// The arrays (room for every point) come from `scratch`.
BlockColumns findColumns(const PointBlock& points, ScratchFrame& scratch);

} // namespace strata::terrain::detail
