// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/FractalNoise.h>

#include "ShowValue.h"

#include <strata/Error.h>

#include "NoiseKernels.h"
#include "NoiseSimd.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace strata::terrain {

namespace {

using namespace detail;

inline double unit(std::uint64_t h) { return unitInterval(h); }

double value3(std::uint64_t s, const glm::dvec3& p)
{
    const Split3 q = splitCube(p);
    ValueCell3 cell;
    valueCell(s, q, cell);
    return valueInCell(cell, q);
}

double value2(std::uint64_t s, const glm::dvec2& p)
{
    const Split2 q = splitSquare(p);
    ValueCell2 cell;
    valueCell(s, q, cell);
    return valueInCell(cell, q);
}

double simplex3(std::uint64_t s, const glm::dvec3& p)
{
    const Split3 q = splitSimplex(p);
    GradientCell3 cell;
    simplexCell(s, q, cell);
    return simplexInCell(cell, q);
}

double simplex2(std::uint64_t s, const glm::dvec2& p)
{
    const Split2 q = splitSimplex(p);
    GradientCell2 cell;
    simplexCell(s, q, cell);
    return simplexInCell(cell, q);
}

/// max over r of |g|·t³·(8r² + t), t = R² − r²: the largest gradient of one
/// kernel t⁴·(g·d), since ∇ = −8t³(g·d)·d + t⁴·g.
double simplexKernelSlope(double gradientLength)
{
    double best = 0.0;
    for (int n = 0; n <= 20000; ++n) {
        const double r2 = KERNEL_R2 * double(n) / 20000.0, t = KERNEL_R2 - r2;
        best = std::max(best, gradientLength * t * t * t * (8.0 * r2 + t));
    }
    return best * 1.0001; // covers the grid step
}

// ---- cellular noise ------------------------------------------------------------

// Feature points lie in [JITTER_MIN, 1 − JITTER_MIN] of their cell
// (NoiseKernels.h). Proof that the 3×3×3 search then finds F1 and F2
// exactly: let p lie at distance u <= 1/2 from the nearest face of its cell.
// Its own feature is at most √3·(1 − a) away and the one across that face at
// most √((1 − a + u)² + 2(1 − a − u)²) <= √((1.5 − a)² + 2(0.5 − a)²); every
// cell outside the 3×3×3 block holds its feature at least 1 + a away. With
// a = 0.3: 1.212 and 1.233 < 1.3. In 2D: 0.990 and 1.217 < 1.3.

CellularDistances cellular3(std::uint64_t s, const glm::dvec3& p)
{
    const Split3 q = splitCube(p);
    CellularCell3 cell;
    cellularCell(s, q, cell);
    double f1, f2; // squared
    cellularInCell(cell, q, f1, f2);
    return {std::sqrt(f1), std::sqrt(f2)};
}

CellularDistances cellular2(std::uint64_t s, const glm::dvec2& p)
{
    const Split2 q = splitSquare(p);
    CellularCell2 cell;
    cellularCell(s, q, cell);
    double f1, f2;
    cellularInCell(cell, q, f1, f2);
    return {std::sqrt(f1), std::sqrt(f2)};
}

using detail::show;

} // namespace

float valueNoise(std::uint64_t seed, const glm::dvec3& p) { return float(value3(seedHash(seed), p)); }
float valueNoise(std::uint64_t seed, const glm::dvec2& p) { return float(value2(seedHash(seed), p)); }
float simplexNoise(std::uint64_t seed, const glm::dvec3& p) { return float(simplex3(seedHash(seed), p)); }
float simplexNoise(std::uint64_t seed, const glm::dvec2& p) { return float(simplex2(seedHash(seed), p)); }
CellularDistances cellularNoise(std::uint64_t seed, const glm::dvec3& p) { return cellular3(seedHash(seed), p); }
CellularDistances cellularNoise(std::uint64_t seed, const glm::dvec2& p) { return cellular2(seedHash(seed), p); }

double simplexNoiseLipschitz(int dimensions)
{
    static const double bound3 = 4.0 * SIMPLEX3_SCALE * simplexKernelSlope(std::sqrt(2.0));
    static const double bound2 = 3.0 * SIMPLEX2_SCALE * simplexKernelSlope(1.0);
    return dimensions == 2 ? bound2 : bound3;
}

bool parseNoiseType(const std::string& name, NoiseType& type)
{
    if (name == "gradient") type = NoiseType::GRADIENT;
    else if (name == "simplex") type = NoiseType::SIMPLEX;
    else if (name == "value") type = NoiseType::VALUE;
    else if (name == "cellular_f1") type = NoiseType::CELLULAR_F1;
    else if (name == "cellular_f2") type = NoiseType::CELLULAR_F2;
    else return false;
    return true;
}

bool parseFractalType(const std::string& name, FractalType& type)
{
    if (name == "fbm") type = FractalType::FBM;
    else if (name == "ridged") type = FractalType::RIDGED;
    else if (name == "billow") type = FractalType::BILLOW;
    else return false;
    return true;
}

double noiseLipschitz(NoiseType type, int dimensions)
{
    switch (type) {
    case NoiseType::GRADIENT: return dimensions == 2 ? GRADIENT_NOISE_LIPSCHITZ_2D : GRADIENT_NOISE_LIPSCHITZ;
    case NoiseType::SIMPLEX: return simplexNoiseLipschitz(dimensions);
    case NoiseType::VALUE: return dimensions == 2 ? VALUE_NOISE_LIPSCHITZ_2D : VALUE_NOISE_LIPSCHITZ;
    case NoiseType::CELLULAR_F1:
    case NoiseType::CELLULAR_F2: return 2.0;
    }
    return 0.0;
}

FractalNoise::FractalNoise(std::uint64_t seed, const FractalOptions& options)
    : mOptions(options)
{
    if (options.octaves < 1 || options.octaves > MAX_OCTAVES) {
        throw Error(ErrorKind::BadInput, "octaves = " + std::to_string(options.octaves) + " is out of range 1..24");
    }
    if (!(std::isfinite(options.lacunarity) && options.lacunarity > 0.0)) {
        throw Error(ErrorKind::BadInput, "lacunarity = " + show(options.lacunarity) + " must be a finite number > 0");
    }
    if (!(std::isfinite(options.gain) && options.gain >= 0.0)) {
        throw Error(ErrorKind::BadInput, "gain = " + show(options.gain) + " must be a finite number >= 0");
    }
    if (options.version < NOISE_VERSION_MIN || options.version > NOISE_VERSION_MAX) {
        throw Error(ErrorKind::BadInput, "noise_version = " + std::to_string(options.version) + " must be 1 or 2");
    }
    mCount = options.octaves;
    double norm = 0.0, amplitude = 1.0, frequency = 1.0;
    for (int i = 0; i < mCount; ++i) {
        Octave& o = mOctaves[i];
        const std::uint64_t octaveSeed = deriveSeed(seed, std::uint64_t(i));
        o.seed = seedHash(octaveSeed);
        std::uint64_t h = octaveSeed;
        for (double& c : o.offset) {
            h = mix64(h + 0x9e3779b97f4a7c15ULL);
            c = unit(h);
        }
        o.frequency = frequency;
        o.weight = amplitude;
        norm += amplitude;
        amplitude *= options.gain;
        frequency *= options.lacunarity;
    }
    for (int i = 0; i < mCount; ++i) mOctaves[i].weight /= norm;
}

double FractalNoise::basis(std::uint64_t s, const glm::dvec3& p) const
{
    if (mOptions.version == 2) {
        double value = 0.0;
        basisVersion2(mOptions.noise, s, &p.x, &p.y, &p.z, 1, &value);
        return value;
    }
    switch (mOptions.noise) {
    case NoiseType::GRADIENT: return noise3(s, p);
    case NoiseType::SIMPLEX: return simplex3(s, p);
    case NoiseType::VALUE: return value3(s, p);
    case NoiseType::CELLULAR_F1: return 2.0 * cellular3(s, p).f1 - 1.0;
    case NoiseType::CELLULAR_F2: return 2.0 * cellular3(s, p).f2 - 1.4;
    }
    return 0.0;
}

double FractalNoise::basis(std::uint64_t s, const glm::dvec2& p) const
{
    if (mOptions.version == 2) {
        double value = 0.0;
        basisVersion2(mOptions.noise, s, &p.x, &p.y, nullptr, 1, &value);
        return value;
    }
    switch (mOptions.noise) {
    case NoiseType::GRADIENT: return noise2(s, p);
    case NoiseType::SIMPLEX: return simplex2(s, p);
    case NoiseType::VALUE: return value2(s, p);
    case NoiseType::CELLULAR_F1: return 2.0 * cellular2(s, p).f1 - 1.0;
    case NoiseType::CELLULAR_F2: return 2.0 * cellular2(s, p).f2 - 1.4;
    }
    return 0.0;
}

double FractalNoise::shape(double n) const
{
    switch (mOptions.fractal) {
    case FractalType::FBM: return fractalShape<FractalType::FBM>(n);
    case FractalType::RIDGED: return fractalShape<FractalType::RIDGED>(n);
    case FractalType::BILLOW: return fractalShape<FractalType::BILLOW>(n);
    }
    return n;
}

double FractalNoise::operator()(const glm::dvec3& p) const
{
    if (mOptions.version == 2) {
        double sum = 0.0;
        evaluateVersion2(&p.x, &p.y, &p.z, 1, &sum);
        return sum;
    }
    double sum = 0.0;
    for (int i = 0; i < mCount; ++i) {
        const Octave& o = mOctaves[i];
        const glm::dvec3 q = p * o.frequency + glm::dvec3(o.offset[0], o.offset[1], o.offset[2]);
        sum += o.weight * shape(basis(o.seed, q));
    }
    return sum;
}

double FractalNoise::operator()(const glm::dvec2& p) const
{
    if (mOptions.version == 2) {
        double sum = 0.0;
        evaluateVersion2(&p.x, &p.y, nullptr, 1, &sum);
        return sum;
    }
    double sum = 0.0;
    for (int i = 0; i < mCount; ++i) {
        const Octave& o = mOctaves[i];
        const glm::dvec2 q = p * o.frequency + glm::dvec2(o.offset[0], o.offset[1]);
        sum += o.weight * shape(basis(o.seed, q));
    }
    return sum;
}

double FractalNoise::lipschitz(int dimensions) const
{
    double bound = 0.0;
    for (int i = 0; i < mCount; ++i) bound += mOctaves[i].weight * mOctaves[i].frequency;
    const double shapeSlope = mOptions.fractal == FractalType::FBM ? 1.0 : 2.0;
    return shapeSlope * noiseLipschitz(mOptions.noise, dimensions) * bound;
}

Interval basisRange(NoiseType type, int dimensions)
{
    const double halfDiagonal = 0.5 * std::sqrt(double(dimensions));
    switch (type) {
    case NoiseType::GRADIENT: {
        const double r = noiseLipschitz(type, dimensions) * halfDiagonal;
        return {-r, r};
    }
    case NoiseType::VALUE: return {-1.0, 1.0};
    case NoiseType::CELLULAR_F1: return {-1.0, 2.0 * 0.7 * 2.0 * halfDiagonal - 1.0};
    case NoiseType::SIMPLEX:
    case NoiseType::CELLULAR_F2: break;
    }
    return {-HUGE_VAL, HUGE_VAL};
}

namespace {

/// The bases are computed in double (the fraction inside the cell from the
/// unrounded floor), with rounding errors of order 1e-15 relative to the
/// lattice coordinates: below 1e-9 out to 1e6 noise units. Each octave's
/// interval is widened by far more than that, so it stays rigorous.
constexpr double BASIS_ROUNDING = 1e-6;
/// Version 2 rounds the offset in the cell to float (2^-25 absolute, times
/// the gradient bound) and does some thirty float operations on values of
/// order one (each 2^-24 relative): below 1e-5 for every basis, so 1e-4.
constexpr double BASIS_ROUNDING_V2 = 1e-4;

/// The shape of a fractal sum applied to an interval of basis values: the
/// identity (fBm), 1 − 2|n| (ridged) or 2|n| − 1 (billow), exactly.
Interval shapeInterval(FractalType fractal, double lo, double hi)
{
    if (fractal == FractalType::FBM) return {lo, hi};
    // |n| over [lo, hi]: 0 when it straddles zero, else the nearer end.
    const double absLo = (lo <= 0.0 && hi >= 0.0) ? 0.0 : std::min(std::abs(lo), std::abs(hi));
    const double absHi = std::max(std::abs(lo), std::abs(hi));
    if (fractal == FractalType::RIDGED) return {1.0 - 2.0 * absHi, 1.0 - 2.0 * absLo};
    return {2.0 * absLo - 1.0, 2.0 * absHi - 1.0};
}

} // namespace

template <class Vec>
Interval FractalNoise::boxBounds(const Vec& lo, const Vec& hi) const
{
    constexpr int D = Vec::length();
    const double slope = noiseLipschitz(mOptions.noise, D);
    const Interval range = basisRange(mOptions.noise, D);
    const Vec centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    const double radius = glm::length(half);
    const double rounding = mOptions.version == 2 ? BASIS_ROUNDING_V2 : BASIS_ROUNDING;
    // Octave by octave: each one's interval (shaped and clamped to the
    // basis' range), summed with the weights.
    Interval sum{0.0, 0.0};
    // An fBm of gradient noise is also bounded as one function: its value at
    // the centre plus its gradient's enclosure times the half extents, the
    // octaves' gradient enclosures summed first. Octaves of similar slope
    // point their gradients in unrelated directions, so the slope of the sum
    // is well below the sum of their slopes (about √octaves times): this
    // form takes that, the per-octave form cannot. Octaves whose box spans
    // cells add their reach as they are. Both forms are rigorous; the
    // result is their intersection.
    const bool asOne = mOptions.fractal == FractalType::FBM && mOptions.noise == NoiseType::GRADIENT;
    double centreSum = 0.0, reachSum = 0.0;
    Interval slopeSum[D] = {};
    for (int i = 0; i < mCount; ++i) {
        const Octave& o = mOctaves[i];
        Vec offset;
        for (int a = 0; a < D; ++a) offset[a] = o.offset[a];
        const Vec qlo = lo * o.frequency + offset, qhi = hi * o.frequency + offset;
        bool inCell = mOptions.noise == NoiseType::GRADIENT;
        for (int a = 0; a < D; ++a) inCell = inCell && std::floor(qlo[a]) == std::floor(qhi[a]);
        // The octave sees a box of half diagonal f_i·radius around its centre.
        double n = 0.0, reach = slope * o.frequency * radius;
        Interval gradient[D];
        if (inCell) {
            // Inside one lattice cell: the mean value form, usually several
            // times tighter than the gradient bound (both are rigorous).
            // (Cutting a box that crosses a cell face into pieces, each with
            // its own mean value form, evaluated 3 % fewer points on the
            // default scene and took 10 % longer: left out.)
            double spread = 0.0;
            const std::uint32_t seed32 = std::uint32_t(o.seed >> 32);
            if constexpr (D == 3) {
                n = mOptions.version == 2 ? noise3SpreadVersion2(seed32, qlo, qhi, spread, gradient)
                                          : noise3Spread(o.seed, qlo, qhi, spread, gradient);
            } else {
                n = mOptions.version == 2 ? noise2SpreadVersion2(seed32, qlo, qhi, spread, gradient)
                                          : noise2Spread(o.seed, qlo, qhi, spread, gradient);
            }
            reach = std::min(reach, spread);
        } else {
            n = basis(o.seed, centre * o.frequency + offset);
        }
        reach += rounding;
        const Interval shaped =
            shapeInterval(mOptions.fractal, std::max(n - reach, range.lo), std::min(n + reach, range.hi));
        sum.lo += o.weight * shaped.lo;
        sum.hi += o.weight * shaped.hi;
        if (!asOne) continue;
        centreSum += o.weight * n;
        if (inCell) {
            // ∂/∂p of weight·n(p·f + offset) = weight·f·∇n (weight, f >= 0).
            const double scale = o.weight * o.frequency;
            for (int a = 0; a < D; ++a) {
                slopeSum[a].lo += scale * gradient[a].lo;
                slopeSum[a].hi += scale * gradient[a].hi;
            }
            reachSum += o.weight * rounding;
        } else {
            reachSum += o.weight * reach;
        }
    }
    if (asOne) {
        double spread = reachSum;
        for (int a = 0; a < D; ++a) spread += std::max(std::abs(slopeSum[a].lo), std::abs(slopeSum[a].hi)) * half[a];
        sum.lo = std::max(sum.lo, centreSum - spread);
        sum.hi = std::min(sum.hi, centreSum + spread);
    }
    return sum;
}

Interval FractalNoise::bounds(const glm::dvec3& lo, const glm::dvec3& hi) const
{
    return boxBounds(lo, hi);
}

Interval FractalNoise::bounds(const glm::dvec2& lo, const glm::dvec2& hi) const
{
    return boxBounds(lo, hi);
}

DomainWarp::DomainWarp(std::uint64_t seed, const FractalOptions& options, double amplitude)
    : mX(deriveSeed(seed, 101), options)
    , mY(deriveSeed(seed, 102), options)
    , mZ(deriveSeed(seed, 103), options)
    , mAmplitude(amplitude)
{
}

glm::dvec3 DomainWarp::operator()(const glm::dvec3& p) const
{
    return p + mAmplitude * glm::dvec3(mX(p), mY(p), mZ(p));
}

double DomainWarp::lipschitz() const
{
    return 1.0 + std::abs(mAmplitude) * std::sqrt(3.0) * mX.lipschitz(3);
}

} // namespace strata::terrain
