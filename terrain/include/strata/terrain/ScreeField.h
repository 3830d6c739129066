// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The `scree` node: a `talus` node's cones laid over 3D rock.
///
/// The talus of a height node is computed on its ground (TalusHeightfield);
/// the rock a player sees may have been cut further in 3D after that ground
/// (beds retreating into alcoves, warps). Built into the height graph, the
/// talus would be cut with it: ledged, warped, steeper than its angle. This
/// node adds it afterwards, as a slab from below the foot of the faces (L −
/// depth) up to the cones (C), united with the rock:
///   density = min(rock(p), max(y − top(x, z), (L − depth) − y))
///   top     = C − clamp(1 m − (C − H), 0, 1 m)
/// so the talus fills the alcoves and retreats at the foot of a wall (up to
/// a metre under the cones there: H is the uncut ground) as well as the
/// ground in front of it, and stays a metre under the ground where the
/// cones do not rise above it. Where it lies at least a metre
/// thick its surface is the cones: never steeper than the talus angle.
/// Caves subtracted after this node cut through the talus too.

#include <strata/terrain/DensityField.h>
#include <strata/terrain/LandformMasks.h>
#include <strata/terrain/TalusHeightfield.h>

#include <memory>

namespace strata::terrain {

class ScreeField final : public DensityField, public LandformMasks
{
public:
    /// `depth` (metres, > 0): how far below the foot the slab reaches.
    /// Throws strata::Error naming `depth` when it is out of range.
    ScreeField(std::shared_ptr<const DensityField> rock, std::shared_ptr<const TalusHeightfield> talus, double depth);

    double density(const glm::dvec3& p) const override;
    void densities(const PointBlock& points, double* out) const override;
    double lipschitz() const override { return mLipschitz; }
    /// min of the rock's and the slab's (a union is at least as far from
    /// its surface as the nearer of the two).
    double distanceBound(const glm::dvec3& p) const override;
    /// The rock's bounds, lowered to the slab's (its value at the centre ±
    /// its own gradient bound times the box's radius).
    Interval bounds(const WorldBox& box) const override;
    /// The talus' landform masks: its thickness above the ground H.
    void landformMasks(const double* x, const double* z, std::size_t n, glm::vec4* out) const override;

private:
    /// The slab's density at n points.
    void slab(const double* x, const double* y, const double* z, std::size_t n, double* out) const;

    std::shared_ptr<const DensityField> mRock;
    std::shared_ptr<const TalusHeightfield> mTalus;
    double mDepth;
    double mLipschitz = 1.0;
    double mSlabLipschitz = 1.0;
};

} // namespace strata::terrain
