#pragma once
/// \file
/// The interface every density field implements: a signed, distance-like
/// scalar in world metres, negative inside rock, with a known gradient bound.

#include <glm/vec3.hpp>

namespace strata::terrain {

class DensityField
{
public:
    virtual ~DensityField() = default;

    /// Density at a world position (metres). Negative inside solid, positive
    /// in air, zero on the surface. Must be a pure function of `p` (thread-safe,
    /// deterministic).
    virtual double density(const glm::dvec3& p) const = 0;

    /// Upper bound of |∇density| over all space (Lipschitz constant). A true
    /// signed distance has 1. Sampling relies on it to skip whole tiles:
    /// |density(p)| > L·r means no surface within r of p.
    virtual double lipschitz() const = 0;
};

/// An exact sphere signed distance: |p − center| − radius.
class SphereField final : public DensityField
{
public:
    SphereField(const glm::dvec3& center, double radius)
        : mCenter(center), mRadius(radius)
    {
    }
    double density(const glm::dvec3& p) const override;
    double lipschitz() const override { return 1.0; }

private:
    glm::dvec3 mCenter;
    double mRadius;
};

} // namespace strata::terrain
