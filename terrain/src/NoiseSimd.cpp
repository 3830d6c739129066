// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The vector halves of block noise evaluation (see NoiseSimd.h), compiled
// once per instruction set by Highway's foreach_target and dispatched at run
// time. Each kernel below is its scalar twin in NoiseKernels.h written in
// lanes: the same operations in the same order, so the same bits. Keep them
// in step: BlockEvaluationTest compares the two on every target.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "NoiseSimd.cpp" // found through this folder's include path
#include <hwy/foreach_target.h> // IWYU pragma: keep
#include <hwy/highway.h>

#include "NoiseSimd.h"
#include "NoiseSplit-inl.h"

#include <strata/terrain/SimdTarget.h>

#include <strata/Error.h>

#include <algorithm>

HWY_BEFORE_NAMESPACE();
namespace strata::terrain::detail {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;
// Every kernel is a template on the lane count: full vectors for the body
// of a run, then 4, 2 and 1 lanes for its tail (runs at the fine octaves of
// a fractal sum are a point or two long; padding them to a full vector
// would waste most of its lanes).
#define STRATA_LANES template <class D, class V = hn::Vec<D>>

// A tail of split points shorter than a vector goes through a zero-padded
// buffer this long.
constexpr std::size_t MAX_LANES = HWY_MAX_BYTES / sizeof(double);

// ---- shared arithmetic (NoiseHash.h) ------------------------------------------

STRATA_LANES HWY_INLINE V fade(D d, V t)
{
    // t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
    const V cube = hn::Mul(hn::Mul(t, t), t);
    const V inner = hn::Add(hn::Mul(t, hn::Sub(hn::Mul(t, hn::Set(d, 6.0)), hn::Set(d, 15.0))), hn::Set(d, 10.0));
    return hn::Mul(cube, inner);
}

template <class V>
HWY_INLINE V lerp(V a, V b, V t) { return hn::Add(a, hn::Mul(t, hn::Sub(b, a))); }

template <class V>
HWY_INLINE V dot3(const V (&g)[3], V x, V y, V z)
{
    return hn::Add(hn::Add(hn::Mul(g[0], x), hn::Mul(g[1], y)), hn::Mul(g[2], z));
}

template <class V>
HWY_INLINE V dot2(const V (&g)[2], V x, V y)
{
    return hn::Add(hn::Mul(g[0], x), hn::Mul(g[1], y));
}

// ---- kernels: NoiseKernels.h's *InCell, lane-wise ---------------------------

/// gradientInCell (3D) with corner c's gradient in g[c][0..2].
STRATA_LANES HWY_INLINE V gradientInCell3(D d, const V (&g)[8][3], V x, V y, V z)
{
    const V one = hn::Set(d, 1.0);
    const V x1 = hn::Sub(x, one), y1 = hn::Sub(y, one), z1 = hn::Sub(z, one);
    const V n000 = dot3(g[0], x, y, z), n001 = dot3(g[1], x, y, z1);
    const V n010 = dot3(g[2], x, y1, z), n011 = dot3(g[3], x, y1, z1);
    const V n100 = dot3(g[4], x1, y, z), n101 = dot3(g[5], x1, y, z1);
    const V n110 = dot3(g[6], x1, y1, z), n111 = dot3(g[7], x1, y1, z1);
    const V u = fade(d, x), v = fade(d, y), w = fade(d, z);
    const V n00 = lerp(n000, n001, w), n01 = lerp(n010, n011, w);
    const V n10 = lerp(n100, n101, w), n11 = lerp(n110, n111, w);
    return lerp(lerp(n00, n01, v), lerp(n10, n11, v), u);
}

/// gradientInCell (2D) with corner c's gradient in g[c][0..1].
STRATA_LANES HWY_INLINE V gradientInCell2(D d, const V (&g)[4][2], V x, V y)
{
    const V one = hn::Set(d, 1.0);
    const V x1 = hn::Sub(x, one), y1 = hn::Sub(y, one);
    const V n00 = dot2(g[0], x, y), n01 = dot2(g[1], x, y1);
    const V n10 = dot2(g[2], x1, y), n11 = dot2(g[3], x1, y1);
    const V u = fade(d, x), v = fade(d, y);
    return hn::Mul(hn::Set(d, 1.41421356237309504880), lerp(lerp(n00, n01, v), lerp(n10, n11, v), u)); // NOISE2_SCALE
}

struct Gradient3
{
    STRATA_LANES static V at(D d, const double* c, V x, V y, V z)
    {
        V g[8][3];
        for (int corner = 0; corner < 8; ++corner)
            for (int k = 0; k < 3; ++k) g[corner][k] = hn::Set(d, c[3 * corner + k]);
        return gradientInCell3(d, g, x, y, z);
    }
};

/// valueInCell (3D) with corner (a, b, c)'s value in c[4a + 2b + c].
STRATA_LANES HWY_INLINE V valueInCell3(D d, const V (&c)[8], V x, V y, V z)
{
    const V u = fade(d, x), v = fade(d, y), w = fade(d, z);
    const V n00 = lerp(c[0], c[1], w), n01 = lerp(c[2], c[3], w);
    const V n10 = lerp(c[4], c[5], w), n11 = lerp(c[6], c[7], w);
    return lerp(lerp(n00, n01, v), lerp(n10, n11, v), u);
}

/// valueInCell (2D) with corner (a, b)'s value in c[2a + b].
STRATA_LANES HWY_INLINE V valueInCell2(D d, const V (&c)[4], V x, V y)
{
    const V u = fade(d, x), v = fade(d, y);
    return lerp(lerp(c[0], c[1], v), lerp(c[2], c[3], v), u);
}

struct Value3
{
    STRATA_LANES static V at(D d, const double* c, V x, V y, V z)
    {
        V corners[8];
        for (int k = 0; k < 8; ++k) corners[k] = hn::Set(d, c[k]);
        return valueInCell3(d, corners, x, y, z);
    }
};

// simplexKernel3/2: t⁴·(g·d) inside the kernel's support, +0 outside.
STRATA_LANES HWY_INLINE V simplexKernel3(D d, V gx, V gy, V gz, V x, V y, V z)
{
    const V t = hn::Sub(hn::Sub(hn::Sub(hn::Set(d, 0.5), hn::Mul(x, x)), hn::Mul(y, y)), hn::Mul(z, z));
    const V t2 = hn::Mul(t, t);
    const V dot = hn::Add(hn::Add(hn::Mul(gx, x), hn::Mul(gy, y)), hn::Mul(gz, z));
    return hn::IfThenElseZero(hn::Gt(t, hn::Zero(d)), hn::Mul(hn::Mul(t2, t2), dot));
}

STRATA_LANES HWY_INLINE V simplexKernel2(D d, V gx, V gy, V x, V y)
{
    const V t = hn::Sub(hn::Sub(hn::Set(d, 0.5), hn::Mul(x, x)), hn::Mul(y, y));
    const V t2 = hn::Mul(t, t);
    const V dot = hn::Add(hn::Mul(gx, x), hn::Mul(gy, y));
    return hn::IfThenElseZero(hn::Gt(t, hn::Zero(d)), hn::Mul(hn::Mul(t2, t2), dot));
}

/// simplexInCell (3D) with corner (a, b, c)'s gradient in g[4a + 2b + c].
STRATA_LANES HWY_INLINE V simplexInCell3(D d, const V (&g)[8][3], V x0, V y0, V z0)
{
    constexpr double G3 = 1.0 / 6.0;
    // simplexInCell's branches as masks: the second corner is one of
    // (1,0,0) (0,1,0) (0,0,1), the third one of (1,1,0) (1,0,1) (0,1,1).
    const auto xy = hn::Ge(x0, y0), yz = hn::Ge(y0, z0), xz = hn::Ge(x0, z0);
    const auto i1 = hn::And(xy, xz), j1 = hn::AndNot(xy, yz);
    const auto i2 = hn::Or(xy, xz), j2 = hn::Or(hn::Not(xy), yz), k2 = hn::Not(hn::And(xz, yz));
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
    // Corners: (1,0,0) → 4, (0,1,0) → 2, (0,0,1) → 1, (1,1,0) → 6, (1,0,1) → 5, (0,1,1) → 3.
    V g1[3], g2[3];
    for (int k = 0; k < 3; ++k) {
        g1[k] = hn::IfThenElse(i1, g[4][k], hn::IfThenElse(j1, g[2][k], g[1][k]));
        // the third: (1,1,0) unless k2; then (1,0,1) if i2, else (0,1,1)
        g2[k] = hn::IfThenElse(k2, hn::IfThenElse(i2, g[5][k], g[3][k]), g[6][k]);
    }
    const V di1 = hn::IfThenElseZero(i1, one), dj1 = hn::IfThenElseZero(j1, one);
    const V dk1 = hn::IfThenElse(hn::Or(i1, j1), zero, one);
    const V di2 = hn::IfThenElseZero(i2, one), dj2 = hn::IfThenElseZero(j2, one), dk2 = hn::IfThenElseZero(k2, one);
    const V gs = hn::Set(d, G3), g2x = hn::Set(d, 2.0 * G3), g3x = hn::Set(d, 3.0 * G3);
    V n = simplexKernel3(d, g[0][0], g[0][1], g[0][2], x0, y0, z0);
    n = hn::Add(n, simplexKernel3(d, g1[0], g1[1], g1[2], hn::Add(hn::Sub(x0, di1), gs), hn::Add(hn::Sub(y0, dj1), gs),
                                  hn::Add(hn::Sub(z0, dk1), gs)));
    n = hn::Add(n, simplexKernel3(d, g2[0], g2[1], g2[2], hn::Add(hn::Sub(x0, di2), g2x),
                                  hn::Add(hn::Sub(y0, dj2), g2x), hn::Add(hn::Sub(z0, dk2), g2x)));
    n = hn::Add(n, simplexKernel3(d, g[7][0], g[7][1], g[7][2], hn::Add(hn::Sub(x0, one), g3x),
                                  hn::Add(hn::Sub(y0, one), g3x), hn::Add(hn::Sub(z0, one), g3x)));
    return hn::Mul(hn::Set(d, 77.0), n); // SIMPLEX3_SCALE
}

struct Simplex3
{
    STRATA_LANES static V at(D d, const double* c, V x0, V y0, V z0)
    {
        V g[8][3];
        for (int corner = 0; corner < 8; ++corner)
            for (int k = 0; k < 3; ++k) g[corner][k] = hn::Set(d, c[3 * corner + k]);
        return simplexInCell3(d, g, x0, y0, z0);
    }
};

// keepTwoNearest() without branches: the same two minima.
template <class V>
HWY_INLINE void keepTwoNearest(V d2, V& f1, V& f2)
{
    f2 = hn::Min(f2, hn::Max(f1, d2));
    f1 = hn::Min(f1, d2);
}

template <bool SECOND>
struct Cellular3
{
    STRATA_LANES static V at(D d, const double* c, V x, V y, V z)
    {
        V f1 = hn::Set(d, 1e9), f2 = f1;
        for (int n = 0; n < 27; ++n) {
            const V dx = hn::Sub(x, hn::Set(d, c[n])), dy = hn::Sub(y, hn::Set(d, c[27 + n]));
            const V dz = hn::Sub(z, hn::Set(d, c[54 + n]));
            keepTwoNearest(hn::Add(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Mul(dz, dz)), f1, f2);
        }
        if (SECOND) return hn::Sub(hn::Mul(hn::Set(d, 2.0), hn::Sqrt(f2)), hn::Set(d, 1.4));
        return hn::Sub(hn::Mul(hn::Set(d, 2.0), hn::Sqrt(f1)), hn::Set(d, 1.0));
    }
};

struct Gradient2
{
    STRATA_LANES static V at(D d, const double* c, V x, V y, V)
    {
        V g[4][2];
        for (int corner = 0; corner < 4; ++corner)
            for (int k = 0; k < 2; ++k) g[corner][k] = hn::Set(d, c[2 * corner + k]);
        return gradientInCell2(d, g, x, y);
    }
};

struct Value2
{
    STRATA_LANES static V at(D d, const double* c, V x, V y, V)
    {
        V corners[4];
        for (int k = 0; k < 4; ++k) corners[k] = hn::Set(d, c[k]);
        return valueInCell2(d, corners, x, y);
    }
};

/// simplexInCell (2D) with corner (a, b)'s gradient in g[2a + b].
STRATA_LANES HWY_INLINE V simplexInCell2(D d, const V (&g)[4][2], V x0, V y0)
{
    const double G2 = (3.0 - 1.7320508075688772) / 6.0; // SIMPLEX2_G
    const V one = hn::Set(d, 1.0), gs = hn::Set(d, G2), g2x = hn::Set(d, 2.0 * G2);
    const auto i1 = hn::Gt(x0, y0); // second corner (1,0) → 2, else (0,1) → 1
    const V di1 = hn::IfThenElseZero(i1, one), dj1 = hn::Sub(one, di1);
    const V gx = hn::IfThenElse(i1, g[2][0], g[1][0]);
    const V gy = hn::IfThenElse(i1, g[2][1], g[1][1]);
    V n = simplexKernel2(d, g[0][0], g[0][1], x0, y0);
    n = hn::Add(n, simplexKernel2(d, gx, gy, hn::Add(hn::Sub(x0, di1), gs), hn::Add(hn::Sub(y0, dj1), gs)));
    n = hn::Add(n, simplexKernel2(d, g[3][0], g[3][1], hn::Add(hn::Sub(x0, one), g2x), hn::Add(hn::Sub(y0, one), g2x)));
    return hn::Mul(hn::Set(d, 99.0), n); // SIMPLEX2_SCALE
}

struct Simplex2
{
    STRATA_LANES static V at(D d, const double* c, V x0, V y0, V)
    {
        V g[4][2];
        for (int corner = 0; corner < 4; ++corner)
            for (int k = 0; k < 2; ++k) g[corner][k] = hn::Set(d, c[2 * corner + k]);
        return simplexInCell2(d, g, x0, y0);
    }
};

template <bool SECOND>
struct Cellular2
{
    STRATA_LANES static V at(D d, const double* c, V x, V y, V)
    {
        V f1 = hn::Set(d, 1e9), f2 = f1;
        for (int n = 0; n < 9; ++n) {
            const V dx = hn::Sub(x, hn::Set(d, c[n])), dy = hn::Sub(y, hn::Set(d, c[9 + n]));
            keepTwoNearest(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), f1, f2);
        }
        if (SECOND) return hn::Sub(hn::Mul(hn::Set(d, 2.0), hn::Sqrt(f2)), hn::Set(d, 1.4));
        return hn::Sub(hn::Mul(hn::Set(d, 2.0), hn::Sqrt(f1)), hn::Set(d, 1.0));
    }
};

// ---- cells hashed in lanes (NoiseHash.h, NoiseKernels.h's gradientCell) ----------
// Where points seldom share a cell (the fine octaves of a fractal sum), each
// lane hashes its own point's cell: 64-bit integer arithmetic, exact, so the
// same gradients as the scalar hash.

using DU = hn::ScalableTag<std::uint64_t>;
using VU = hn::Vec<DU>;

/// a · b mod 2^64 (AVX-512 and the scalar target multiply 64-bit lanes;
/// the others from 32-bit halves).
HWY_INLINE VU mul64(VU a, std::uint64_t b)
{
    const DU du;
#if HWY_TARGET == HWY_SCALAR || HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL
    return a * hn::Set(du, b);
#else
    const hn::Repartition<std::uint32_t, DU> d32;
    const auto bLo = hn::BitCast(d32, hn::Set(du, b & 0xffffffffULL));
    const auto bHi = hn::BitCast(d32, hn::Set(du, b >> 32));
    const auto aLo = hn::BitCast(d32, a), aHi = hn::BitCast(d32, hn::ShiftRight<32>(a));
    const VU cross = hn::Add(hn::MulEven(aHi, bLo), hn::MulEven(aLo, bHi));
    return hn::Add(hn::MulEven(aLo, bLo), hn::ShiftLeft<32>(cross));
#endif
}

HWY_INLINE VU mix64(VU h)
{
    h = hn::Xor(h, hn::ShiftRight<30>(h));
    h = mul64(h, 0xbf58476d1ce4e5b9ULL);
    h = hn::Xor(h, hn::ShiftRight<27>(h));
    h = mul64(h, 0x94d049bb133111ebULL);
    return hn::Xor(h, hn::ShiftRight<31>(h));
}

HWY_INLINE VU hashCombine(VU h, VU v) { return mix64(hn::Xor(h, hn::Add(v, hn::Set(DU(), 0x9e3779b97f4a7c15ULL)))); }

/// latticeIndex() of floors, as 64-bit lanes: beyond ±2^62 (and NaN) saturated.
HWY_INLINE VU latticeIndex(hn::ScalableTag<double> d, hn::Vec<hn::ScalableTag<double>> floor)
{
    constexpr double LIMIT = 4611686018427387904.0; // 2^62
    const auto limit = hn::Set(d, LIMIT);
    const auto saturated = hn::IfThenElse(hn::Gt(floor, hn::Zero(d)), limit, hn::Neg(limit));
    const auto inRange = hn::Lt(hn::Abs(floor), limit);
    const hn::RebindToSigned<decltype(d)> di;
    return hn::BitCast(DU(), hn::ConvertTo(di, hn::IfThenElse(inRange, floor, saturated)));
}

/// pick(h, n): ((h >> 32) · n) >> 32, n < 2^32.
HWY_INLINE VU pick(VU h, std::uint64_t n)
{
    return hn::ShiftRight<32>(mul64(hn::ShiftRight<32>(h), n));
}

/// GRAD3[i] for lane indices i in 0..11: (±1, ±1, 0), (±1, 0, ±1), (0, ±1, ±1),
/// the signs from bits 0 and 1.
HWY_INLINE void gradient3(hn::ScalableTag<double> d, VU index, hn::Vec<decltype(d)> (&g)[3])
{
    const DU du;
    const auto bit0 = hn::RebindMask(d, hn::TestBit(index, hn::Set(du, 1)));
    const auto bit1 = hn::RebindMask(d, hn::TestBit(index, hn::Set(du, 2)));
    const auto first8 = hn::RebindMask(d, hn::Lt(index, hn::Set(du, 8)));
    const auto first4 = hn::RebindMask(d, hn::Lt(index, hn::Set(du, 4)));
    const auto one = hn::Set(d, 1.0), minusOne = hn::Set(d, -1.0), zero = hn::Zero(d);
    const auto sign0 = hn::IfThenElse(bit0, minusOne, one), sign1 = hn::IfThenElse(bit1, minusOne, one);
    g[0] = hn::IfThenElse(first8, sign0, zero);
    g[1] = hn::IfThenElse(first4, sign1, hn::IfThenElse(first8, zero, sign0));
    g[2] = hn::IfThenElse(first4, zero, sign1);
}

/// GRAD2[i] for lane indices i in 0..7: (±1, 0), (0, ±1), (±√½, ±√½).
HWY_INLINE void gradient2(hn::ScalableTag<double> d, VU index, hn::Vec<decltype(d)> (&g)[2])
{
    const DU du;
    const auto bit0 = hn::RebindMask(d, hn::TestBit(index, hn::Set(du, 1)));
    const auto bit1 = hn::RebindMask(d, hn::TestBit(index, hn::Set(du, 2)));
    const auto first2 = hn::RebindMask(d, hn::Lt(index, hn::Set(du, 2)));
    const auto first4 = hn::RebindMask(d, hn::Lt(index, hn::Set(du, 4)));
    const double diag = 0.70710678118654752440; // DIAG
    const auto zero = hn::Zero(d);
    const auto axis = hn::IfThenElse(bit0, hn::Set(d, -1.0), hn::Set(d, 1.0));
    const auto diag0 = hn::IfThenElse(bit0, hn::Set(d, -diag), hn::Set(d, diag));
    const auto diag1 = hn::IfThenElse(bit1, hn::Set(d, -diag), hn::Set(d, diag));
    g[0] = hn::IfThenElse(first2, axis, hn::IfThenElse(first4, zero, diag0));
    g[1] = hn::IfThenElse(first2, zero, hn::IfThenElse(first4, axis, diag1));
}

/// unitInterval() of lane hashes: double(h >> 11)·2^-53, exact.
HWY_INLINE hn::Vec<hn::ScalableTag<double>> unitInterval(VU h)
{
    const hn::ScalableTag<double> d;
    const hn::RebindToSigned<decltype(d)> di;
    return hn::Mul(hn::ConvertTo(d, hn::BitCast(di, hn::ShiftRight<11>(h))), hn::Set(d, 0x1.0p-53));
}

/// latticeValue() of lane hashes: 2·(double(h >> 11)·2^-53) − 1, exact as the scalar one.
HWY_INLINE hn::Vec<hn::ScalableTag<double>> latticeValue(VU h)
{
    const hn::ScalableTag<double> d;
    return hn::Sub(hn::Mul(hn::Set(d, 2.0), unitInterval(h)), hn::Set(d, 1.0));
}

/// cellularCell() and cellularInCell() in lanes, each lane its own point's
/// 3^D cells (z unused in 2D): the feature points' jitters from the same
/// hashes in the same order, the two nearest kept as Cellular3/2 keep them.
/// Returns the nearest (SECOND: second nearest) distance, shaped as the
/// scalar bases shape it.
template <bool SECOND>
HWY_INLINE hn::Vec<hn::ScalableTag<double>> cellularLanes(VU s, VU ci, VU cj, VU ck, bool threeD,
                                                          hn::Vec<hn::ScalableTag<double>> x,
                                                          hn::Vec<hn::ScalableTag<double>> y,
                                                          hn::Vec<hn::ScalableTag<double>> z)
{
    using VD = hn::Vec<hn::ScalableTag<double>>;
    const hn::ScalableTag<double> d;
    const DU du;
    const VU golden = hn::Set(du, 0x9e3779b97f4a7c15ULL);
    const VD jitterMin = hn::Set(d, 0.3), jitterSpan = hn::Set(d, 0.4); // JITTER_MIN, JITTER_SPAN
    const auto jitter = [&](VU h) { return hn::Add(jitterMin, hn::Mul(jitterSpan, unitInterval(h))); };
    VD f1 = hn::Set(d, 1e9), f2 = f1;
    for (int a = -1; a <= 1; ++a) {
        const VU ha = hashCombine(s, hn::Add(ci, hn::Set(du, std::uint64_t(std::int64_t(a)))));
        for (int b = -1; b <= 1; ++b) {
            const VU hb = hashCombine(ha, hn::Add(cj, hn::Set(du, std::uint64_t(std::int64_t(b)))));
            if (!threeD) {
                VU h = hb;
                const VD jx = jitter(h);
                h = mix64(hn::Add(h, golden));
                const VD jy = jitter(h);
                const VD dx = hn::Sub(x, hn::Add(hn::Set(d, double(a)), jx));
                const VD dy = hn::Sub(y, hn::Add(hn::Set(d, double(b)), jy));
                keepTwoNearest(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), f1, f2);
                continue;
            }
            for (int c = -1; c <= 1; ++c) {
                VU h = hashCombine(hb, hn::Add(ck, hn::Set(du, std::uint64_t(std::int64_t(c)))));
                const VD jx = jitter(h);
                h = mix64(hn::Add(h, golden));
                const VD jy = jitter(h);
                h = mix64(hn::Add(h, golden));
                const VD jz = jitter(h);
                const VD dx = hn::Sub(x, hn::Add(hn::Set(d, double(a)), jx));
                const VD dy = hn::Sub(y, hn::Add(hn::Set(d, double(b)), jy));
                const VD dz = hn::Sub(z, hn::Add(hn::Set(d, double(c)), jz));
                keepTwoNearest(hn::Add(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Mul(dz, dz)), f1, f2);
            }
        }
    }
    if (SECOND) return hn::Sub(hn::Mul(hn::Set(d, 2.0), hn::Sqrt(f2)), hn::Set(d, 1.4));
    return hn::Sub(hn::Mul(hn::Set(d, 2.0), hn::Sqrt(f1)), hn::Set(d, 1.0));
}

/// The corner values of value noise cells (NoiseKernels.h's valueCell),
/// each lane its own cell: corner (a, b, c) in v[4a + 2b + c] (3D; 2D:
/// (a, b) in v[2a + b]).
HWY_INLINE void valueCorners(VU s, VU ci, VU cj, VU ck, bool threeD, hn::Vec<hn::ScalableTag<double>> (&v)[8])
{
    const VU one = hn::Set(DU(), 1);
    const VU hx[2] = {hashCombine(s, ci), hashCombine(s, hn::Add(ci, one))};
    for (int a = 0; a < 2; ++a) {
        if (!threeD) {
            v[2 * a] = latticeValue(hashCombine(hx[a], cj));
            v[2 * a + 1] = latticeValue(hashCombine(hx[a], hn::Add(cj, one)));
            continue;
        }
        for (int b = 0; b < 2; ++b) {
            const VU h = hashCombine(hx[a], b ? hn::Add(cj, one) : cj);
            v[4 * a + 2 * b] = latticeValue(hashCombine(h, ck));
            v[4 * a + 2 * b + 1] = latticeValue(hashCombine(h, hn::Add(ck, one)));
        }
    }
}

/// The corner gradients of gradient (and simplex) noise cells
/// (gradientCell, simplexCell: the same hashes), each lane its own cell:
/// corner (a, b, c)'s in g[4a + 2b + c][0..2] (3D; 2D: (a, b)'s in
/// g[2a + b][0..1]).
HWY_INLINE void gradientCorners(VU s, VU ci, VU cj, VU ck, bool threeD, hn::Vec<hn::ScalableTag<double>> (&g)[8][3])
{
    const hn::ScalableTag<double> d;
    const VU one = hn::Set(DU(), 1);
    const VU hx[2] = {hashCombine(s, ci), hashCombine(s, hn::Add(ci, one))};
    for (int a = 0; a < 2; ++a) {
        if (!threeD) {
            hn::Vec<decltype(d)> g2[2][2];
            gradient2(d, pick(hashCombine(hx[a], cj), 8), g2[0]);
            gradient2(d, pick(hashCombine(hx[a], hn::Add(cj, one)), 8), g2[1]);
            for (int b = 0; b < 2; ++b) {
                g[2 * a + b][0] = g2[b][0];
                g[2 * a + b][1] = g2[b][1];
            }
            continue;
        }
        for (int b = 0; b < 2; ++b) {
            const VU h = hashCombine(hx[a], b ? hn::Add(cj, one) : cj);
            gradient3(d, pick(hashCombine(h, ck), 12), g[4 * a + 2 * b]);
            gradient3(d, pick(hashCombine(h, hn::Add(ck, one)), 12), g[4 * a + 2 * b + 1]);
        }
    }
}

void HashedLanesImpl(LaneBasis basis, std::uint64_t seed, const SplitPoints& p, std::size_t n, bool threeD, double* out)
{
    using DD = hn::ScalableTag<double>;
    using VD = hn::Vec<DD>;
    const DD d;
    const DU du;
    const std::size_t lanes = hn::Lanes(d);
    const VU s = hn::Set(du, seed);
    HWY_ALIGN double b[6][MAX_LANES] = {};
    HWY_ALIGN double result[MAX_LANES];
    for (std::size_t i = 0; i < n; i += lanes) {
        const bool full = i + lanes <= n;
        const double* src[6] = {p.cellX + i, p.cellY + i, threeD ? p.cellZ + i : nullptr, p.x + i, p.y + i,
                                threeD ? p.z + i : nullptr};
        if (!full) { // the tail, zero-padded
            for (int a = 0; a < 6; ++a) {
                if (src[a]) std::copy(src[a], src[a] + (n - i), b[a]);
                src[a] = b[a];
            }
        }
        const VU ci = latticeIndex(d, hn::LoadU(d, src[0])), cj = latticeIndex(d, hn::LoadU(d, src[1]));
        const VU ck = threeD ? latticeIndex(d, hn::LoadU(d, src[2])) : hn::Zero(du);
        const VD x = hn::LoadU(d, src[3]), y = hn::LoadU(d, src[4]), z = threeD ? hn::LoadU(d, src[5]) : hn::Zero(d);
        VD value;
        switch (basis) {
        case LaneBasis::CELLULAR_F1: value = cellularLanes<false>(s, ci, cj, ck, threeD, x, y, z); break;
        case LaneBasis::CELLULAR_F2: value = cellularLanes<true>(s, ci, cj, ck, threeD, x, y, z); break;
        case LaneBasis::VALUE: {
            VD c[8];
            valueCorners(s, ci, cj, ck, threeD, c);
            if (threeD) {
                value = valueInCell3(d, c, x, y, z);
            } else {
                const VD c2[4] = {c[0], c[1], c[2], c[3]};
                value = valueInCell2(d, c2, x, y);
            }
            break;
        }
        default: {
            VD g[8][3];
            gradientCorners(s, ci, cj, ck, threeD, g);
            const bool simplex = basis == LaneBasis::SIMPLEX;
            if (threeD) {
                value = simplex ? simplexInCell3(d, g, x, y, z) : gradientInCell3(d, g, x, y, z);
            } else {
                const VD g2[4][2] = {{g[0][0], g[0][1]}, {g[1][0], g[1][1]}, {g[2][0], g[2][1]}, {g[3][0], g[3][1]}};
                value = simplex ? simplexInCell2(d, g2, x, y) : gradientInCell2(d, g2, x, y);
            }
        }
        }
        if (full) {
            hn::StoreU(value, d, out + i);
        } else {
            hn::Store(value, d, result);
            std::copy(result, result + (n - i), out + i);
        }
    }
}

void CellDataLanesImpl(InCell kind, std::uint64_t seed, const double* cellX, const double* cellY, const double* cellZ,
                       std::size_t count, double* out)
{
    using DD = hn::ScalableTag<double>;
    using VD = hn::Vec<DD>;
    const DD d;
    const DU du;
    const std::size_t lanes = hn::Lanes(d);
    const bool threeD = kind == InCell::GRADIENT3 || kind == InCell::SIMPLEX3 || kind == InCell::VALUE3;
    const bool value = kind == InCell::VALUE3 || kind == InCell::VALUE2;
    const std::size_t size = cellSize(kind);
    const VU s = hn::Set(du, seed);
    HWY_ALIGN double b[3][MAX_LANES] = {};
    HWY_ALIGN double lane[24][MAX_LANES];
    for (std::size_t i = 0; i < count; i += lanes) {
        const std::size_t m = std::min(lanes, count - i);
        const double* src[3] = {cellX + i, cellY + i, threeD ? cellZ + i : nullptr};
        if (m < lanes) {
            for (int a = 0; a < 3; ++a) {
                if (src[a]) std::copy(src[a], src[a] + m, b[a]);
                src[a] = b[a];
            }
        }
        const VU ci = latticeIndex(d, hn::LoadU(d, src[0])), cj = latticeIndex(d, hn::LoadU(d, src[1]));
        const VU ck = threeD ? latticeIndex(d, hn::LoadU(d, src[2])) : hn::Zero(du);
        const int corners = threeD ? 8 : 4;
        if (value) {
            VD v[8];
            valueCorners(s, ci, cj, ck, threeD, v);
            for (int c = 0; c < corners; ++c) hn::Store(v[c], d, lane[c]);
        } else {
            VD g[8][3];
            gradientCorners(s, ci, cj, ck, threeD, g);
            const int dims = threeD ? 3 : 2;
            for (int c = 0; c < corners; ++c)
                for (int k = 0; k < dims; ++k) hn::Store(g[c][k], d, lane[dims * c + k]);
        }
        // NoiseSimd.h's layouts: cell r's data at out + r·size, in the order stored above.
        for (std::size_t r = 0; r < m; ++r)
            for (std::size_t k = 0; k < size; ++k) out[(i + r) * size + k] = lane[k][r];
    }
}

// ---- drivers ------------------------------------------------------------------

/// Kernel over the points [i, end) of one cell, as many as fill whole
/// vectors of d's lanes; returns where it stopped.
template <class Kernel, class D>
HWY_INLINE std::size_t withLanes(D d, const double* cell, std::size_t i, std::size_t end, const double* x,
                                 const double* y, const double* z, double* out)
{
    const std::size_t lanes = hn::Lanes(d);
    for (; i + lanes <= end; i += lanes) {
        const auto vz = z ? hn::LoadU(d, z + i) : hn::Zero(d);
        hn::StoreU(Kernel::at(d, cell, hn::LoadU(d, x + i), hn::LoadU(d, y + i), vz), d, out + i);
    }
    return i;
}

template <class Kernel>
void overRuns(const CellRuns& runs, std::size_t size, const double* x, const double* y, const double* z, double* out)
{
    std::size_t begin = 0;
    for (std::size_t r = 0; r < runs.count; ++r) {
        const std::size_t end = runs.end[r];
        const double* cell = runs.cells + r * size;
        std::size_t i = withLanes<Kernel>(hn::ScalableTag<double>(), cell, begin, end, x, y, z, out);
        i = withLanes<Kernel>(hn::CappedTag<double, 4>(), cell, i, end, x, y, z, out);
        i = withLanes<Kernel>(hn::CappedTag<double, 2>(), cell, i, end, x, y, z, out);
        withLanes<Kernel>(hn::CappedTag<double, 1>(), cell, i, end, x, y, z, out);
        begin = end;
    }
}

void EvaluateRuns(InCell kind, const CellRuns& runs, const double* x, const double* y, const double* z, double* out)
{
    const std::size_t size = cellSize(kind);
    switch (kind) {
    case InCell::GRADIENT3: return overRuns<Gradient3>(runs, size, x, y, z, out);
    case InCell::VALUE3: return overRuns<Value3>(runs, size, x, y, z, out);
    case InCell::SIMPLEX3: return overRuns<Simplex3>(runs, size, x, y, z, out);
    case InCell::CELLULAR3_F1: return overRuns<Cellular3<false>>(runs, size, x, y, z, out);
    case InCell::CELLULAR3_F2: return overRuns<Cellular3<true>>(runs, size, x, y, z, out);
    case InCell::GRADIENT2: return overRuns<Gradient2>(runs, size, x, y, nullptr, out);
    case InCell::VALUE2: return overRuns<Value2>(runs, size, x, y, nullptr, out);
    case InCell::SIMPLEX2: return overRuns<Simplex2>(runs, size, x, y, nullptr, out);
    case InCell::CELLULAR2_F1: return overRuns<Cellular2<false>>(runs, size, x, y, nullptr, out);
    case InCell::CELLULAR2_F2: return overRuns<Cellular2<true>>(runs, size, x, y, nullptr, out);
    }
}

// splitCube / splitSquare / splitSimplex (NoiseKernels.h), lane-wise
// (NoiseSplit-inl.h, shared with version 2).
struct Splitter
{
    Lattice lattice;
    bool threeD;

    STRATA_LANES void operator()(D d, V x, V y, V z, V& cx, V& cy, V& cz, V& fx, V& fy, V& fz) const
    {
        splitLattice(d, lattice == Lattice::SIMPLEX, threeD, x, y, z, cx, cy, cz, fx, fy, fz);
    }
};

void SplitPointsImpl(Lattice lattice, const double* x, const double* y, const double* z, std::size_t n,
                     const SplitPoints& o)
{
    using V = hn::Vec<hn::ScalableTag<double>>;
    const hn::ScalableTag<double> d;
    const std::size_t lanes = hn::Lanes(d);
    const bool threeD = z != nullptr;
    const Splitter split{lattice, threeD};
    std::size_t i = 0;
    for (; i + lanes <= n; i += lanes) {
        V cx, cy, cz, fx, fy, fz;
        split(d, hn::LoadU(d, x + i), hn::LoadU(d, y + i), threeD ? hn::LoadU(d, z + i) : hn::Zero(d), cx, cy, cz,
              fx, fy, fz);
        hn::StoreU(cx, d, o.cellX + i);
        hn::StoreU(cy, d, o.cellY + i);
        hn::StoreU(fx, d, o.x + i);
        hn::StoreU(fy, d, o.y + i);
        if (threeD) {
            hn::StoreU(cz, d, o.cellZ + i);
            hn::StoreU(fz, d, o.z + i);
        }
    }
    if (i < n) {
        HWY_ALIGN double b[9][MAX_LANES] = {};
        const std::size_t m = n - i;
        std::copy(x + i, x + n, b[0]);
        std::copy(y + i, y + n, b[1]);
        if (threeD) std::copy(z + i, z + n, b[2]);
        V cx, cy, cz, fx, fy, fz;
        split(d, hn::Load(d, b[0]), hn::Load(d, b[1]), hn::Load(d, b[2]), cx, cy, cz, fx, fy, fz);
        hn::Store(cx, d, b[3]);
        hn::Store(cy, d, b[4]);
        hn::Store(cz, d, b[5]);
        hn::Store(fx, d, b[6]);
        hn::Store(fy, d, b[7]);
        hn::Store(fz, d, b[8]);
        std::copy(b[3], b[3] + m, o.cellX + i);
        std::copy(b[4], b[4] + m, o.cellY + i);
        std::copy(b[6], b[6] + m, o.x + i);
        std::copy(b[7], b[7] + m, o.y + i);
        if (threeD) {
            std::copy(b[5], b[5] + m, o.cellZ + i);
            std::copy(b[8], b[8] + m, o.z + i);
        }
    }
}

#undef STRATA_LANES

const char* TargetInUse() { return hwy::TargetName(HWY_TARGET); }

/// Whether 64-bit lanes multiply natively: then hashing in lanes is twice
/// as fast as reusing cells for 5-octave fBm (strata bench noise, AVX3: 18
/// against 9.5 M points/s). Elsewhere the multiply is made of three and
/// reusing cells wins (AVX2 fBm: 6 against 10).
bool NativeLaneHashingImpl() { return HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL; }

} // namespace HWY_NAMESPACE
} // namespace strata::terrain::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace strata::terrain {
namespace detail {

HWY_EXPORT(EvaluateRuns);
HWY_EXPORT(SplitPointsImpl);
HWY_EXPORT(TargetInUse);
HWY_EXPORT(HashedLanesImpl);
HWY_EXPORT(CellDataLanesImpl);
HWY_EXPORT(NativeLaneHashingImpl);

namespace {

/// The target Strata's noise runs on: our own hwy::ChosenTarget, not
/// Highway's process-wide one (hwy::GetChosenTarget()), so choosing a
/// target here changes nothing for other Highway users in the process, and
/// no test-only Highway call (SetSupportedTargetsForTest) ships. Its
/// GetIndex() is the index into the HWY_EXPORT tables of this file for the
/// best target its mask holds; Update(SupportedTargets()) is what
/// HWY_DYNAMIC_DISPATCH does on its first call.
hwy::ChosenTarget& chosenTarget()
{
    static hwy::ChosenTarget target;
    static const bool initialized = [] {
        target.Update(hwy::SupportedTargets());
        return true;
    }();
    (void)initialized;
    return target;
}

} // namespace

// HWY_DYNAMIC_DISPATCH with chosenTarget() in place of Highway's global.
#if HWY_IDE || ((HWY_TARGETS & (HWY_TARGETS - 1)) == 0)
#define STRATA_DISPATCH(FUNC_NAME) HWY_STATIC_DISPATCH(FUNC_NAME)
#else
#define STRATA_DISPATCH(FUNC_NAME) (*(HWY_DISPATCH_TABLE(FUNC_NAME)[::strata::terrain::detail::chosenTarget().GetIndex()]))
#endif

bool nativeLaneHashing() { return STRATA_DISPATCH(NativeLaneHashingImpl)(); }

std::size_t noiseTargetIndex() { return std::size_t(chosenTarget().GetIndex()); }

// Called from inside namespace detail: with a single target (aarch64 has
// NEON alone) the dispatch names the function in the target's namespace.
std::string targetInUse() { return STRATA_DISPATCH(TargetInUse)(); }

void hashedLanes(LaneBasis basis, std::uint64_t seed, const SplitPoints& split, std::size_t n, bool threeD, double* out)
{
    STRATA_DISPATCH(HashedLanesImpl)(basis, seed, split, n, threeD, out);
}

void cellDataLanes(InCell kind, std::uint64_t seed, const double* cellX, const double* cellY, const double* cellZ,
                   std::size_t count, double* out)
{
    STRATA_DISPATCH(CellDataLanesImpl)(kind, seed, cellX, cellY, cellZ, count, out);
}

std::size_t cellSize(InCell kind)
{
    switch (kind) {
    case InCell::GRADIENT3:
    case InCell::SIMPLEX3: return 24;
    case InCell::VALUE3: return 8;
    case InCell::CELLULAR3_F1:
    case InCell::CELLULAR3_F2: return 81;
    case InCell::GRADIENT2:
    case InCell::SIMPLEX2: return 8;
    case InCell::VALUE2: return 4;
    case InCell::CELLULAR2_F1:
    case InCell::CELLULAR2_F2: return 18;
    }
    return 0;
}

void evaluateRuns(InCell kind, const CellRuns& runs, const double* x, const double* y, const double* z, double* out)
{
    STRATA_DISPATCH(EvaluateRuns)(kind, runs, x, y, z, out);
}

void splitPoints(Lattice lattice, const double* x, const double* y, const double* z, std::size_t n,
                 const SplitPoints& out)
{
    STRATA_DISPATCH(SplitPointsImpl)(lattice, x, y, z, n, out);
}

} // namespace detail

std::vector<std::string> availableSimdTargets()
{
    std::vector<std::string> list; // Highway numbers better targets with lower bits: best first
    for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) list.emplace_back(hwy::TargetName(target));
    return list;
}

std::string simdTarget() { return detail::targetInUse(); }

void useSimdTarget(const std::string& name)
{
    if (name.empty()) {
        detail::chosenTarget().Update(hwy::SupportedTargets());
        return;
    }
    for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
        if (name == hwy::TargetName(target)) {
            // The mask holds this target and the fallback: GetIndex() picks this one.
            detail::chosenTarget().Update(target);
            return;
        }
    }
    std::string list;
    for (const std::string& n : availableSimdTargets()) list += (list.empty() ? "" : ", ") + n;
    throw Error(ErrorKind::BadInput, "unknown SIMD target '" + name + "' (this machine: " + list + ")",
                {.value = name});
}

} // namespace strata::terrain
#endif // HWY_ONCE
