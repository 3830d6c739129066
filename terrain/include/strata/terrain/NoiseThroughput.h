// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Measures the noise family's throughput on one core: each basis and its
/// 5-octave fBm, 3D and 2D, through the scalar path (one call per point)
/// and the block path (FractalNoise::evaluate on 8³ blocks of voxels) with
/// and without SIMD, on the same points. Backs `strata bench noise`; numbers only, no verdict.

#include <strata/terrain/FractalNoise.h>

#include <string>
#include <vector>

namespace strata::terrain {

struct NoiseThroughputOptions
{
    /// Voxel spacing in noise units (1/16: sixteen voxels per lattice cell
    /// of the first octave, as 0.5 m voxels under an 8 m wavelength).
    double spacing = 1.0 / 16.0;
    /// Processor seconds spent per measurement (the best of a few runs).
    double seconds = 0.3;
};

struct NoiseThroughput
{
    std::string name;       ///< "gradient", "gradient fBm 5", ...
    int dimensions = 3;     ///< 3 or 2
    double scalarRate = 0;  ///< points per second, one core, lattice order
    double blockRate = 0;   ///< points per second, one core, same points, SIMD target in use
    double blockScalarTargetRate = 0; ///< the block path without SIMD (Highway's portable target)
    double scatteredRate = 0; ///< scalar path, points scattered over 64 cells
};

/// Every basis alone and as 5-octave fBm, 3D then 2D. Runs on the calling
/// thread; takes about 20 · 4 · options.seconds.
std::vector<NoiseThroughput> measureNoiseThroughput(const NoiseThroughputOptions& options = {});

} // namespace strata::terrain
