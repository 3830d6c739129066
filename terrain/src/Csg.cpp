// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/Csg.h>

#include "BlockScratch.h"
#include "NodeRegistrations.h"
#include <strata/terrain/NodeRegistry.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

namespace strata::terrain {

double smoothMin(double a, double b, double k)
{
    // Outside the blend the result is exactly min(a, b).
    if (k <= 0.0 || b - a >= k || a - b >= k) return std::min(a, b);
    const double h = std::clamp(0.5 + 0.5 * (b - a) / k, 0.0, 1.0);
    return b + h * (a - b) - k * h * (1.0 - h);
}

double smoothMax(double a, double b, double k)
{
    return -smoothMin(-a, -b, k);
}

CsgField::CsgField(CsgOperation operation, std::vector<DensityFieldPtr> children, double smoothRadius)
    : mOperation(operation), mChildren(std::move(children)), mSmooth(smoothRadius)
{
    assert(mChildren.size() >= 2 && smoothRadius >= 0.0);
    mLipschitz = 0.0;
    for (const DensityFieldPtr& child : mChildren) {
        assert(child);
        mLipschitz = std::max(mLipschitz, child->lipschitz());
    }
}

double CsgField::density(const glm::dvec3& p) const
{
    double d = mChildren[0]->density(p);
    for (std::size_t i = 1; i < mChildren.size(); ++i) {
        // A child that cannot change the result is not evaluated: −c is at
        // most −minDensity for a subtraction, c at least minDensity for a union.
        const double floor = mChildren[i]->minDensity();
        if (mOperation == CsgOperation::SUBTRACT && d >= mSmooth - floor) continue;
        if (mOperation == CsgOperation::UNION && d <= floor - mSmooth) continue;
        const double c = mChildren[i]->density(p);
        switch (mOperation) {
        case CsgOperation::UNION: d = smoothMin(d, c, mSmooth); break;
        case CsgOperation::SUBTRACT: d = smoothMax(d, -c, mSmooth); break;
        case CsgOperation::INTERSECT: d = smoothMax(d, c, mSmooth); break;
        }
    }
    return d;
}

namespace {

/// Bounds are rigorous up to rounding of about 1e-7 relative (DensityField::
/// bounds); a skip decided by them keeps this much more margin, so a value
/// the child leaves unchanged by the interval is unchanged point by point.
double skipMargin(const Interval& c, double dLo, double dHi)
{
    return 1e-4 + 1e-6 * (std::abs(c.lo) + std::abs(c.hi) + std::abs(dLo) + std::abs(dHi));
}

} // namespace

void CsgField::densities(const PointBlock& points, double* out) const
{
    const std::size_t n = points.count;
    mChildren[0]->densities(points, out);
    detail::ScratchFrame scratch;
    std::size_t* need = scratch.array<std::size_t>(n);
    double *x = scratch.array<double>(4 * n), *y = x + n, *z = y + n, *c = z + n;
    for (std::size_t i = 1; i < mChildren.size(); ++i) {
        const DensityField& child = *mChildren[i];
        // The points where density() would evaluate this child.
        const double floor = child.minDensity();
        std::size_t m = 0;
        double dLo = HUGE_VAL, dHi = -HUGE_VAL;
        for (std::size_t j = 0; j < n; ++j) {
            const double d = out[j];
            if (mOperation == CsgOperation::SUBTRACT && d >= mSmooth - floor) continue;
            if (mOperation == CsgOperation::UNION && d <= floor - mSmooth) continue;
            need[m++] = j;
            dLo = std::min(dLo, d);
            dHi = std::max(dHi, d);
        }
        if (m == 0) continue;
        // Outside the blend, smooth-min/max return the unchanged operand
        // exactly: d when c + d >= k (subtract), c − d >= k (union),
        // d − c >= k (intersect). A bound costs about one evaluation.
        if (m >= 8) {
            const Interval c = child.bounds(points.box);
            const double margin = mSmooth + skipMargin(c, dLo, dHi);
            if ((mOperation == CsgOperation::SUBTRACT && c.lo + dLo >= margin) ||
                (mOperation == CsgOperation::UNION && c.lo - dHi >= margin) ||
                (mOperation == CsgOperation::INTERSECT && dLo - c.hi >= margin))
                continue;
        }
        for (std::size_t k = 0; k < m; ++k) {
            x[k] = points.x[need[k]];
            y[k] = points.y[need[k]];
            z[k] = points.z[need[k]];
        }
        PointBlock some{x, y, z, m, points.box};
        if (m < n) some.box = spannedBox(some);
        child.densities(some, c);
        for (std::size_t k = 0; k < m; ++k) {
            double& d = out[need[k]];
            switch (mOperation) {
            case CsgOperation::UNION: d = smoothMin(d, c[k], mSmooth); break;
            case CsgOperation::SUBTRACT: d = smoothMax(d, -c[k], mSmooth); break;
            case CsgOperation::INTERSECT: d = smoothMax(d, c[k], mSmooth); break;
            }
        }
    }
}

Interval CsgField::bounds(const WorldBox& box) const
{
    Interval d = mChildren[0]->bounds(box);
    for (std::size_t i = 1; i < mChildren.size(); ++i) {
        // density() skips the child at p when it cannot change the result
        // there; if that holds at every point of the box (d.lo, d.hi decide
        // it), every value is unchanged and so is the interval.
        const double floor = mChildren[i]->minDensity();
        if (mOperation == CsgOperation::SUBTRACT && d.lo >= mSmooth - floor) continue;
        if (mOperation == CsgOperation::UNION && d.hi <= floor - mSmooth) continue;
        const Interval c = mChildren[i]->bounds(box);
        switch (mOperation) {
        case CsgOperation::UNION: d = {smoothMin(d.lo, c.lo, mSmooth), smoothMin(d.hi, c.hi, mSmooth)}; break;
        case CsgOperation::SUBTRACT: d = {smoothMax(d.lo, -c.hi, mSmooth), smoothMax(d.hi, -c.lo, mSmooth)}; break;
        case CsgOperation::INTERSECT: d = {smoothMax(d.lo, c.lo, mSmooth), smoothMax(d.hi, c.hi, mSmooth)}; break;
        }
    }
    return d;
}

double CsgField::distanceBound(const glm::dvec3& p) const
{
    // Sharp min/max of lower distance bounds are lower bounds of the sharp
    // result. The smooth result differs from the sharp one by at most k/4 in
    // density; the bound moves by k/2 on the side the blend can reach.
    double b = mChildren[0]->distanceBound(p);
    for (std::size_t i = 1; i < mChildren.size(); ++i) {
        const double floor = mChildren[i]->minDistanceBound();
        if (mOperation == CsgOperation::SUBTRACT && b >= -floor) continue;
        if (mOperation == CsgOperation::UNION && b <= floor) continue;
        const double c = mChildren[i]->distanceBound(p);
        switch (mOperation) {
        case CsgOperation::UNION: b = std::min(b, c); break;
        case CsgOperation::SUBTRACT: b = std::max(b, -c); break;
        case CsgOperation::INTERSECT: b = std::max(b, c); break;
        }
    }
    if (mSmooth <= 0.0) return b;
    const double slack = 0.5 * mSmooth * double(mChildren.size() - 1);
    if (mOperation == CsgOperation::UNION) return b > 0.0 ? std::max(0.0, b - slack) : b;
    return b < 0.0 ? std::min(0.0, b + slack) : b;
}

} // namespace strata::terrain

namespace strata::terrain {

void registerCsgNodes(NodeRegistry& registry)
{
    const struct
    {
        const char* name;
        CsgOperation operation;
        const char* description;
    } operations[] = {
        {"union", CsgOperation::UNION, "CSG union (min) of the children"},
        {"subtract", CsgOperation::SUBTRACT, "CSG: the first child minus the others"},
        {"intersect", CsgOperation::INTERSECT, "CSG intersection (max) of the children"},
    };
    for (const auto& op : operations) {
        NodeType type{op.name, op.description, {}, {}};
        type.keys = {childrenKey("children", "the nodes to combine, in order"),
                     numberKey("smooth", 0.0, 0.0, 1e4, "m", "> 0 blends with a polynomial smooth-min of this radius")};
        const CsgOperation operation = op.operation;
        type.build = [operation](const NodeArgs& a) -> DensityFieldPtr {
            return std::make_shared<CsgField>(operation, a.children("children"), a.number("smooth"));
        };
        registry.add(std::move(type));
    }
}

} // namespace strata::terrain
