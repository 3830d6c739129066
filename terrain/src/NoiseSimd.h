// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Internal: the two vector halves of block noise evaluation (NoiseBlock.cpp),
/// in SIMD lanes through Google Highway, dispatched at run time to the best
/// instruction set the CPU has (NoiseSimd.cpp):
///   1. splitting points into their lattice cells and fractions, as
///      splitCube() and splitSimplex() do;
///   2. the arithmetic inside a cell (NoiseKernels.h's *InCell functions) for
///      runs of consecutive points that share one cell, the cell's data
///      broadcast to every lane.
/// Hashing the cells (64-bit multiplies, once per cell) is scalar between
/// the two, or in lanes where 64-bit lanes multiply natively (AVX-512):
/// cellDataLanes() for runs' cells, hashedLanes() where each point has a
/// cell of its own. Every lane performs the scalar code's operations in its order,
/// unfused (-ffp-contract=off; no MulAdd), and Floor and Sqrt are exact, so
/// every target gives the scalar path's bits.

#include <strata/terrain/FractalNoise.h>

#include <cstddef>
#include <cstdint>

namespace strata::terrain::detail {

/// Points in structure-of-arrays form, split: the floor of each (skewed)
/// coordinate (the cell, still as a double) and the offset in the cell.
struct SplitPoints
{
    double *cellX, *cellY, *cellZ; ///< cellZ unused in 2D
    double *x, *y, *z;             ///< z unused in 2D
};

enum class Lattice
{
    CUBE,   ///< splitCube() / splitSquare()
    SIMPLEX ///< splitSimplex()
};

/// Splits n points; z == nullptr splits 2D points.
void splitPoints(Lattice lattice, const double* x, const double* y, const double* z, std::size_t n,
                 const SplitPoints& out);

/// Runs of consecutive points in one cell: run r is the points
/// [end[r − 1], end[r]) (from 0 for r = 0), its cell's data at cells + r·size.
struct CellRuns
{
    const std::uint32_t* end;
    std::size_t count;
    const double* cells;
};

/// What a cell's data is, and the arithmetic inside it.
enum class InCell
{
    GRADIENT3,    ///< 8 corner gradients, corner c's (x, y, z) at 3c
    VALUE3,       ///< 8 corner values
    SIMPLEX3,     ///< as GRADIENT3, for the skewed cube
    CELLULAR3_F1, ///< 27 feature points: x[27], y[27], z[27]
    CELLULAR3_F2,
    GRADIENT2, ///< 4 corner gradients, corner c's (x, y) at 2c
    VALUE2,    ///< 4 corner values
    SIMPLEX2,  ///< as GRADIENT2
    CELLULAR2_F1, ///< 9 feature points: x[9], y[9]
    CELLULAR2_F2,
};

/// Doubles of cell data per run for `kind`.
std::size_t cellSize(InCell kind);

/// The noise value (before the fractal shape) at every point of the runs,
/// from the split offsets x, y (and z in 3D).
void evaluateRuns(InCell kind, const CellRuns& runs, const double* x, const double* y, const double* z,
                  double* out);

/// The bases hashedLanes() evaluates.
enum class LaneBasis
{
    GRADIENT,
    VALUE,
    SIMPLEX, ///< on points split on the simplex lattice
    CELLULAR_F1,
    CELLULAR_F2,
};

/// Gradient, value, simplex or cellular noise (3D, or 2D when !threeD;
/// before the fractal shape) at n split points, each
/// lane hashing its own point's cell: for points that seldom share a cell.
void hashedLanes(LaneBasis basis, std::uint64_t seed, const SplitPoints& split, std::size_t n, bool threeD,
                 double* out);

/// The data of `count` cells (NoiseSimd.h's layouts, cellSize(kind) doubles
/// each, cell r at out + r·size) from their floors, hashed in lanes, the
/// same values as NoiseKernels.h's cell functions. Gradient, simplex and
/// value kinds only (not cellular).
void cellDataLanes(InCell kind, std::uint64_t seed, const double* cellX, const double* cellY, const double* cellZ,
                   std::size_t count, double* out);

/// Whether the target in use multiplies 64-bit lanes natively (AVX-512),
/// which makes hashedLanes() the faster path where runs are short.
bool nativeLaneHashing();

/// The index of the target in use (useSimdTarget()) into the HWY_EXPORT
/// tables, for the other files of SIMD noise to dispatch to the same target.
std::size_t noiseTargetIndex();

// ---- version 2 (NoiseLanes32.cpp) ----------------------------------------------

/// One octave of a version-2 fractal sum: the point at p·frequency +
/// offset, its basis hashed with `seed`, shaped, times `weight`.
struct OctaveLanes32
{
    std::uint32_t seed;
    float weight;
    double frequency;
    double offset[3];
};

struct FractalLanes32
{
    NoiseType type;
    FractalType fractal;
    const OctaveLanes32* octaves;
    int count;
};

/// Version 2's fractal sum at n points (noise units before the octaves'
/// frequencies; z == nullptr: 2D): per octave, each point split in double
/// lanes into its cell (as the two 32-bit words of latticeIndex()'s int64)
/// and its offset (rounded to float), the basis in float lanes with the cell
/// hashed in 32-bit lanes, the shaped values summed in float. A point's
/// value depends on it alone (not its lane or batch), and is the same bits
/// on every target.
void fractalLanes32(const FractalLanes32& sum, const double* x, const double* y, const double* z, std::size_t n,
                    double* out);

/// Version 2's basis (before a fractal shape) at n points in noise units,
/// from a hashed seed (its high word is the 32-bit seed): fractalLanes32
/// with one octave of frequency 1, offset 0 and weight 1.
void basisVersion2(NoiseType type, std::uint64_t hashedSeed, const double* x, const double* y, const double* z,
                   std::size_t n, double* out);

} // namespace strata::terrain::detail
