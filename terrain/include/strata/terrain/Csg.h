// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Constructive solid geometry on density fields: union, subtraction and
/// intersection, sharp or smooth (polynomial smooth-min with a blend radius).

#include <strata/terrain/DensityField.h>

#include <memory>
#include <vector>

namespace strata::terrain {

using DensityFieldPtr = std::shared_ptr<const DensityField>;

enum class CsgOperation
{
    UNION,     ///< min(a, b, ...): solid where any child is
    SUBTRACT,  ///< max(a, −b, −c, ...): the first child minus all the others
    INTERSECT, ///< max(a, b, ...): solid where every child is
};

/// Combines two or more children, left to right. With smoothRadius k > 0 the
/// min/max become the polynomial smooth-min of Quilez,
///   smin(a, b) = lerp(b, a, h) − k·h·(1 − h),  h = clamp(1/2 + (b − a)/(2k), 0, 1),
/// which fills creases with fillets about k wide (it differs from min by at
/// most k/4). Gradient bound: the largest of the children's (the smooth-min
/// is a convex blend of gradients). Distance bound: the sharp combination of
/// the children's bounds (exact for min/max), widened by k/2 towards the side
/// the blend grows (smooth union grows outward, smooth subtraction and
/// intersection shrink inward).
class CsgField final : public DensityField
{
public:
    /// `children` holds at least two non-null fields; smoothRadius >= 0
    /// (asserted: the scene reader validates).
    CsgField(CsgOperation operation, std::vector<DensityFieldPtr> children, double smoothRadius = 0.0);

    double density(const glm::dvec3& p) const override;
    /// density()'s per-point skip, and per block: a child whose bounds()
    /// over the block show it leaves every value unchanged (beyond a margin
    /// for rounding) is not evaluated; one needed at a few points only is
    /// evaluated at those.
    void densities(const PointBlock& points, double* out) const override;
    double lipschitz() const override { return mLipschitz; }
    double distanceBound(const glm::dvec3& p) const override;
    /// The children's intervals combined by the same operation applied to
    /// their ends: min, max and the smooth-min/max are non-decreasing in each
    /// argument (the smooth-min's partial derivatives are h and 1 − h, both in
    /// [0, 1]), so op([a0, a1], [b0, b1]) lies in [op(a0, b0), op(a1, b1)]
    /// (subtraction takes −b, i.e. [−b1, −b0]). A child that density() would
    /// skip at every point of the box (its minDensity() cannot change the
    /// result) is skipped here too.
    Interval bounds(const WorldBox& box) const override;

private:
    CsgOperation mOperation;
    std::vector<DensityFieldPtr> mChildren;
    double mSmooth;
    double mLipschitz = 1.0;
};

/// Polynomial smooth minimum, radius k >= 0 (k = 0: min).
double smoothMin(double a, double b, double k);
/// −smoothMin(−a, −b, k).
double smoothMax(double a, double b, double k);

} // namespace strata::terrain
