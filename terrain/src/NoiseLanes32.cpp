// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Noise version 2's bases (NoiseSimd.h, "version 2"): every point in its
// own float lane, its lattice cell hashed in 32-bit integer lanes. Version 1
// hashes 64-bit cells once per run of points and does the arithmetic in
// double; here nothing is shared between points and every lane does the
// whole basis, which is what float lanes and 32-bit multiplies (native on
// SSE4, AVX2, AVX-512 and NEON) make cheap.
//
// The bits: every operation is IEEE single precision, unfused
// (-ffp-contract=off; no MulAdd), in the order written, and Sqrt and the
// integer-to-float conversions are exactly rounded, so every target gives
// the same bits; the SCALAR target is the reference. A point's value depends
// on its own cell and offset only, never on its lane or its neighbours.

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "NoiseLanes32.cpp" // found through this folder's include path
#include <hwy/foreach_target.h> // IWYU pragma: keep
#include <hwy/highway.h>

#include "NoiseHash.h"
#include "NoiseSimd.h"
#include "NoiseSplit-inl.h"

#include <algorithm>

HWY_BEFORE_NAMESPACE();
namespace strata::terrain::detail {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;

using DF = hn::ScalableTag<float>;
using DU = hn::RebindToUnsigned<DF>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VU = hn::Vec<DU>;
using MF = hn::Mask<DF>;

constexpr std::size_t MAX_FLOAT_LANES = HWY_MAX_BYTES / sizeof(float);

// ---- the lattice hash ----------------------------------------------------------

// Odd multipliers per axis for the low and the high 32 bits of a cell index
// (NoiseHash.h's hash32, the scalar form).
using hash32::HIGH_PRIME;
using hash32::LOW_PRIME;

/// One axis of a point's cell, i = hi·2^32 + lo, as the two products its
/// term T(i) = lo·P ^ hi·Q is made of.
// The structs of vectors below have user-provided constructors: GCC
// defines implicit ones outside the target's attributes, which NEON's
// always-inline vector constructors refuse.
struct Axis
{
    VU lo, loP, hiQ;
    HWY_INLINE Axis() {}
    HWY_INLINE Axis(VU low, VU lowP, VU highQ) : lo(low), loP(lowP), hiQ(highQ) {}
};

HWY_INLINE Axis axis(DU du, VU lo, VU hi, int a)
{
    return Axis(lo, hn::Mul(lo, hn::Set(du, LOW_PRIME[a])), hn::Mul(hi, hn::Set(du, HIGH_PRIME[a])));
}

/// T(i + k) for k in {−1, 0, 1}, from T(i)'s products: (lo + k)·P is lo·P + k·P
/// modulo 2^32, and the high word moves by one where the low word wraps, so
/// a cell's term is the same from whichever neighbour it is reached.
HWY_INLINE VU term(DU du, const Axis& x, int k, int a)
{
    if (k == 0) return hn::Xor(x.loP, x.hiQ);
    const VU p = hn::Set(du, LOW_PRIME[a]), q = hn::Set(du, HIGH_PRIME[a]);
    if (k > 0) {
        const auto wraps = hn::Eq(x.lo, hn::Set(du, 0xFFFFFFFFu));
        return hn::Xor(hn::Add(x.loP, p), hn::Add(x.hiQ, hn::IfThenElseZero(wraps, q)));
    }
    const auto wraps = hn::Eq(x.lo, hn::Zero(du));
    return hn::Xor(hn::Sub(x.loP, p), hn::Sub(x.hiQ, hn::IfThenElseZero(wraps, q)));
}

/// Chris Wellons' lowbias32 (common/include/strata/detail/IntegerHash.h), in lanes.
HWY_INLINE VU lowbias32(DU du, VU h)
{
    h = hn::Xor(h, hn::ShiftRight<16>(h));
    h = hn::Mul(h, hn::Set(du, 0x7feb352du));
    h = hn::Xor(h, hn::ShiftRight<15>(h));
    h = hn::Mul(h, hn::Set(du, 0x846ca68bu));
    return hn::Xor(h, hn::ShiftRight<16>(h));
}

/// A corner's hash: the seed and its three axis terms, avalanched.
HWY_INLINE VU cornerHash(DU du, VU seed, VU tx, VU ty, VU tz) { return lowbias32(du, hn::Xor(hn::Xor(seed, tx), hn::Xor(ty, tz))); }

// ---- what a hash gives a corner --------------------------------------------------

HWY_INLINE VF signOf(VU bit) { return hn::BitCast(DF(), hn::And(bit, hn::Set(DU(), 0x80000000u))); }

/// g·(x, y, z) for the gradient the top 4 bits pick from Perlin's 16 (the 12
/// cube edges, 4 of them twice): ±u ± v, exact sign flips and one add.
HWY_INLINE VF gradientDot3(VU h, VF x, VF y, VF z)
{
    const DU du;
    const DF df;
    const VU index = hn::ShiftRight<28>(h);
    const MF below8 = hn::RebindMask(df, hn::Lt(hn::BitCast(DI(), index), hn::Set(DI(), 8)));
    const MF below4 = hn::RebindMask(df, hn::Lt(hn::BitCast(DI(), index), hn::Set(DI(), 4)));
    const MF twelveOr14 = hn::RebindMask(df, hn::Eq(hn::Or(index, hn::Set(du, 2u)), hn::Set(du, 14u)));
    const VF u = hn::IfThenElse(below8, x, y);
    const VF v = hn::IfThenElse(below4, y, hn::IfThenElse(twelveOr14, x, z));
    return hn::Add(hn::Xor(u, signOf(hn::ShiftLeft<3>(h))), hn::Xor(v, signOf(hn::ShiftLeft<2>(h))));
}

/// g·(x, y) for the one of 8 unit directions (4 axes, 4 diagonals) the top
/// 3 bits pick, as version 1's set.
HWY_INLINE VF gradientDot2(VU h, VF x, VF y)
{
    const DF df;
    const DU du;
    const VF sx = signOf(hn::ShiftLeft<2>(h)), sy = signOf(hn::ShiftLeft<1>(h));
    const MF diagonal = hn::RebindMask(df, hn::Lt(hn::BitCast(DI(), h), hn::Zero(DI())));
    const MF yAxis = hn::RebindMask(df, hn::Ne(hn::And(h, hn::Set(du, 0x40000000u)), hn::Zero(du)));
    const VF along = hn::Xor(hn::IfThenElse(yAxis, y, x), sx);
    const VF across = hn::Mul(hn::Set(df, 0.70710678118654752440f), hn::Add(hn::Xor(x, sx), hn::Xor(y, sy)));
    return hn::IfThenElse(diagonal, across, along);
}

/// A lattice value in [−1, 1): the hash as a signed integer times 2^−31.
HWY_INLINE VF latticeValue(VU h)
{
    return hn::Mul(hn::ConvertTo(DF(), hn::BitCast(DI(), h)), hn::Set(DF(), 0x1.0p-31f));
}

/// A feature point's offset in its cell, in [0.3, 0.7): 10 bits of the hash
/// from bit `shift` (JITTER_MIN, JITTER_SPAN of NoiseKernels.h).
template <int SHIFT>
HWY_INLINE VF jitter(VU h)
{
    const DF df;
    const VF u = hn::Mul(hn::ConvertTo(df, hn::BitCast(DI(), hn::And(hn::ShiftRight<SHIFT>(h), hn::Set(DU(), 1023u)))),
                         hn::Set(df, 0x1.0p-10f));
    return hn::Add(hn::Set(df, 0.3f), hn::Mul(hn::Set(df, 0.4f), u));
}

// ---- arithmetic ------------------------------------------------------------------

HWY_INLINE VF fade(VF t)
{
    const DF df;
    // t * t * t * (t * (t * 6 - 15) + 10), as version 1
    const VF cube = hn::Mul(hn::Mul(t, t), t);
    return hn::Mul(cube, hn::Add(hn::Mul(t, hn::Sub(hn::Mul(t, hn::Set(df, 6.0f)), hn::Set(df, 15.0f))),
                                 hn::Set(df, 10.0f)));
}

HWY_INLINE VF lerp(VF a, VF b, VF t) { return hn::Add(a, hn::Mul(t, hn::Sub(b, a))); }

/// A point: its cell's axes and its offset in the cell.
struct Point
{
    Axis axes[3];
    VF f[3];
    HWY_INLINE Point() {}
};

// ---- the bases -------------------------------------------------------------------

/// The hash of 2D corner (a, b) from cellTerms()'s terms: a 2D corner's z term is 0.
HWY_INLINE VU cornerHash2(VU s, const VU (&t)[3][2], int a, int b)
{
    return cornerHash(DU(), s, t[0][a], t[1][b], hn::Zero(DU()));
}

/// T(i) and T(i + 1) on each axis: the terms of the cell's 8 corners (4 in 2D).
HWY_INLINE void cellTerms(const Point& p, VU (&t)[3][2])
{
    const DU du;
    for (int a = 0; a < 3; ++a) {
        t[a][0] = term(du, p.axes[a], 0, a);
        t[a][1] = term(du, p.axes[a], 1, a);
    }
}

VF gradient3(VU s, const Point& p)
{
    const DU du;
    const DF df;
    VU t[3][2];
    cellTerms(p, t);
    const VF one = hn::Set(df, 1.0f);
    const VF x = p.f[0], y = p.f[1], z = p.f[2];
    const VF x1 = hn::Sub(x, one), y1 = hn::Sub(y, one), z1 = hn::Sub(z, one);
    const auto dot = [&](int a, int b, int c, VF px, VF py, VF pz) {
        return gradientDot3(cornerHash(du, s, t[0][a], t[1][b], t[2][c]), px, py, pz);
    };
    const VF n000 = dot(0, 0, 0, x, y, z), n001 = dot(0, 0, 1, x, y, z1);
    const VF n010 = dot(0, 1, 0, x, y1, z), n011 = dot(0, 1, 1, x, y1, z1);
    const VF n100 = dot(1, 0, 0, x1, y, z), n101 = dot(1, 0, 1, x1, y, z1);
    const VF n110 = dot(1, 1, 0, x1, y1, z), n111 = dot(1, 1, 1, x1, y1, z1);
    const VF u = fade(x), v = fade(y), w = fade(z);
    const VF n00 = lerp(n000, n001, w), n01 = lerp(n010, n011, w);
    const VF n10 = lerp(n100, n101, w), n11 = lerp(n110, n111, w);
    return lerp(lerp(n00, n01, v), lerp(n10, n11, v), u);
}

VF gradient2(VU s, const Point& p)
{
    const DF df;
    VU t[3][2];
    cellTerms(p, t); // z's terms unused in 2D
    const VF one = hn::Set(df, 1.0f);
    const VF x = p.f[0], y = p.f[1], x1 = hn::Sub(x, one), y1 = hn::Sub(y, one);
    const VF n00 = gradientDot2(cornerHash2(s, t, 0, 0), x, y);
    const VF n01 = gradientDot2(cornerHash2(s, t, 0, 1), x, y1);
    const VF n10 = gradientDot2(cornerHash2(s, t, 1, 0), x1, y);
    const VF n11 = gradientDot2(cornerHash2(s, t, 1, 1), x1, y1);
    const VF u = fade(x), v = fade(y);
    return hn::Mul(hn::Set(df, 1.41421356237309504880f), lerp(lerp(n00, n01, v), lerp(n10, n11, v), u)); // NOISE2_SCALE
}

VF value3(VU s, const Point& p)
{
    const DU du;
    VU t[3][2];
    cellTerms(p, t);
    VF c[8];
    for (int corner = 0; corner < 8; ++corner)
        c[corner] = latticeValue(cornerHash(du, s, t[0][corner >> 2], t[1][(corner >> 1) & 1], t[2][corner & 1]));
    const VF u = fade(p.f[0]), v = fade(p.f[1]), w = fade(p.f[2]);
    const VF n00 = lerp(c[0], c[1], w), n01 = lerp(c[2], c[3], w);
    const VF n10 = lerp(c[4], c[5], w), n11 = lerp(c[6], c[7], w);
    return lerp(lerp(n00, n01, v), lerp(n10, n11, v), u);
}

VF value2(VU s, const Point& p)
{
    VU t[3][2];
    cellTerms(p, t); // z's terms unused in 2D
    const VF c00 = latticeValue(cornerHash2(s, t, 0, 0)), c01 = latticeValue(cornerHash2(s, t, 0, 1));
    const VF c10 = latticeValue(cornerHash2(s, t, 1, 0)), c11 = latticeValue(cornerHash2(s, t, 1, 1));
    const VF u = fade(p.f[0]), v = fade(p.f[1]);
    return lerp(lerp(c00, c01, v), lerp(c10, c11, v), u);
}

/// The radial kernel max(0.5 − r², 0)⁴ (KERNEL_R2 of NoiseKernels.h).
HWY_INLINE VF kernelWeight(VF r2)
{
    const DF df;
    const VF t = hn::Max(hn::Sub(hn::Set(df, 0.5f), r2), hn::Zero(df));
    const VF t2 = hn::Mul(t, t);
    return hn::Mul(t2, t2);
}

HWY_INLINE VF simplexCorner3(VU h, VF x, VF y, VF z)
{
    const VF r2 = hn::Add(hn::Add(hn::Mul(x, x), hn::Mul(y, y)), hn::Mul(z, z));
    return hn::Mul(kernelWeight(r2), gradientDot3(h, x, y, z));
}

/// On points split on the simplex lattice (the skewed cube's floor, the
/// unskewed offset from its first corner).
VF simplex3(VU s, const Point& p)
{
    const DU du;
    const DF df;
    VU t[3][2];
    cellTerms(p, t);
    const VF x0 = p.f[0], y0 = p.f[1], z0 = p.f[2];
    const MF xy = hn::Ge(x0, y0), yz = hn::Ge(y0, z0), xz = hn::Ge(x0, z0);
    // The simplex's second corner steps along the largest offset, its third
    // along the two largest (version 1's table, written as masks).
    const MF first[3] = {hn::And(xy, xz), hn::AndNot(xy, yz), hn::AndNot(xz, hn::Not(yz))};
    const MF second[3] = {hn::Or(xy, xz), hn::Or(hn::Not(xy), yz), hn::Not(hn::And(xz, yz))};
    const VF one = hn::Set(df, 1.0f);
    const VF g1 = hn::Set(df, 1.0f / 6.0f), g2 = hn::Set(df, 1.0f / 3.0f), g3 = hn::Set(df, 0.5f);
    const VU hash0 = cornerHash(du, s, t[0][0], t[1][0], t[2][0]);
    const VU hash3 = cornerHash(du, s, t[0][1], t[1][1], t[2][1]);
    VU th1[3], th2[3];
    VF d1[3], d2[3];
    for (int a = 0; a < 3; ++a) {
        th1[a] = hn::IfThenElse(hn::RebindMask(du, first[a]), t[a][1], t[a][0]);
        th2[a] = hn::IfThenElse(hn::RebindMask(du, second[a]), t[a][1], t[a][0]);
        d1[a] = hn::Add(hn::Sub(p.f[a], hn::IfThenElseZero(first[a], one)), g1);
        d2[a] = hn::Add(hn::Sub(p.f[a], hn::IfThenElseZero(second[a], one)), g2);
    }
    VF n = simplexCorner3(hash0, x0, y0, z0);
    n = hn::Add(n, simplexCorner3(cornerHash(du, s, th1[0], th1[1], th1[2]), d1[0], d1[1], d1[2]));
    n = hn::Add(n, simplexCorner3(cornerHash(du, s, th2[0], th2[1], th2[2]), d2[0], d2[1], d2[2]));
    n = hn::Add(n, simplexCorner3(hash3, hn::Add(hn::Sub(x0, one), g3), hn::Add(hn::Sub(y0, one), g3),
                                  hn::Add(hn::Sub(z0, one), g3)));
    return hn::Mul(hn::Set(df, 77.0f), n); // SIMPLEX3_SCALE
}

VF simplex2(VU s, const Point& p)
{
    const DU du;
    const DF df;
    VU t[3][2];
    cellTerms(p, t); // z's terms unused in 2D
    const VF x0 = p.f[0], y0 = p.f[1];
    const MF alongX = hn::Gt(x0, y0); // the middle corner: (1, 0) below the diagonal, else (0, 1)
    const VF one = hn::Set(df, 1.0f);
    const VF g = hn::Set(df, float((3.0 - 1.7320508075688772) / 6.0)); // SIMPLEX2_G
    const VF g2 = hn::Add(g, g);
    const auto corner = [&](VU h, VF x, VF y) {
        return hn::Mul(kernelWeight(hn::Add(hn::Mul(x, x), hn::Mul(y, y))), gradientDot2(h, x, y));
    };
    const auto mx = hn::RebindMask(du, alongX);
    VF n = corner(cornerHash2(s, t, 0, 0), x0, y0);
    n = hn::Add(n, corner(cornerHash(du, s, hn::IfThenElse(mx, t[0][1], t[0][0]), hn::IfThenElse(mx, t[1][0], t[1][1]), hn::Zero(du)),
                          hn::Add(hn::Sub(x0, hn::IfThenElseZero(alongX, one)), g),
                          hn::Add(hn::Sub(y0, hn::IfThenElse(alongX, hn::Zero(df), one)), g)));
    n = hn::Add(n, corner(cornerHash2(s, t, 1, 1), hn::Add(hn::Sub(x0, one), g2),
                          hn::Add(hn::Sub(y0, one), g2)));
    return hn::Mul(hn::Set(df, 99.0f), n); // SIMPLEX2_SCALE
}

/// Keeps the two smallest squared distances (f1 <= f2).
HWY_INLINE void keepTwoNearest(VF d2, VF& f1, VF& f2)
{
    f2 = hn::Min(f2, hn::Max(f1, d2));
    f1 = hn::Min(f1, d2);
}

/// The nearest and second nearest feature point's squared distance, over
/// the 27 (3D) or 9 (2D) cells around the point's own; feature points in
/// the middle [0.3, 0.7) of their cells make that search exact (the proof
/// is in FractalNoise.cpp).
template <bool THREE_D>
void cellular(VU s, const Point& p, VF& f1, VF& f2)
{
    const DU du;
    const DF df;
    VU t[3][3];
    for (int a = 0; a < (THREE_D ? 3 : 2); ++a)
        for (int k = -1; k <= 1; ++k) t[a][k + 1] = term(du, p.axes[a], k, a);
    f1 = hn::Set(df, 1e9f);
    f2 = f1;
    for (int a = -1; a <= 1; ++a) {
        const VF dxCell = hn::Sub(p.f[0], hn::Set(df, float(a)));
        for (int b = -1; b <= 1; ++b) {
            const VF dyCell = hn::Sub(p.f[1], hn::Set(df, float(b)));
            for (int c = -1; c <= (THREE_D ? 1 : -1); ++c) {
                const VU h = cornerHash(du, s, t[0][a + 1], t[1][b + 1], THREE_D ? t[2][c + 1] : hn::Zero(du));
                const VF dx = hn::Sub(dxCell, jitter<0>(h)), dy = hn::Sub(dyCell, jitter<10>(h));
                VF d2 = hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy));
                if constexpr (THREE_D) {
                    const VF dz = hn::Sub(hn::Sub(p.f[2], hn::Set(df, float(c))), jitter<20>(h));
                    d2 = hn::Add(d2, hn::Mul(dz, dz));
                }
                keepTwoNearest(d2, f1, f2);
            }
        }
    }
}

/// The basis (before a fractal shape) at one vector of points.
VF basisAt(NoiseType type, bool threeD, VU s, const Point& p)
{
    const DF df;
    switch (type) {
    case NoiseType::GRADIENT: return threeD ? gradient3(s, p) : gradient2(s, p);
    case NoiseType::VALUE: return threeD ? value3(s, p) : value2(s, p);
    case NoiseType::SIMPLEX: return threeD ? simplex3(s, p) : simplex2(s, p);
    case NoiseType::CELLULAR_F1:
    case NoiseType::CELLULAR_F2: {
        VF f1, f2;
        if (threeD) cellular<true>(s, p, f1, f2);
        else cellular<false>(s, p, f1, f2);
        // 2·F1 − 1 and 2·F2 − 1.4, as version 1's bases.
        if (type == NoiseType::CELLULAR_F1) return hn::Sub(hn::Mul(hn::Set(df, 2.0f), hn::Sqrt(f1)), hn::Set(df, 1.0f));
        return hn::Sub(hn::Mul(hn::Set(df, 2.0f), hn::Sqrt(f2)), hn::Set(df, 1.4f));
    }
    }
    return hn::Zero(df);
}

/// A cell index held as a double (an integer, or NaN) as latticeIndex()'s
/// int64: saturated beyond ±2^62, NaN to −2^62 (comparisons with NaN are
/// false on every target), then converted exactly.
template <class DD, class VD = hn::Vec<DD>>
HWY_INLINE hn::Vec<hn::RebindToSigned<DD>> cellIndex(DD dd, VD cell)
{
    const VD limit = hn::Set(dd, 4611686018427387904.0); // 2^62
    const VD saturated = hn::IfThenElse(hn::Gt(cell, hn::Zero(dd)), limit, hn::Neg(limit));
    return hn::ConvertTo(hn::RebindToSigned<DD>(), hn::IfThenElse(hn::Lt(hn::Abs(cell), limit), cell, saturated));
}

/// A fractal sum's shape of one octave's basis value, in float
/// (fractalShape of NoiseKernels.h).
HWY_INLINE VF shape(FractalType fractal, VF n)
{
    const DF df;
    if (fractal == FractalType::RIDGED) return hn::Sub(hn::Set(df, 1.0f), hn::Mul(hn::Set(df, 2.0f), hn::Abs(n)));
    if (fractal == FractalType::BILLOW) return hn::Sub(hn::Mul(hn::Set(df, 2.0f), hn::Abs(n)), hn::Set(df, 1.0f));
    return n;
}

/// The double lanes of one half of a float vector's points.
template <class DD, class VD = hn::Vec<DD>>
struct SplitHalf
{
    hn::Vec<hn::RebindToSigned<DD>> cell[3]; ///< latticeIndex() per axis
    VD offset[3];
    HWY_INLINE SplitHalf() {}
};

/// Splits the points at p[a] + j (a < 3; null: a zero coordinate) in this
/// octave's lattice.
template <class DD, class VD = hn::Vec<DD>>
HWY_INLINE SplitHalf<DD> splitHalf(DD dd, const OctaveLanes32& o, bool simplex, bool threeD, const double* const (&p)[3],
                                   std::size_t j)
{
    VD q[3], cell[3];
    SplitHalf<DD> h;
    for (int a = 0; a < 3; ++a) {
        q[a] = p[a] ? hn::Add(hn::Mul(hn::LoadU(dd, p[a] + j), hn::Set(dd, o.frequency)), hn::Set(dd, o.offset[a]))
                    : hn::Zero(dd);
    }
    splitLattice(dd, simplex, threeD, q[0], q[1], q[2], cell[0], cell[1], cell[2], h.offset[0], h.offset[1], h.offset[2]);
    for (int a = 0; a < 3; ++a) h.cell[a] = cellIndex(dd, cell[a]);
    return h;
}

/// The point in a float vector's lanes: its cell's 32-bit words and its
/// offset rounded to float, from the double lanes of its halves.
HWY_INLINE Point pointOf(const double* const (&p)[3], const OctaveLanes32& o, bool simplex, bool threeD)
{
    using DD = hn::ScalableTag<double>;
    const DD dd;
    const DF df;
    const DU du;
    Point point;
#if HWY_TARGET == HWY_SCALAR
    // One lane each: no halves to combine.
    const SplitHalf<DD> h = splitHalf(dd, o, simplex, threeD, p, 0);
    for (int a = 0; a < 3; ++a) {
        const std::uint64_t index = std::uint64_t(hn::GetLane(h.cell[a]));
        point.axes[a] = axis(du, hn::Set(du, std::uint32_t(index)), hn::Set(du, std::uint32_t(index >> 32)), a);
        point.f[a] = hn::DemoteTo(df, h.offset[a]);
    }
#else
    const hn::Half<DF> dfHalf;
    const SplitHalf<DD> lower = splitHalf(dd, o, simplex, threeD, p, 0);
    const SplitHalf<DD> upper = splitHalf(dd, o, simplex, threeD, p, hn::Lanes(dd));
    for (int a = 0; a < 3; ++a) {
        // An int64 lane is two 32-bit lanes, the low word first (x86 and
        // aarch64 are little-endian): the even lanes of both halves are the
        // points' low words, the odd lanes their high words.
        const VU first = hn::BitCast(du, lower.cell[a]), second = hn::BitCast(du, upper.cell[a]);
        point.axes[a] = axis(du, hn::ConcatEven(du, second, first), hn::ConcatOdd(du, second, first), a);
        point.f[a] = hn::Combine(df, hn::DemoteTo(dfHalf, upper.offset[a]), hn::DemoteTo(dfHalf, lower.offset[a]));
    }
#endif
    return point;
}

void FractalLanes32Impl(const FractalLanes32& sum, const double* x, const double* y, const double* z, std::size_t n,
                        double* out)
{
    const DF df;
    const DU du;
    const std::size_t lanes = hn::Lanes(df);
    const bool threeD = z != nullptr, simplex = sum.type == NoiseType::SIMPLEX;
    HWY_ALIGN double tail[3][MAX_FLOAT_LANES] = {};
    HWY_ALIGN float result[MAX_FLOAT_LANES] = {};
    const double* input[3] = {x, y, z};
    for (std::size_t i = 0; i < n; i += lanes) {
        const bool full = i + lanes <= n;
        const double* p[3] = {nullptr, nullptr, nullptr};
        for (int a = 0; a < (threeD ? 3 : 2); ++a) {
            p[a] = input[a] + i;
            if (!full) { // the tail, zero-padded
                std::copy(p[a], p[a] + (n - i), tail[a]);
                p[a] = tail[a];
            }
        }
        VF total = hn::Zero(df);
        for (int octave = 0; octave < sum.count; ++octave) {
            const OctaveLanes32& o = sum.octaves[octave];
            const VF value = basisAt(sum.type, threeD, hn::Set(du, o.seed), pointOf(p, o, simplex, threeD));
            total = hn::Add(total, hn::Mul(hn::Set(df, o.weight), shape(sum.fractal, value)));
        }
        hn::Store(total, df, result);
        const std::size_t count = full ? lanes : n - i;
        for (std::size_t k = 0; k < count; ++k) out[i + k] = double(result[k]);
    }
}

} // namespace HWY_NAMESPACE
} // namespace strata::terrain::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace strata::terrain::detail {

HWY_EXPORT(FractalLanes32Impl);

void fractalLanes32(const FractalLanes32& sum, const double* x, const double* y, const double* z, std::size_t n,
                    double* out)
{
#if HWY_IDE || ((HWY_TARGETS & (HWY_TARGETS - 1)) == 0)
    HWY_STATIC_DISPATCH(FractalLanes32Impl)(sum, x, y, z, n, out);
#else
    // The target NoiseSimd.cpp's dispatch uses (useSimdTarget()): the export
    // tables of both files list the same targets in the same order.
    (*(HWY_DISPATCH_TABLE(FractalLanes32Impl)[noiseTargetIndex()]))(sum, x, y, z, n, out);
#endif
}

void basisVersion2(NoiseType type, std::uint64_t hashedSeed, const double* x, const double* y, const double* z,
                   std::size_t n, double* out)
{
    // One octave at frequency 1, offset 0 and weight 1: 0 + 1·b is b, bit for bit.
    const OctaveLanes32 octave{std::uint32_t(hashedSeed >> 32), 1.0f, 1.0, {0.0, 0.0, 0.0}};
    fractalLanes32({type, FractalType::FBM, &octave, 1}, x, y, z, n, out);
}

} // namespace strata::terrain::detail
#endif // HWY_ONCE
