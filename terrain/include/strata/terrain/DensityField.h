#pragma once
/// \file
/// The interface every density field implements: a signed, distance-like
/// scalar in world metres, negative inside rock, with a known gradient bound.

#include <glm/vec3.hpp>

#include <cmath>

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

    /// A lower bound of the distance (metres) from `p` to the surface (the
    /// zero set of density()), signed like density(p): no surface point lies
    /// within |distanceBound(p)| of p. Sampling prunes with it, while the
    /// values it stores come from density(), so a field may return a close
    /// estimate of the true distance from density() (with a Lipschitz bound
    /// above 1) and still prune with a conservative bound here. The default,
    /// density(p) / lipschitz(), is right for every field.
    virtual double distanceBound(const glm::dvec3& p) const;

    /// Lower bounds of density() and of distanceBound() over all space
    /// (−infinity when unknown). A cave that is never deeper than its radius
    /// says so, and CSG then skips evaluating it where the rock around is
    /// already decided (e.g. in the air above the ground).
    virtual double minDensity() const { return -HUGE_VAL; }
    virtual double minDistanceBound() const { return -HUGE_VAL; }
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
    double distanceBound(const glm::dvec3& p) const override { return density(p); }

private:
    glm::dvec3 mCenter;
    double mRadius;
};

} // namespace strata::terrain
