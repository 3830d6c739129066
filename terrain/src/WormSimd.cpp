// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Worm caves' distance at a block of points, one point per SIMD lane (see
// WormSimd.h). The twin of WormCaves::distanceAmong() and
// roundConeDistance() in Caves.cpp: keep the two in step (BlockEvaluationTest
// compares them bit for bit on every target).

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "WormSimd.cpp" // found through this folder's include path
#include <hwy/foreach_target.h> // IWYU pragma: keep
#include <hwy/highway.h>

#include "WormSimd.h"

#include <algorithm>
#include <cmath>

HWY_BEFORE_NAMESPACE();
namespace strata::terrain::detail {
namespace HWY_NAMESPACE {

namespace hn = hwy::HWY_NAMESPACE;
using D = hn::ScalableTag<double>;
using V = hn::Vec<D>;

constexpr std::size_t MAX_LANES = HWY_MAX_BYTES / sizeof(double);

/// glm::dot of two dvec3: the products, then (x + y) + z.
HWY_INLINE V dot(V ax, V ay, V az, V bx, V by, V bz)
{
    return hn::Add(hn::Add(hn::Mul(ax, bx), hn::Mul(ay, by)), hn::Mul(az, bz));
}

/// std::min(a, b): b if b < a, else a.
HWY_INLINE V minOf(V a, V b) { return hn::IfThenElse(hn::Lt(b, a), b, a); }

/// roundConeDistance(p, a, b, ra, rb), lane-wise.
HWY_INLINE V coneDistance(D d, const LaneCone& c, V px, V py, V pz)
{
    const V wx = hn::Sub(px, hn::Set(d, c.ax)), wy = hn::Sub(py, hn::Set(d, c.ay)), wz = hn::Sub(pz, hn::Set(d, c.az));
    if (!(std::abs(c.slope) < 1.0)) { // one end sphere holds the cone
        const V ex = hn::Sub(px, hn::Set(d, c.bx)), ey = hn::Sub(py, hn::Set(d, c.by)), ez = hn::Sub(pz, hn::Set(d, c.bz));
        return minOf(hn::Sub(hn::Sqrt(dot(wx, wy, wz, wx, wy, wz)), hn::Set(d, c.ra)),
                     hn::Sub(hn::Sqrt(dot(ex, ey, ez, ex, ey, ez)), hn::Set(d, c.rb)));
    }
    const V vx = hn::Set(d, c.vx), vy = hn::Set(d, c.vy), vz = hn::Set(d, c.vz), len = hn::Set(d, c.len);
    const V along = hn::Div(dot(wx, wy, wz, vx, vy, vz), len);
    const V k = hn::Div(along, len);
    const V hx = hn::Sub(wx, hn::Mul(k, vx)), hy = hn::Sub(wy, hn::Mul(k, vy)), hz = hn::Sub(wz, hn::Mul(k, vz));
    const V h = hn::Sqrt(dot(hx, hy, hz, hx, hy, hz));
    const V u = hn::Div(hn::Mul(hn::Set(d, c.slope), h), hn::Set(d, c.slopeRoot));
    // std::clamp(v, 0, 1): 0 if v < 0, else 1 if 1 < v, else v.
    const V raw = hn::Div(hn::Add(along, u), len), zero = hn::Zero(d), one = hn::Set(d, 1.0);
    const V t = hn::IfThenElse(hn::Lt(raw, zero), zero, hn::IfThenElse(hn::Lt(one, raw), one, raw));
    const V qx = hn::Sub(px, hn::Add(hn::Set(d, c.ax), hn::Mul(t, vx)));
    const V qy = hn::Sub(py, hn::Add(hn::Set(d, c.ay), hn::Mul(t, vy)));
    const V qz = hn::Sub(pz, hn::Add(hn::Set(d, c.az), hn::Mul(t, vz)));
    const V radius = hn::Add(hn::Set(d, c.ra), hn::Mul(t, hn::Set(d, c.rb - c.ra)));
    return hn::Sub(hn::Sqrt(dot(qx, qy, qz, qx, qy, qz)), radius);
}

/// distanceAmong() for one vector of points.
HWY_INLINE V distanceAmong(D d, const LaneCone* cones, std::size_t count, double cap, V px, V py, V pz)
{
    V dist = hn::Set(d, cap);
    for (std::size_t i = 0; i < count; ++i) {
        const LaneCone& c = cones[i];
        // Rejected where |p − mid|² >= (d + reach)²: d stays.
        const V vx = hn::Sub(px, hn::Set(d, c.midX)), vy = hn::Sub(py, hn::Set(d, c.midY));
        const V vz = hn::Sub(pz, hn::Set(d, c.midZ));
        const V far = hn::Add(dist, hn::Set(d, c.reach));
        const auto near = hn::Not(hn::Ge(dot(vx, vy, vz, vx, vy, vz), hn::Mul(far, far))); // NaN: near, as in Caves.cpp
        if (hn::AllFalse(d, near)) continue;
        dist = hn::IfThenElse(near, minOf(dist, coneDistance(d, c, px, py, pz)), dist);
    }
    return dist;
}

void WormDistancesImpl(const LaneCone* cones, std::size_t count, double cap, const double* x, const double* y,
                       const double* z, std::size_t n, double* out)
{
    const D d;
    const std::size_t lanes = hn::Lanes(d);
    std::size_t i = 0;
    for (; i + lanes <= n; i += lanes) {
        const V r = distanceAmong(d, cones, count, cap, hn::LoadU(d, x + i), hn::LoadU(d, y + i), hn::LoadU(d, z + i));
        hn::StoreU(r, d, out + i);
    }
    if (i < n) { // the tail, zero-padded
        HWY_ALIGN double bx[MAX_LANES] = {}, by[MAX_LANES] = {}, bz[MAX_LANES] = {}, bo[MAX_LANES];
        std::copy(x + i, x + n, bx);
        std::copy(y + i, y + n, by);
        std::copy(z + i, z + n, bz);
        hn::Store(distanceAmong(d, cones, count, cap, hn::Load(d, bx), hn::Load(d, by), hn::Load(d, bz)), d, bo);
        std::copy(bo, bo + (n - i), out + i);
    }
}

} // namespace HWY_NAMESPACE
} // namespace strata::terrain::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace strata::terrain::detail {

HWY_EXPORT(WormDistancesImpl);

void deriveLaneCone(LaneCone& c)
{
    c.vx = c.bx - c.ax;
    c.vy = c.by - c.ay;
    c.vz = c.bz - c.az;
    c.len = std::sqrt(c.vx * c.vx + c.vy * c.vy + c.vz * c.vz);
    c.slope = c.len > 0.0 ? (c.rb - c.ra) / c.len : 2.0;
    c.slopeRoot = std::abs(c.slope) < 1.0 ? std::sqrt(1.0 - c.slope * c.slope) : 0.0;
}

void wormDistances(const LaneCone* cones, std::size_t count, double cap, const double* x, const double* y,
                   const double* z, std::size_t n, double* out)
{
    HWY_DYNAMIC_DISPATCH(WormDistancesImpl)(cones, count, cap, x, y, z, n, out);
}

} // namespace strata::terrain::detail
#endif // HWY_ONCE
