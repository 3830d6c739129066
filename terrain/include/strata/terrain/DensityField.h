// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The interface every density field implements: a signed, distance-like
/// scalar in world metres, negative inside rock, with a known gradient bound.

#include <glm/vec3.hpp>

#include <cmath>
#include <cstddef>

namespace strata::terrain {

/// A closed interval [lo, hi] of density values.
struct Interval
{
    double lo = 0.0;
    double hi = 0.0;
};

/// An axis-aligned box of world positions, metres, both faces included
/// (min <= max per axis; a point is a box with min == max).
struct WorldBox
{
    glm::dvec3 min{0.0};
    glm::dvec3 max{0.0};

    glm::dvec3 centre() const { return 0.5 * (min + max); }
    /// Half the length of the diagonal: every point of the box lies within
    /// this distance of centre().
    double radius() const;
};

/// A block of points in structure-of-arrays form (metres), with a box that
/// holds every one of them: the unit of block evaluation
/// (DensityField::densities). The arrays are the caller's; count may be 0.
struct PointBlock
{
    const double* x = nullptr;
    const double* y = nullptr;
    const double* z = nullptr;
    std::size_t count = 0;
    WorldBox box; ///< min <= every point <= max, per axis
};

/// The smallest box holding the block's points (its `box` is not read).
WorldBox spannedBox(const PointBlock& points);

class DensityField
{
public:
    virtual ~DensityField() = default;

    /// Density at a world position (metres). Negative inside solid, positive
    /// in air, zero on the surface. Must be a pure function of `p` (thread-safe,
    /// deterministic).
    virtual double density(const glm::dvec3& p) const = 0;

    /// density() at every point of `points`, into out[0, count): the same
    /// bits as density() point by point (checked node by node), in
    /// one virtual call per node and block instead of one per point. Nodes
    /// override it to share work across the block: lattice hashes of noise
    /// cells, a heightfield's columns, a cave's segment list, a CSG child
    /// that the block's interval shows cannot change the result. The
    /// default calls density() per point. Thread-safe like density().
    virtual void densities(const PointBlock& points, double* out) const;

    /// Upper bound of |∇density| over all space (Lipschitz constant). A true
    /// signed distance has 1. The default bounds() relies on it:
    /// |density(p) − density(c)| <= L·|p − c|.
    virtual double lipschitz() const = 0;

    /// A lower bound of the distance (metres) from `p` to the surface (the
    /// zero set of density()), signed like density(p): no surface point lies
    /// within |distanceBound(p)| of p. For callers that step through space
    /// (sphere tracing, probes); sampling prunes with bounds() instead. A
    /// field may return a close estimate of the true distance from density()
    /// (with a Lipschitz bound above 1) and a conservative bound here. The
    /// default, density(p) / lipschitz(), is right for every field.
    virtual double distanceBound(const glm::dvec3& p) const;

    /// distanceBound() at every point of a block, the same bits point by
    /// point. The default calls distanceBound() per point; a field whose
    /// distanceBound() is density() / lipschitz() overrides it to evaluate
    /// the block at once (the World prunes a chunk's blocks with it).
    virtual void distanceBounds(const PointBlock& points, double* out) const;

    /// Lower bounds of density() and of distanceBound() over all space
    /// (−infinity when unknown). A cave that is never deeper than its radius
    /// says so, and CSG then skips evaluating it where the rock around is
    /// already decided (e.g. in the air above the ground).
    virtual double minDensity() const { return -HUGE_VAL; }
    virtual double minDistanceBound() const { return -HUGE_VAL; }

    /// An interval that holds density(p) for every p in `box`: sampling
    /// prunes a block of voxels when the interval of its box lies outside
    /// the narrow band (and takes the block's sign from it), so it must be
    /// conservative; the tighter, the fewer voxels are evaluated. Must be a
    /// pure function of the box (thread-safe, deterministic).
    ///
    /// The default, density(c) ± lipschitz()·radius (c the box centre), raised
    /// to minDensity(), is right for every field (Lipschitz: |d(p) − d(c)| <=
    /// L·|p − c| <= L·radius). Nodes override it where the math allows a
    /// tighter one (terraces map intervals monotonically, a warp moves the box
    /// by the bounds of its noise, CSG combines intervals, a heightfield bounds
    /// y − h over the box's xz footprint, primitives are exact or convex).
    /// Cost: the node's noise sums once, at the box centre, plus interval
    /// arithmetic: one to about two and a half density() calls for the
    /// library's nodes (the sampler counts each call as one evaluated point
    /// and reports them separately, SampleStats::boundEvaluations). Values are rigorous
    /// for exact arithmetic; float noise adds rounding of about 1e-7 relative,
    /// which the sampler's pruning slack covers.
    virtual Interval bounds(const WorldBox& box) const;
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
    /// Exact: the distances from the centre to the box's nearest point and
    /// farthest corner, minus the radius.
    Interval bounds(const WorldBox& box) const override;

private:
    glm::dvec3 mCenter;
    double mRadius;
};

} // namespace strata::terrain
