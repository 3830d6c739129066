// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/DifferentialErosion.h>

#include "NodeRegistrations.h"
#include "ShowValue.h"

#include <strata/Error.h>
#include <strata/terrain/NodeRegistry.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace strata::terrain {

using detail::show;

namespace {

/// The squared length below which a difference gradient counts as this
/// long when normalizing: a distance-like field's is about 1, and a flat
/// spot (a saddle, a clamp) must not divide by nearly 0.
constexpr double MIN_GRADIENT_SQUARED = 0.25;

double dot3(double ax, double ay, double az, double bx, double by, double bz)
{
    double d = ax * bx;
    d = d + ay * by;
    d = d + az * bz;
    return d;
}

} // namespace

DifferentialErosionField::DifferentialErosionField(DensityFieldPtr child, std::shared_ptr<const Lithology> lithology,
                                                   const DifferentialErosionOptions& options)
    : mChild(std::move(child))
    , mLithology(std::move(lithology))
    , mOptions(options)
{
    if (!(std::isfinite(options.retreat) && options.retreat >= 0.0 && options.retreat <= 1e4)) {
        throw Error(ErrorKind::BadInput, "retreat = " + show(options.retreat) + " must be in 0 .. 1e4 metres");
    }
    if (!(std::isfinite(options.smoothing) && options.smoothing > 0.0 && options.smoothing <= 1e4)) {
        throw Error(ErrorKind::BadInput, "smoothing = " + show(options.smoothing) + " must be in (0, 1e4] metres");
    }
    // |∇e| <= 2|∇c|, c the cosine of the normalized gradients; each
    // difference gradient's Jacobian is at most 2√3·L/step, and normalizing
    // by at least √MIN_GRADIENT_SQUARED = 0.5 doubles it.
    const double childL = mChild->lipschitz();
    const bool planar = mLithology->planar(); // the beds' normal is then exact
    const double jacobian = 2.0 * std::sqrt(3.0) / options.smoothing / std::sqrt(MIN_GRADIENT_SQUARED);
    const double stratigraphicL = planar ? 0.0 : mLithology->stratigraphicLipschitz();
    const double exposureL = 2.0 * jacobian * (childL + stratigraphicL);
    mLipschitz = childL + options.retreat * mLithology->hardnessLipschitz() +
                 options.retreat * (1.0 - mLithology->minHardness()) * exposureL;
}

double DifferentialErosionField::combine(const glm::dvec3& p, double d0, double dx, double dy, double dz,
                                         double* exposureOut) const
{
    const Lithology& lith = *mLithology;
    const double step = mOptions.smoothing;
    const double s0 = lith.stratigraphicHeight(p);
    // The beds' normal: exact for planar beds, by the same differences as
    // the face's where folds or a fault bend them.
    double bx = lith.normal().x, by = lith.normal().y, bz = lith.normal().z;
    if (!lith.planar()) {
        bx = lith.stratigraphicHeight({p.x + step, p.y, p.z}) - s0;
        by = lith.stratigraphicHeight({p.x, p.y + step, p.z}) - s0;
        bz = lith.stratigraphicHeight({p.x, p.y, p.z + step}) - s0;
        bx = bx / step;
        by = by / step;
        bz = bz / step;
    }
    const double gx = (dx - d0) / step, gy = (dy - d0) / step, gz = (dz - d0) / step;
    const double gg = dot3(gx, gy, gz, gx, gy, gz);
    const double bb = dot3(bx, by, bz, bx, by, bz);
    const double gb = dot3(gx, gy, gz, bx, by, bz);
    const double cos2 = std::min(1.0, (gb * gb) / (std::max(gg, MIN_GRADIENT_SQUARED) * std::max(bb, MIN_GRADIENT_SQUARED)));
    const double exposure = 1.0 - cos2;
    if (exposureOut) *exposureOut = exposure;
    const double hardness = lith.hardnessAt(s0);
    return d0 + mOptions.retreat * (1.0 - hardness) * exposure;
}

double DifferentialErosionField::density(const glm::dvec3& p) const
{
    double out = 0.0;
    const PointBlock one{&p.x, &p.y, &p.z, 1, {p, p}};
    densities(one, &out);
    return out;
}

double DifferentialErosionField::distanceBound(const glm::dvec3& p) const
{
    const double d = density(p);
    if (d == 0.0) return 0.0;
    const double child = mChild->density(p);
    const double loose = d / mLipschitz;
    if (d > 0.0) {
        // Every surface point q has child(q) <= 0: in the child's air, the
        // child's own bound holds.
        return child > 0.0 ? std::max(loose, mChild->distanceBound(p)) : loose;
    }
    // Air needs child(q) >= −R, at least (−child − R) / L_child away.
    const double deepest = mOptions.retreat * (1.0 - mLithology->minHardness());
    const double L = mChild->lipschitz();
    const double solid = (-child - deepest) / L;
    return solid > 0.0 ? std::min(loose, -solid) : loose;
}

double DifferentialErosionField::exposure(const glm::dvec3& p) const
{
    const double step = mOptions.smoothing;
    double e = 0.0;
    combine(p, mChild->density(p), mChild->density({p.x + step, p.y, p.z}), mChild->density({p.x, p.y + step, p.z}),
            mChild->density({p.x, p.y, p.z + step}), &e);
    return e;
}

void DifferentialErosionField::rockMasks(const double* x, const double* y, const double* z, std::size_t n,
                                         glm::vec2* out) const
{
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 p(x[i], y[i], z[i]);
        const double s = mLithology->stratigraphicHeight(p);
        out[i] = glm::vec2(float(mLithology->hardnessAt(s)), float(mLithology->bedAt(s)));
    }
}

void DifferentialErosionField::densities(const PointBlock& points, double* out) const
{
    const std::size_t n = points.count;
    if (n == 0) return;
    const double step = mOptions.smoothing;
    // d0, dx, dy, dz, then one shifted coordinate array.
    std::vector<double> buffer(5 * n);
    double* d0 = buffer.data();
    double* shifted = d0 + 4 * n;
    mChild->densities(points, d0);
    const double* axes[3] = {points.x, points.y, points.z};
    for (int a = 0; a < 3; ++a) {
        for (std::size_t i = 0; i < n; ++i) shifted[i] = axes[a][i] + step;
        PointBlock moved = points;
        (a == 0 ? moved.x : a == 1 ? moved.y : moved.z) = shifted;
        moved.box.min[a] = points.box.min[a] + step;
        moved.box.max[a] = points.box.max[a] + step;
        mChild->densities(moved, d0 + std::size_t(a + 1) * n);
    }
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 p(points.x[i], points.y[i], points.z[i]);
        out[i] = combine(p, d0[i], d0[n + i], d0[2 * n + i], d0[3 * n + i], nullptr);
    }
}

Interval DifferentialErosionField::bounds(const WorldBox& box) const
{
    const Interval child = mChild->bounds(box);
    // Blends round within an ulp of the beds' hardness: widen by far more.
    const double softest = std::max(0.0, mLithology->hardnessBounds(box).lo - 1e-12);
    return {child.lo, child.hi + mOptions.retreat * (1.0 - softest) + 1e-12 * mOptions.retreat};
}

namespace {

/// Re-throws a Lithology or DifferentialErosion check as NodeArgs::fail on
/// the key its message starts with ("transition = ...", "beds[2] hardness
/// = ..."), so the scene reader points at that key's line.
[[noreturn]] void failOnKey(const NodeArgs& args, const Error& e)
{
    const std::string what = e.what();
    const std::size_t end = what.find_first_of(" [");
    const std::string key = what.substr(0, end);
    if (end == std::string::npos || args.nodeName().empty()) throw;
    args.fail(key, what.substr(what[end] == ' ' ? end + 1 : end));
}

} // namespace

void registerGeologyNodes(NodeRegistry& registry)
{
    const LithologyOptions l;
    const DifferentialErosionOptions d;
    NodeType beds{"beds",
                  "the child cut into rock beds: soft beds retreat from faces across them under hard ones (ledges, "
                  "overhangs, alcoves, arches)",
                  {},
                  {}};
    std::vector<glm::dvec2> sequence;
    for (const RockBed& b : l.beds) sequence.push_back({b.thickness, b.hardness});
    beds.keys = {
        childKey("child", "the rock to weather"),
        pointsKey("beds", sequence, 1e6, "",
                  "the sequence bottom to top, [thickness m, hardness 0..1] per bed (1 does not weather)"),
        booleanKey("repeat", l.repeat, "the sequence repeats above and below (else the end beds extend)"),
        numberKey("datum", l.datum, -1e12, 1e12, "m", "stratigraphic height of the first bed's base"),
        numberKey("dip", l.dip, 0.0, 90.0, "degrees", "tilt of the beds from horizontal"),
        numberKey("dip_direction", l.dipDirection, -360.0, 360.0, "degrees",
                  "horizontal direction the beds descend toward, from +x toward +z"),
        numberKey("transition", l.transition, 1e-3, 1e6, "m",
                  "width of the hardness change at a contact (at most the thinnest bed)"),
        numberKey("fold_amplitude", l.foldAmplitude, 0.0, 1e5, "m", "how far folds move the beds up and down"),
        numberKey("fold_wavelength", l.foldWavelength, 1e-3, MAX_LENGTH, "m", "size of the folds"),
        numberKey("fault_throw", l.faultThrow, -1e5, 1e5, "m", "offset of the beds across the fault (0: none)"),
        vec3Key("fault_point", l.faultPoint, HUGE_LENGTH, "m", "a point on the fault plane"),
        numberKey("fault_strike", l.faultStrike, -360.0, 360.0, "degrees", "the fault's horizontal trace, from +x toward +z"),
        numberKey("fault_dip", l.faultDip, 0.0, 90.0, "degrees", "the fault plane's tilt (90: vertical)"),
        numberKey("fault_width", l.faultWidth, 1e-3, 1e6, "m", "width of the fault zone the offset ramps over"),
        numberKey("retreat", d.retreat, 0.0, 1e4, "m", "how far a bed of hardness 0 retreats from a cliff"),
        numberKey("smoothing", d.smoothing, 1e-3, 1e4, "m", "step of the differences that orient faces and beds"),
        seedKey()};
    beds.build = [](const NodeArgs& a) -> DensityFieldPtr {
        LithologyOptions o;
        o.beds.clear();
        for (const glm::dvec2& b : a.points("beds")) o.beds.push_back({b.x, b.y});
        o.repeat = a.boolean("repeat");
        o.datum = a.number("datum");
        o.dip = a.number("dip");
        o.dipDirection = a.number("dip_direction");
        o.transition = a.number("transition");
        o.foldAmplitude = a.number("fold_amplitude");
        o.foldWavelength = a.number("fold_wavelength");
        o.foldNoise.version = a.context().noiseVersion;
        o.faultThrow = a.number("fault_throw");
        o.faultPoint = a.vec3("fault_point");
        o.faultStrike = a.number("fault_strike");
        o.faultDip = a.number("fault_dip");
        o.faultWidth = a.number("fault_width");
        DifferentialErosionOptions d;
        d.retreat = a.number("retreat");
        d.smoothing = a.number("smoothing");
        try {
            return std::make_shared<DifferentialErosionField>(a.child("child"), std::make_shared<Lithology>(a.seed(), o), d);
        } catch (const Error& e) {
            failOnKey(a, e);
        }
    };
    registry.add(std::move(beds));
}

} // namespace strata::terrain
