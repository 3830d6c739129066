// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/CrestHeightfield.h>

#include "ShowValue.h"

#include <strata/Error.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace strata::terrain {

namespace {

constexpr int DIRECTIONS = 4;
constexpr int FLANKS = 4 * DIRECTIONS; ///< per column: 4 directions × 2 sides × 2 steps
constexpr double HALF_SQRT2 = 0.70710678118654752440;
constexpr double DIRECTION_X[DIRECTIONS] = {1.0, HALF_SQRT2, 0.0, -HALF_SQRT2};
constexpr double DIRECTION_Z[DIRECTIONS] = {0.0, HALF_SQRT2, 1.0, HALF_SQRT2};

void check(bool ok, const char* key, double value, const char* what)
{
    if (!ok) throw Error(ErrorKind::BadInput, std::string(key) + " = " + detail::show(value) + " " + what, {"", 0, key, ""});
}

} // namespace

CrestHeightfield::CrestHeightfield(HeightNodePtr child, const CrestOptions& options, HeightNodePtr mask,
                                   std::shared_ptr<const Lithology> lithology)
    : mChild(std::move(child))
    , mMask(std::move(mask))
    , mLithology(std::move(lithology))
    , mOptions(options)
{
    if (!mChild) throw Error(ErrorKind::BadInput, "crests: no height node to sharpen");
    check(std::isfinite(options.reach) && options.reach > 0.0 && options.reach <= 1e6, "reach", options.reach,
          "must be a number in (0, 1e6] metres");
    check(options.amount >= 0.0 && options.amount <= 1.0, "amount", options.amount, "must be within [0, 1]");
    check(std::isfinite(options.maxLift) && options.maxLift >= 0.0, "max_lift", options.maxLift,
          "must be a finite number >= 0 metres");
    // |P± − h| <= 2·S·d + S·2d, so the lift never exceeds a·4·S·d; each P±
    // is 3S-Lipschitz, T − h 4S-Lipschitz.
    const double s = mChild->slopeBound();
    const double excess = 4.0 * s * options.reach;
    mLiftBound = std::min(options.maxLift, options.amount * excess);
    // |∇w| along the ground: the mask's slope, plus the hardness' 3D
    // gradient along a surface of slope S.
    double weightSlope = 0.0;
    if (mMask) weightSlope += mMask->slopeBound();
    if (mLithology) weightSlope += mLithology->hardnessLipschitz() * std::sqrt(1.0 + s * s);
    const double liftSlope = options.amount * (weightSlope * excess + 4.0 * s);
    setSlopeBound(s + (mLiftBound > 0.0 ? liftSlope : 0.0));
}

double CrestHeightfield::lift(double x, double z, double h, const double* flanks, double mask) const
{
    double edge = -HUGE_VAL; // T: where the flanks, extended, meet
    for (int k = 0; k < DIRECTIONS; ++k) {
        const double* f = flanks + 4 * k;
        const double forward = 2.0 * f[0] - f[1], backward = 2.0 * f[2] - f[3];
        edge = std::max(edge, std::min(forward, backward));
    }
    const double excess = edge - h;
    // On a plane the extensions give h again up to rounding: lifts below a
    // micrometre per kilometre of height are that rounding, not a crest.
    if (!(excess > 1e-9 * (1.0 + std::abs(h)))) return 0.0;
    double weight = std::clamp(mask, 0.0, 1.0);
    if (mLithology) weight *= mLithology->hardness(glm::dvec3(x, h, z));
    return std::min(mOptions.maxLift, mOptions.amount * weight * excess);
}

double CrestHeightfield::height(double x, double z) const
{
    double out = 0.0;
    heights(&x, &z, 1, &out);
    return out;
}

void CrestHeightfield::heights(const double* x, const double* z, std::size_t n, double* out) const
{
    if (n == 0) return;
    if (mLiftBound == 0.0) {
        mChild->heights(x, z, n, out);
        return;
    }
    // Per column: itself, then the 16 flank points.
    const std::size_t stride = 1 + FLANKS;
    std::vector<double> px(n * stride), pz(n * stride), h(n * stride), mask(n, 1.0);
    for (std::size_t i = 0; i < n; ++i) {
        double* cx = px.data() + i * stride;
        double* cz = pz.data() + i * stride;
        cx[0] = x[i];
        cz[0] = z[i];
        for (int k = 0; k < DIRECTIONS; ++k) {
            for (int side = 0; side < 2; ++side) {
                for (int step = 0; step < 2; ++step) {
                    const double distance = (side == 0 ? 1.0 : -1.0) * double(step + 1) * mOptions.reach;
                    cx[1 + 4 * k + 2 * side + step] = x[i] + distance * DIRECTION_X[k];
                    cz[1 + 4 * k + 2 * side + step] = z[i] + distance * DIRECTION_Z[k];
                }
            }
        }
    }
    mChild->heights(px.data(), pz.data(), n * stride, h.data());
    if (mMask) mMask->heights(x, z, n, mask.data());
    for (std::size_t i = 0; i < n; ++i) {
        const double* column = h.data() + i * stride;
        out[i] = column[0] + lift(x[i], z[i], column[0], column + 1, mask[i]);
    }
}

Interval CrestHeightfield::heightBounds(const glm::dvec2& min, const glm::dvec2& max) const
{
    const Interval child = mChild->heightBounds(min, max);
    return {child.lo, child.hi + mLiftBound};
}

} // namespace strata::terrain
