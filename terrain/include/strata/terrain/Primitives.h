#pragma once
/// \file
/// Exact signed-distance primitives for edits and tests: sphere (in
/// DensityField.h), box, capsule and half-space. All lengths in world metres;
/// negative inside. Each is 1-Lipschitz and its density is its own distance
/// bound.

#include <strata/terrain/DensityField.h>

namespace strata::terrain {

/// An axis-aligned box, optionally with rounded edges.
class BoxField final : public DensityField
{
public:
    /// `halfSize` > 0 per axis; 0 <= `rounding` <= min(halfSize) (asserted).
    BoxField(const glm::dvec3& center, const glm::dvec3& halfSize, double rounding = 0.0);
    double density(const glm::dvec3& p) const override;
    double lipschitz() const override { return 1.0; }
    double distanceBound(const glm::dvec3& p) const override { return density(p); }

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

private:
    glm::dvec3 mNormal;
    double mOffset;
};

} // namespace strata::terrain
