// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Measures the noise family's throughput on one core: each basis and its
/// 5-octave fBm, 3D and 2D, through the scalar path (one call per point)
/// and the block path (FractalNoise::evaluate on 8³ blocks of voxels) with
/// and without SIMD, noise version 1 and 2, on the same points, and
/// optionally FastNoiseLite on them too. Backs `strata bench noise`; numbers only, no verdict.

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
    /// A copy of FastNoiseLite.h (the C++ version) to measure beside the
    /// block path on the same points, compiled at run time with -O3
    /// -march=native ($CXX, else the compiler Strata was built with); empty:
    /// none. Throws Error(BadInput) naming the path if it is missing or does
    /// not compile.
    std::string fastNoiseLite;
};

struct NoiseThroughput
{
    std::string name;       ///< "gradient", "gradient fBm 5", ...
    int dimensions = 3;     ///< 3 or 2
    double scalarRate = 0;  ///< points per second, one core, lattice order
    double blockRate = 0;   ///< points per second, one core, same points, SIMD target in use
    double blockScalarTargetRate = 0; ///< the block path without SIMD (Highway's portable target)
    double scatteredRate = 0; ///< scalar path, points scattered over 64 cells
    double fastNoiseLiteRate = 0; ///< FastNoiseLite's matching basis (GetNoise per point); 0 without options.fastNoiseLite
    double version2Rate = 0;          ///< noise version 2's block path, same points, SIMD target in use
    double version2ScatteredRate = 0; ///< version 2's block path on the scattered points
};

/// Every basis alone and as 5-octave fBm, 3D then 2D. Runs on the calling
/// thread; takes about 20 · 4 · options.seconds.
std::vector<NoiseThroughput> measureNoiseThroughput(const NoiseThroughputOptions& options = {});

} // namespace strata::terrain
