// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Internal, per SIMD target (Highway's -inl.h convention: included after
// foreach_target by each file that compiles lanes): splitCube /
// splitSquare / splitSimplex of NoiseKernels.h in double lanes, the scalar
// path's operations in its order. One definition for version 1's split
// (NoiseSimd.cpp) and version 2's (NoiseLanes32.cpp), so both versions
// place a point in the same cell with the same offset.

#if defined(STRATA_NOISE_SPLIT_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef STRATA_NOISE_SPLIT_INL_H_
#undef STRATA_NOISE_SPLIT_INL_H_
#else
#define STRATA_NOISE_SPLIT_INL_H_
#endif

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace strata::terrain::detail {
namespace HWY_NAMESPACE {

/// The cell's floor (cx, cy, cz) and the offset in it (fx, fy, fz) of the
/// points (x, y, z): on the cube lattice, or the simplex lattice's skewed
/// cube and the unskewed offset from its first corner. In 2D (!threeD) z is
/// ignored on the simplex lattice and cz, fz are zero there.
template <class D, class V = hwy::HWY_NAMESPACE::Vec<D>>
HWY_INLINE void splitLattice(D d, bool simplex, bool threeD, V x, V y, V z, V& cx, V& cy, V& cz, V& fx, V& fy, V& fz)
{
    namespace hn = hwy::HWY_NAMESPACE;
    if (!simplex) {
        cx = hn::Floor(x);
        cy = hn::Floor(y);
        cz = hn::Floor(z);
        fx = hn::Sub(x, cx);
        fy = hn::Sub(y, cy);
        fz = hn::Sub(z, cz);
    } else if (threeD) {
        const V skew = hn::Mul(hn::Add(hn::Add(x, y), z), hn::Set(d, 1.0 / 3.0));
        cx = hn::Floor(hn::Add(x, skew));
        cy = hn::Floor(hn::Add(y, skew));
        cz = hn::Floor(hn::Add(z, skew));
        const V unskew = hn::Mul(hn::Add(hn::Add(cx, cy), cz), hn::Set(d, 1.0 / 6.0));
        fx = hn::Add(hn::Sub(x, cx), unskew);
        fy = hn::Add(hn::Sub(y, cy), unskew);
        fz = hn::Add(hn::Sub(z, cz), unskew);
    } else {
        const double F2 = 0.5 * (1.7320508075688772 - 1.0), G2 = (3.0 - 1.7320508075688772) / 6.0;
        const V skew = hn::Mul(hn::Add(x, y), hn::Set(d, F2));
        cx = hn::Floor(hn::Add(x, skew));
        cy = hn::Floor(hn::Add(y, skew));
        cz = hn::Zero(d);
        const V unskew = hn::Mul(hn::Add(cx, cy), hn::Set(d, G2));
        fx = hn::Add(hn::Sub(x, cx), unskew);
        fy = hn::Add(hn::Sub(y, cy), unskew);
        fz = hn::Zero(d);
    }
}

} // namespace HWY_NAMESPACE
} // namespace strata::terrain::detail
HWY_AFTER_NAMESPACE();

#endif // STRATA_NOISE_SPLIT_INL_H_
