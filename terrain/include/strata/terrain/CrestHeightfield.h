// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Sharp crests on a height node whose ridges came out rounded: an erosion
/// grid upsampled by a smooth spline (ErodedHeightfield) rounds every ridge
/// over about two of its cells, where real hard rock meets at an edge.
///
/// In each of four directions u (0°, 45°, 90°, 135°) both flanks are read
/// at reach d and 2d and extended straight back to the point:
///   P± = 2·h(p ± d·u) − h(p ± 2d·u),  T = max over u of min(P+, P−).
/// Where the flanks are planes meeting at a rounded ridge, T is the height
/// at which they meet (for any reach past the rounding), so the ridge
/// becomes their edge again; on a plane T = h; in a valley or hollow T <= h.
/// The node lifts only:
///   h' = h + min(maxLift, amount · w · max(0, T − h)),
/// w = clamp(mask, 0, 1) · hardness of the rock at (x, h, z) (each 1 when
/// not given), so crests are sharp where rock is hard and stay rounded in
/// soft beds. A pointwise function of the child: tile-exact and the same
/// bits on any thread count, computed with + − × and min/max only.

#include <strata/terrain/HeightGraph.h>
#include <strata/terrain/Lithology.h>

#include <memory>

namespace strata::terrain {

struct CrestOptions
{
    double reach = 12.0;  ///< metres, > 0: d, past the width of the rounding (about 1.5 erosion cells)
    double amount = 1.0;  ///< 0..1: the share of the way to the flanks' edge
    double maxLift = 10.0; ///< metres, >= 0: the most a crest is raised
};

class CrestHeightfield final : public HeightfieldBase
{
public:
    /// `mask` (a height node read as 0..1) and `lithology` (whose hardness
    /// at the ground scales the lift) may be null. Throws strata::Error
    /// naming "reach", "amount" or "max_lift" when out of range.
    CrestHeightfield(HeightNodePtr child, const CrestOptions& options, HeightNodePtr mask = nullptr,
                     std::shared_ptr<const Lithology> lithology = nullptr);
    double height(double x, double z) const override;
    /// The child at all 17 points of n columns in one call, then the lifts.
    void heights(const double* x, const double* z, std::size_t n, double* out) const override;
    /// [child's low, child's high + the largest lift]: the node only lifts.
    Interval heightBounds(const glm::dvec2& min, const glm::dvec2& max) const override;

private:
    /// The lift at a column from its own height h and the 16 flank heights
    /// (direction k, side s, step t at index 4k + 2s + t).
    double lift(double x, double z, double h, const double* flanks, double mask) const;

    HeightNodePtr mChild, mMask;
    std::shared_ptr<const Lithology> mLithology;
    CrestOptions mOptions;
    double mLiftBound = 0.0; ///< the largest lift anywhere, metres
};

} // namespace strata::terrain
