// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// How close a narrow-band level set is to a true signed distance.

#include <openvdb/openvdb.h>

#include <cstdint>

namespace strata::terrain {

struct SdfQuality
{
    double meanError = 0.0;    ///< mean of | |∇φ| − 1 | over the measured voxels
    double maxError = 0.0;     ///< its maximum
    double meanGradient = 0.0; ///< mean |∇φ| (below 1: distances underestimated)
    std::uint64_t voxels = 0;  ///< measured voxels
};

/// Measures | |∇φ| − 1 | with central differences (world units) at every
/// active voxel whose six neighbours are active too and whose |φ| is below
/// `bandFraction` of the background (the inner band, away from the clamped
/// edge). Creases of CSG and the region box cut add a few large errors
/// (they show in maxError). Serial and deterministic; O(active voxels).
SdfQuality measureSdfQuality(const openvdb::FloatGrid& grid, double bandFraction = 0.67);

} // namespace strata::terrain
