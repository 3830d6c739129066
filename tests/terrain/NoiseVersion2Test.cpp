// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Noise version 2 (float lanes, 32-bit lattice hashing): the lanes against
// a plain scalar reference written here from the definition, bit for bit on
// every SIMD target; the fractal sums' block path against their scalar
// path; continuity across the 32-bit words of a cell index; the gradient
// bounds and box bounds that sampling prunes with; and version 1 untouched.

#include "NoiseHash.h"    // internal: noise2SpreadVersion2, noise3SpreadVersion2
#include "NoiseKernels.h" // internal: splitCube, splitSimplex
#include "NoiseSimd.h"    // internal: basisVersion2

#include <strata/Error.h>
#include <strata/detail/IntegerHash.h>
#include <strata/terrain/FractalNoise.h>
#include <strata/terrain/SimdTarget.h>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace strata::terrain;

namespace {

// ---- the reference: version 2 as its definition states it, one point at a time

namespace reference {

constexpr std::uint32_t LOW_PRIME[3] = {0x9E3779B1u, 0x85EBCA77u, 0xC2B2AE3Du};
constexpr std::uint32_t HIGH_PRIME[3] = {0x27D4EB2Fu, 0x165667B1u, 0xD3A2646Du};
constexpr std::uint32_t SIGN = 0x80000000u;

/// T(i) = lo·P ^ hi·Q of the cell index i on axis a.
std::uint32_t term(std::int64_t i, int a)
{
    const std::uint64_t u = std::uint64_t(i);
    return (std::uint32_t(u) * LOW_PRIME[a]) ^ (std::uint32_t(u >> 32) * HIGH_PRIME[a]);
}

std::uint32_t cornerHash(std::uint32_t seed, std::uint32_t tx, std::uint32_t ty, std::uint32_t tz)
{
    return strata::detail::lowbias32(seed ^ tx ^ ty ^ tz);
}

float flip(float v, std::uint32_t signBit)
{
    std::uint32_t bits;
    std::memcpy(&bits, &v, 4);
    bits ^= signBit & SIGN;
    std::memcpy(&v, &bits, 4);
    return v;
}

float dot3(std::uint32_t h, float x, float y, float z)
{
    const std::uint32_t index = h >> 28;
    const float u = index < 8 ? x : y;
    const float v = index < 4 ? y : (index == 12 || index == 14 ? x : z);
    return flip(u, h << 3) + flip(v, h << 2);
}

float dot2(std::uint32_t h, float x, float y)
{
    const float along = flip((h & 0x40000000u) ? y : x, h << 2);
    const float across = 0.70710678118654752440f * (flip(x, h << 2) + flip(y, h << 1));
    return (h & SIGN) ? across : along;
}

float value(std::uint32_t h) { return float(std::int32_t(h)) * 0x1.0p-31f; }

float jitter(std::uint32_t h, int shift) { return 0.3f + 0.4f * (float(std::int32_t((h >> shift) & 1023u)) * 0x1.0p-10f); }

float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
float lerp(float a, float b, float t) { return a + t * (b - a); }

float kernel(float r2)
{
    float t = 0.5f - r2;
    t = t > 0.0f ? t : 0.0f;
    const float t2 = t * t;
    return t2 * t2;
}

/// The basis at p (noise units), z ignored in 2D.
float basis(NoiseType type, std::uint32_t s, const glm::dvec3& p, bool threeD)
{
    const bool simplex = type == NoiseType::SIMPLEX;
    std::int64_t cell[3] = {0, 0, 0};
    float f[3] = {0.0f, 0.0f, 0.0f};
    if (threeD) {
        const detail::Split3 q = simplex ? detail::splitSimplex(p) : detail::splitCube(p);
        cell[0] = q.i, cell[1] = q.j, cell[2] = q.k;
        f[0] = float(q.x), f[1] = float(q.y), f[2] = float(q.z);
    } else {
        const glm::dvec2 p2(p.x, p.y);
        const detail::Split2 q = simplex ? detail::splitSimplex(p2) : detail::splitSquare(p2);
        cell[0] = q.i, cell[1] = q.j;
        f[0] = float(q.x), f[1] = float(q.y);
    }
    // The cell's neighbours' terms, k = −1, 0, 1 (2D: z's term is 0).
    std::uint32_t t[3][3] = {};
    for (int a = 0; a < (threeD ? 3 : 2); ++a)
        for (int k = -1; k <= 1; ++k) t[a][k + 1] = term(cell[a] + k, a);
    const auto hash = [&](int a, int b, int c) { return cornerHash(s, t[0][a + 1], t[1][b + 1], t[2][c + 1]); };
    const float x = f[0], y = f[1], z = f[2];
    switch (type) {
    case NoiseType::GRADIENT: {
        if (!threeD) {
            const float n00 = dot2(hash(0, 0, -1), x, y), n01 = dot2(hash(0, 1, -1), x, y - 1.0f);
            const float n10 = dot2(hash(1, 0, -1), x - 1.0f, y), n11 = dot2(hash(1, 1, -1), x - 1.0f, y - 1.0f);
            return 1.41421356237309504880f * lerp(lerp(n00, n01, fade(y)), lerp(n10, n11, fade(y)), fade(x));
        }
        float n[8];
        for (int c = 0; c < 8; ++c) {
            const int a = c >> 2, b = (c >> 1) & 1, k = c & 1;
            n[c] = dot3(hash(a, b, k), x - float(a), y - float(b), z - float(k));
        }
        const float u = fade(x), v = fade(y), w = fade(z);
        return lerp(lerp(lerp(n[0], n[1], w), lerp(n[2], n[3], w), v), lerp(lerp(n[4], n[5], w), lerp(n[6], n[7], w), v),
                    u);
    }
    case NoiseType::VALUE: {
        if (!threeD) {
            return lerp(lerp(value(hash(0, 0, -1)), value(hash(0, 1, -1)), fade(y)),
                        lerp(value(hash(1, 0, -1)), value(hash(1, 1, -1)), fade(y)), fade(x));
        }
        float c[8];
        for (int i = 0; i < 8; ++i) c[i] = value(hash(i >> 2, (i >> 1) & 1, i & 1));
        const float u = fade(x), v = fade(y), w = fade(z);
        return lerp(lerp(lerp(c[0], c[1], w), lerp(c[2], c[3], w), v), lerp(lerp(c[4], c[5], w), lerp(c[6], c[7], w), v),
                    u);
    }
    case NoiseType::SIMPLEX: {
        if (!threeD) {
            const float g = float((3.0 - 1.7320508075688772) / 6.0);
            const int i1 = x > y ? 1 : 0, j1 = 1 - i1;
            const auto corner = [&](std::uint32_t h, float px, float py) { return kernel(px * px + py * py) * dot2(h, px, py); };
            float n = corner(hash(0, 0, -1), x, y);
            n = n + corner(hash(i1, j1, -1), (x - float(i1)) + g, (y - float(j1)) + g);
            n = n + corner(hash(1, 1, -1), (x - 1.0f) + (g + g), (y - 1.0f) + (g + g));
            return 99.0f * n;
        }
        int c1[3], c2[3]; // version 1's table of the simplex's second and third corners
        if (x >= y) {
            if (y >= z) c1[0] = 1, c1[1] = 0, c1[2] = 0, c2[0] = 1, c2[1] = 1, c2[2] = 0;
            else if (x >= z) c1[0] = 1, c1[1] = 0, c1[2] = 0, c2[0] = 1, c2[1] = 0, c2[2] = 1;
            else c1[0] = 0, c1[1] = 0, c1[2] = 1, c2[0] = 1, c2[1] = 0, c2[2] = 1;
        } else {
            if (y < z) c1[0] = 0, c1[1] = 0, c1[2] = 1, c2[0] = 0, c2[1] = 1, c2[2] = 1;
            else if (x < z) c1[0] = 0, c1[1] = 1, c1[2] = 0, c2[0] = 0, c2[1] = 1, c2[2] = 1;
            else c1[0] = 0, c1[1] = 1, c1[2] = 0, c2[0] = 1, c2[1] = 1, c2[2] = 0;
        }
        const auto corner = [&](std::uint32_t h, float px, float py, float pz) {
            return kernel(px * px + py * py + pz * pz) * dot3(h, px, py, pz);
        };
        const float g1 = 1.0f / 6.0f, g2 = 1.0f / 3.0f;
        float n = corner(hash(0, 0, 0), x, y, z);
        n = n + corner(hash(c1[0], c1[1], c1[2]), (x - float(c1[0])) + g1, (y - float(c1[1])) + g1, (z - float(c1[2])) + g1);
        n = n + corner(hash(c2[0], c2[1], c2[2]), (x - float(c2[0])) + g2, (y - float(c2[1])) + g2, (z - float(c2[2])) + g2);
        n = n + corner(hash(1, 1, 1), (x - 1.0f) + 0.5f, (y - 1.0f) + 0.5f, (z - 1.0f) + 0.5f);
        return 77.0f * n;
    }
    case NoiseType::CELLULAR_F1:
    case NoiseType::CELLULAR_F2: {
        float f1 = 1e9f, f2 = 1e9f;
        for (int a = -1; a <= 1; ++a)
            for (int b = -1; b <= 1; ++b)
                for (int c = -1; c <= (threeD ? 1 : -1); ++c) {
                    const std::uint32_t h = threeD ? hash(a, b, c) : cornerHash(s, t[0][a + 1], t[1][b + 1], 0);
                    const float dx = (x - float(a)) - jitter(h, 0), dy = (y - float(b)) - jitter(h, 10);
                    float d2 = dx * dx + dy * dy;
                    if (threeD) {
                        const float dz = (z - float(c)) - jitter(h, 20);
                        d2 = d2 + dz * dz;
                    }
                    if (d2 < f1) f2 = f1, f1 = d2;
                    else if (d2 < f2) f2 = d2;
                }
        return type == NoiseType::CELLULAR_F1 ? 2.0f * std::sqrt(f1) - 1.0f : 2.0f * std::sqrt(f2) - 1.4f;
    }
    }
    return 0.0f;
}

} // namespace reference

const NoiseType BASES[] = {NoiseType::GRADIENT, NoiseType::SIMPLEX, NoiseType::VALUE, NoiseType::CELLULAR_F1,
                           NoiseType::CELLULAR_F2};

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Deterministic uniform numbers in [0, 1) for test points (a 64-bit LCG's
/// top 53 bits; no std:: distributions, whose output differs by library).
struct Unit
{
    std::uint64_t state;
    double operator()()
    {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return double(state >> 11) * 0x1.0p-53;
    }
};

/// Points in noise units: lattice-ordered runs, scattered ones, points on
/// cell faces and corners, and points around the words of a cell index
/// (2^32, −2^32, 0) and far out (2^40, 1e12), where the carry between the
/// low and the high word matters.
std::vector<glm::dvec3> testPoints()
{
    std::vector<glm::dvec3> points;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j)
            for (int k = 0; k < 6; ++k) points.emplace_back(-1.3 + 0.37 * i, 0.11 + 0.29 * j, 2.9 - 0.43 * k);
    Unit unit{12345};
    const auto next = [&unit] { return unit() - 0.5; };
    for (int i = 0; i < 300; ++i) points.emplace_back(400.0 * next(), 400.0 * next(), 400.0 * next());
    for (const double base : {0.0, 4294967296.0, -4294967296.0, 1099511627776.0, 1e12, -3e15}) {
        for (int i = 0; i < 40; ++i) points.emplace_back(base + 3.0 * next(), base + 3.0 * next(), -base + 3.0 * next());
        points.emplace_back(base, base, base);
        points.emplace_back(base - 0.5, base + 0.5, base);
    }
    return points;
}

/// Every basis, 3D and 2D, against the reference at every test point, on
/// the target in use; batches of 1, 7 and all points (the tails differ).
void expectReferenceBits(const std::string& target)
{
    const std::vector<glm::dvec3> points = testPoints();
    std::vector<double> x, y, z;
    for (const glm::dvec3& p : points) {
        x.push_back(p.x);
        y.push_back(p.y);
        z.push_back(p.z);
    }
    const std::uint64_t hashedSeed = 0x0123456789abcdefULL;
    for (const NoiseType type : BASES)
        for (const bool threeD : {true, false})
            for (const std::size_t batch : {std::size_t(1), std::size_t(7), points.size()}) {
                std::vector<double> out(points.size() + 1, 777.0);
                for (std::size_t at = 0; at < points.size(); at += batch) {
                    const std::size_t n = std::min(batch, points.size() - at);
                    detail::basisVersion2(type, hashedSeed, &x[at], &y[at], threeD ? &z[at] : nullptr, n, &out[at]);
                }
                ASSERT_EQ(out.back(), 777.0) << "wrote past the points";
                for (std::size_t i = 0; i < points.size(); ++i) {
                    const double expected = reference::basis(type, std::uint32_t(hashedSeed >> 32), points[i], threeD);
                    ASSERT_TRUE(sameBits(out[i], expected))
                        << target << ": basis " << int(type) << (threeD ? " 3D" : " 2D") << ", batch " << batch
                        << ", point " << i << " (" << points[i].x << ", " << points[i].y << ", " << points[i].z
                        << "): lanes " << out[i] << ", reference " << expected;
                }
            }
}

/// Every basis and fractal at version 2, block against scalar, 3D and 2D.
void expectBlockSameAsScalar(const std::string& target)
{
    const std::vector<glm::dvec3> points = testPoints();
    std::vector<double> x, y, z;
    for (const glm::dvec3& p : points) {
        // World metres under a 40 m wavelength, so the octaves cover
        // fractions of a cell to several cells between points.
        x.push_back(p.x * 40.0);
        y.push_back(p.y * 40.0);
        z.push_back(p.z * 40.0);
    }
    for (const NoiseType type : BASES)
        for (const FractalType fractal : {FractalType::FBM, FractalType::RIDGED, FractalType::BILLOW}) {
            const FractalNoise noise(5, {type, fractal, 5, 2.0, 0.5, 2});
            const std::size_t n = points.size();
            std::vector<double> out3(n), out2(n);
            noise.evaluate(x.data(), y.data(), z.data(), n, out3.data());
            noise.evaluate(x.data(), z.data(), n, out2.data());
            for (std::size_t i = 0; i < n; ++i) {
                ASSERT_TRUE(sameBits(out3[i], noise({x[i], y[i], z[i]})))
                    << target << ": basis " << int(type) << " fractal " << int(fractal) << ", point " << i;
                ASSERT_TRUE(sameBits(out2[i], noise(glm::dvec2(x[i], z[i]))))
                    << target << ": 2D basis " << int(type) << " fractal " << int(fractal) << ", point " << i;
            }
        }
}

} // namespace

TEST(NoiseVersion2, LanesGiveTheReferenceBitsOnEveryTarget)
{
    const std::vector<std::string> targets = availableSimdTargets();
    for (const std::string& target : targets) {
        useSimdTarget(target);
        expectReferenceBits(target);
        expectBlockSameAsScalar(target);
    }
    useSimdTarget("");
}

TEST(NoiseVersion2, IsContinuousAcrossTheWordsOfACellIndex)
{
    // Points 1e-4 either side of a cell face, on each axis, differ by at
    // most L·2e-4 (plus float rounding): the far cell's corners are hashed
    // the same from both sides, at 0, where the low word wraps (2^32, the
    // high word steps), at −2^32 and 2^33. A corner hashed wrongly from one
    // side jumps by up to the basis' whole range.
    const std::uint64_t hashedSeed = 0xfeedfacecafebeefULL;
    for (const NoiseType type : BASES) {
        const double slope = noiseLipschitz(type, 3);
        for (const double face : {0.0, 4294967296.0, -4294967296.0, 8589934592.0})
            for (int axis = 0; axis < 3; ++axis)
                for (int i = 0; i < 20; ++i) {
                    glm::dvec3 a(0.05 * i + 0.01, 0.37 - 0.03 * i, 0.61 + 0.02 * i), b = a;
                    a[axis] = face - 1e-4;
                    b[axis] = face + 1e-4;
                    double va = 0.0, vb = 0.0;
                    detail::basisVersion2(type, hashedSeed, &a.x, &a.y, &a.z, 1, &va);
                    detail::basisVersion2(type, hashedSeed, &b.x, &b.y, &b.z, 1, &vb);
                    EXPECT_LE(std::abs(va - vb), slope * 2e-4 + 1e-4)
                        << "basis " << int(type) << ", axis " << axis << ", face " << face << ", point " << i;
                }
    }
}

TEST(NoiseVersion2, StaysWithinItsGradientAndBoxBounds)
{
    Unit next{99};
    for (const NoiseType type : BASES)
        for (const FractalType fractal : {FractalType::FBM, FractalType::RIDGED}) {
            const FractalNoise noise(11, {type, fractal, 3, 2.0, 0.5, 2});
            const double slope3 = noise.lipschitz(3), slope2 = noise.lipschitz(2);
            double lo = HUGE_VAL, hi = -HUGE_VAL;
            for (int i = 0; i < 2000; ++i) {
                const glm::dvec3 p(60.0 * next() - 30.0, 60.0 * next() - 30.0, 60.0 * next() - 30.0);
                const glm::dvec3 d(0.02 * next() - 0.01, 0.02 * next() - 0.01, 0.02 * next() - 0.01);
                const double v = noise(p);
                lo = std::min(lo, v);
                hi = std::max(hi, v);
                EXPECT_LE(std::abs(noise(p + d) - v), slope3 * glm::length(d) + 1e-4) << "basis " << int(type);
                const glm::dvec2 q(p.x, p.z), e(d.x, d.z);
                EXPECT_LE(std::abs(noise(q + e) - noise(q)), slope2 * glm::length(e) + 1e-4) << "2D basis " << int(type);
                // A box around p holds the sum at its corners and centre.
                const glm::dvec3 half(0.3 * next(), 0.3 * next(), 0.3 * next());
                const Interval box = noise.bounds(p - half, p + half);
                for (const glm::dvec3& corner : {p - half, p + half, p, glm::dvec3(p.x - half.x, p.y + half.y, p.z)}) {
                    const double value = noise(corner);
                    EXPECT_GE(value, box.lo) << "basis " << int(type);
                    EXPECT_LE(value, box.hi) << "basis " << int(type);
                }
                const Interval box2 = noise.bounds(glm::dvec2(p.x - half.x, p.z - half.z), glm::dvec2(p.x + half.x, p.z + half.z));
                EXPECT_GE(noise(q), box2.lo);
                EXPECT_LE(noise(q), box2.hi);
            }
            // Varied, not constant: the sum covers a good part of its range.
            EXPECT_GT(hi - lo, 0.5) << "basis " << int(type) << " fractal " << int(fractal);
        }
}

namespace {

/// One in-cell box [lo, hi] of version 2's gradient noise (2D or 3D): the
/// mean value form's centre is the lanes' value there (so its scalar
/// gradients are the lanes' own), and its spread holds the lanes' value at
/// every corner (the extremes of an affine part) and at points inside.
/// Returns the spread.
template <class Vec>
double checkedSpread(Unit& next, std::uint64_t hashedSeed, const Vec& lo, const Vec& hi)
{
    constexpr int D = Vec::length();
    const std::uint32_t seed = std::uint32_t(hashedSeed >> 32);
    const auto lanes = [hashedSeed](const Vec& p) {
        double value = 0.0;
        detail::basisVersion2(NoiseType::GRADIENT, hashedSeed, &p[0], &p[1], D == 3 ? &p[D - 1] : nullptr, 1, &value);
        return value;
    };
    double spread = 0.0, centre = 0.0;
    if constexpr (D == 3) centre = detail::noise3SpreadVersion2(seed, lo, hi, spread);
    else centre = detail::noise2SpreadVersion2(seed, lo, hi, spread);
    EXPECT_NEAR(lanes(0.5 * (lo + hi)), centre, 1e-5) << "cell at " << lo[0] << ", " << lo[1] << ": another gradient than the lanes'";
    for (int k = 0; k < (1 << D) + 4; ++k) {
        Vec t;
        for (int a = 0; a < D; ++a) t[a] = k < (1 << D) ? double((k >> a) & 1) : next();
        EXPECT_LE(std::abs(lanes(lo + (hi - lo) * t) - centre), spread + 1e-5);
    }
    return spread;
}

} // namespace

TEST(NoiseVersion2, TheMeanValueFormHoldsTheLanesAndIsTighterThanTheSlope)
{
    // 2D gradient octaves whose box lies in one cell take the mean value
    // form (noise2SpreadVersion2, with the scalar hash32 gradients).
    Unit next{5};
    double spreadSum = 0.0, slopeSum = 0.0;
    for (int i = 0; i < 2000; ++i) {
        const double cx = std::floor(400.0 * next() - 200.0) + (i == 0 ? 4294967296.0 : 0.0);
        const double cy = std::floor(400.0 * next() - 200.0);
        const glm::dvec2 lo(cx + 0.9 * next(), cy + 0.9 * next());
        // Boxes of up to a tenth of a cell, as a block of voxels is to an octave.
        const glm::dvec2 hi(lo.x + 0.1 * next(), lo.y + 0.1 * next());
        spreadSum += checkedSpread(next, 0x9e3779b97f4a7c15ULL, lo, hi);
        slopeSum += GRADIENT_NOISE_LIPSCHITZ_2D * 0.5 * glm::length(hi - lo);
    }
    EXPECT_LT(spreadSum, 0.8 * slopeSum) << "the mean value form should be tighter than the gradient bound";
}

TEST(NoiseVersion2, The3DMeanValueFormHoldsTheLanesAndIsTighterThanTheSlope)
{
    // 3D gradient octaves whose box lies in one cell take the mean value form
    // too (noise3SpreadVersion2, with hash32::gradient3), near a 32-bit
    // word's wrap as well.
    Unit next{11};
    double spreadSum = 0.0, slopeSum = 0.0;
    for (int i = 0; i < 2000; ++i) {
        const double wrap = (i % 3 == 0) ? 4294967295.0 : 0.0; // the cell just below 2^32 on x
        const glm::dvec3 cell(std::floor(200.0 * next() - 100.0) + wrap, std::floor(200.0 * next() - 100.0),
                              std::floor(200.0 * next() - 100.0));
        const glm::dvec3 lo = cell + glm::dvec3(0.9 * next(), 0.9 * next(), 0.9 * next());
        const glm::dvec3 hi = lo + glm::dvec3(0.1 * next(), 0.1 * next(), 0.1 * next());
        spreadSum += checkedSpread(next, 0x2545f4914f6cdd1dULL, lo, hi);
        slopeSum += GRADIENT_NOISE_LIPSCHITZ * 0.5 * glm::length(hi - lo);
    }
    std::printf("3D mean value form: %.3f of the gradient bound\n", spreadSum / slopeSum);
    EXPECT_LT(spreadSum, 0.6 * slopeSum) << "the mean value form should be tighter than the gradient bound";
}

TEST(NoiseVersion2, IsAnotherPatternAndLeavesVersion1Alone)
{
    for (const NoiseType type : BASES) {
        const FractalNoise one(7, {type, FractalType::FBM, 3, 2.0, 0.5, 1});
        const FractalNoise two(7, {type, FractalType::FBM, 3, 2.0, 0.5, 2});
        const FractalNoise defaulted(7, {type, FractalType::FBM, 3, 2.0, 0.5});
        int differ = 0;
        for (int i = 0; i < 100; ++i) {
            const glm::dvec3 p(0.7 * i, 0.3 * i - 5.0, 11.0 - 0.5 * i);
            EXPECT_TRUE(sameBits(one(p), defaulted(p))) << "version 1 is the default";
            differ += !sameBits(one(p), two(p));
        }
        EXPECT_GT(differ, 90) << "basis " << int(type);
    }
}

TEST(NoiseVersion2, AnUnknownVersionIsRefusedNamingTheKey)
{
    for (const int version : {0, 3, -1}) {
        try {
            FractalNoise(1, {NoiseType::GRADIENT, FractalType::FBM, 3, 2.0, 0.5, version});
            ADD_FAILURE() << "version " << version << " was accepted";
        } catch (const strata::Error& e) {
            EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput);
            EXPECT_NE(std::string(e.what()).find("noise_version = " + std::to_string(version)), std::string::npos)
                << e.what();
        }
    }
}
