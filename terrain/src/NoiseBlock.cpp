// Block evaluation of the noise bases and their fractal sums: each point is
// split into its lattice cell and its fraction as in the scalar path, and
// the cell's hashes (gradients, lattice values, feature points) are reused
// while consecutive points stay in one cell. Hashing is most of a basis'
// cost (14 to 81 64-bit mixes), and in a block of voxels smaller than the
// noise's cells most points share their neighbour's cell. The arithmetic is
// the scalar path's own (NoiseKernels.h), so the bits are the same.

#include <strata/terrain/FractalNoise.h>

#include "NoiseKernels.h"

#include <cmath>
#include <vector>

namespace strata::terrain {

namespace {

using namespace detail;

/// Runs `inCell` at every point, rebuilding the cell only when a point
/// leaves the previous point's cell.
template <class Cell, class Split, class Splitter, class MakeCell, class InCell>
void overCells(std::size_t n, double* out, Splitter split, MakeCell makeCell, InCell inCell)
{
    Cell cell{};
    Split last{};
    bool have = false;
    for (std::size_t i = 0; i < n; ++i) {
        const Split q = split(i);
        if (!have || !q.sameCell(last)) {
            makeCell(q, cell);
            last = q;
            have = true;
        }
        out[i] = inCell(cell, q);
    }
}

void basis3(NoiseType type, std::uint64_t s, const double* x, const double* y, const double* z, std::size_t n,
            double* out)
{
    const auto cube = [&](std::size_t i) { return splitCube({x[i], y[i], z[i]}); };
    switch (type) {
    case NoiseType::GRADIENT:
        overCells<GradientCell3, Split3>(
            n, out, cube, [s](const Split3& q, GradientCell3& c) { gradientCell(s, q, c); },
            [](const GradientCell3& c, const Split3& q) { return gradientInCell(c, q); });
        return;
    case NoiseType::VALUE:
        overCells<ValueCell3, Split3>(
            n, out, cube, [s](const Split3& q, ValueCell3& c) { valueCell(s, q, c); },
            [](const ValueCell3& c, const Split3& q) { return valueInCell(c, q); });
        return;
    case NoiseType::SIMPLEX:
        overCells<GradientCell3, Split3>(
            n, out, [&](std::size_t i) { return splitSimplex(glm::dvec3(x[i], y[i], z[i])); },
            [s](const Split3& q, GradientCell3& c) { simplexCell(s, q, c); },
            [](const GradientCell3& c, const Split3& q) { return simplexInCell(c, q); });
        return;
    case NoiseType::CELLULAR_F1:
    case NoiseType::CELLULAR_F2: {
        const bool second = type == NoiseType::CELLULAR_F2;
        overCells<CellularCell3, Split3>(
            n, out, cube, [s](const Split3& q, CellularCell3& c) { cellularCell(s, q, c); },
            [second](const CellularCell3& c, const Split3& q) {
                double f1, f2;
                cellularInCell(c, q, f1, f2);
                return second ? 2.0 * std::sqrt(f2) - 1.4 : 2.0 * std::sqrt(f1) - 1.0;
            });
        return;
    }
    }
}

void basis2(NoiseType type, std::uint64_t s, const double* x, const double* y, std::size_t n, double* out)
{
    const auto square = [&](std::size_t i) { return splitSquare({x[i], y[i]}); };
    switch (type) {
    case NoiseType::GRADIENT:
        overCells<GradientCell2, Split2>(
            n, out, square, [s](const Split2& q, GradientCell2& c) { gradientCell(s, q, c); },
            [](const GradientCell2& c, const Split2& q) { return gradientInCell(c, q); });
        return;
    case NoiseType::VALUE:
        overCells<ValueCell2, Split2>(
            n, out, square, [s](const Split2& q, ValueCell2& c) { valueCell(s, q, c); },
            [](const ValueCell2& c, const Split2& q) { return valueInCell(c, q); });
        return;
    case NoiseType::SIMPLEX:
        overCells<GradientCell2, Split2>(
            n, out, [&](std::size_t i) { return splitSimplex(glm::dvec2(x[i], y[i])); },
            [s](const Split2& q, GradientCell2& c) { simplexCell(s, q, c); },
            [](const GradientCell2& c, const Split2& q) { return simplexInCell(c, q); });
        return;
    case NoiseType::CELLULAR_F1:
    case NoiseType::CELLULAR_F2: {
        const bool second = type == NoiseType::CELLULAR_F2;
        overCells<CellularCell2, Split2>(
            n, out, square, [s](const Split2& q, CellularCell2& c) { cellularCell(s, q, c); },
            [second](const CellularCell2& c, const Split2& q) {
                double f1, f2;
                cellularInCell(c, q, f1, f2);
                return second ? 2.0 * std::sqrt(f2) - 1.4 : 2.0 * std::sqrt(f1) - 1.0;
            });
        return;
    }
    }
}

} // namespace

void FractalNoise::evaluate(const double* x, const double* y, const double* z, std::size_t n, double* out) const
{
    // A leaf: nothing it calls uses the scratch, so one per thread is safe
    // (and saves an allocation per call).
    thread_local std::vector<double> scratch;
    scratch.resize(4 * n);
    double *qx = scratch.data(), *qy = qx + n, *qz = qy + n, *b = qz + n;
    for (std::size_t i = 0; i < n; ++i) out[i] = 0.0;
    for (int octave = 0; octave < mCount; ++octave) {
        const Octave& o = mOctaves[octave];
        // As operator(): q = p·f + offset, per component.
        for (std::size_t i = 0; i < n; ++i) {
            qx[i] = x[i] * o.frequency + o.offset[0];
            qy[i] = y[i] * o.frequency + o.offset[1];
            qz[i] = z[i] * o.frequency + o.offset[2];
        }
        basis3(mOptions.noise, o.seed, qx, qy, qz, n, b);
        for (std::size_t i = 0; i < n; ++i) out[i] += o.weight * shape(b[i]);
    }
}

void FractalNoise::evaluate(const double* x, const double* y, std::size_t n, double* out) const
{
    thread_local std::vector<double> scratch;
    scratch.resize(3 * n);
    double *qx = scratch.data(), *qy = qx + n, *b = qy + n;
    for (std::size_t i = 0; i < n; ++i) out[i] = 0.0;
    for (int octave = 0; octave < mCount; ++octave) {
        const Octave& o = mOctaves[octave];
        for (std::size_t i = 0; i < n; ++i) {
            qx[i] = x[i] * o.frequency + o.offset[0];
            qy[i] = y[i] * o.frequency + o.offset[1];
        }
        basis2(mOptions.noise, o.seed, qx, qy, n, b);
        for (std::size_t i = 0; i < n; ++i) out[i] += o.weight * shape(b[i]);
    }
}

} // namespace strata::terrain
