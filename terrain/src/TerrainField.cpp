// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/TerrainField.h>

#include "BlockColumns.h"

#include <strata/Error.h>
#include <strata/Format.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace strata::terrain {

namespace {

/// Typical |∇n| of the cave fbm across a tunnel, per noise unit: converts the
/// tunnel radius from metres to noise units. Calibrated by measuring tunnels
/// (walking from the axis to the wall, horizontally, over 400 tunnels): with
/// 1.0 the mean horizontal radius is `radius` (median 0.8·radius), for 1 or 2
/// octaves. (The RMS directional derivative is about 0.7, but tunnels are
/// fattest where the gradients are small, which raises the mean.)
constexpr double CAVE_TYPICAL_GRADIENT = 1.0;

/// Seed streams, so the heightfield and the two cave fields are independent.
enum SeedStream : std::uint64_t { HEIGHT_STREAM = 1, CAVE_A_STREAM = 2, CAVE_B_STREAM = 3 };

std::string show(double value) { return formatNumber(value); }

void requirePositive(const char* key, double value)
{
    if (!(std::isfinite(value) && value > 0.0)) {
        throw Error(ErrorKind::BadInput, std::string("terrain: ") + key + " = " + show(value) + " must be a finite number > 0");
    }
}

void requireNonNegative(const char* key, double value)
{
    if (!(std::isfinite(value) && value >= 0.0)) {
        throw Error(ErrorKind::BadInput, std::string("terrain: ") + key + " = " + show(value) + " must be a finite number >= 0");
    }
}

void requireFinite(const char* key, double value)
{
    if (!std::isfinite(value)) {
        throw Error(ErrorKind::BadInput, std::string("terrain: ") + key + " = " + show(value) + " must be a finite number");
    }
}

void validateFbm(const char* prefix, const FbmOptions& fbm)
{
    const std::string p(prefix);
    if (fbm.octaves < 1 || fbm.octaves > 24) {
        throw Error(ErrorKind::BadInput, "terrain: " + p + ".octaves = " + std::to_string(fbm.octaves) + " is out of range 1..24");
    }
    requirePositive((p + ".lacunarity").c_str(), fbm.lacunarity);
    requireNonNegative((p + ".gain").c_str(), fbm.gain);
}

/// Throws on a bad option; returns `o` so it can run in an initialiser list.
const TerrainOptions& validated(const TerrainOptions& o)
{
    requireFinite("height.base", o.height.baseHeight);
    requireNonNegative("height.amplitude", o.height.amplitude);
    requirePositive("height.wavelength", o.height.wavelength);
    validateFbm("height", o.height.fbm);
    // Validated even when disabled: a scene that turns caves back on should
    // not discover a bad value only then.
    requirePositive("caves.wavelength", o.caves.wavelength);
    requirePositive("caves.radius", o.caves.radius);
    requirePositive("caves.vertical_squash", o.caves.verticalSquash);
    validateFbm("caves", o.caves.fbm);
    if (std::isnan(o.caves.maxHeight)) {
        throw Error(ErrorKind::BadInput, "terrain: caves.max_height = nan must be a number");
    }
    if (o.noiseVersion < NOISE_VERSION_MIN || o.noiseVersion > NOISE_VERSION_MAX) {
        throw Error(ErrorKind::BadInput, "terrain: noise_version = " + std::to_string(o.noiseVersion) +
                                             " is out of range " + std::to_string(NOISE_VERSION_MIN) + ".." +
                                             std::to_string(NOISE_VERSION_MAX));
    }
    return o;
}

/// Version 2's fBm: gradient noise summed as Fbm sums it (the same seed,
/// octaves and normalisation), in float lanes.
std::optional<FractalNoise> version2Fbm(const TerrainOptions& o, std::uint64_t seed, const FbmOptions& fbm)
{
    if (o.noiseVersion != 2) return std::nullopt;
    FractalOptions f;
    f.noise = NoiseType::GRADIENT;
    f.fractal = FractalType::FBM;
    f.octaves = fbm.octaves;
    f.lacunarity = fbm.lacunarity;
    f.gain = fbm.gain;
    f.version = 2;
    return FractalNoise(seed, f);
}

/// [lo, hi] of x² over x in [lo, hi].
Interval squared(const Interval& x)
{
    const double a = x.lo * x.lo, b = x.hi * x.hi;
    if (x.lo <= 0.0 && x.hi >= 0.0) return {0.0, std::max(a, b)};
    return {std::min(a, b), std::max(a, b)};
}

} // namespace

TerrainField::TerrainField(const TerrainOptions& options)
    : mOptions(validated(options))
    , mHeight(deriveSeed(options.seed, HEIGHT_STREAM), options.height.fbm)
    , mCaveA(deriveSeed(options.seed, CAVE_A_STREAM), options.caves.fbm)
    , mCaveB(deriveSeed(options.seed, CAVE_B_STREAM), options.caves.fbm)
    , mHeight2(version2Fbm(options, deriveSeed(options.seed, HEIGHT_STREAM), options.height.fbm))
    , mCaveA2(version2Fbm(options, deriveSeed(options.seed, CAVE_A_STREAM), options.caves.fbm))
    , mCaveB2(version2Fbm(options, deriveSeed(options.seed, CAVE_B_STREAM), options.caves.fbm))
{
    const HeightfieldOptions& h = mOptions.height;
    const CaveOptions& c = mOptions.caves;

    // |∇h| <= amplitude/wavelength · fbm bound (m/m). The gradient of y − h(x, z)
    // is (−h_x, 1, −h_z), of length <= sqrt(1 + L_h²): dividing by it makes the
    // height term 1-Lipschitz.
    const double heightSlope = h.amplitude / h.wavelength * fbmGradientBound(h.fbm, GRADIENT_NOISE_LIPSCHITZ_2D);
    mHeightScale = 1.0 / std::sqrt(1.0 + heightSlope * heightSlope);

    // The cave fields are evaluated at q = (x, y·squash, z) / wavelength, so
    // |∇_p n| <= fbm bound · max(1, squash) / wavelength per metre, and the
    // radius r = sqrt(n1² + n2²) has |∇r| <= sqrt(L1² + L2²) = sqrt(2)·L.
    const double fieldSlope = fbmGradientBound(c.fbm) * std::max(1.0, c.verticalSquash) / c.wavelength;
    mCaveScale = 1.0 / (std::sqrt(2.0) * fieldSlope);

    // Near a tunnel axis r grows like |∇n|·distance, and a typical horizontal
    // |∇n| is CAVE_TYPICAL_GRADIENT per noise unit, so r = r_noise about
    // `radius` metres from the axis (less vertically, by the squash).
    mCaveNoiseRadius = c.radius * CAVE_TYPICAL_GRADIENT / c.wavelength;
}

double TerrainField::height(double x, double z) const
{
    const HeightfieldOptions& h = mOptions.height;
    const glm::dvec2 q(x / h.wavelength, z / h.wavelength);
    if (mHeight2) return h.baseHeight + h.amplitude * (*mHeight2)(q);
    return h.baseHeight + h.amplitude * double(mHeight(q));
}

double TerrainField::caveDistance(const glm::dvec3& p) const
{
    const CaveOptions& c = mOptions.caves;
    const glm::dvec3 q(p.x / c.wavelength, p.y * c.verticalSquash / c.wavelength, p.z / c.wavelength);
    const double n1 = mCaveA2 ? (*mCaveA2)(q) : double(mCaveA(q));
    const double n2 = mCaveB2 ? (*mCaveB2)(q) : double(mCaveB(q));
    const double tube = (std::sqrt(n1 * n1 + n2 * n2) - mCaveNoiseRadius) * mCaveScale;
    // Above maxHeight the term rises with slope 1: no tunnels, still 1-Lipschitz.
    return std::max(tube, p.y - c.maxHeight);
}

double TerrainField::density(const glm::dvec3& p) const
{
    const double ground = (p.y - height(p.x, p.z)) * mHeightScale;
    if (!mOptions.caves.enabled) return ground;

    // −caveDistance is at most r_noise·scale (on a tunnel axis) and at most
    // maxHeight − y: where the ground term is already larger, the max below
    // cannot change, so skip the two 3D fbm evaluations (same result exactly).
    const double deepestCave = std::min(mCaveNoiseRadius * mCaveScale, mOptions.caves.maxHeight - p.y);
    if (ground >= deepestCave) return ground;
    return std::max(ground, -caveDistance(p));
}

void TerrainField::densities(const PointBlock& points, double* out) const
{
    const std::size_t n = points.count;
    if (n == 0) return;
    const HeightfieldOptions& h = mOptions.height;
    const CaveOptions& c = mOptions.caves;

    // A leaf (Fbm calls nothing back): scratch kept per thread, not per call.
    detail::ScratchFrame frame;
    thread_local struct
    {
        std::vector<double> qx, qy, qz;
        std::vector<float> n1, n2;         // version 1 (Fbm is float)
        std::vector<double> n1v2, n2v2;    // version 2
        std::vector<std::uint32_t> deep;
    } scratch;
    auto& [qx, qy, qz, n1, n2, n1v2, n2v2, deep] = scratch;

    // height() once per column: q = (x, z) / wavelength, as height() divides.
    const detail::BlockColumns columns = detail::findColumns(points, frame);
    const std::size_t m = columns.count;
    qx.resize(m);
    qz.resize(m);
    n1.resize(m); // the columns' height noise first, the first cave noise after
    for (std::size_t i = 0; i < m; ++i) {
        qx[i] = columns.x[i] / h.wavelength;
        qz[i] = columns.z[i] / h.wavelength;
    }
    if (mHeight2) {
        n1v2.resize(m);
        mHeight2->evaluate(qx.data(), qz.data(), m, n1v2.data());
        for (std::size_t i = 0; i < n; ++i) {
            const double height = h.baseHeight + h.amplitude * n1v2[columns.of[i]];
            out[i] = (points.y[i] - height) * mHeightScale;
        }
    } else {
        mHeight.evaluate(qx.data(), qz.data(), m, n1.data());
        for (std::size_t i = 0; i < n; ++i) {
            const double height = h.baseHeight + h.amplitude * double(n1[columns.of[i]]);
            out[i] = (points.y[i] - height) * mHeightScale;
        }
    }
    if (!c.enabled) return;

    // The caves where density() evaluates them (its early return, per point).
    deep.clear();
    for (std::size_t i = 0; i < n; ++i) {
        const double deepestCave = std::min(mCaveNoiseRadius * mCaveScale, c.maxHeight - points.y[i]);
        if (!(out[i] >= deepestCave)) deep.push_back(std::uint32_t(i));
    }
    if (deep.empty()) return;
    const std::size_t k = deep.size();
    qx.resize(k);
    qy.resize(k);
    qz.resize(k);
    n1.resize(k);
    n2.resize(k);
    for (std::size_t j = 0; j < k; ++j) {
        const std::size_t i = deep[j];
        qx[j] = points.x[i] / c.wavelength;
        qy[j] = points.y[i] * c.verticalSquash / c.wavelength;
        qz[j] = points.z[i] / c.wavelength;
    }
    if (mCaveA2) {
        n1v2.resize(k);
        n2v2.resize(k);
        mCaveA2->evaluate(qx.data(), qy.data(), qz.data(), k, n1v2.data());
        mCaveB2->evaluate(qx.data(), qy.data(), qz.data(), k, n2v2.data());
    } else {
        mCaveA.evaluate(qx.data(), qy.data(), qz.data(), k, n1.data());
        mCaveB.evaluate(qx.data(), qy.data(), qz.data(), k, n2.data());
    }
    for (std::size_t j = 0; j < k; ++j) {
        const std::size_t i = deep[j];
        const double a = mCaveA2 ? n1v2[j] : double(n1[j]), b = mCaveA2 ? n2v2[j] : double(n2[j]);
        const double tube = (std::sqrt(a * a + b * b) - mCaveNoiseRadius) * mCaveScale;
        const double caveDistance = std::max(tube, points.y[i] - c.maxHeight);
        out[i] = std::max(out[i], -caveDistance);
    }
}

Interval TerrainField::bounds(const WorldBox& box) const
{
    if (!mHeight2) return DensityField::bounds(box);
    const HeightfieldOptions& h = mOptions.height;
    const CaveOptions& c = mOptions.caves;
    // The double arithmetic after the fBms (a few operations on values of
    // order one to 1e7) rounds far below this; the fBms' own rounding is in
    // their bounds.
    const auto widened = [](Interval v) {
        const double slack = 1e-9 * (1.0 + std::max(std::abs(v.lo), std::abs(v.hi)));
        return Interval{v.lo - slack, v.hi + slack};
    };
    const Interval n = mHeight2->bounds(glm::dvec2(box.min.x, box.min.z) / h.wavelength,
                                        glm::dvec2(box.max.x, box.max.z) / h.wavelength);
    const Interval height{h.baseHeight + h.amplitude * n.lo, h.baseHeight + h.amplitude * n.hi};
    const Interval ground =
        widened({(box.min.y - height.hi) * mHeightScale, (box.max.y - height.lo) * mHeightScale});
    if (!c.enabled) return ground;

    // The box in noise units, as caveDistance() divides.
    const auto noiseUnits = [&c](const glm::dvec3& p) {
        return glm::dvec3(p.x / c.wavelength, p.y * c.verticalSquash / c.wavelength, p.z / c.wavelength);
    };
    const glm::dvec3 lo = noiseUnits(box.min), hi = noiseUnits(box.max);
    const Interval a = squared(mCaveA2->bounds(lo, hi));
    const Interval b = squared(mCaveB2->bounds(lo, hi));
    const Interval tube{(std::sqrt(a.lo + b.lo) - mCaveNoiseRadius) * mCaveScale,
                        (std::sqrt(a.hi + b.hi) - mCaveNoiseRadius) * mCaveScale};
    const Interval cave = widened({std::max(tube.lo, box.min.y - c.maxHeight), std::max(tube.hi, box.max.y - c.maxHeight)});
    // density = max(ground, −caveDistance) (density()'s early return takes
    // the same value).
    return {std::max(ground.lo, -cave.hi), std::max(ground.hi, -cave.lo)};
}

} // namespace strata::terrain
