// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Block evaluation of the noise bases and their fractal sums, in three
// passes per octave:
//   1. split every point into its lattice cell and its fraction (SIMD);
//   2. walk the points in order and hash a cell only when a point leaves the
//      previous point's cell (64-bit mixes, 14 to 81 per cell: scalar, or
//      eight cells at a time in lanes on AVX-512), which in a block of
//      voxels smaller than the noise's cells is rare; where it is not (runs
//      under 8 points), AVX-512 hashes each point's cell in its own lane;
//   3. the arithmetic inside the cell for each run of points sharing one,
//      the cell broadcast to every lane (SIMD).
// Passes 1 and 3 do the scalar path's operations in its order (NoiseSimd.h)
// and pass 2 calls its cell functions (NoiseKernels.h), so the bits are the
// scalar path's on every instruction set.

#include <strata/terrain/FractalNoise.h>
#include <strata/terrain/Noise.h>

#include "NoiseKernels.h"
#include "NoiseSimd.h"

#include <cmath>
#include <vector>

namespace strata::terrain {

namespace {

using namespace detail;

/// Scratch for one basis evaluation (a leaf: one per thread is safe).
struct BasisScratch
{
    std::vector<double> split;     ///< cellX, cellY, cellZ, x, y, z: n each
    std::vector<std::uint32_t> end; ///< run ends
    std::vector<double> cells;     ///< cell data, cellSize() per run
    std::vector<std::uint32_t> first; ///< each run's first point
    std::vector<double> floors;       ///< each run's cell floors: x, then y, then z
};

/// NoiseKernels.h's cell types per dimension.
template <int D>
struct Cells;
template <>
struct Cells<3>
{
    using Split = Split3;
    using Gradient = GradientCell3;
    using Value = ValueCell3;
    using Cellular = CellularCell3;
    static constexpr int CORNERS = 8, FEATURES = 27;
};
template <>
struct Cells<2>
{
    using Split = Split2;
    using Gradient = GradientCell2;
    using Value = ValueCell2;
    using Cellular = CellularCell2;
    static constexpr int CORNERS = 4, FEATURES = 9;
};

/// The cell data NoiseSimd.cpp's kernels read (NoiseSimd.h's layouts), from
/// NoiseKernels.h's cells.
template <int D>
void cellData(InCell kind, std::uint64_t s, const typename Cells<D>::Split& q, double* out)
{
    using C = Cells<D>;
    switch (kind) {
    case InCell::GRADIENT3:
    case InCell::GRADIENT2:
    case InCell::SIMPLEX3:
    case InCell::SIMPLEX2: {
        typename C::Gradient c;
        if (kind == InCell::GRADIENT3 || kind == InCell::GRADIENT2) gradientCell(s, q, c);
        else simplexCell(s, q, c);
        for (int corner = 0; corner < C::CORNERS; ++corner)
            for (int k = 0; k < D; ++k) out[D * corner + k] = c.g[corner][k];
        return;
    }
    case InCell::VALUE3:
    case InCell::VALUE2: {
        typename C::Value c;
        valueCell(s, q, c);
        for (int corner = 0; corner < C::CORNERS; ++corner) out[corner] = c.v[corner];
        return;
    }
    default: {
        typename C::Cellular c;
        cellularCell(s, q, c);
        for (int n = 0; n < C::FEATURES; ++n) {
            out[n] = c.x[n];
            out[C::FEATURES + n] = c.y[n];
            if constexpr (D == 3) out[2 * C::FEATURES + n] = c.z[n];
        }
        return;
    }
    }
}

InCell inCell3(NoiseType type)
{
    switch (type) {
    case NoiseType::GRADIENT: return InCell::GRADIENT3;
    case NoiseType::VALUE: return InCell::VALUE3;
    case NoiseType::SIMPLEX: return InCell::SIMPLEX3;
    case NoiseType::CELLULAR_F1: return InCell::CELLULAR3_F1;
    case NoiseType::CELLULAR_F2: return InCell::CELLULAR3_F2;
    }
    return InCell::GRADIENT3;
}

InCell inCell2(NoiseType type)
{
    switch (type) {
    case NoiseType::GRADIENT: return InCell::GRADIENT2;
    case NoiseType::VALUE: return InCell::VALUE2;
    case NoiseType::SIMPLEX: return InCell::SIMPLEX2;
    case NoiseType::CELLULAR_F1: return InCell::CELLULAR2_F1;
    case NoiseType::CELLULAR_F2: return InCell::CELLULAR2_F2;
    }
    return InCell::GRADIENT2;
}

/// One basis at n points: z == nullptr for 2D.
void basisAt(NoiseType type, std::uint64_t s, const double* x, const double* y, const double* z, std::size_t n,
           double* out)
{
    if (n == 0) return;
    thread_local BasisScratch scratch;
    const bool threeD = z != nullptr;
    const InCell kind = threeD ? inCell3(type) : inCell2(type);
    const std::size_t size = cellSize(kind);

    scratch.split.resize(6 * n);
    double* p = scratch.split.data();
    const SplitPoints split{p, p + n, p + 2 * n, p + 3 * n, p + 4 * n, p + 5 * n};
    splitPoints(type == NoiseType::SIMPLEX ? Lattice::SIMPLEX : Lattice::CUBE, x, y, z, n, split);

    const auto sameCell = [&](std::size_t a, std::size_t b) {
        return split.cellX[a] == split.cellX[b] && split.cellY[a] == split.cellY[b] &&
               (!threeD || split.cellZ[a] == split.cellZ[b]);
    };
    if (nativeLaneHashing()) {
        // Where 64-bit lanes multiply natively (AVX-512), points that seldom
        // share a cell (runs shorter than 8 on average: the fine octaves of a
        // sum) hash each its own cell in lanes; long runs reuse cells, which
        // is 5 % faster on the default scene (its heightfield's cells are large).
        std::size_t runs = 1;
        for (std::size_t i = 1; i < n; ++i) runs += !sameCell(i, i - 1);
        if (8 * runs > n) {
            const LaneBasis basis = type == NoiseType::VALUE         ? LaneBasis::VALUE
                                    : type == NoiseType::SIMPLEX     ? LaneBasis::SIMPLEX
                                    : type == NoiseType::CELLULAR_F1 ? LaneBasis::CELLULAR_F1
                                    : type == NoiseType::CELLULAR_F2 ? LaneBasis::CELLULAR_F2
                                                                     : LaneBasis::GRADIENT;
            hashedLanes(basis, s, split, n, threeD, out);
            return;
        }
    }

    // Pass 2. Equal floors are one cell; floors that differ but saturate to
    // one lattice index (beyond 2^62) only cost a second, identical cell.
    scratch.end.clear();
    scratch.first.clear();
    for (std::size_t i = 0; i < n; ++i) {
        if (i > 0 && sameCell(i, i - 1)) continue;
        if (i > 0) scratch.end.push_back(std::uint32_t(i));
        scratch.first.push_back(std::uint32_t(i));
    }
    scratch.end.push_back(std::uint32_t(n));
    const std::size_t count = scratch.first.size();
    scratch.cells.resize(count * size);
    const bool cellular = type == NoiseType::CELLULAR_F1 || type == NoiseType::CELLULAR_F2;
    if (!cellular && count >= 4 && nativeLaneHashing()) {
        // Cells hashed in lanes, eight at a time (fewer than four would
        // mostly hash padding: then the scalar path below).
        scratch.floors.resize(3 * count);
        double *fx = scratch.floors.data(), *fy = fx + count, *fz = fy + count;
        for (std::size_t r = 0; r < count; ++r) {
            const std::uint32_t i = scratch.first[r];
            fx[r] = split.cellX[i];
            fy[r] = split.cellY[i];
            fz[r] = threeD ? split.cellZ[i] : 0.0;
        }
        cellDataLanes(kind, s, fx, fy, threeD ? fz : nullptr, count, scratch.cells.data());
    } else {
        for (std::size_t r = 0; r < count; ++r) {
            const std::uint32_t i = scratch.first[r];
            double* data = scratch.cells.data() + r * size;
            if (threeD) {
                const Split3 q{latticeIndex(split.cellX[i]), latticeIndex(split.cellY[i]), latticeIndex(split.cellZ[i]),
                               0, 0, 0};
                cellData<3>(kind, s, q, data);
            } else {
                const Split2 q{latticeIndex(split.cellX[i]), latticeIndex(split.cellY[i]), 0, 0};
                cellData<2>(kind, s, q, data);
            }
        }
    }
    const CellRuns runs{scratch.end.data(), scratch.end.size(), scratch.cells.data()};
    evaluateRuns(kind, runs, split.x, split.y, threeD ? split.z : nullptr, out);
}

/// A fractal sum at n points (z == nullptr: 2D) as the scalar operator()s
/// compute it: octave by octave, the basis at p·frequency + offset, through
/// `shape`, times the octave's weight, added to sum[i] from 0.
template <class Octave, class SeedOf, class Shape>
void octaveSum(NoiseType type, const Octave* octaves, int count, SeedOf seedOf, Shape shape, const double* x,
               const double* y, const double* z, std::size_t n, double* sum)
{
    // Nothing this calls uses the scratch: one per thread is safe.
    thread_local std::vector<double> scratch;
    scratch.resize(4 * n);
    double *qx = scratch.data(), *qy = qx + n, *qz = qy + n, *b = qz + n;
    for (std::size_t i = 0; i < n; ++i) sum[i] = 0.0;
    for (int octave = 0; octave < count; ++octave) {
        const Octave& o = octaves[octave];
        for (std::size_t i = 0; i < n; ++i) {
            qx[i] = x[i] * o.frequency + o.offset[0];
            qy[i] = y[i] * o.frequency + o.offset[1];
        }
        if (z) {
            for (std::size_t i = 0; i < n; ++i) qz[i] = z[i] * o.frequency + o.offset[2];
        }
        basisAt(type, seedOf(o), qx, qy, z ? qz : nullptr, n, b);
        for (std::size_t i = 0; i < n; ++i) sum[i] += o.weight * shape(b[i]);
    }
}

} // namespace

namespace {

/// octaveSum with the sum's fractal shape inlined (fractalShape<>, which
/// FractalNoise::shape() calls too: the same bits).
template <class Octave>
void fractalSum(FractalType fractal, NoiseType type, const Octave* octaves, int count, const double* x,
                const double* y, const double* z, std::size_t n, double* out)
{
    const auto seedOf = [](const Octave& o) { return o.seed; };
    switch (fractal) {
    case FractalType::FBM:
        return octaveSum(
            type, octaves, count, seedOf, [](double v) { return fractalShape<FractalType::FBM>(v); }, x, y, z, n, out);
    case FractalType::RIDGED:
        return octaveSum(
            type, octaves, count, seedOf, [](double v) { return fractalShape<FractalType::RIDGED>(v); }, x, y, z, n, out);
    case FractalType::BILLOW:
        return octaveSum(
            type, octaves, count, seedOf, [](double v) { return fractalShape<FractalType::BILLOW>(v); }, x, y, z, n, out);
    }
}

} // namespace

void FractalNoise::evaluate(const double* x, const double* y, const double* z, std::size_t n, double* out) const
{
    if (mOptions.version == 2) return evaluateVersion2(x, y, z, n, out);
    fractalSum(mOptions.fractal, mOptions.noise, mOctaves, mCount, x, y, z, n, out);
}

void FractalNoise::evaluate(const double* x, const double* y, std::size_t n, double* out) const
{
    if (mOptions.version == 2) return evaluateVersion2(x, y, nullptr, n, out);
    fractalSum(mOptions.fractal, mOptions.noise, mOctaves, mCount, x, y, nullptr, n, out);
}

void FractalNoise::evaluateVersion2(const double* x, const double* y, const double* z, std::size_t n,
                                    double* out) const
{
    OctaveLanes32 octaves[MAX_OCTAVES];
    for (int i = 0; i < mCount; ++i) {
        const Octave& o = mOctaves[i];
        octaves[i] = {std::uint32_t(o.seed >> 32), float(o.weight), o.frequency, {o.offset[0], o.offset[1], o.offset[2]}};
    }
    fractalLanes32({mOptions.noise, mOptions.fractal, octaves, mCount}, x, y, z, n, out);
}

void Fbm::evaluate(const double* x, const double* y, const double* z, std::size_t n, float* out) const
{
    thread_local std::vector<double> sum;
    sum.resize(n);
    octaveSum(
        NoiseType::GRADIENT, mOctaves, mCount, [](const Octave& o) { return o.hashedSeed; },
        [](double v) { return v; }, x, y, z, n, sum.data());
    for (std::size_t i = 0; i < n; ++i) out[i] = float(sum[i]);
}

void Fbm::evaluate(const double* x, const double* y, std::size_t n, float* out) const
{
    thread_local std::vector<double> sum;
    sum.resize(n);
    octaveSum(
        NoiseType::GRADIENT, mOctaves, mCount, [](const Octave& o) { return o.hashedSeed; },
        [](double v) { return v; }, x, y, nullptr, n, sum.data());
    for (std::size_t i = 0; i < n; ++i) out[i] = float(sum[i]);
}

} // namespace strata::terrain
