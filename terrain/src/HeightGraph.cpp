// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/HeightGraph.h>

#include "ShowValue.h"

#include <strata/DeterministicMath.h>
#include <strata/Error.h>

#include <algorithm>
#include <cmath>

namespace strata::terrain {

using detail::show;

namespace {

constexpr double WORLD = 1e9; // HUGE_LENGTH: the rectangle "everywhere" stands for

/// heightBounds over the whole world: the node's range, for slope bounds of
/// products and blends.
Interval range(const HeightfieldBase& h)
{
    return h.heightBounds(glm::dvec2(-WORLD), glm::dvec2(WORLD));
}

double magnitude(const Interval& i) { return std::max(std::abs(i.lo), std::abs(i.hi)); }

/// Interval arithmetic for a product (exact for the four corner products).
Interval multiply(Interval a, Interval b)
{
    const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
    return {*std::min_element(p, p + 4), *std::max_element(p, p + 4)};
}

/// Heights of `node` at n columns into a new vector.
std::vector<double> heightsOf(const HeightfieldBase& node, const double* x, const double* z, std::size_t n)
{
    std::vector<double> h(n);
    node.heights(x, z, n, h.data());
    return h;
}


} // namespace

// --- constant ---------------------------------------------------------------

ConstantHeight::ConstantHeight(double value)
    : mValue(value)
{
    if (!std::isfinite(value)) throw Error(ErrorKind::BadInput, "value = " + show(value) + " must be a finite number");
    setSlopeBound(0.0);
}

// --- combine ----------------------------------------------------------------

HeightCombine::HeightCombine(HeightOp op, std::vector<HeightNodePtr> inputs)
    : mOp(op), mInputs(std::move(inputs))
{
    if (mInputs.size() < 2) throw Error(ErrorKind::BadInput, "children must name at least two height nodes");
    double slope = mInputs[0]->slopeBound();
    Interval value = range(*mInputs[0]);
    for (std::size_t i = 1; i < mInputs.size(); ++i) {
        const double s = mInputs[i]->slopeBound();
        const Interval v = range(*mInputs[i]);
        switch (op) {
        case HeightOp::Add:
        case HeightOp::Subtract: slope += s; break;
        case HeightOp::Min:
        case HeightOp::Max: slope = std::max(slope, s); break;
        case HeightOp::Multiply: slope = magnitude(value) * s + magnitude(v) * slope; break; // |∇(ab)| <= |a||∇b| + |b||∇a|
        }
        value = fold(value, v);
    }
    if (!std::isfinite(slope)) {
        throw Error(ErrorKind::BadInput, "children: the product of these inputs has no finite slope bound (an input is unbounded); "
                    "clamp it first with height_scale's min and max");
    }
    setSlopeBound(slope);
}

double HeightCombine::fold(double a, double b) const
{
    switch (mOp) {
    case HeightOp::Add: return a + b;
    case HeightOp::Subtract: return a - b;
    case HeightOp::Multiply: return a * b;
    case HeightOp::Min: return std::min(a, b);
    case HeightOp::Max: return std::max(a, b);
    }
    return a;
}

Interval HeightCombine::fold(Interval a, Interval b) const
{
    switch (mOp) {
    case HeightOp::Add: return {a.lo + b.lo, a.hi + b.hi};
    case HeightOp::Subtract: return {a.lo - b.hi, a.hi - b.lo};
    case HeightOp::Multiply: return multiply(a, b);
    case HeightOp::Min: return {std::min(a.lo, b.lo), std::min(a.hi, b.hi)};
    case HeightOp::Max: return {std::max(a.lo, b.lo), std::max(a.hi, b.hi)};
    }
    return a;
}

double HeightCombine::height(double x, double z) const
{
    double h = mInputs[0]->height(x, z);
    for (std::size_t i = 1; i < mInputs.size(); ++i) h = fold(h, mInputs[i]->height(x, z));
    return h;
}

void HeightCombine::heights(const double* x, const double* z, std::size_t n, double* out) const
{
    mInputs[0]->heights(x, z, n, out);
    std::vector<double> h(n);
    for (std::size_t i = 1; i < mInputs.size(); ++i) {
        mInputs[i]->heights(x, z, n, h.data());
        for (std::size_t k = 0; k < n; ++k) out[k] = fold(out[k], h[k]);
    }
}

Interval HeightCombine::heightBounds(const glm::dvec2& min, const glm::dvec2& max) const
{
    Interval b = mInputs[0]->heightBounds(min, max);
    for (std::size_t i = 1; i < mInputs.size(); ++i) b = fold(b, mInputs[i]->heightBounds(min, max));
    return b;
}

// --- blend ------------------------------------------------------------------

HeightBlend::HeightBlend(HeightNodePtr a, HeightNodePtr b, HeightNodePtr mask)
    : mA(std::move(a)), mB(std::move(b)), mMask(std::move(mask))
{
    // ∇h = (1 − m)∇a + m∇b + (b − a)∇m, m clamped to [0, 1] (which keeps
    // its slope bound).
    const Interval ra = range(*mA), rb = range(*mB);
    const double spread = std::max(std::abs(rb.hi - ra.lo), std::abs(ra.hi - rb.lo));
    const double slope = std::max(mA->slopeBound(), mB->slopeBound()) + spread * mMask->slopeBound();
    if (!std::isfinite(slope)) {
        throw Error(ErrorKind::BadInput, "mask: blending unbounded inputs by a varying mask has no finite slope bound; clamp a and b "
                    "with height_scale's min and max");
    }
    setSlopeBound(slope);
}

double HeightBlend::height(double x, double z) const
{
    const double m = std::clamp(mMask->height(x, z), 0.0, 1.0);
    const double a = mA->height(x, z);
    return a + m * (mB->height(x, z) - a);
}

void HeightBlend::heights(const double* x, const double* z, std::size_t n, double* out) const
{
    mA->heights(x, z, n, out);
    const std::vector<double> b = heightsOf(*mB, x, z, n), m = heightsOf(*mMask, x, z, n);
    for (std::size_t i = 0; i < n; ++i) out[i] = out[i] + std::clamp(m[i], 0.0, 1.0) * (b[i] - out[i]);
}

Interval HeightBlend::heightBounds(const glm::dvec2& min, const glm::dvec2& max) const
{
    // A convex combination stays between its ends.
    const Interval a = mA->heightBounds(min, max), b = mB->heightBounds(min, max);
    const Interval m = mMask->heightBounds(min, max);
    if (m.hi <= 0.0) return a;
    if (m.lo >= 1.0) return b;
    return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
}

// --- heights mapped one by one ---------------------------------------------

void MappedHeight::heights(const double* x, const double* z, std::size_t n, double* out) const
{
    mChild->heights(x, z, n, out);
    for (std::size_t i = 0; i < n; ++i) out[i] = map(out[i]);
}

// --- scale, offset and clamp ---------------------------------------------------

HeightAffine::HeightAffine(HeightNodePtr child, const HeightAffineOptions& options)
    : MappedHeight(std::move(child)), mOptions(options)
{
    if (!std::isfinite(options.scale)) throw Error(ErrorKind::BadInput, "scale = " + show(options.scale) + " must be a finite number");
    if (!std::isfinite(options.offset)) throw Error(ErrorKind::BadInput, "offset = " + show(options.offset) + " must be a finite number");
    if (std::isnan(options.min) || std::isnan(options.max) || options.min > options.max) {
        throw Error(ErrorKind::BadInput, "max = " + show(options.max) + " must be >= min = " + show(options.min));
    }
    setSlopeBound(std::abs(options.scale) * mChild->slopeBound());
}

double HeightAffine::map(double h) const
{
    return std::clamp(h * mOptions.scale + mOptions.offset, mOptions.min, mOptions.max);
}

Interval HeightAffine::heightBounds(const glm::dvec2& min, const glm::dvec2& max) const
{
    const Interval c = mChild->heightBounds(min, max);
    const double a = map(c.lo), b = map(c.hi); // map is monotone
    return {std::min(a, b), std::max(a, b)};
}

// --- curve ------------------------------------------------------------------

HeightCurve::HeightCurve(HeightNodePtr child, std::vector<glm::dvec2> points)
    : MappedHeight(std::move(child)), mPoints(std::move(points))
{
    auto fail = [](const std::string& what) { throw Error(ErrorKind::BadInput, "points " + what, {"", 0, "points", ""}); };
    if (mPoints.size() < 2) fail("must hold at least two [input, output] pairs");
    for (std::size_t i = 0; i < mPoints.size(); ++i) {
        if (!std::isfinite(mPoints[i].x) || !std::isfinite(mPoints[i].y)) {
            fail("has a pair that is not finite (pair " + std::to_string(i + 1) + ")");
        }
        if (i > 0 && !(mPoints[i].x > mPoints[i - 1].x)) {
            fail("must have strictly increasing inputs (pair " + std::to_string(i + 1) + " has input " +
                 show(mPoints[i].x) + " after " + show(mPoints[i - 1].x) + ")");
        }
    }
    // Fritsch–Carlson tangents: the harmonic mean of neighbouring secants,
    // zero at a local extremum, so each piece stays between its points.
    const std::size_t k = mPoints.size();
    std::vector<double> secant(k - 1);
    for (std::size_t i = 0; i + 1 < k; ++i) {
        secant[i] = (mPoints[i + 1].y - mPoints[i].y) / (mPoints[i + 1].x - mPoints[i].x);
    }
    mTangents.assign(k, 0.0);
    mTangents[0] = secant[0];
    mTangents[k - 1] = secant[k - 2];
    for (std::size_t i = 1; i + 1 < k; ++i) {
        const double a = secant[i - 1], b = secant[i];
        if (a * b > 0.0) {
            const double w1 = 2.0 * (mPoints[i + 1].x - mPoints[i].x) + (mPoints[i].x - mPoints[i - 1].x);
            const double w2 = (mPoints[i + 1].x - mPoints[i].x) + 2.0 * (mPoints[i].x - mPoints[i - 1].x);
            mTangents[i] = (w1 + w2) / (w1 / a + w2 / b);
        }
    }
    // The end tangents too are limited to 3 secants (monotone pieces).
    for (std::size_t i = 0; i + 1 < k; ++i) {
        const double limit = 3.0 * std::abs(secant[i]);
        mTangents[i] = std::clamp(mTangents[i], -limit, limit);
        mTangents[i + 1] = std::clamp(mTangents[i + 1], -limit, limit);
    }
    // |p'(t)| <= 1.5|δ| + |m0| + |m1| on a Hermite piece (the basis
    // derivatives are bounded by 1.5, 1 and 1 on [0, 1]).
    double steepest = 0.0;
    for (std::size_t i = 0; i + 1 < k; ++i) {
        steepest = std::max(steepest, 1.5 * std::abs(secant[i]) + std::abs(mTangents[i]) + std::abs(mTangents[i + 1]));
    }
    setSlopeBound(steepest * mChild->slopeBound());
}

double HeightCurve::map(double h) const
{
    if (!(h > mPoints.front().x)) return mPoints.front().y; // NaN too
    if (h >= mPoints.back().x) return mPoints.back().y;
    const auto upper = std::upper_bound(mPoints.begin(), mPoints.end(), h,
                                        [](double v, const glm::dvec2& p) { return v < p.x; });
    const std::size_t i = std::size_t(upper - mPoints.begin()) - 1;
    const double dx = mPoints[i + 1].x - mPoints[i].x;
    const double t = (h - mPoints[i].x) / dx, t2 = t * t, t3 = t2 * t;
    return (2.0 * t3 - 3.0 * t2 + 1.0) * mPoints[i].y + (t3 - 2.0 * t2 + t) * dx * mTangents[i] +
           (-2.0 * t3 + 3.0 * t2) * mPoints[i + 1].y + (t3 - t2) * dx * mTangents[i + 1];
}

Interval HeightCurve::heightBounds(const glm::dvec2& min, const glm::dvec2& max) const
{
    // Each piece stays between its two points, so over [lo, hi] the curve
    // lies between the values at lo, hi and the points inside.
    const Interval c = mChild->heightBounds(min, max);
    double lo = std::min(map(c.lo), map(c.hi)), hi = std::max(map(c.lo), map(c.hi));
    for (const glm::dvec2& p : mPoints) {
        if (p.x > c.lo && p.x < c.hi) {
            lo = std::min(lo, p.y);
            hi = std::max(hi, p.y);
        }
    }
    // The pieces on both sides of lo and hi reach their points' values.
    const std::size_t k = mPoints.size();
    for (std::size_t i = 0; i + 1 < k; ++i) {
        if (mPoints[i + 1].x > c.lo && mPoints[i].x < c.hi) {
            lo = std::min(lo, std::min(mPoints[i].y, mPoints[i + 1].y));
            hi = std::max(hi, std::max(mPoints[i].y, mPoints[i + 1].y));
        }
    }
    return {lo, hi};
}

// --- terrace ----------------------------------------------------------------

HeightTerrace::HeightTerrace(HeightNodePtr child, double step, double sharpness)
    : MappedHeight(std::move(child)), mStep(step), mSharpness(sharpness)
{
    if (!(std::isfinite(step) && step > 0.0)) throw Error(ErrorKind::BadInput, "step = " + show(step) + " must be a finite number > 0");
    if (!(std::isfinite(sharpness) && sharpness >= 1.0 && sharpness <= 64.0)) {
        throw Error(ErrorKind::BadInput, "sharpness = " + show(sharpness) + " is out of range [1, 64]");
    }
    // d/dh step·f^s = s·f^(s−1) <= s.
    setSlopeBound(sharpness * mChild->slopeBound());
}

double HeightTerrace::map(double h) const
{
    const double s = h / mStep, k = std::floor(s);
    return mStep * (k + dmath::pow(s - k, mSharpness));
}

Interval HeightTerrace::heightBounds(const glm::dvec2& min, const glm::dvec2& max) const
{
    // The profile is increasing; 1e-12 relative slack covers floor and pow.
    const Interval c = mChild->heightBounds(min, max);
    const double lo = map(c.lo), hi = map(c.hi);
    const double slack = 1e-12 * (std::abs(lo) + std::abs(hi) + mStep);
    return {lo - slack, hi + slack};
}

// --- 2D domain warp ------------------------------------------------------------

HeightWarp::HeightWarp(HeightNodePtr child, std::uint64_t seed, const HeightWarpOptions& options)
    : mChild(std::move(child)), mOptions(options), mNoiseX(seed, options.noise),
      mNoiseZ(seed ^ 0x9E3779B97F4A7C15ull, options.noise)
{
    if (!(std::isfinite(options.amplitude) && options.amplitude >= 0.0)) {
        throw Error(ErrorKind::BadInput, "amplitude = " + show(options.amplitude) + " must be a finite number >= 0");
    }
    if (!(std::isfinite(options.wavelength) && options.wavelength > 0.0)) {
        throw Error(ErrorKind::BadInput, "wavelength = " + show(options.wavelength) + " must be a finite number > 0");
    }
    // ∇h = Jᵀ∇child with J = I + (A/w)·(∇n₁; ∇n₂), whose norm is at most
    // 1 + √2·(A/w)·L (each row's gradient bounded by L).
    const double stretch = 1.0 + std::sqrt(2.0) * options.amplitude / options.wavelength * mNoiseX.lipschitz(2);
    setSlopeBound(mChild->slopeBound() * stretch);
}

double HeightWarp::height(double x, double z) const
{
    const glm::dvec2 q(x / mOptions.wavelength, z / mOptions.wavelength);
    return mChild->height(x + mOptions.amplitude * mNoiseX(q), z + mOptions.amplitude * mNoiseZ(q));
}

void HeightWarp::heights(const double* x, const double* z, std::size_t n, double* out) const
{
    std::vector<double> q(2 * n), d(2 * n);
    for (std::size_t i = 0; i < n; ++i) {
        q[i] = x[i] / mOptions.wavelength;
        q[n + i] = z[i] / mOptions.wavelength;
    }
    mNoiseX.evaluate(q.data(), q.data() + n, n, d.data());
    mNoiseZ.evaluate(q.data(), q.data() + n, n, d.data() + n);
    for (std::size_t i = 0; i < n; ++i) {
        d[i] = x[i] + mOptions.amplitude * d[i];
        d[n + i] = z[i] + mOptions.amplitude * d[n + i];
    }
    mChild->heights(d.data(), d.data() + n, n, out);
}

Interval HeightWarp::heightBounds(const glm::dvec2& min, const glm::dvec2& max) const
{
    const double w = mOptions.wavelength, a = mOptions.amplitude;
    const Interval nx = mNoiseX.bounds(min / w, max / w), nz = mNoiseZ.bounds(min / w, max / w);
    return mChild->heightBounds({min.x + a * nx.lo, min.y + a * nz.lo}, {max.x + a * nx.hi, max.y + a * nz.hi});
}

// --- masks ------------------------------------------------------------------

HeightMask::HeightMask(HeightNodePtr child, const MaskOptions& options)
    : mChild(std::move(child)), mOptions(options)
{
    if (!(std::isfinite(options.min) && std::isfinite(options.max) && options.max >= options.min)) {
        throw Error(ErrorKind::BadInput, "max = " + show(options.max) + " must be a finite number >= min = " + show(options.min));
    }
    if (!(std::isfinite(options.softness) && options.softness > 0.0)) {
        throw Error(ErrorKind::BadInput, "softness = " + show(options.softness) + " must be a finite number > 0");
    }
    if (!(std::isfinite(options.radius) && options.radius > 0.0)) {
        throw Error(ErrorKind::BadInput, "radius = " + show(options.radius) + " must be a finite number > 0");
    }
    // The band's steepest smoothstep is 1.5/softness; the measured value's
    // own bound: |∇h| <= S; a central difference over ±r is S/r-Lipschitz
    // per axis (√2·S/r for the slope's length); the 5-point Laplacian 8S/r².
    const double s = mChild->slopeBound(), r = options.radius;
    double source = s;
    if (options.source == MaskSource::Slope) source = std::sqrt(2.0) * s / r;
    if (options.source == MaskSource::Curvature) source = 8.0 * s / (r * r);
    setSlopeBound(1.5 / options.softness * source);
}

double HeightMask::band(double v) const
{
    if (v < mOptions.min) return dmath::smoothstep01(1.0 - (mOptions.min - v) / mOptions.softness);
    if (v > mOptions.max) return dmath::smoothstep01(1.0 - (v - mOptions.max) / mOptions.softness);
    return 1.0;
}

double HeightMask::height(double x, double z) const
{
    double out = 0.0;
    heights(&x, &z, 1, &out);
    return out;
}

void HeightMask::heights(const double* x, const double* z, std::size_t n, double* out) const
{
    if (mOptions.source == MaskSource::Height) {
        mChild->heights(x, z, n, out);
        for (std::size_t i = 0; i < n; ++i) out[i] = band(out[i]);
        return;
    }
    // Five taps per column, in one child evaluation: centre, ±x, ±z.
    const double r = mOptions.radius;
    std::vector<double> px(5 * n), pz(5 * n), h(5 * n);
    const double dx[5] = {0.0, r, -r, 0.0, 0.0}, dz[5] = {0.0, 0.0, 0.0, r, -r};
    for (int t = 0; t < 5; ++t) {
        for (std::size_t i = 0; i < n; ++i) {
            px[t * n + i] = x[i] + dx[t];
            pz[t * n + i] = z[i] + dz[t];
        }
    }
    mChild->heights(px.data(), pz.data(), 5 * n, h.data());
    for (std::size_t i = 0; i < n; ++i) {
        const double c = h[i], e = h[n + i], w = h[2 * n + i], s = h[3 * n + i], nn = h[4 * n + i];
        double v;
        if (mOptions.source == MaskSource::Slope) {
            v = dmath::hypot((e - w) / (2.0 * r), (s - nn) / (2.0 * r));
        } else {
            v = -(e + w + s + nn - 4.0 * c) / (r * r);
        }
        out[i] = band(v);
    }
}

Interval HeightMask::heightBounds(const glm::dvec2& min, const glm::dvec2& max) const
{
    if (mOptions.source != MaskSource::Height) {
        const Interval lipschitz = HeightfieldBase::heightBounds(min, max);
        return {std::clamp(lipschitz.lo, 0.0, 1.0), std::clamp(lipschitz.hi, 0.0, 1.0)};
    }
    // The band rises to 1 over [min, max] and falls on both sides: over an
    // interval its least value is at an end, its greatest at the point
    // nearest the plateau.
    const Interval c = mChild->heightBounds(min, max);
    const double nearest = std::clamp(0.5 * (mOptions.min + mOptions.max), c.lo, c.hi);
    return {std::min(band(c.lo), band(c.hi)), band(nearest)};
}

} // namespace strata::terrain
