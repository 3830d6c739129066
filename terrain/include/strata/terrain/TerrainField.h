// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The default terrain: an fBm heightfield with spaghetti-style cave tunnels
/// carved out of it.

#include <strata/terrain/DensityField.h>
#include <strata/terrain/FractalNoise.h>
#include <strata/terrain/Noise.h>

#include <cstdint>
#include <optional>

namespace strata::terrain {

/// A heightfield y = h(x, z) = baseHeight + amplitude · fbm2D((x, z) / wavelength),
/// all lengths in metres.
struct HeightfieldOptions
{
    double baseHeight = 0.0;   ///< mean surface height, finite
    /// Height scale, >= 0: heights stay within about baseHeight ± amplitude, and
    /// the fbm's spread makes them typically ± amplitude / 5 (hills of about
    /// ±11 m, peaks near ±30 m with the defaults).
    double amplitude = 55.0;
    double wavelength = 150.0;  ///< horizontal size of the largest features, > 0
    FbmOptions fbm{6, 2.0, 0.45}; ///< octaves 1..24; the finest is wavelength / lacunarity^(octaves−1)
};

/// Tunnels where two independent 3D fbm fields n1, n2, evaluated at
/// (x, y·verticalSquash, z) / wavelength, are both near zero: long, winding,
/// connected tubes that cross the surface here and there.
///
/// The cave term is (sqrt(n1² + n2²) − r) / (its gradient bound), which
/// keeps the density 1-Lipschitz but underestimates the distance to a tunnel
/// about tenfold: the sampled narrow band around tunnels is wide, and
/// sampling cost grows with the tunnel count (shorter wavelength, more
/// octaves, larger squash all cost more).
///
/// Defaults: with seed 1, the default scene's region (x, z in [−96, 96],
/// y in [−44, 44]) holds dozens of openings to the surface.
struct CaveOptions
{
    bool enabled = true;
    double wavelength = 56.0;  ///< horizontal size of the tunnel meanders (m), > 0
    /// Tunnel radius (m), > 0: the mean horizontal radius (the median is
    /// about 0.8·radius: tunnels widen where they meander slowly); vertically
    /// about radius / verticalSquash.
    double radius = 4.5;
    double verticalSquash = 1.6; ///< > 0; > 1 makes tunnels run more horizontally
    double maxHeight = 1e30;   ///< no tunnels above this height (m); not NaN
    /// The two 3D fields (octaves 1..24). Few octaves keep the tunnels smooth
    /// and the gradient bound, hence the sampling cost, low: one octave gives
    /// simpler tubes at about 0.7× the active voxels.
    FbmOptions fbm{2, 2.0, 0.5};
};

struct TerrainOptions
{
    std::uint64_t seed = 1;
    HeightfieldOptions height;
    CaveOptions caves;
    /// The noise version (a scene's `noise_version`, FractalOptions::version):
    /// 1 keeps this field's values bit for bit; 2 evaluates the three fBms
    /// in float lanes (another pattern, 2–4× faster).
    int noiseVersion = 1;
};

/// Heightfield minus caves, as a distance-like field (negative in rock):
/// density = max((y − h(x, z)) · s_h, −caveDistance), with s_h making the
/// height term 1-Lipschitz, so density() is 1-Lipschitz.
class TerrainField final : public DensityField
{
public:
    /// Throws strata::Error naming the option (e.g. "terrain: height.octaves
    /// = 40 is out of range 1..24") if one is not finite or out of range.
    explicit TerrainField(const TerrainOptions& options);

    double density(const glm::dvec3& p) const override;
    /// density() at a block of points, the same bits: the height once per
    /// (x, z) column, the cave noise only where density() needs it.
    void densities(const PointBlock& points, double* out) const override;
    double lipschitz() const override { return 1.0; }
    /// density() / lipschitz() = densities(): the block path.
    void distanceBounds(const PointBlock& points, double* out) const override { densities(points, out); }
    /// Version 1: DensityField's (density at the centre ± the half
    /// diagonal). Version 2: the fBms' own box bounds (FractalNoise::bounds,
    /// rounding included) through the height and tunnel terms, which is
    /// also rigorous for its float evaluation.
    Interval bounds(const WorldBox& box) const override;

    /// The heightfield alone: surface height at (x, z), metres.
    double height(double x, double z) const;

    /// The cave term alone: negative inside a tunnel, 1-Lipschitz, in metres
    /// but an underestimate of the distance to the tunnel wall (see
    /// CaveOptions). Ignores `enabled`.
    double caveDistance(const glm::dvec3& p) const;

    const TerrainOptions& options() const { return mOptions; }

private:
    TerrainOptions mOptions;
    Fbm mHeight, mCaveA, mCaveB; ///< seeds derived from options.seed (version 1)
    /// The same fBms at noise version 2 (empty at version 1).
    std::optional<FractalNoise> mHeight2, mCaveA2, mCaveB2;
    double mHeightScale;     ///< 1 / Lipschitz bound of (y − h), keeps density 1-Lipschitz
    double mCaveScale;       ///< the same for the cave term (metres per noise unit)
    double mCaveNoiseRadius; ///< tunnel radius in noise units (see the constructor)
};

} // namespace strata::terrain
