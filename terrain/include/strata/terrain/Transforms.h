// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Fields that evaluate a child at a moved point: domain warp (overhangs,
/// cliffs), terraces (strata steps) and translation.

#include <strata/terrain/Csg.h>
#include <strata/terrain/FractalNoise.h>

#include <cstdint>

namespace strata::terrain {

/// Warps the child's domain with 3D fractal noise:
///   density(p) = child(p + amplitude · (f1, f2, f3)(p / wavelength)).
/// Warping a heightfield sideways by more than its local slope folds it over
/// into overhangs and undercut cliffs. Gradient bound: the child's times
/// 1 + √3·amplitude·L_f / wavelength (the warp's Jacobian norm); the distance
/// bound is the child's divided by that factor.
struct WarpOptions
{
    double amplitude = 6.0;   ///< metres, >= 0
    double wavelength = 40.0; ///< metres, > 0
    FractalOptions noise{NoiseType::GRADIENT, FractalType::FBM, 2, 2.0, 0.5};
    /// Scales the vertical warp component (0 = horizontal warp only, which
    /// makes overhangs without lifting the ground), >= 0.
    double vertical = 0.5;
};

class WarpField final : public DensityField
{
public:
    /// Throws strata::Error naming the option when out of range.
    WarpField(DensityFieldPtr child, std::uint64_t seed, const WarpOptions& options);
    double density(const glm::dvec3& p) const override;
    /// The three noise sums as block evaluations, then the child's block at
    /// the warped points (their box is the one they span).
    void densities(const PointBlock& points, double* out) const override;
    double lipschitz() const override { return mChild->lipschitz() * mStretch; }
    double distanceBound(const glm::dvec3& p) const override;
    double minDensity() const override { return mChild->minDensity(); }
    double minDistanceBound() const override { return std::min(0.0, mChild->minDistanceBound()); }
    /// For p in the box, each warp component a·f_a(p/λ) lies in a·F_a with
    /// F_a = FractalNoise::bounds() over the box in noise units (within the
    /// noise's range), so w(p) lies in the box moved by those
    /// intervals (min + a·F.lo, max + a·F.hi per axis): the child's bounds
    /// over that box hold density(p). Costs the two or three noise sums.
    Interval bounds(const WorldBox& box) const override;

private:
    glm::dvec3 warp(const glm::dvec3& p) const;

    DensityFieldPtr mChild;
    WarpOptions mOptions;
    FractalNoise mX, mY, mZ;
    double mStretch = 1.0;
};

/// Terraces: evaluates the child at (x, T(y), z) with
///   T(y) = step · (k + t^sharpness),  k = floor(y / step), t = y / step − k,
/// which is continuous and monotone: where T is flat the surface climbs
/// steeply (risers), where it is steep the surface stays level (treads), so
/// a heightfield becomes a flight of terraces and caves get strata bands.
/// Gradient bound: the child's times max(1, sharpness).
class TerraceField final : public DensityField
{
public:
    /// step > 0 (metres), sharpness >= 1; throws strata::Error otherwise.
    TerraceField(DensityFieldPtr child, double step, double sharpness);
    double density(const glm::dvec3& p) const override;
    /// terrace() per point through the memo, then the child's block.
    void densities(const PointBlock& points, double* out) const override;
    double lipschitz() const override { return mChild->lipschitz() * std::max(1.0, mSharpness); }
    double distanceBound(const glm::dvec3& p) const override;
    double minDensity() const override { return mChild->minDensity(); }
    double minDistanceBound() const override { return std::min(0.0, mChild->minDistanceBound()); }
    /// T is continuous and non-decreasing (t^sharpness grows with t within a
    /// step and reaches k + 1 where the next step starts), so for y in
    /// [y0, y1], T(y) lies in [T(y0), T(y1)]: the child's bounds over the box
    /// with that y range hold density(). Widened by a few ulps for rounding.
    Interval bounds(const WorldBox& box) const override;

    /// The height map T(y), metres.
    double terrace(double y) const;

private:
    /// terrace(y), remembered per thread: a pow costs as much as a noise
    /// octave, and sampling asks for the same few hundred heights (one per
    /// voxel layer) millions of times, in densities() and bounds() alike.
    double terraceMemo(double y) const;

    DensityFieldPtr mChild;
    double mStep, mSharpness;
    std::uint64_t mIdentity; ///< tells this node's memo entries from another's
};

/// The child moved by `offset` metres: density(p) = child(p − offset).
class TranslateField final : public DensityField
{
public:
    TranslateField(DensityFieldPtr child, const glm::dvec3& offset) : mChild(std::move(child)), mOffset(offset) {}
    double density(const glm::dvec3& p) const override { return mChild->density(p - mOffset); }
    void densities(const PointBlock& points, double* out) const override;
    double lipschitz() const override { return mChild->lipschitz(); }
    double distanceBound(const glm::dvec3& p) const override { return mChild->distanceBound(p - mOffset); }
    double minDensity() const override { return mChild->minDensity(); }
    double minDistanceBound() const override { return std::min(0.0, mChild->minDistanceBound()); }
    /// The child's bounds over the moved box (exactly the points it sees).
    Interval bounds(const WorldBox& box) const override
    {
        return mChild->bounds({box.min - mOffset, box.max - mOffset});
    }

private:
    DensityFieldPtr mChild;
    glm::dvec3 mOffset;
};

} // namespace strata::terrain
