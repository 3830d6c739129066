// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Differential erosion in 3D: where a face cuts across the beds of a
/// Lithology, soft beds retreat into the rock and hard ones stand out, so
/// caprock makes ledges and overhangs, soft beds make alcoves and undercuts,
/// and a fin narrower than twice the retreat of its soft beds opens into an
/// arch under its cap. It acts on the density, not on a height, so the
/// overhangs are real.
///
///   density(p) = child(p) + retreat · (1 − hardness(p)) · exposure(p)
///
/// exposure = 1 − cos²θ, θ the angle between the surface normal (the
/// child's gradient) and the bed normal (the gradient of the stratigraphic
/// height), both taken by forward differences `smoothing` metres long: 0 on
/// a face parallel to the beds (a flat top of horizontal beds keeps its
/// caprock, and rock under a thin cap is protected by it), 1 on a face
/// across them (a cliff). Rock is only removed (density >= child), by at
/// most `retreat` metres measured as the child's distance.
///
/// A pure function of the position: the same bits in any tile, chunk,
/// thread count or SIMD target, with no halo to exchange; the sampler's
/// pruning stays exact through bounds().

#include <strata/terrain/Csg.h>
#include <strata/terrain/Lithology.h>
#include <strata/terrain/RockMasks.h>

namespace strata::terrain {

struct DifferentialErosionOptions
{
    /// Metres, >= 0: how far a bed of hardness 0 retreats from a face across
    /// the beds (a bed of hardness h retreats (1 − h) of it).
    double retreat = 4.0;
    /// Metres, > 0: the step of the differences that measure the face's
    /// and the beds' orientation. Longer smooths the exposure over more
    /// rock; shorter follows small faces.
    double smoothing = 1.0;
};

class DifferentialErosionField final : public DensityField, public RockMasks
{
public:
    /// Throws strata::Error naming the option ("retreat", "smoothing") when
    /// out of range, or naming the Lithology option.
    DifferentialErosionField(DensityFieldPtr child, std::shared_ptr<const Lithology> lithology,
                             const DifferentialErosionOptions& options);

    double density(const glm::dvec3& p) const override;
    /// The child at the block and at the block moved by `smoothing` along
    /// x, y and z (four block calls), then the exposure point by point.
    void densities(const PointBlock& points, double* out) const override;
    /// The child's, plus retreat times the gradient bounds of hardness and
    /// of the exposure. The exposure's is loose (it divides by the
    /// differences' step); distanceBound() avoids it away from faces.
    double lipschitz() const override { return mLipschitz; }
    /// Tighter than density / lipschitz() where it can be: rock is only
    /// removed, and by at most R = retreat · (1 − softest bed), so a point
    /// in the child's air is at least the child's distanceBound() from any
    /// surface, and a point in rock at least (−child − R) / L_child; near a
    /// weathered face, density / lipschitz(). Costs five child evaluations.
    double distanceBound(const glm::dvec3& p) const override;
    double minDensity() const override { return mChild->minDensity(); }
    /// [child.lo, child.hi + retreat · (1 − min hardness over the box)]:
    /// exposure lies in [0, 1] and rock is only removed.
    Interval bounds(const WorldBox& box) const override;

    const Lithology& lithology() const { return *mLithology; }
    /// The same, shared (for nodes that read the rock too).
    std::shared_ptr<const Lithology> lithologyPtr() const { return mLithology; }
    /// The lithology's hardness and bed (RockMasks), at world points as
    /// this node sees them (a transform above it is not undone).
    void rockMasks(const double* x, const double* y, const double* z, std::size_t n, glm::vec2* out) const override;
    /// The exposure (0..1) at p: what multiplies the retreat.
    double exposure(const glm::dvec3& p) const;

private:
    /// One point's result from the child's value at p and at p + smoothing
    /// along each axis (d0, dx, dy, dz), the same arithmetic for density()
    /// and densities().
    double combine(const glm::dvec3& p, double d0, double dx, double dy, double dz, double* exposureOut) const;

    DensityFieldPtr mChild;
    std::shared_ptr<const Lithology> mLithology;
    DifferentialErosionOptions mOptions;
    double mLipschitz = 1.0;
};

} // namespace strata::terrain
