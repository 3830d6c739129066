// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/Noise.h>

#include <algorithm>
#include <cassert>
#include <cmath>

#include "NoiseKernels.h"

namespace strata::terrain {

namespace detail {

/// 3D gradient noise from an already hashed seed.
double noise3(std::uint64_t s, const glm::dvec3& p)
{
    const Split3 q = splitCube(p);
    GradientCell3 cell;
    gradientCell(s, q, cell);
    return gradientInCell(cell, q);
}

/// 2D gradient noise from an already hashed seed.
double noise2(std::uint64_t s, const glm::dvec2& p)
{
    const Split2 q = splitSquare(p);
    GradientCell2 cell;
    gradientCell(s, q, cell);
    return gradientInCell(cell, q);
}

namespace {

/// A closed interval and the operations the gradient enclosure needs.
struct Range
{
    double lo, hi;
};
inline Range operator+(Range a, Range b) { return {a.lo + b.lo, a.hi + b.hi}; }
inline Range operator*(Range a, Range b)
{
    const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
    return {std::min(std::min(p[0], p[1]), std::min(p[2], p[3])), std::max(std::max(p[0], p[1]), std::max(p[2], p[3]))};
}
inline Range point(double v) { return {v, v}; }
inline double magnitude(Range a) { return std::max(std::abs(a.lo), std::abs(a.hi)); }

/// fade' (t) = 30 t² (1 − t)² over [a, b] ⊂ [0, 1]: it rises on [0, 1/2]
/// and falls on [1/2, 1], so its extremes are at the ends or 1/2 (1.875).
inline Range fadeSlope(double a, double b)
{
    const auto f = [](double t) { return 30.0 * t * t * (1.0 - t) * (1.0 - t); };
    const double fa = f(a), fb = f(b);
    return {std::min(fa, fb), (a <= 0.5 && b >= 0.5) ? 1.875 : std::max(fa, fb)};
}

/// g·(x, y) + k over the rectangle: exact (affine).
inline Range affine(const double* g, double k, double xc, double yc, double hx, double hy)
{
    const double c = g[0] * xc + g[1] * yc + k, r = std::abs(g[0]) * hx + std::abs(g[1]) * hy;
    return {c - r, c + r};
}

} // namespace

namespace {

/// noise2 (either version's gradients g00, g01, g10, g11) over the rectangle
/// [x0, x1] × [y0, y1] of fractions in one cell: the value at its centre,
/// and in `spread` a bound of how far the value moves from it.
double spreadInCell(const double* g00, const double* g01, const double* g10, const double* g11, double x0, double x1,
                    double y0, double y1, double& spread, Interval* gradient)
{
    // Inside one cell, with x, y the fractions and u = fade(x), v = fade(y):
    //   n / NOISE2_SCALE = n00 + v·D0 + u·(E + v·F),
    // with the affine functions n00 = g00·(x, y), D0 = n01 − n00,
    // E = n10 − n00, F = n11 − n10 − n01 + n00 (n_ij = g_ij·((x, y) − (i, j))).
    // That is noise2's lerp(lerp(n00, n01, v), lerp(n10, n11, v), u) expanded.
    // Its partial derivatives are
    //   ∂x = g00.x + v·D0_x + u'·(E + v·F) + u·(E_x + v·F_x)
    //   ∂y = g00.y + v'·D0 + v·D0_y + u·(E_y + v'·F + v·F_y),
    // (D0_x etc. constants). Evaluating them in interval arithmetic over the
    // rectangle (u, v increasing, u', v' by fadeSlope, the affine terms
    // exact) encloses ∇n at every point of it (the inclusion property of
    // interval arithmetic). For p in the rectangle the segment from the
    // centre c to p stays in it, so by the mean value theorem
    //   |n(p) − n(c)| = |∇n(ξ)·(p − c)| <= max|∂x|·hx + max|∂y|·hy.
    const double xc = 0.5 * (x0 + x1), yc = 0.5 * (y0 + y1), hx = 0.5 * (x1 - x0), hy = 0.5 * (y1 - y0);
    const double d0[2] = {g01[0] - g00[0], g01[1] - g00[1]};
    const double e[2] = {g10[0] - g00[0], g10[1] - g00[1]};
    const double f[2] = {g11[0] - g10[0] - g01[0] + g00[0], g11[1] - g10[1] - g01[1] + g00[1]};
    const Range D0 = affine(d0, -g01[1], xc, yc, hx, hy);
    const Range E = affine(e, -g10[0], xc, yc, hx, hy);
    const Range F = affine(f, -g11[0] - g11[1] + g10[0] + g01[1], xc, yc, hx, hy);
    const Range u{fade(x0), fade(x1)}, v{fade(y0), fade(y1)};
    const Range du = fadeSlope(x0, x1), dv = fadeSlope(y0, y1);
    const Range gx = point(g00[0]) + v * point(d0[0]) + du * (E + v * F) + u * (point(e[0]) + v * point(f[0]));
    const Range gy = point(g00[1]) + dv * D0 + v * point(d0[1]) + u * (point(e[1]) + dv * F + v * point(f[1]));
    spread = NOISE2_SCALE * (magnitude(gx) * hx + magnitude(gy) * hy);
    if (gradient) {
        gradient[0] = {NOISE2_SCALE * gx.lo, NOISE2_SCALE * gx.hi};
        gradient[1] = {NOISE2_SCALE * gy.lo, NOISE2_SCALE * gy.hi};
    }

    // The centre value as noise2 computes it (grad2 with the same gradients).
    const double n00 = g00[0] * xc + g00[1] * yc;
    const double n01 = g01[0] * xc + g01[1] * (yc - 1.0);
    const double n10 = g10[0] * (xc - 1.0) + g10[1] * yc;
    const double n11 = g11[0] * (xc - 1.0) + g11[1] * (yc - 1.0);
    const double uc = fade(xc), vc = fade(yc);
    return NOISE2_SCALE * lerp(lerp(n00, n01, vc), lerp(n10, n11, vc), uc);
}

} // namespace

double noise2Spread(std::uint64_t s, const glm::dvec2& lo, const glm::dvec2& hi, double& spread, Interval* gradient)
{
    const double fx = std::floor(lo.x), fy = std::floor(lo.y);
    GradientCell2 cell;
    gradientCell(s, Split2{latticeIndex(fx), latticeIndex(fy), 0.0, 0.0}, cell);
    return spreadInCell(cell.g[0], cell.g[1], cell.g[2], cell.g[3], lo.x - fx, hi.x - fx, lo.y - fy, hi.y - fy, spread,
                        gradient);
}

double noise2SpreadVersion2(std::uint32_t seed, const glm::dvec2& lo, const glm::dvec2& hi, double& spread,
                            Interval* gradient)
{
    const double fx = std::floor(lo.x), fy = std::floor(lo.y);
    const std::int64_t ix = latticeIndex(fx), iy = latticeIndex(fy);
    // Version 2 rounds the fractions to float: spread the rectangle by that
    // rounding (half an ulp of numbers below 1) so it holds them.
    constexpr double ROUNDING = 0x1.0p-25;
    const double x0 = std::max(lo.x - fx - ROUNDING, 0.0), x1 = std::min(hi.x - fx + ROUNDING, 1.0);
    const double y0 = std::max(lo.y - fy - ROUNDING, 0.0), y1 = std::min(hi.y - fy + ROUNDING, 1.0);
    double g[4][2];
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
            const std::uint32_t h = hash32::corner(seed, hash32::term(ix + a, 0), hash32::term(iy + b, 1), 0);
            hash32::gradient2(h, g[2 * a + b]);
        }
    return spreadInCell(g[0], g[1], g[2], g[3], x0, x1, y0, y1, spread, gradient);
}

namespace {

/// An affine function of the cell fractions: c·(x, y, z) + k.
struct Affine3
{
    double c[3];
    double k;
};

/// noise3 (either version's gradients, corner (a, b, c) at index 4a + 2b + c)
/// over the box lo..hi of fractions in one cell: the value at its centre, and
/// in `spread` a bound of how far the value moves from it. The 3D analogue of
/// spreadInCell (same proof): with u, v, w the fades of x, y, z,
///   n = Σ_S (Π_{a∈S} fade_a) · T_S   over the subsets S of {x, y, z},
/// T_S = Σ_{C⊆S} (−1)^{|S|−|C|} n_C the affine finite differences of the
/// corner functions n_C = g_C·(p − C). Its partial derivative on axis j, with
/// k and l the other two axes, grouped so that each fade range is used once
/// per product (interval arithmetic is subdistributive, so this is the tighter
/// grouping):
///   ∂_j n = T_∅.c_j + f'_j·(T_j + f_k·T_jk + f_l·(T_jl + f_k·T_jkl))
///         + f_j·(T_j.c_j + f_k·T_jk.c_j + f_l·(T_jl.c_j + f_k·T_jkl.c_j))
///         + f_k·T_k.c_j + f_l·(T_l.c_j + f_k·T_kl.c_j).
/// Every T_S is exact over the box (affine), the fades are increasing and
/// fadeSlope bounds their slopes, so the ranges enclose ∇n over the box, and
/// |n(p) − n(centre)| <= Σ_j max|∂_j n|·h_j (mean value theorem).
double spreadInCell3(const double* const g[8], const double lo[3], const double hi[3], double& spread, Interval* gradient)
{
    double centre[3], half[3];
    for (int a = 0; a < 3; ++a) {
        centre[a] = 0.5 * (lo[a] + hi[a]);
        half[a] = 0.5 * (hi[a] - lo[a]);
    }
    // Corner bit of axis a in the index 4a + 2b + c: x 4, y 2, z 1.
    constexpr int BIT[3] = {4, 2, 1};
    // The corner functions, then their finite differences in place, one
    // axis at a time (T_S for S ∋ a becomes T_S − T_{S∖a}): after the three
    // passes t[S] is the alternating sum over the corners in S.
    Affine3 t[8];
    for (int corner = 0; corner < 8; ++corner) {
        double k = 0.0;
        for (int a = 0; a < 3; ++a) {
            t[corner].c[a] = g[corner][a];
            if (corner & BIT[a]) k -= g[corner][a];
        }
        t[corner].k = k;
    }
    for (int a = 0; a < 3; ++a)
        for (int set = 0; set < 8; ++set) {
            if (!(set & BIT[a])) continue;
            const Affine3& without = t[set ^ BIT[a]];
            for (int b = 0; b < 3; ++b) t[set].c[b] -= without.c[b];
            t[set].k -= without.k;
        }
    Range ranges[8]; // of each T_S over the box: exact, as T_S is affine
    for (int set = 1; set < 8; ++set) {
        double c = t[set].k, r = 0.0;
        for (int a = 0; a < 3; ++a) {
            c += t[set].c[a] * centre[a];
            r += std::abs(t[set].c[a]) * half[a];
        }
        ranges[set] = Range{c - r, c + r};
    }
    Range f[3], df[3];
    for (int a = 0; a < 3; ++a) {
        f[a] = {fade(lo[a]), fade(hi[a])};
        df[a] = fadeSlope(lo[a], hi[a]);
    }
    spread = 0.0;
    for (int j = 0; j < 3; ++j) {
        const int k = (j + 1) % 3, l = (j + 2) % 3;
        const int J = BIT[j], K = BIT[k], L = BIT[l];
        const Range inner = ranges[J] + f[k] * ranges[J | K] + f[l] * (ranges[J | L] + f[k] * ranges[J | K | L]);
        const Range own = point(t[J].c[j]) + f[k] * point(t[J | K].c[j]) +
                          f[l] * (point(t[J | L].c[j]) + f[k] * point(t[J | K | L].c[j]));
        const Range rest = f[k] * point(t[K].c[j]) + f[l] * (point(t[L].c[j]) + f[k] * point(t[K | L].c[j]));
        const Range slope = point(t[0].c[j]) + df[j] * inner + f[j] * own + rest;
        spread += magnitude(slope) * half[j];
        if (gradient) gradient[j] = {slope.lo, slope.hi};
    }

    // The centre value as noise3 computes it (the same gradients).
    const double x = centre[0], y = centre[1], z = centre[2];
    const auto dot = [&](int corner) {
        const double* gc = g[corner];
        return gc[0] * (x - double((corner >> 2) & 1)) + gc[1] * (y - double((corner >> 1) & 1)) +
               gc[2] * (z - double(corner & 1));
    };
    const double u = fade(x), v = fade(y), w = fade(z);
    const double n00 = lerp(dot(0), dot(1), w), n01 = lerp(dot(2), dot(3), w);
    const double n10 = lerp(dot(4), dot(5), w), n11 = lerp(dot(6), dot(7), w);
    return lerp(lerp(n00, n01, v), lerp(n10, n11, v), u);
}

} // namespace

double noise3Spread(std::uint64_t s, const glm::dvec3& lo, const glm::dvec3& hi, double& spread, Interval* gradient)
{
    const double fx = std::floor(lo.x), fy = std::floor(lo.y), fz = std::floor(lo.z);
    GradientCell3 cell;
    gradientCell(s, Split3{latticeIndex(fx), latticeIndex(fy), latticeIndex(fz), 0.0, 0.0, 0.0}, cell);
    const double a[3] = {lo.x - fx, lo.y - fy, lo.z - fz}, b[3] = {hi.x - fx, hi.y - fy, hi.z - fz};
    return spreadInCell3(cell.g, a, b, spread, gradient);
}

double noise3SpreadVersion2(std::uint32_t seed, const glm::dvec3& lo, const glm::dvec3& hi, double& spread,
                            Interval* gradient)
{
    const double floors[3] = {std::floor(lo.x), std::floor(lo.y), std::floor(lo.z)};
    const double los[3] = {lo.x, lo.y, lo.z}, his[3] = {hi.x, hi.y, hi.z};
    std::uint32_t terms[3][2];
    double a[3], b[3];
    for (int axis = 0; axis < 3; ++axis) {
        const std::int64_t i = latticeIndex(floors[axis]);
        terms[axis][0] = hash32::term(i, axis);
        terms[axis][1] = hash32::term(i + 1, axis);
        // Version 2 rounds the fractions to float: spread the box by that
        // rounding (half an ulp of numbers below 1) so it holds them.
        constexpr double ROUNDING = 0x1.0p-25;
        a[axis] = std::max(los[axis] - floors[axis] - ROUNDING, 0.0);
        b[axis] = std::min(his[axis] - floors[axis] + ROUNDING, 1.0);
    }
    double gradients[8][3];
    const double* g[8];
    for (int corner = 0; corner < 8; ++corner) {
        const std::uint32_t h =
            hash32::corner(seed, terms[0][corner >> 2], terms[1][(corner >> 1) & 1], terms[2][corner & 1]);
        hash32::gradient3(h, gradients[corner]);
        g[corner] = gradients[corner];
    }
    return spreadInCell3(g, a, b, spread, gradient);
}

} // namespace detail

using namespace detail;

std::uint64_t deriveSeed(std::uint64_t seed, std::uint64_t stream)
{
    return mix64(seedHash(seed) ^ mix64(stream + 0xd1b54a32d192ed03ULL));
}

float gradientNoise(std::uint64_t seed, const glm::dvec3& p)
{
    return float(noise3(seedHash(seed), p));
}

float gradientNoise(std::uint64_t seed, const glm::dvec2& p)
{
    return float(noise2(seedHash(seed), p));
}

Fbm::Fbm(std::uint64_t seed, const FbmOptions& options)
    : mOptions(options)
{
    assert(options.octaves >= 1 && options.octaves <= MAX_OCTAVES);
    mCount = std::clamp(options.octaves, 1, MAX_OCTAVES);
    double norm = 0.0, amplitude = 1.0, frequency = 1.0;
    for (int i = 0; i < mCount; ++i) {
        Octave& o = mOctaves[i];
        // Each octave gets its own seed and a random offset of its input,
        // so that the octaves are independent and do not all vanish on the
        // integer lattice (with lacunarity 2 every octave's lattice holds
        // the first one's).
        const std::uint64_t octaveSeed = deriveSeed(seed, std::uint64_t(i));
        o.hashedSeed = seedHash(octaveSeed);
        std::uint64_t h = octaveSeed;
        for (double& c : o.offset) {
            h = mix64(h + 0x9e3779b97f4a7c15ULL);
            c = double(h >> 11) * 0x1.0p-53; // [0, 1)
        }
        o.frequency = frequency;
        o.weight = amplitude;
        norm += amplitude;
        amplitude *= options.gain;
        frequency *= options.lacunarity;
    }
    for (int i = 0; i < mCount; ++i) mOctaves[i].weight /= norm;
}

float Fbm::operator()(const glm::dvec3& p) const
{
    double sum = 0.0;
    for (int i = 0; i < mCount; ++i) {
        const Octave& o = mOctaves[i];
        sum += o.weight * noise3(o.hashedSeed, p * o.frequency + glm::dvec3(o.offset[0], o.offset[1], o.offset[2]));
    }
    return float(sum);
}

float Fbm::operator()(const glm::dvec2& p) const
{
    double sum = 0.0;
    for (int i = 0; i < mCount; ++i) {
        const Octave& o = mOctaves[i];
        sum += o.weight * noise2(o.hashedSeed, p * o.frequency + glm::dvec2(o.offset[0], o.offset[1]));
    }
    return float(sum);
}

float fbm(std::uint64_t seed, const glm::dvec3& p, const FbmOptions& options)
{
    return Fbm(seed, options)(p);
}

float fbm(std::uint64_t seed, const glm::dvec2& p, const FbmOptions& options)
{
    return Fbm(seed, options)(p);
}

double fbmGradientBound(const FbmOptions& options, double noiseLipschitz)
{
    // Octave i is amplitude_i * noise(frequency_i * p): its gradient is at
    // most amplitude_i * frequency_i * noiseLipschitz.
    double bound = 0.0, norm = 0.0, amplitude = 1.0, frequency = 1.0;
    for (int i = 0; i < options.octaves; ++i) {
        bound += std::abs(amplitude) * frequency;
        norm += amplitude;
        amplitude *= options.gain;
        frequency *= options.lacunarity;
    }
    return norm > 0.0 ? noiseLipschitz * bound / norm : 0.0;
}

} // namespace strata::terrain
