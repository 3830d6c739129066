// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/Lithology.h>

#include "ShowValue.h"

#include <strata/DeterministicMath.h>
#include <strata/Error.h>
#include <strata/terrain/Noise.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace strata::terrain {

using detail::show;

namespace {

void require(bool ok, const std::string& key, double value, const std::string& what)
{
    if (!ok) throw Error(ErrorKind::BadInput, key + " = " + show(value) + " " + what);
}


/// The interval of a·x for x in [lo, hi].
Interval scaled(double a, double lo, double hi)
{
    const double u = a * lo, v = a * hi;
    return {std::min(u, v), std::max(u, v)};
}

} // namespace

Lithology::Lithology(std::uint64_t seed, const LithologyOptions& options)
    : mOptions(options)
    , mFold(deriveSeed(seed, 11), options.foldNoise)
{
    const LithologyOptions& o = options;
    if (o.beds.empty()) throw Error(ErrorKind::BadInput, "beds must hold at least one bed");
    double thinnest = HUGE_VAL;
    for (std::size_t i = 0; i < o.beds.size(); ++i) {
        const RockBed& b = o.beds[i];
        const std::string key = "beds[" + std::to_string(i) + "]";
        require(std::isfinite(b.thickness) && b.thickness >= 0.0 && b.thickness <= 1e6, key + " thickness",
                b.thickness, "must be a finite number of metres in 0 .. 1e6");
        require(std::isfinite(b.hardness) && b.hardness >= 0.0 && b.hardness <= 1.0, key + " hardness", b.hardness,
                "must be in 0 .. 1");
        if (b.thickness == 0.0) continue; // a bed of no thickness is not there
        mBeds.push_back({mPeriod, b.hardness, int(i)});
        mPeriod += b.thickness;
        thinnest = std::min(thinnest, b.thickness);
    }
    if (mBeds.empty()) throw Error(ErrorKind::BadInput, "beds must hold a bed of thickness > 0 (all are 0)");
    require(std::isfinite(o.datum) && std::abs(o.datum) <= 1e12, "datum", o.datum, "must be a finite number of metres within ±1e12");
    require(std::isfinite(o.dip) && o.dip >= 0.0 && o.dip <= 90.0, "dip", o.dip, "must be in 0 .. 90 degrees");
    require(std::isfinite(o.dipDirection) && std::abs(o.dipDirection) <= 360.0, "dip_direction", o.dipDirection,
            "must be in -360 .. 360 degrees");
    const bool layered = mBeds.size() > 1;
    require(std::isfinite(o.transition) && o.transition > 0.0 && (!layered || o.transition <= thinnest), "transition",
            o.transition, "must be > 0 and at most the thinnest bed (" + show(thinnest) + " m)");
    require(std::isfinite(o.foldAmplitude) && o.foldAmplitude >= 0.0 && o.foldAmplitude <= 1e5, "fold_amplitude",
            o.foldAmplitude, "must be in 0 .. 1e5 metres");
    require(std::isfinite(o.foldWavelength) && o.foldWavelength > 0.0, "fold_wavelength", o.foldWavelength,
            "must be a finite number of metres > 0");
    require(std::isfinite(o.faultThrow) && std::abs(o.faultThrow) <= 1e5, "fault_throw", o.faultThrow,
            "must be within ±1e5 metres");
    require(std::isfinite(o.faultStrike) && std::abs(o.faultStrike) <= 360.0, "fault_strike", o.faultStrike,
            "must be in -360 .. 360 degrees");
    require(std::isfinite(o.faultDip) && o.faultDip >= 0.0 && o.faultDip <= 90.0, "fault_dip", o.faultDip,
            "must be in 0 .. 90 degrees");
    require(std::isfinite(o.faultWidth) && o.faultWidth > 0.0, "fault_width", o.faultWidth,
            "must be a finite number of metres > 0");
    for (int a = 0; a < 3; ++a) {
        require(std::isfinite(o.faultPoint[a]) && std::abs(o.faultPoint[a]) <= 1e12, "fault_point", o.faultPoint[a],
                "must be finite, within ±1e12 metres");
    }

    double sd = 0.0, cd = 1.0, sa = 0.0, ca = 1.0;
    dmath::sinCosDegrees(o.dip, sd, cd);
    dmath::sinCosDegrees(o.dipDirection, sa, ca);
    mNormal = glm::dvec3(sd * ca, cd, sd * sa); // rises away from the dip direction
    double sfd = 1.0, cfd = 0.0, ss = 0.0, cs = 1.0;
    dmath::sinCosDegrees(o.faultDip, sfd, cfd);
    dmath::sinCosDegrees(o.faultStrike, ss, cs);
    mFaultNormal = glm::dvec3(-ss * sfd, cfd, cs * sfd);

    mMinHardness = mMaxHardness = mBeds[0].hardness;
    for (std::size_t i = 0; i < mBeds.size(); ++i) {
        mMinHardness = std::min(mMinHardness, mBeds[i].hardness);
        mMaxHardness = std::max(mMaxHardness, mBeds[i].hardness);
        const bool hasUpper = i + 1 < mBeds.size() || o.repeat;
        if (!hasUpper) continue;
        const double above = mBeds[(i + 1) % mBeds.size()].hardness;
        mHardnessSlope = std::max(mHardnessSlope, std::abs(above - mBeds[i].hardness) * 1.5 / o.transition);
    }
    mStratigraphicLipschitz = 1.0 + std::abs(o.faultThrow) * 1.5 / o.faultWidth;
    if (o.foldAmplitude > 0.0) mStratigraphicLipschitz += o.foldAmplitude * mFold.lipschitz(3) / o.foldWavelength;
}

double Lithology::faultOffset(double across) const
{
    if (mOptions.faultThrow == 0.0) return 0.0;
    return mOptions.faultThrow * dmath::smoothstep01(across / mOptions.faultWidth + 0.5);
}

double Lithology::stratigraphicHeight(const glm::dvec3& p) const
{
    const LithologyOptions& o = mOptions;
    // A fixed order of operations (no glm::dot, whose order is the library's).
    double s = mNormal.x * p.x;
    s = s + mNormal.y * p.y;
    s = s + mNormal.z * p.z;
    if (o.foldAmplitude > 0.0) s = s + o.foldAmplitude * mFold(p / o.foldWavelength);
    if (o.faultThrow != 0.0) {
        double across = mFaultNormal.x * (p.x - o.faultPoint.x);
        across = across + mFaultNormal.y * (p.y - o.faultPoint.y);
        across = across + mFaultNormal.z * (p.z - o.faultPoint.z);
        s = s + faultOffset(across);
    }
    return s - o.datum;
}

std::size_t Lithology::bedIndexAt(double s, double& u) const
{
    u = s;
    if (mOptions.repeat) {
        u = s - mPeriod * std::floor(s / mPeriod);
        if (!(u < mPeriod)) u = 0.0; // s a hair below a multiple of the period rounds up to it
        if (u < 0.0) u = 0.0;
    }
    // The last contact at or below u (the first bed extends down when not repeating).
    std::size_t i = std::size_t(std::upper_bound(mBeds.begin(), mBeds.end(), u,
                                                 [](double v, const Contact& c) { return v < c.base; }) -
                                mBeds.begin());
    return i == 0 ? 0 : i - 1;
}

double Lithology::hardnessAt(double s) const
{
    double u = 0.0;
    const std::size_t i = bedIndexAt(s, u);
    const std::size_t n = mBeds.size();
    const double h = mBeds[i].hardness;
    const double half = 0.5 * mOptions.transition;
    const bool repeat = mOptions.repeat;
    // The contact below: with the bed under it, when there is one.
    if (i > 0 || repeat) {
        const double below = u - mBeds[i].base;
        if (below < half) {
            const double other = mBeds[i > 0 ? i - 1 : n - 1].hardness;
            return other + (h - other) * dmath::smoothstep01(0.5 + below / mOptions.transition);
        }
    }
    if (i + 1 < n || repeat) {
        const double top = i + 1 < n ? mBeds[i + 1].base : mPeriod;
        const double above = top - u;
        if (above < half) {
            const double other = mBeds[(i + 1) % n].hardness;
            return h + (other - h) * dmath::smoothstep01(0.5 - above / mOptions.transition);
        }
    }
    return h;
}

int Lithology::bedAt(double s) const
{
    double u = 0.0;
    return mBeds[bedIndexAt(s, u)].index;
}

Interval Lithology::stratigraphicBounds(const WorldBox& box) const
{
    const LithologyOptions& o = mOptions;
    Interval s{0.0, 0.0};
    for (int a = 0; a < 3; ++a) {
        const Interval t = scaled(mNormal[a], box.min[a], box.max[a]);
        s.lo += t.lo;
        s.hi += t.hi;
    }
    if (o.foldAmplitude > 0.0) {
        const Interval f = mFold.bounds(box.min / o.foldWavelength, box.max / o.foldWavelength);
        s.lo += o.foldAmplitude * f.lo;
        s.hi += o.foldAmplitude * f.hi;
    }
    if (o.faultThrow != 0.0) {
        Interval across{0.0, 0.0};
        for (int a = 0; a < 3; ++a) {
            const Interval t = scaled(mFaultNormal[a], box.min[a] - o.faultPoint[a], box.max[a] - o.faultPoint[a]);
            across.lo += t.lo;
            across.hi += t.hi;
        }
        const double f0 = faultOffset(across.lo), f1 = faultOffset(across.hi); // monotone in `across`
        s.lo += std::min(f0, f1);
        s.hi += std::max(f0, f1);
    }
    // Rounding of the sums (a few ulps of the largest term) and of the datum.
    const double slack = 1e-12 * (std::abs(s.lo) + std::abs(s.hi) + std::abs(o.datum)) + 1e-12;
    return {s.lo - o.datum - slack, s.hi - o.datum + slack};
}

Interval Lithology::hardnessBounds(const WorldBox& box) const
{
    const Interval s = stratigraphicBounds(box);
    const double half = 0.5 * mOptions.transition;
    const double lo = s.lo - half, hi = s.hi + half;
    if (mOptions.repeat && hi - lo >= mPeriod) return {mMinHardness, mMaxHardness};
    // Every bed the widened interval touches: a point's hardness blends its
    // own bed with a neighbour at most half a transition away.
    double u = 0.0;
    std::size_t i = bedIndexAt(lo, u);
    double base = lo - u + mBeds[i].base; // where bed i starts, in stratigraphic height
    Interval h{mBeds[i].hardness, mBeds[i].hardness};
    for (std::size_t steps = 0; steps <= mBeds.size(); ++steps) {
        h.lo = std::min(h.lo, mBeds[i].hardness);
        h.hi = std::max(h.hi, mBeds[i].hardness);
        const bool last = i + 1 == mBeds.size();
        if (last && !mOptions.repeat) break;
        const double thickness = (last ? mPeriod : mBeds[i + 1].base) - mBeds[i].base;
        base += thickness;
        if (base > hi) break;
        i = last ? 0 : i + 1;
    }
    return h;
}

} // namespace strata::terrain
