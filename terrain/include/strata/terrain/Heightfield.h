// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Heightfields y = h(x, z) as density fields: from fractal noise or from an
/// image (the image's pixels are supplied by the caller; the CLI reads PNG
/// and EXR through OpenImageIO, which this library does not depend on).

#include <strata/terrain/DensityField.h>
#include <strata/terrain/FractalNoise.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace strata::terrain {

/// Density of a heightfield with slope bound S (metres per metre):
/// (y − h)·s with s = 1/√(1 + min(S, 1)²), which is the exact distance
/// on flat ground, at most √2 times too large on slopes steeper than 45°
/// (gradient bound √(1 + S²)·s), and whose sign and zero set are exact.
/// The distance bound is the rigorous (y − h)/√(1 + S²).
class HeightfieldBase : public DensityField
{
public:
    double density(const glm::dvec3& p) const final { return (p.y - height(p.x, p.z)) * mScale; }
    /// One height per distinct column (x, z) of the block: a block of n³
    /// voxels asks heights() for n² columns, not n³ points.
    void densities(const PointBlock& points, double* out) const final;
    double lipschitz() const final { return mLipschitz; }
    double distanceBound(const glm::dvec3& p) const final { return (p.y - height(p.x, p.z)) * mBoundScale; }
    /// (y − h)·s is increasing in y and decreasing in h, so over the box it
    /// lies within [(y0 − h1)·s, (y1 − h0)·s] with [h0, h1] =
    /// heightBounds() of the box's xz footprint: exact up to that interval.
    Interval bounds(const WorldBox& box) const final;

    /// Surface height at (x, z), metres.
    virtual double height(double x, double z) const = 0;
    /// height() at n columns, into out[0, n): the same bits. The default
    /// calls height() per column.
    virtual void heights(const double* x, const double* z, std::size_t n, double* out) const;
    /// An interval holding height() over the rectangle [min.x, max.x] ×
    /// [min.y, max.y] (world x and z, metres). The default is h(c) ± S·r
    /// (S = slopeBound(), r the rectangle's half diagonal: h is S-Lipschitz).
    virtual Interval heightBounds(const glm::dvec2& min, const glm::dvec2& max) const;
    /// Bound of |∇h| (metres per metre).
    double slopeBound() const { return mSlope; }

protected:
    void setSlopeBound(double slope);

private:
    double mSlope = 0.0, mScale = 1.0, mBoundScale = 1.0, mLipschitz = 1.0;
};

/// h(x, z) = base + amplitude · f((x, z) / wavelength), f a 2D fractal sum.
struct NoiseHeightfieldOptions
{
    double base = 0.0;        ///< metres, finite
    double amplitude = 55.0;  ///< metres, >= 0 (heights typically ± amplitude/5 for fBm)
    double wavelength = 150.0; ///< metres, > 0: the largest features
    FractalOptions noise{NoiseType::GRADIENT, FractalType::FBM, 6, 2.0, 0.45};
};

class NoiseHeightfield final : public HeightfieldBase
{
public:
    /// Throws strata::Error naming the option ("amplitude = -1 ...").
    NoiseHeightfield(std::uint64_t seed, const NoiseHeightfieldOptions& options);
    double height(double x, double z) const override;
    /// The noise sum as one block evaluation (FractalNoise::evaluate).
    void heights(const double* x, const double* z, std::size_t n, double* out) const override;
    /// base + amplitude·FractalNoise::bounds() over the rectangle in noise
    /// units (amplitude >= 0, so the map is increasing).
    Interval heightBounds(const glm::dvec2& min, const glm::dvec2& max) const override;

private:
    NoiseHeightfieldOptions mOptions;
    FractalNoise mNoise;
};

/// A grid of heights, row-major, `values[z·width + x]`, normalised to [0, 1]
/// (an 8-bit image gives steps of 1/255, a 16-bit one of 1/65535).
struct HeightImage
{
    int width = 0;
    int height = 0;
    std::vector<float> values;
};

/// The image laid over the world rectangle [min.x, max.x] × [min.z, max.z]
/// (column 0 at min.x, row 0 at min.z; pixel centres on the rectangle's
/// edges and evenly in between), bilinearly interpolated and clamped at the
/// edges: h = base + heightScale · value.
struct ImageHeightfieldOptions
{
    glm::dvec2 min{-96.0, -96.0}; ///< world (x, z) of pixel (0, 0), metres
    glm::dvec2 max{96.0, 96.0};   ///< world (x, z) of the last pixel, metres
    double base = 0.0;            ///< metres
    double heightScale = 40.0;    ///< metres for value 1
};

class ImageHeightfield final : public HeightfieldBase
{
public:
    /// Throws strata::Error if the image is smaller than 2×2, has the wrong
    /// number of values or a non-finite one, or the rectangle is empty.
    ImageHeightfield(HeightImage image, const ImageHeightfieldOptions& options);
    double height(double x, double z) const override;
    /// Bilinear interpolation stays within the values of the 4 pixels around
    /// it, and clamping maps the rectangle onto a block of pixels: their
    /// smallest and largest value bound h over it (exact at pixel centres).
    /// Rectangles over more than 4096 pixels use the image's overall range
    /// intersected with the Lipschitz default instead (bounded cost).
    Interval heightBounds(const glm::dvec2& min, const glm::dvec2& max) const override;

private:
    HeightImage mImage;
    ImageHeightfieldOptions mOptions;
    float mMinValue = 0.0f, mMaxValue = 0.0f; ///< over the whole image
};

} // namespace strata::terrain
