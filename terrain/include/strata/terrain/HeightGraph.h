// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The height graph: 2D nodes that produce h(x, z), metres, and combine into
/// one heightfield (the way Gaea's and World Machine's graphs do). Every
/// node is a HeightfieldBase, so it is also the density field y − h and can
/// be a scene's root or a child of any 3D node; height nodes take other
/// height nodes (heightfield, image_heightfield, erode, the nodes below) as
/// children. Each keeps a rigorous slope bound |∇h| <= slopeBound() and
/// interval bounds over rectangles, which the sampler prunes with.
///
/// Masks (height, slope, curvature) are height nodes with values in [0, 1],
/// for height_blend and height_multiply.

#include <strata/terrain/FractalNoise.h>
#include <strata/terrain/Heightfield.h>

#include <glm/vec2.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace strata::terrain {

using HeightNodePtr = std::shared_ptr<const HeightfieldBase>;

/// h = value everywhere.
class ConstantHeight final : public HeightfieldBase
{
public:
    explicit ConstantHeight(double value);
    double height(double, double) const override { return mValue; }
    Interval heightBounds(const glm::dvec2&, const glm::dvec2&) const override { return {mValue, mValue}; }

private:
    double mValue;
};

/// How HeightCombine folds its inputs, left to right.
enum class HeightOp
{
    Add,      ///< a + b + ...
    Subtract, ///< a − b − ...
    Multiply, ///< a · b · ...
    Min,      ///< min(a, b, ...)
    Max,      ///< max(a, b, ...)
};

/// Two or more heights folded by one operation.
class HeightCombine final : public HeightfieldBase
{
public:
    /// Throws strata::Error when fewer than two inputs are given, or when a
    /// product's inputs have no finite bound (their slope bound would be
    /// infinite).
    HeightCombine(HeightOp op, std::vector<HeightNodePtr> inputs);
    double height(double x, double z) const override;
    void heights(const double* x, const double* z, std::size_t n, double* out) const override;
    Interval heightBounds(const glm::dvec2& min, const glm::dvec2& max) const override;

private:
    double fold(double a, double b) const;
    Interval fold(Interval a, Interval b) const;
    HeightOp mOp;
    std::vector<HeightNodePtr> mInputs;
};

/// h = a + clamp(mask, 0, 1) · (b − a): b where the mask is 1, a where 0.
class HeightBlend final : public HeightfieldBase
{
public:
    HeightBlend(HeightNodePtr a, HeightNodePtr b, HeightNodePtr mask);
    double height(double x, double z) const override;
    void heights(const double* x, const double* z, std::size_t n, double* out) const override;
    Interval heightBounds(const glm::dvec2& min, const glm::dvec2& max) const override;

private:
    HeightNodePtr mA, mB, mMask;
};

/// A height node that maps its child's heights one by one, h = map(child):
/// the column loop is shared; each subclass gives map() and its bounds.
class MappedHeight : public HeightfieldBase
{
public:
    double height(double x, double z) const final { return map(mChild->height(x, z)); }
    void heights(const double* x, const double* z, std::size_t n, double* out) const final;
    /// The map from the child's height to this node's, metres.
    virtual double map(double h) const = 0;

protected:
    explicit MappedHeight(HeightNodePtr child) : mChild(std::move(child)) {}
    HeightNodePtr mChild;
};

/// h = clamp(child · scale + offset, min, max).
struct HeightAffineOptions
{
    double scale = 1.0;
    double offset = 0.0; ///< metres
    double min = -HUGE_VAL, max = HUGE_VAL; ///< metres, min <= max
};

class HeightAffine final : public MappedHeight
{
public:
    HeightAffine(HeightNodePtr child, const HeightAffineOptions& options);
    double map(double h) const override;
    Interval heightBounds(const glm::dvec2& min, const glm::dvec2& max) const override;

private:
    HeightAffineOptions mOptions;
};

/// h = curve(child): a monotone piecewise cubic (Fritsch–Carlson, as
/// PCHIP) through the points (input height, output height), inputs strictly
/// increasing; it never overshoots its points, and extends flat beyond the
/// first and last point.
class HeightCurve final : public MappedHeight
{
public:
    /// Throws strata::Error "points ..." for fewer than 2 points, inputs not
    /// strictly increasing or non-finite values.
    HeightCurve(HeightNodePtr child, std::vector<glm::dvec2> points);
    double map(double h) const override;
    Interval heightBounds(const glm::dvec2& min, const glm::dvec2& max) const override;

private:
    std::vector<glm::dvec2> mPoints;
    std::vector<double> mTangents;
};

/// Terraces of height `step`: h = step·(k + f^sharpness), k = ⌊child/step⌋,
/// f the fraction (the 3D terrace node's profile, on heights).
class HeightTerrace final : public MappedHeight
{
public:
    HeightTerrace(HeightNodePtr child, double step, double sharpness);
    /// step·(k + f^sharpness).
    double map(double h) const override;
    Interval heightBounds(const glm::dvec2& min, const glm::dvec2& max) const override;

private:
    double mStep, mSharpness;
};

/// 2D domain warp: h(p) = child(p + amplitude · (n₁, n₂)(p / wavelength)),
/// two decorrelated fractal noises.
struct HeightWarpOptions
{
    double amplitude = 30.0;   ///< metres, >= 0
    double wavelength = 200.0; ///< metres, > 0
    FractalOptions noise{NoiseType::GRADIENT, FractalType::FBM, 3, 2.0, 0.5};
};

class HeightWarp final : public HeightfieldBase
{
public:
    HeightWarp(HeightNodePtr child, std::uint64_t seed, const HeightWarpOptions& options);
    double height(double x, double z) const override;
    void heights(const double* x, const double* z, std::size_t n, double* out) const override;
    Interval heightBounds(const glm::dvec2& min, const glm::dvec2& max) const override;

private:
    HeightNodePtr mChild;
    HeightWarpOptions mOptions;
    FractalNoise mNoiseX, mNoiseZ;
};

/// What a mask measures of its input.
enum class MaskSource
{
    Height,    ///< the input height, metres
    Slope,     ///< |∇h| by central differences over `radius` (rise over run)
    Curvature, ///< −∇²h by differences over `radius`, 1/m: > 0 on ridges and peaks, < 0 in valleys
};

/// A soft band on the measured value v: 1 for v in [min, max], falling to 0
/// over `softness` outside (smoothstep).
struct MaskOptions
{
    MaskSource source = MaskSource::Height;
    double min = 0.0, max = 1.0; ///< min <= max, in the source's unit
    double softness = 1.0;       ///< > 0, in the source's unit
    double radius = 4.0;         ///< metres, > 0: the differences' step (slope, curvature)
};

class HeightMask final : public HeightfieldBase
{
public:
    HeightMask(HeightNodePtr child, const MaskOptions& options);
    double height(double x, double z) const override;
    void heights(const double* x, const double* z, std::size_t n, double* out) const override;
    Interval heightBounds(const glm::dvec2& min, const glm::dvec2& max) const override;

private:
    double band(double v) const;
    HeightNodePtr mChild;
    MaskOptions mOptions;
};

} // namespace strata::terrain
