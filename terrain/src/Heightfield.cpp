// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/Heightfield.h>

#include "BlockColumns.h"

#include "NodeRegistrations.h"
#include <strata/Format.h>
#include <strata/terrain/NodeRegistry.h>

#include "ShowValue.h"

#include <strata/Error.h>
#include <strata/IntegerMath.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace strata::terrain {

using detail::show;

void HeightfieldBase::setSlopeBound(double slope)
{
    mSlope = slope;
    const double typical = std::min(slope, 1.0);
    mScale = 1.0 / std::sqrt(1.0 + typical * typical);
    mBoundScale = 1.0 / std::sqrt(1.0 + slope * slope);
    mLipschitz = std::sqrt(1.0 + slope * slope) * mScale;
}

Interval HeightfieldBase::bounds(const WorldBox& box) const
{
    const Interval h = heightBounds(glm::dvec2(box.min.x, box.min.z), glm::dvec2(box.max.x, box.max.z));
    return {(box.min.y - h.hi) * mScale, (box.max.y - h.lo) * mScale};
}

void HeightfieldBase::heights(const double* x, const double* z, std::size_t n, double* out) const
{
    for (std::size_t i = 0; i < n; ++i) out[i] = height(x[i], z[i]);
}

void HeightfieldBase::densities(const PointBlock& points, double* out) const
{
    const std::size_t n = points.count;
    if (n == 0) return;
    detail::ScratchFrame scratch;
    const detail::BlockColumns columns = detail::findColumns(points, scratch);
    double* h = scratch.array<double>(columns.count);
    heights(columns.x, columns.z, columns.count, h);
    for (std::size_t i = 0; i < n; ++i) out[i] = (points.y[i] - h[columns.of[i]]) * mScale;
}

Interval HeightfieldBase::heightBounds(const glm::dvec2& min, const glm::dvec2& max) const
{
    const glm::dvec2 c = 0.5 * (min + max);
    const double reach = mSlope * 0.5 * glm::length(max - min);
    const double h = height(c.x, c.y);
    return {h - reach, h + reach};
}

NoiseHeightfield::NoiseHeightfield(std::uint64_t seed, const NoiseHeightfieldOptions& options)
    : mOptions(options), mNoise(seed, options.noise)
{
    if (!std::isfinite(options.base)) throw Error(ErrorKind::BadInput, "base = " + show(options.base) + " must be a finite number");
    if (!(std::isfinite(options.amplitude) && options.amplitude >= 0.0)) {
        throw Error(ErrorKind::BadInput, "amplitude = " + show(options.amplitude) + " must be a finite number >= 0");
    }
    if (!(std::isfinite(options.wavelength) && options.wavelength > 0.0)) {
        throw Error(ErrorKind::BadInput, "wavelength = " + show(options.wavelength) + " must be a finite number > 0");
    }
    setSlopeBound(options.amplitude / options.wavelength * mNoise.lipschitz(2));
}

double NoiseHeightfield::height(double x, double z) const
{
    return mOptions.base + mOptions.amplitude * mNoise(glm::dvec2(x / mOptions.wavelength, z / mOptions.wavelength));
}

void NoiseHeightfield::heights(const double* x, const double* z, std::size_t n, double* out) const
{
    // As height(): base + amplitude·noise(x / wavelength, z / wavelength).
    const double w = mOptions.wavelength;
    detail::ScratchFrame scratch;
    double* q = scratch.array<double>(2 * n);
    for (std::size_t i = 0; i < n; ++i) {
        q[i] = x[i] / w;
        q[n + i] = z[i] / w;
    }
    mNoise.evaluate(q, q + n, n, out);
    for (std::size_t i = 0; i < n; ++i) out[i] = mOptions.base + mOptions.amplitude * out[i];
}

Interval NoiseHeightfield::heightBounds(const glm::dvec2& min, const glm::dvec2& max) const
{
    const double w = mOptions.wavelength;
    const Interval n = mNoise.bounds(min / w, max / w);
    return {mOptions.base + mOptions.amplitude * n.lo, mOptions.base + mOptions.amplitude * n.hi};
}

ImageHeightfield::ImageHeightfield(HeightImage image, const ImageHeightfieldOptions& options)
    : mImage(std::move(image)), mOptions(options)
{
    if (mImage.width < 2 || mImage.height < 2) {
        throw Error(ErrorKind::BadInput, "image is " + std::to_string(mImage.width) + "x" + std::to_string(mImage.height) +
                    " pixels, at least 2x2 are needed");
    }
    if (mImage.values.size() != std::size_t(mImage.width) * std::size_t(mImage.height)) {
        throw Error(ErrorKind::BadInput, "image has " + std::to_string(mImage.values.size()) + " values for " +
                    std::to_string(mImage.width) + "x" + std::to_string(mImage.height) + " pixels");
    }
    for (int a = 0; a < 2; ++a) {
        if (!(std::isfinite(options.min[a]) && std::isfinite(options.max[a]) && options.max[a] > options.min[a])) {
            throw Error(ErrorKind::BadInput, std::string("the image rectangle is empty or not finite along ") + (a == 0 ? "x" : "z") +
                        ": min = " + show(options.min[a]) + ", max = " + show(options.max[a]));
        }
    }
    if (!std::isfinite(options.base)) throw Error(ErrorKind::BadInput, "base = " + show(options.base) + " must be a finite number");
    if (!std::isfinite(options.heightScale)) {
        throw Error(ErrorKind::BadInput, "height_scale = " + show(options.heightScale) + " must be a finite number");
    }
    // Bilinear interpolation: the slope along an axis is at most the largest
    // step between neighbouring pixels along it, over the pixel spacing.
    double stepX = 0.0, stepZ = 0.0;
    for (int z = 0; z < mImage.height; ++z) {
        for (int x = 0; x < mImage.width; ++x) {
            const float v = mImage.values[std::size_t(z) * mImage.width + x];
            if (!std::isfinite(v)) throw Error(ErrorKind::BadInput, "image value at pixel (" + std::to_string(x) + ", " +
                                               std::to_string(z) + ") is not finite");
            if (x + 1 < mImage.width) stepX = std::max(stepX, double(std::abs(mImage.values[std::size_t(z) * mImage.width + x + 1] - v)));
            if (z + 1 < mImage.height) stepZ = std::max(stepZ, double(std::abs(mImage.values[std::size_t(z + 1) * mImage.width + x] - v)));
        }
    }
    const double spacingX = (options.max.x - options.min.x) / double(mImage.width - 1);
    const double spacingZ = (options.max.y - options.min.y) / double(mImage.height - 1);
    const double sx = std::abs(options.heightScale) * stepX / spacingX;
    const double sz = std::abs(options.heightScale) * stepZ / spacingZ;
    setSlopeBound(std::sqrt(sx * sx + sz * sz));
    const auto [lo, hi] = std::minmax_element(mImage.values.begin(), mImage.values.end());
    mMinValue = *lo;
    mMaxValue = *hi;
}

Interval ImageHeightfield::heightBounds(const glm::dvec2& min, const glm::dvec2& max) const
{
    // The pixel coordinates of the rectangle's corners, as height() computes
    // them (clamping is monotone, so the rectangle maps into [u0, u1] × [v0, v1]).
    const auto pixel = [](double x, double lo, double hi, int size) {
        return std::clamp((x - lo) / (hi - lo), 0.0, 1.0) * (size - 1);
    };
    const double u0 = pixel(min.x, mOptions.min.x, mOptions.max.x, mImage.width);
    const double u1 = pixel(max.x, mOptions.min.x, mOptions.max.x, mImage.width);
    const double v0 = pixel(min.y, mOptions.min.y, mOptions.max.y, mImage.height);
    const double v1 = pixel(max.y, mOptions.min.y, mOptions.max.y, mImage.height);
    const int i0 = std::max(0, floorToInt<int>(u0)), i1 = std::min(mImage.width - 1, ceilToInt<int>(u1));
    const int j0 = std::max(0, floorToInt<int>(v0)), j1 = std::min(mImage.height - 1, ceilToInt<int>(v1));
    double lo = mMinValue, hi = mMaxValue;
    constexpr double MAX_PIXELS = 4096.0;
    if (double(i1 - i0 + 1) * double(j1 - j0 + 1) <= MAX_PIXELS) {
        lo = HUGE_VAL;
        hi = -HUGE_VAL;
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) {
                const double v = mImage.values[std::size_t(j) * mImage.width + i];
                lo = std::min(lo, v);
                hi = std::max(hi, v);
            }
    }
    const double a = mOptions.base + mOptions.heightScale * lo, b = mOptions.base + mOptions.heightScale * hi;
    Interval h{std::min(a, b), std::max(a, b)};
    const Interval lipschitz = HeightfieldBase::heightBounds(min, max);
    return {std::max(h.lo, lipschitz.lo), std::min(h.hi, lipschitz.hi)};
}

double ImageHeightfield::height(double x, double z) const
{
    const double u = std::clamp((x - mOptions.min.x) / (mOptions.max.x - mOptions.min.x), 0.0, 1.0) * (mImage.width - 1);
    const double v = std::clamp((z - mOptions.min.y) / (mOptions.max.y - mOptions.min.y), 0.0, 1.0) * (mImage.height - 1);
    const int i = std::min(int(u), mImage.width - 2), j = std::min(int(v), mImage.height - 2);
    const double fu = u - i, fv = v - j;
    const auto at = [&](int a, int b) { return double(mImage.values[std::size_t(b) * mImage.width + a]); };
    const double top = at(i, j) + fu * (at(i + 1, j) - at(i, j));
    const double bottom = at(i, j + 1) + fu * (at(i + 1, j + 1) - at(i, j + 1));
    return mOptions.base + mOptions.heightScale * (top + fv * (bottom - top));
}

} // namespace strata::terrain

namespace strata::terrain {

void registerHeightfieldNodes(NodeRegistry& registry)
{
    const NoiseHeightfieldOptions n;
    NodeType noise{"heightfield", "y = base + amplitude * noise(x/wavelength, z/wavelength): rolling terrain", {}, {}};
    noise.keys = {numberKey("base", n.base, -HUGE_LENGTH, HUGE_LENGTH, "m", "height of the noise's zero"),
                  numberKey("amplitude", n.amplitude, 0.0, 1e6, "m", "height scale of the noise"),
                  numberKey("wavelength", n.wavelength, 1e-3, MAX_LENGTH, "m", "size of the largest features")};
    addFractalKeys(noise.keys, n.noise);
    noise.keys.push_back(optionalChildKey("height", "a height node (height graph) instead of the noise keys"));
    noise.build = [](const NodeArgs& a) -> DensityFieldPtr {
        if (DensityFieldPtr graph = heightChild(a, "height")) {
            for (const char* key : {"base", "amplitude", "wavelength", "noise", "fractal", "octaves", "lacunarity", "gain"}) {
                if (a.given(key)) a.fail(key, "cannot be given with height: the height node replaces the noise");
            }
            return graph;
        }
        NoiseHeightfieldOptions o;
        o.base = a.number("base");
        o.amplitude = a.number("amplitude");
        o.wavelength = a.number("wavelength");
        o.noise = fractalOptions(a);
        return std::make_shared<NoiseHeightfield>(a.seed(), o);
    };
    registry.add(std::move(noise));

    const ImageHeightfieldOptions i;
    NodeType image{"image_heightfield",
                   "a height image (8/16-bit PNG, EXR, TIFF..., channel 0) laid over the XZ rectangle min..max, "
                   "bilinear",
                   {},
                   {}};
    image.keys = {imageKey("file", "the height image; relative paths from the scene's folder"),
                  vec2Key("min", i.min, HUGE_LENGTH, "m", "world (x, z) of the first pixel"),
                  vec2Key("max", i.max, HUGE_LENGTH, "m", "world (x, z) of the last pixel"),
                  numberKey("base", i.base, -HUGE_LENGTH, HUGE_LENGTH, "m", "height of pixel value 0"),
                  numberKey("height_scale", i.heightScale, -1e6, 1e6, "m", "height of pixel value 1 above base")};
    image.build = [](const NodeArgs& a) -> DensityFieldPtr {
        ImageHeightfieldOptions o;
        o.min = a.vec2("min");
        o.max = a.vec2("max");
        for (int axis = 0; axis < 2; ++axis) {
            if (!(o.max[axis] > o.min[axis])) {
                a.fail("max", "must be greater than min on both axes (" + formatNumber(o.min[axis]) +
                                  " >= " + formatNumber(o.max[axis]) + ")");
            }
        }
        o.base = a.number("base");
        o.heightScale = a.number("height_scale");
        return std::make_shared<ImageHeightfield>(a.image("file"), o);
    };
    registry.add(std::move(image));
}

} // namespace strata::terrain
