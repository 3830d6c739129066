// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/Transforms.h>

#include "BlockScratch.h"
#include "NodeRegistrations.h"
#include <strata/Format.h>
#include <strata/terrain/NodeRegistry.h>

#include "ShowValue.h"

#include <strata/DeterministicMath.h>
#include <strata/Error.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <vector>

namespace strata::terrain {

using detail::show;

WarpField::WarpField(DensityFieldPtr child, std::uint64_t seed, const WarpOptions& options)
    : mChild(std::move(child))
    , mOptions(options)
    , mX(deriveSeed(seed, 1), options.noise)
    , mY(deriveSeed(seed, 2), options.noise)
    , mZ(deriveSeed(seed, 3), options.noise)
{
    if (!(std::isfinite(options.amplitude) && options.amplitude >= 0.0)) {
        throw Error(ErrorKind::BadInput, "amplitude = " + show(options.amplitude) + " must be a finite number >= 0");
    }
    if (!(std::isfinite(options.wavelength) && options.wavelength > 0.0)) {
        throw Error(ErrorKind::BadInput, "wavelength = " + show(options.wavelength) + " must be a finite number > 0");
    }
    if (!(std::isfinite(options.vertical) && options.vertical >= 0.0)) {
        throw Error(ErrorKind::BadInput, "vertical = " + show(options.vertical) + " must be a finite number >= 0");
    }
    // ‖J‖ <= 1 + ‖amplitude·∇(f1, v·f2, f3)/wavelength‖_F.
    const double lf = mX.lipschitz(3) / options.wavelength;
    mStretch = 1.0 + options.amplitude * lf * std::sqrt(2.0 + options.vertical * options.vertical);
}

glm::dvec3 WarpField::warp(const glm::dvec3& p) const
{
    const glm::dvec3 q = p / mOptions.wavelength;
    const double y = mOptions.vertical != 0.0 ? mOptions.vertical * mY(q) : 0.0;
    return p + mOptions.amplitude * glm::dvec3(mX(q), y, mZ(q));
}

double WarpField::density(const glm::dvec3& p) const
{
    return mChild->density(warp(p));
}

void WarpField::densities(const PointBlock& points, double* out) const
{
    const std::size_t n = points.count;
    if (n == 0) return;
    detail::ScratchFrame scratch;
    double *qx = scratch.array<double>(6 * n), *qy = qx + n, *qz = qy + n, *fx = qz + n, *fy = fx + n, *fz = fy + n;
    // As warp(): q = p / wavelength, then p + amplitude·(fx, v·fy or 0, fz).
    const double w = mOptions.wavelength, a = mOptions.amplitude;
    for (std::size_t i = 0; i < n; ++i) {
        qx[i] = points.x[i] / w;
        qy[i] = points.y[i] / w;
        qz[i] = points.z[i] / w;
    }
    mX.evaluate(qx, qy, qz, n, fx);
    mZ.evaluate(qx, qy, qz, n, fz);
    if (mOptions.vertical != 0.0) {
        mY.evaluate(qx, qy, qz, n, fy);
        for (std::size_t i = 0; i < n; ++i) fy[i] = mOptions.vertical * fy[i];
    } else {
        for (std::size_t i = 0; i < n; ++i) fy[i] = 0.0;
    }
    PointBlock warped{qx, qy, qz, n, {}};
    for (std::size_t i = 0; i < n; ++i) {
        qx[i] = points.x[i] + a * fx[i];
        qy[i] = points.y[i] + a * fy[i];
        qz[i] = points.z[i] + a * fz[i];
    }
    warped.box = spannedBox(warped);
    mChild->densities(warped, out);
}

double WarpField::distanceBound(const glm::dvec3& p) const
{
    return mChild->distanceBound(warp(p)) / mStretch;
}

Interval WarpField::bounds(const WorldBox& box) const
{
    const glm::dvec3 qlo = box.min / mOptions.wavelength, qhi = box.max / mOptions.wavelength;
    const double a = mOptions.amplitude; // >= 0
    const Interval fx = mX.bounds(qlo, qhi), fz = mZ.bounds(qlo, qhi);
    Interval fy{0.0, 0.0};
    if (mOptions.vertical != 0.0) {
        const Interval n = mY.bounds(qlo, qhi);
        fy = {mOptions.vertical * n.lo, mOptions.vertical * n.hi}; // vertical >= 0
    }
    const glm::dvec3 lo(box.min.x + a * fx.lo, box.min.y + a * fy.lo, box.min.z + a * fz.lo);
    const glm::dvec3 hi(box.max.x + a * fx.hi, box.max.y + a * fy.hi, box.max.z + a * fz.hi);
    return mChild->bounds({lo, hi});
}

namespace {

std::atomic<std::uint64_t> gNextTerraceIdentity{1};

/// A direct-mapped memo of terrace heights, per thread (no locks), shared by
/// every terrace node on it: an entry holds its node's identity and the
/// height's bits, so a hit is the value terrace() would compute.
struct TerraceMemo
{
    static constexpr int BITS = 9;
    std::uint64_t node[1 << BITS] = {};
    std::uint64_t height[1 << BITS] = {};
    double value[1 << BITS] = {};
};

thread_local TerraceMemo tTerraceMemo;

} // namespace

TerraceField::TerraceField(DensityFieldPtr child, double step, double sharpness)
    : mChild(std::move(child)), mStep(step), mSharpness(sharpness), mIdentity(gNextTerraceIdentity.fetch_add(1))
{
    if (!(std::isfinite(step) && step > 0.0)) throw Error(ErrorKind::BadInput, "step = " + show(step) + " must be a finite number > 0");
    if (!(std::isfinite(sharpness) && sharpness >= 1.0 && sharpness <= 64.0)) {
        throw Error(ErrorKind::BadInput, "sharpness = " + show(sharpness) + " is out of range [1, 64]");
    }
}

double TerraceField::terrace(double y) const
{
    const double s = y / mStep, k = std::floor(s);
    return mStep * (k + dmath::pow(s - k, mSharpness));
}

double TerraceField::terraceMemo(double y) const
{
    const std::uint64_t bits = std::bit_cast<std::uint64_t>(y);
    const std::size_t slot = std::size_t(((bits ^ mIdentity) * 0x9E3779B97F4A7C15ULL) >> (64 - TerraceMemo::BITS));
    TerraceMemo& memo = tTerraceMemo;
    if (memo.node[slot] == mIdentity && memo.height[slot] == bits) return memo.value[slot];
    const double t = terrace(y);
    memo.node[slot] = mIdentity;
    memo.height[slot] = bits;
    memo.value[slot] = t;
    return t;
}

double TerraceField::density(const glm::dvec3& p) const
{
    return mChild->density({p.x, terrace(p.y), p.z});
}

void TerraceField::densities(const PointBlock& points, double* out) const
{
    const std::size_t n = points.count;
    if (n == 0) return;
    detail::ScratchFrame scratch;
    double* terraced = scratch.array<double>(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double y = points.y[i];
        terraced[i] = (i > 0 && y == points.y[i - 1]) ? terraced[i - 1] : terraceMemo(y);
    }
    PointBlock child{points.x, terraced, points.z, n, points.box};
    const WorldBox spanned = spannedBox(child);
    child.box.min.y = spanned.min.y;
    child.box.max.y = spanned.max.y;
    mChild->densities(child, out);
}

double TerraceField::distanceBound(const glm::dvec3& p) const
{
    return mChild->distanceBound({p.x, terrace(p.y), p.z}) / std::max(1.0, mSharpness);
}

} // namespace strata::terrain

namespace strata::terrain {

Interval TerraceField::bounds(const WorldBox& box) const
{
    // A relative widening of 1e-12 plus 1e-12 m covers the rounding of the
    // division, floor and pow (far below any voxel).
    const double lo = terraceMemo(box.min.y), hi = terraceMemo(box.max.y);
    const double slack = 1e-12 * (std::abs(lo) + std::abs(hi) + mStep);
    return mChild->bounds({{box.min.x, lo - slack, box.min.z}, {box.max.x, hi + slack, box.max.z}});
}

} // namespace strata::terrain

namespace strata::terrain {

void TranslateField::densities(const PointBlock& points, double* out) const
{
    const std::size_t n = points.count;
    detail::ScratchFrame scratch;
    double *x = scratch.array<double>(3 * n), *y = x + n, *z = y + n;
    for (std::size_t i = 0; i < n; ++i) {
        x[i] = points.x[i] - mOffset.x;
        y[i] = points.y[i] - mOffset.y;
        z[i] = points.z[i] - mOffset.z;
    }
    mChild->densities({x, y, z, n, {points.box.min - mOffset, points.box.max - mOffset}}, out);
}

void registerTransformNodes(NodeRegistry& registry)
{
    const WarpOptions w;
    NodeType warp{"warp",
                  "the child evaluated at p + amplitude * noise3(p/wavelength): overhangs and undercut cliffs",
                  {},
                  {}};
    warp.keys = {childKey("child", "the node to warp"),
                 numberKey("amplitude", w.amplitude, 0.0, 1e6, "m", "largest displacement"),
                 numberKey("wavelength", w.wavelength, 1e-3, MAX_LENGTH, "m", "size of the warp's noise"),
                 numberKey("vertical", w.vertical, 0.0, 10.0, "", "scale of the vertical displacement")};
    addFractalKeys(warp.keys, w.noise);
    warp.build = [](const NodeArgs& a) -> DensityFieldPtr {
        WarpOptions o;
        o.amplitude = a.number("amplitude");
        o.wavelength = a.number("wavelength");
        o.vertical = a.number("vertical");
        o.noise = fractalOptions(a);
        return std::make_shared<WarpField>(a.child("child"), a.seed(), o);
    };
    registry.add(std::move(warp));

    NodeType terrace{"terrace", "the child evaluated at y mapped through steps: terraces, strata ledges", {}, {}};
    terrace.keys = {childKey("child", "the node to terrace"),
                    numberKey("step", 4.0, 1e-3, 1e6, "m", "height of one terrace"),
                    numberKey("sharpness", 3.0, 1.0, 64.0, "", "1 = no terraces; higher = flatter treads")};
    terrace.build = [](const NodeArgs& a) -> DensityFieldPtr {
        return std::make_shared<TerraceField>(a.child("child"), a.number("step"), a.number("sharpness"));
    };
    registry.add(std::move(terrace));

    NodeType translate{"translate", "the child moved by offset", {}, {}};
    translate.keys = {childKey("child", "the node to move"),
                      vec3Key("offset", glm::dvec3(0.0), HUGE_LENGTH, "m", "how far to move it")};
    translate.build = [](const NodeArgs& a) -> DensityFieldPtr {
        return std::make_shared<TranslateField>(a.child("child"), a.vec3("offset"));
    };
    registry.add(std::move(translate));
}

} // namespace strata::terrain
