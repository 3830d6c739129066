// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The rock a world is made of: a sequence of sedimentary beds, each with a
/// thickness and a hardness, tilted by dip and dip direction, folded by a 3D
/// warp and offset across a fault. A pure function of the world position,
/// so it reads the same in any tile, chunk or thread. What the beds do to
/// the ground is DifferentialErosion.h; this file only says which bed is
/// where and how hard it is.

#include <strata/terrain/DensityField.h>
#include <strata/terrain/FractalNoise.h>

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace strata::terrain {

/// One bed of the sequence.
struct RockBed
{
    double thickness = 1.0; ///< metres, >= 0 (a bed of 0 is left out)
    double hardness = 0.5;  ///< 0 (weathers away fastest) .. 1 (does not weather)
};

struct LithologyOptions
{
    /// The sequence, bottom to top; at least one bed of thickness > 0.
    std::vector<RockBed> beds{{4.0, 0.9}, {10.0, 0.2}};
    /// Whether the sequence repeats above and below (period: the summed
    /// thicknesses). Without it the first bed extends down forever and the
    /// last one up.
    bool repeat = true;
    /// Metres: the stratigraphic height at which the first bed's base lies
    /// (at the origin, for horizontal beds: its elevation). Finite.
    double datum = 0.0;
    /// Degrees 0..90: the beds' tilt from horizontal (90: vertical beds).
    double dip = 0.0;
    /// Degrees 0..360: the horizontal direction the beds descend toward,
    /// measured from +x toward +z.
    double dipDirection = 0.0;
    /// Metres, > 0: the width over which hardness changes smoothly from one
    /// bed to the next (at most the thinnest bed). The gradient of hardness,
    /// and so the sharpness of the ledges it makes, is |Δhardness|·1.5 /
    /// transition per metre of stratigraphic height.
    double transition = 0.5;
    /// Folding: the stratigraphic height is moved by foldAmplitude ·
    /// noise(p / foldWavelength) (metres; 0 = no folds).
    double foldAmplitude = 0.0;
    double foldWavelength = 300.0; ///< metres, > 0
    FractalOptions foldNoise{NoiseType::GRADIENT, FractalType::FBM, 2, 2.0, 0.5};
    /// A fault: the block on the side the plane's normal points to is moved
    /// `faultThrow` metres up the sequence (0 = no fault), ramped over
    /// `faultWidth` metres so the field stays continuous.
    double faultThrow = 0.0;
    glm::dvec3 faultPoint{0.0}; ///< metres: a point on the fault plane
    double faultStrike = 0.0;   ///< degrees 0..360: the plane's horizontal trace, from +x toward +z
    double faultDip = 90.0;     ///< degrees 0..90 (90: a vertical fault)
    double faultWidth = 1.0;    ///< metres, > 0
};

/// The bed sequence in space. Thread-safe; every value is a pure function
/// of the position, computed with + − × ÷ only (no libm), so the same bits
/// on every compiler and CPU.
class Lithology
{
public:
    /// Throws strata::Error (BadInput) naming the option ("beds",
    /// "transition", "dip", ...) when one is out of range.
    Lithology(std::uint64_t seed, const LithologyOptions& options);

    /// Metres up the sequence at `p`: the height along the bed normal, plus
    /// the fold and the fault's throw, minus the datum. Beds are level sets of it.
    double stratigraphicHeight(const glm::dvec3& p) const;
    /// Hardness 0..1 at stratigraphic height `s` (stratigraphicHeight()).
    double hardnessAt(double s) const;
    /// hardnessAt(stratigraphicHeight(p)).
    double hardness(const glm::dvec3& p) const { return hardnessAt(stratigraphicHeight(p)); }
    /// The index in `beds` (of the beds as given, zero-thickness ones
    /// counted) of the bed at stratigraphic height `s`.
    int bedAt(double s) const;
    /// bedAt(stratigraphicHeight(p)): the mask layer rules read (RockMasks).
    int bed(const glm::dvec3& p) const { return bedAt(stratigraphicHeight(p)); }

    /// An interval holding stratigraphicHeight(p) for every p in `box`.
    Interval stratigraphicBounds(const WorldBox& box) const;
    /// An interval holding hardness(p) for every p in `box` (rigorous: the
    /// extremes of every bed the box's stratigraphic interval touches).
    Interval hardnessBounds(const WorldBox& box) const;
    /// Upper bound of |∇ hardness| (per metre).
    double hardnessLipschitz() const { return mHardnessSlope * mStratigraphicLipschitz; }
    /// Upper bound of |∇ stratigraphicHeight| (1 without folds and faults).
    double stratigraphicLipschitz() const { return mStratigraphicLipschitz; }
    /// The unit normal of the bedding planes before folds and faults
    /// (pointing up the sequence).
    const glm::dvec3& normal() const { return mNormal; }
    /// Whether the beds are parallel planes (no folds, no fault): normal()
    /// is then the exact gradient of stratigraphicHeight().
    bool planar() const { return mOptions.foldAmplitude == 0.0 && mOptions.faultThrow == 0.0; }

    double minHardness() const { return mMinHardness; }
    double maxHardness() const { return mMaxHardness; }
    const LithologyOptions& options() const { return mOptions; }

private:
    struct Contact
    {
        double base;     ///< metres up the sequence (from 0 to the period)
        double hardness; ///< of the bed above the contact
        int index;       ///< in LithologyOptions::beds
    };
    /// The bed holding sequence height u: its index in mBeds, and u's
    /// position relative to the period (u reduced into [0, period) when
    /// repeating).
    std::size_t bedIndexAt(double s, double& u) const;
    double faultOffset(double across) const;

    LithologyOptions mOptions;
    std::vector<Contact> mBeds; ///< beds of thickness > 0, bottom to top
    double mPeriod = 0.0;
    glm::dvec3 mNormal{0.0, 1.0, 0.0};      ///< unit normal of the bedding planes
    glm::dvec3 mFaultNormal{1.0, 0.0, 0.0}; ///< unit normal of the fault plane
    FractalNoise mFold;
    double mStratigraphicLipschitz = 1.0; ///< |∇ stratigraphicHeight| bound
    double mHardnessSlope = 0.0;          ///< |d hardness / d s| bound
    double mMinHardness = 0.0, mMaxHardness = 0.0;
};

} // namespace strata::terrain
