// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/ScreeField.h>

#include "ShowValue.h"

#include <strata/DeterministicMath.h>
#include <strata/Error.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace strata::terrain {

namespace {

/// Talus thinner than this over the ground feathers out under it.
constexpr double FEATHER = 1.0; // metres

} // namespace

ScreeField::ScreeField(std::shared_ptr<const DensityField> rock, std::shared_ptr<const TalusHeightfield> talus,
                       double depth)
    : mRock(std::move(rock)), mTalus(std::move(talus)), mDepth(depth)
{
    if (!(depth > 0.0 && depth <= 1e4)) {
        throw Error(ErrorKind::BadInput, "depth = " + detail::show(depth) + " is out of range (0, 1e4] m",
                    {"", 0, "depth", ""});
    }
    // |∇C| <= √2·tan(angle) (bilinear of nodes whose differences along an
    // axis are at most tan·cell), |∇H| and |∇L| <= √2·s (the ground's
    // bound; L is a minimum of it); top = 2C − H − 1 m where it feathers.
    const double tan = dmath::tanDegrees(mTalus->options().angle), s = mTalus->slopeBound();
    const double root2 = std::sqrt(2.0);
    const double slope = std::max(2.0 * root2 * tan + root2 * s, root2 * s);
    mSlabLipschitz = std::sqrt(1.0 + slope * slope);
    mLipschitz = std::max(mRock->lipschitz(), mSlabLipschitz);
}

void ScreeField::slab(const double* x, const double* y, const double* z, std::size_t n, double* out) const
{
    // One column at a time: density() calls this for a single point, and
    // the lattice is read per column anyway (no buffers to allocate).
    for (std::size_t k = 0; k < n; ++k) {
        double ground, cone, foot;
        mTalus->lattice(&x[k], &z[k], 1, &ground, &cone, &foot);
        if (!(cone > -HUGE_VAL)) {
            out[k] = HUGE_VAL; // no lattice this far out: no talus
            continue;
        }
        const double top = cone - std::clamp(FEATHER - (cone - ground), 0.0, FEATHER);
        out[k] = std::max(y[k] - top, (foot - mDepth) - y[k]);
    }
}

double ScreeField::density(const glm::dvec3& p) const
{
    double talus;
    slab(&p.x, &p.y, &p.z, 1, &talus);
    return std::min(mRock->density(p), talus);
}

void ScreeField::densities(const PointBlock& points, double* out) const
{
    mRock->densities(points, out);
    std::vector<double> talus(points.count);
    slab(points.x, points.y, points.z, points.count, talus.data());
    for (std::size_t k = 0; k < points.count; ++k) out[k] = std::min(out[k], talus[k]);
}

double ScreeField::distanceBound(const glm::dvec3& p) const
{
    double talus;
    slab(&p.x, &p.y, &p.z, 1, &talus);
    return std::min(mRock->distanceBound(p), talus / mSlabLipschitz);
}

Interval ScreeField::bounds(const WorldBox& box) const
{
    const Interval rock = mRock->bounds(box);
    // From the lattice nodes around the box: top = C − clamp(1 m − (C −
    // H), 0, 1 m) lies in [C_lo − 1 m, C_hi], the bottom L − depth in
    // [L_lo − depth, L_hi − depth], and y − top, bottom − y are monotone.
    TalusHeightfield::LatticeRange r;
    if (mTalus->latticeRange({box.min.x, box.min.z}, {box.max.x, box.max.z}, r)) {
        const double topLo = r.coneLo - FEATHER, topHi = r.coneHi;
        const double bottomLo = r.footLo - mDepth, bottomHi = r.footHi - mDepth;
        const Interval slab{std::max(box.min.y - topHi, bottomLo - box.max.y),
                            std::max(box.max.y - topLo, bottomHi - box.min.y)};
        return {std::min(rock.lo, slab.lo), std::min(rock.hi, slab.hi)};
    }
    const glm::dvec3 c = box.centre();
    double talus;
    slab(&c.x, &c.y, &c.z, 1, &talus);
    const double reach = mSlabLipschitz * box.radius();
    return {std::min(rock.lo, talus - reach), std::min(rock.hi, talus + reach)};
}

void ScreeField::landformMasks(const double* x, const double* z, std::size_t n, glm::vec4* out) const
{
    mTalus->landformMasks(x, z, n, out);
}

} // namespace strata::terrain
