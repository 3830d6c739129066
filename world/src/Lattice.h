// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: the lattice every part of the world samples, and integer helpers.

#include <strata/IntegerMath.h>
#include <strata/terrain/DensityField.h>

#include <openvdb/openvdb.h>

#include <array>
#include <cstdint>

namespace strata::world::detail {

/// Levels of a chunk's 7 lower neighbours relative to its own (−1 finer,
/// 0 same or absent, +1 coarser), indexed by a mask whose bit a means "offset
/// −1 along axis a"; entry 0 (the chunk itself) is always 0.
using Signature = std::array<std::int8_t, 8>;

/// The procedural value of lattice point `c` (voxel coordinates). Every part
/// of the world evaluates samples through this one expression, so the same
/// point gives the same float everywhere.
inline float baseSample(const terrain::DensityField& field, std::int64_t x, std::int64_t y, std::int64_t z,
                        double voxelSize)
{
    return float(field.density(glm::dvec3(double(x) * voxelSize, double(y) * voxelSize, double(z) * voxelSize)));
}

} // namespace strata::world::detail
