// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Internal: every noise basis split into its two halves,
///   - the cell: what hashing the lattice gives (gradients, values, feature
///     points), a pure function of the seed and the integer cell;
///   - the arithmetic inside the cell, from the point's position in it.
/// The scalar functions (noise3(), valueNoise()...) and the block kernels
/// (NoiseBlock.cpp) both go through these two halves, so a block that reuses
/// a cell for its next point gives the same bits as computing it afresh:
/// block evaluation is exact by construction, not by tolerance.

#include "NoiseHash.h"

#include <strata/terrain/FractalNoise.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <cstdint>

namespace strata::terrain::detail {

/// A fractal sum's shape of one octave's basis value: the identity (fBm),
/// 1 − 2|n| (ridged) or 2|n| − 1 (billow). One definition for the scalar
/// path (FractalNoise::shape) and the block path (inlined per sum).
template <FractalType F>
inline double fractalShape(double n)
{
    if constexpr (F == FractalType::RIDGED) return 1.0 - 2.0 * std::abs(n);
    else if constexpr (F == FractalType::BILLOW) return 2.0 * std::abs(n) - 1.0;
    else return n;
}

/// The 12 cube-edge directions of improved Perlin noise (length sqrt 2).
inline constexpr double GRAD3[12][3] = {
    {1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1}, {-1, 0, 1},
    {1, 0, -1}, {-1, 0, -1}, {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1},
};

/// 8 directions, 45 degrees apart, unit length.
inline constexpr double DIAG = 0.70710678118654752440;
inline constexpr double GRAD2[8][2] = {
    {1, 0}, {-1, 0}, {0, 1}, {0, -1}, {DIAG, DIAG}, {-DIAG, DIAG}, {DIAG, -DIAG}, {-DIAG, -DIAG},
};

/// Unit gradients give 2D noise a range of about ±0.7; this brings it to
/// about ±1 like the 3D noise (whose gradients have length sqrt 2).
inline constexpr double NOISE2_SCALE = 1.41421356237309504880;

inline const double* gradient3(std::uint64_t h) { return GRAD3[pick(h, 12)]; }
inline const double* gradient2(std::uint64_t h) { return GRAD2[pick(h, 8)]; }

inline double dot3(const double* g, double x, double y, double z) { return g[0] * x + g[1] * y + g[2] * z; }
inline double dot2(const double* g, double x, double y) { return g[0] * x + g[1] * y; }

/// A uniform double in [0, 1) from the top 53 bits of a hash.
inline double unitInterval(std::uint64_t h) { return double(h >> 11) * 0x1.0p-53; }

/// A point split into its integer lattice cell and its fraction in it
/// (from the unrounded floor: exact, and precise far from the origin).
struct Split3
{
    std::int64_t i, j, k;
    double x, y, z;
    bool sameCell(const Split3& o) const { return i == o.i && j == o.j && k == o.k; }
};
struct Split2
{
    std::int64_t i, j;
    double x, y;
    bool sameCell(const Split2& o) const { return i == o.i && j == o.j; }
};

inline Split3 splitCube(const glm::dvec3& p)
{
    const double fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
    return {latticeIndex(fx), latticeIndex(fy), latticeIndex(fz), p.x - fx, p.y - fy, p.z - fz};
}
inline Split2 splitSquare(const glm::dvec2& p)
{
    const double fx = std::floor(p.x), fy = std::floor(p.y);
    return {latticeIndex(fx), latticeIndex(fy), p.x - fx, p.y - fy};
}

// ---- gradient noise ----------------------------------------------------------

struct GradientCell3
{
    const double* g[8]; ///< corner (a, b, c) at index 4a + 2b + c
};

inline void gradientCell(std::uint64_t s, const Split3& p, GradientCell3& cell)
{
    // Hierarchically: 2 + 4 + 8 mixes instead of 8 * 3.
    const std::uint64_t hx0 = hashCombine(s, p.i), hx1 = hashCombine(s, p.i + 1);
    const std::uint64_t h[4] = {hashCombine(hx0, p.j), hashCombine(hx0, p.j + 1), hashCombine(hx1, p.j),
                                hashCombine(hx1, p.j + 1)};
    for (int ab = 0; ab < 4; ++ab) {
        cell.g[2 * ab] = gradient3(hashCombine(h[ab], p.k));
        cell.g[2 * ab + 1] = gradient3(hashCombine(h[ab], p.k + 1));
    }
}

inline double gradientInCell(const GradientCell3& c, const Split3& p)
{
    const double x = p.x, y = p.y, z = p.z;
    const double n000 = dot3(c.g[0], x, y, z), n001 = dot3(c.g[1], x, y, z - 1.0);
    const double n010 = dot3(c.g[2], x, y - 1.0, z), n011 = dot3(c.g[3], x, y - 1.0, z - 1.0);
    const double n100 = dot3(c.g[4], x - 1.0, y, z), n101 = dot3(c.g[5], x - 1.0, y, z - 1.0);
    const double n110 = dot3(c.g[6], x - 1.0, y - 1.0, z), n111 = dot3(c.g[7], x - 1.0, y - 1.0, z - 1.0);
    const double u = fade(x), v = fade(y), w = fade(z);
    const double n00 = lerp(n000, n001, w), n01 = lerp(n010, n011, w);
    const double n10 = lerp(n100, n101, w), n11 = lerp(n110, n111, w);
    return lerp(lerp(n00, n01, v), lerp(n10, n11, v), u);
}

struct GradientCell2
{
    const double* g[4]; ///< corner (a, b) at index 2a + b
};

inline void gradientCell(std::uint64_t s, const Split2& p, GradientCell2& cell)
{
    const std::uint64_t hx0 = hashCombine(s, p.i), hx1 = hashCombine(s, p.i + 1);
    cell.g[0] = gradient2(hashCombine(hx0, p.j));
    cell.g[1] = gradient2(hashCombine(hx0, p.j + 1));
    cell.g[2] = gradient2(hashCombine(hx1, p.j));
    cell.g[3] = gradient2(hashCombine(hx1, p.j + 1));
}

inline double gradientInCell(const GradientCell2& c, const Split2& p)
{
    const double x = p.x, y = p.y;
    const double n00 = dot2(c.g[0], x, y), n01 = dot2(c.g[1], x, y - 1.0);
    const double n10 = dot2(c.g[2], x - 1.0, y), n11 = dot2(c.g[3], x - 1.0, y - 1.0);
    const double u = fade(x), v = fade(y);
    return NOISE2_SCALE * lerp(lerp(n00, n01, v), lerp(n10, n11, v), u);
}

// ---- value noise -------------------------------------------------------------

inline double latticeValue(std::uint64_t h) { return 2.0 * unitInterval(h) - 1.0; }

struct ValueCell3
{
    double v[8]; ///< corner (a, b, c) at index 4a + 2b + c
};

inline void valueCell(std::uint64_t s, const Split3& p, ValueCell3& cell)
{
    const std::uint64_t hx0 = hashCombine(s, p.i), hx1 = hashCombine(s, p.i + 1);
    const std::uint64_t h[4] = {hashCombine(hx0, p.j), hashCombine(hx0, p.j + 1), hashCombine(hx1, p.j),
                                hashCombine(hx1, p.j + 1)};
    for (int ab = 0; ab < 4; ++ab) {
        cell.v[2 * ab] = latticeValue(hashCombine(h[ab], p.k));
        cell.v[2 * ab + 1] = latticeValue(hashCombine(h[ab], p.k + 1));
    }
}

inline double valueInCell(const ValueCell3& c, const Split3& p)
{
    const double u = fade(p.x), v = fade(p.y), w = fade(p.z);
    const double n00 = lerp(c.v[0], c.v[1], w), n01 = lerp(c.v[2], c.v[3], w);
    const double n10 = lerp(c.v[4], c.v[5], w), n11 = lerp(c.v[6], c.v[7], w);
    return lerp(lerp(n00, n01, v), lerp(n10, n11, v), u);
}

struct ValueCell2
{
    double v[4];
};

inline void valueCell(std::uint64_t s, const Split2& p, ValueCell2& cell)
{
    const std::uint64_t hx0 = hashCombine(s, p.i), hx1 = hashCombine(s, p.i + 1);
    cell.v[0] = latticeValue(hashCombine(hx0, p.j));
    cell.v[1] = latticeValue(hashCombine(hx0, p.j + 1));
    cell.v[2] = latticeValue(hashCombine(hx1, p.j));
    cell.v[3] = latticeValue(hashCombine(hx1, p.j + 1));
}

inline double valueInCell(const ValueCell2& c, const Split2& p)
{
    const double u = fade(p.x), v = fade(p.y);
    return lerp(lerp(c.v[0], c.v[1], v), lerp(c.v[2], c.v[3], v), u);
}

// ---- simplex-style noise -------------------------------------------------------

/// Kernel support radius²: 0.5 keeps every kernel inside the simplices
/// around its corner, so the sum over one simplex's corners is continuous.
inline constexpr double KERNEL_R2 = 0.5;
/// Brings the range to about [−1, 1] (measured maxima of the unscaled sums
/// 0.0152 in 3D and 0.0101 in 2D over 2 million points).
inline constexpr double SIMPLEX3_SCALE = 77.0;
inline constexpr double SIMPLEX2_SCALE = 99.0;

inline double simplexKernel3(const double* g, double x, double y, double z)
{
    const double t = KERNEL_R2 - x * x - y * y - z * z;
    if (t <= 0.0) return 0.0;
    const double t2 = t * t;
    return t2 * t2 * (g[0] * x + g[1] * y + g[2] * z);
}

inline double simplexKernel2(const double* g, double x, double y)
{
    const double t = KERNEL_R2 - x * x - y * y;
    if (t <= 0.0) return 0.0;
    const double t2 = t * t;
    return t2 * t2 * (g[0] * x + g[1] * y);
}

/// A point on the simplex lattice: the skewed cube it lies in and its offset
/// from that cube's first corner, unskewed.
inline Split3 splitSimplex(const glm::dvec3& p)
{
    constexpr double F3 = 1.0 / 3.0, G3 = 1.0 / 6.0;
    const double skew = (p.x + p.y + p.z) * F3;
    const double fi = std::floor(p.x + skew), fj = std::floor(p.y + skew), fk = std::floor(p.z + skew);
    // The first corner unskewed is (i, j, k) − (i + j + k)·G3: subtract the
    // large integer part first so the offset keeps its precision far out.
    const double unskew = (fi + fj + fk) * G3;
    return {latticeIndex(fi), latticeIndex(fj), latticeIndex(fk), (p.x - fi) + unskew, (p.y - fj) + unskew,
            (p.z - fk) + unskew};
}

inline const double SIMPLEX2_F = 0.5 * (1.7320508075688772 - 1.0);
inline const double SIMPLEX2_G = (3.0 - 1.7320508075688772) / 6.0;

inline Split2 splitSimplex(const glm::dvec2& p)
{
    const double skew = (p.x + p.y) * SIMPLEX2_F;
    const double fi = std::floor(p.x + skew), fj = std::floor(p.y + skew);
    const double unskew = (fi + fj) * SIMPLEX2_G;
    return {latticeIndex(fi), latticeIndex(fj), (p.x - fi) + unskew, (p.y - fj) + unskew};
}

/// The gradients of the skewed cube's 8 corners (any simplex of it uses 4).
inline void simplexCell(std::uint64_t s, const Split3& p, GradientCell3& cell)
{
    for (int a = 0; a < 2; ++a) {
        const std::uint64_t ha = hashCombine(s, p.i + a);
        for (int b = 0; b < 2; ++b) {
            const std::uint64_t hb = hashCombine(ha, p.j + b);
            for (int c = 0; c < 2; ++c) cell.g[4 * a + 2 * b + c] = gradient3(hashCombine(hb, p.k + c));
        }
    }
}

inline double simplexInCell(const GradientCell3& cell, const Split3& p)
{
    constexpr double G3 = 1.0 / 6.0;
    const double x0 = p.x, y0 = p.y, z0 = p.z;
    int i1, j1, k1, i2, j2, k2; // the simplex's second and third corners
    if (x0 >= y0) {
        if (y0 >= z0) { i1 = 1; j1 = 0; k1 = 0; i2 = 1; j2 = 1; k2 = 0; }
        else if (x0 >= z0) { i1 = 1; j1 = 0; k1 = 0; i2 = 1; j2 = 0; k2 = 1; }
        else { i1 = 0; j1 = 0; k1 = 1; i2 = 1; j2 = 0; k2 = 1; }
    } else {
        if (y0 < z0) { i1 = 0; j1 = 0; k1 = 1; i2 = 0; j2 = 1; k2 = 1; }
        else if (x0 < z0) { i1 = 0; j1 = 1; k1 = 0; i2 = 0; j2 = 1; k2 = 1; }
        else { i1 = 0; j1 = 1; k1 = 0; i2 = 1; j2 = 1; k2 = 0; }
    }
    double n = simplexKernel3(cell.g[0], x0, y0, z0);
    n += simplexKernel3(cell.g[4 * i1 + 2 * j1 + k1], x0 - i1 + G3, y0 - j1 + G3, z0 - k1 + G3);
    n += simplexKernel3(cell.g[4 * i2 + 2 * j2 + k2], x0 - i2 + 2.0 * G3, y0 - j2 + 2.0 * G3, z0 - k2 + 2.0 * G3);
    n += simplexKernel3(cell.g[7], x0 - 1.0 + 3.0 * G3, y0 - 1.0 + 3.0 * G3, z0 - 1.0 + 3.0 * G3);
    return SIMPLEX3_SCALE * n;
}

inline void simplexCell(std::uint64_t s, const Split2& p, GradientCell2& cell)
{
    gradientCell(s, p, cell); // the square's 4 corners; a triangle uses 3
}

inline double simplexInCell(const GradientCell2& cell, const Split2& p)
{
    const double G2 = SIMPLEX2_G;
    const double x0 = p.x, y0 = p.y;
    const int i1 = x0 > y0 ? 1 : 0, j1 = 1 - i1;
    double n = simplexKernel2(cell.g[0], x0, y0);
    n += simplexKernel2(cell.g[2 * i1 + j1], x0 - i1 + G2, y0 - j1 + G2);
    n += simplexKernel2(cell.g[3], x0 - 1.0 + 2.0 * G2, y0 - 1.0 + 2.0 * G2);
    return SIMPLEX2_SCALE * n;
}

// ---- cellular noise ------------------------------------------------------------

/// Feature points lie in [JITTER_MIN, 1 − JITTER_MIN] of their cell (the
/// proof that the 3×3×3 search is then exact is in FractalNoise.cpp).
inline constexpr double JITTER_MIN = 0.3, JITTER_SPAN = 0.4;

/// Feature points of the 27 (3D) or 9 (2D) cells around a cell, relative to
/// its first corner.
struct CellularCell3
{
    double x[27], y[27], z[27];
};
struct CellularCell2
{
    double x[9], y[9];
};

inline void cellularCell(std::uint64_t s, const Split3& p, CellularCell3& cell)
{
    int n = 0;
    for (int a = -1; a <= 1; ++a) {
        const std::uint64_t ha = hashCombine(s, p.i + a);
        for (int b = -1; b <= 1; ++b) {
            const std::uint64_t hb = hashCombine(ha, p.j + b);
            for (int c = -1; c <= 1; ++c, ++n) {
                std::uint64_t h = hashCombine(hb, p.k + c);
                const double jx = JITTER_MIN + JITTER_SPAN * unitInterval(h);
                h = mix64(h + 0x9e3779b97f4a7c15ULL);
                const double jy = JITTER_MIN + JITTER_SPAN * unitInterval(h);
                h = mix64(h + 0x9e3779b97f4a7c15ULL);
                const double jz = JITTER_MIN + JITTER_SPAN * unitInterval(h);
                cell.x[n] = a + jx;
                cell.y[n] = b + jy;
                cell.z[n] = c + jz;
            }
        }
    }
}

inline void cellularCell(std::uint64_t s, const Split2& p, CellularCell2& cell)
{
    int n = 0;
    for (int a = -1; a <= 1; ++a) {
        const std::uint64_t ha = hashCombine(s, p.i + a);
        for (int b = -1; b <= 1; ++b, ++n) {
            std::uint64_t h = hashCombine(ha, p.j + b);
            const double jx = JITTER_MIN + JITTER_SPAN * unitInterval(h);
            h = mix64(h + 0x9e3779b97f4a7c15ULL);
            const double jy = JITTER_MIN + JITTER_SPAN * unitInterval(h);
            cell.x[n] = a + jx;
            cell.y[n] = b + jy;
        }
    }
}

/// Keeps the two smallest squared distances seen so far (f1 <= f2).
inline void keepTwoNearest(double d2, double& f1, double& f2)
{
    if (d2 < f1) {
        f2 = f1;
        f1 = d2;
    } else if (d2 < f2) {
        f2 = d2;
    }
}

/// The squared distances to the nearest and second nearest feature point.
inline void cellularInCell(const CellularCell3& cell, const Split3& p, double& f1, double& f2)
{
    f1 = 1e9;
    f2 = 1e9;
    for (int n = 0; n < 27; ++n) {
        const double dx = p.x - cell.x[n], dy = p.y - cell.y[n], dz = p.z - cell.z[n];
        keepTwoNearest(dx * dx + dy * dy + dz * dz, f1, f2);
    }
}

inline void cellularInCell(const CellularCell2& cell, const Split2& p, double& f1, double& f2)
{
    f1 = 1e9;
    f2 = 1e9;
    for (int n = 0; n < 9; ++n) {
        const double dx = p.x - cell.x[n], dy = p.y - cell.y[n];
        keepTwoNearest(dx * dx + dy * dy, f1, f2);
    }
}

} // namespace strata::terrain::detail
