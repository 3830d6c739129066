// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Exact signed-distance primitives for edits and reference shapes: sphere (in
/// DensityField.h), box, capsule and half-space. All lengths in world metres;
/// negative inside. Each is 1-Lipschitz and its density is its own distance
/// bound.

#include <strata/terrain/DensityField.h>

namespace strata::terrain {

/// Box bounds of the convex primitives (box, capsule): the exact signed
/// distance to a convex solid is a convex function, so its largest value over
/// a box is at one of the box's 8 corners (hi is exact); the smallest is at
/// least density(centre) − radius, since it is 1-Lipschitz.
Interval convexBounds(const DensityField& field, const WorldBox& box);

/// An axis-aligned box, optionally with rounded edges.
class BoxField final : public DensityField
{
public:
    /// `halfSize` > 0 per axis; 0 <= `rounding` <= min(halfSize) (asserted).
    BoxField(const glm::dvec3& center, const glm::dvec3& halfSize, double rounding = 0.0);
    double density(const glm::dvec3& p) const override;
    double lipschitz() const override { return 1.0; }
    double distanceBound(const glm::dvec3& p) const override { return density(p); }
    /// convexBounds().
    Interval bounds(const WorldBox& box) const override { return convexBounds(*this, box); }

private:
    glm::dvec3 mCenter, mHalf;
    double mRounding;
};

/// All points within `radius` of the segment a–b.
class CapsuleField final : public DensityField
{
public:
    CapsuleField(const glm::dvec3& a, const glm::dvec3& b, double radius);
    double density(const glm::dvec3& p) const override;
    double lipschitz() const override { return 1.0; }
    double distanceBound(const glm::dvec3& p) const override { return density(p); }
    /// convexBounds().
    Interval bounds(const WorldBox& box) const override { return convexBounds(*this, box); }

private:
    glm::dvec3 mA, mB;
    double mRadius;
};

/// The half-space below a plane: dot(normal, p) − offset, with `normal`
/// normalised (must not be zero). normal (0, 1, 0), offset h: solid below y = h.
class PlaneField final : public DensityField
{
public:
    PlaneField(const glm::dvec3& normal, double offset);
    double density(const glm::dvec3& p) const override;
    double lipschitz() const override { return 1.0; }
    double distanceBound(const glm::dvec3& p) const override { return density(p); }
    /// Exact: a linear function over a box ranges over n·c ± Σ|n_a|·half_a.
    Interval bounds(const WorldBox& box) const override;

private:
    glm::dvec3 mNormal;
    double mOffset;
};

} // namespace strata::terrain
