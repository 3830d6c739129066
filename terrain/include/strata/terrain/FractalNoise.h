// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The noise family: gradient, simplex-style, value and cellular (Worley)
/// noise, their fractal sums (fBm, ridged, billow) and domain warping.
///
/// Like gradientNoise() (Noise.h), every source hashes 64-bit integer lattice
/// coordinates with the seed (no tables, no std:: distributions), so values
/// are the same bits on every thread count and do not repeat within int64;
/// the position inside a cell is taken from the unrounded floor in double
/// precision, so detail survives at coordinates of 1e9. All coordinates are
/// in noise units (world metres divided by a wavelength).

#include <strata/terrain/DensityField.h>
#include <strata/terrain/Noise.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

namespace strata::terrain {

/// Value noise: random lattice values in [−1, 1], quintic interpolation.
/// C2, range [−1, 1], |∇| <= VALUE_NOISE_LIPSCHITZ (3D) / _2D.
float valueNoise(std::uint64_t seed, const glm::dvec3& p);
float valueNoise(std::uint64_t seed, const glm::dvec2& p);
/// Per axis at most 15/8 · 2 (fade slope times the largest lattice step), so
/// 3.75·√3 in 3D and 3.75·√2 in 2D.
inline constexpr double VALUE_NOISE_LIPSCHITZ = 6.4952;
inline constexpr double VALUE_NOISE_LIPSCHITZ_2D = 5.3034;

/// Simplex-style noise: Perlin's simplex lattice (skewed cubes split into
/// tetrahedra / triangles), radial kernels (0.5 − r²)⁴ with hashed gradients,
/// so the kernels vanish before the next simplex and the noise is C1.
/// Range about [−1, 1]; gradient bound simplexNoiseLipschitz().
float simplexNoise(std::uint64_t seed, const glm::dvec3& p);
float simplexNoise(std::uint64_t seed, const glm::dvec2& p);
/// Upper bound of |∇ simplexNoise|, noise units: corners × the largest
/// kernel gradient (computed once, analytically per corner; checked
/// numerically). Rigorous but about 5× the largest gradient measured.
double simplexNoiseLipschitz(int dimensions);

/// Cellular (Worley) noise: one feature point per lattice cell, placed by
/// hashing within the middle [0.3, 0.7] of the cell. That jitter makes the
/// 27-cell (9 in 2D) search exact for both distances, so F1 and F2 are
/// continuous and 1-Lipschitz (a proof is in FractalNoise.cpp).
struct CellularDistances
{
    double f1 = 0.0; ///< distance to the nearest feature point, noise units
    double f2 = 0.0; ///< distance to the second nearest
};
CellularDistances cellularNoise(std::uint64_t seed, const glm::dvec3& p);
CellularDistances cellularNoise(std::uint64_t seed, const glm::dvec2& p);

/// The basis of a fractal sum.
enum class NoiseType
{
    GRADIENT,    ///< gradientNoise()
    SIMPLEX,     ///< simplexNoise()
    VALUE,       ///< valueNoise()
    CELLULAR_F1, ///< 2·F1 − 1 (range [−1, 0.92]): round cells, high at their borders; |∇| <= 2
    CELLULAR_F2, ///< 2·F2 − 1.4 (range [−0.74, 0.88]): cells with creases; |∇| <= 2
};

/// How octaves combine.
enum class FractalType
{
    FBM,    ///< Σ a_i·n_i
    RIDGED, ///< Σ a_i·(1 − 2|n_i|): sharp crests
    BILLOW, ///< Σ a_i·(2|n_i| − 1): round puffs, sharp valleys
};

/// Parses "gradient", "simplex", "value", "cellular_f1", "cellular_f2";
/// returns false for anything else.
bool parseNoiseType(const std::string& name, NoiseType& type);
/// Parses "fbm", "ridged", "billow".
bool parseFractalType(const std::string& name, FractalType& type);

/// Upper bound of |∇| of one basis, noise units.
double noiseLipschitz(NoiseType type, int dimensions);

struct FractalOptions
{
    NoiseType noise = NoiseType::GRADIENT;
    FractalType fractal = FractalType::FBM;
    int octaves = 5;         ///< 1..24
    double lacunarity = 2.0; ///< frequency ratio between octaves, > 0
    double gain = 0.5;       ///< amplitude ratio between octaves, >= 0
    /// The noise version (a scene's `noise_version`):
    ///   1: the lattice cell in 64-bit integers, the arithmetic in double,
    ///      cells hashed once per run of points that share them;
    ///   2: the cell split in 64-bit integers and hashed in 32-bit lanes, the
    ///      offset in it and all arithmetic in float lanes, every point on its
    ///      own (docs/noise.md). The same shapes, gradient sets and bounds;
    ///      other values. Both give the same bits on every target.
    int version = 1;
};

/// The noise versions FractalOptions::version takes.
inline constexpr int NOISE_VERSION_MIN = 1, NOISE_VERSION_MAX = 2;

/// A fractal sum of one basis, normalised by the sum of octave amplitudes so
/// its range stays about [−1, 1]. Octaves use derived seeds and hashed input
/// offsets, as in Fbm. Immutable and thread-safe.
class FractalNoise
{
public:
    static constexpr int MAX_OCTAVES = 24;

    /// Throws strata::Error naming "octaves", "lacunarity", "gain" or
    /// "noise_version" when out of range (octaves 1..24, lacunarity finite
    /// > 0, gain finite >= 0, version 1 or 2).
    FractalNoise(std::uint64_t seed, const FractalOptions& options);

    double operator()(const glm::dvec3& p) const;
    double operator()(const glm::dvec2& p) const;

    /// operator() at n points given as arrays (noise units), into out[0, n):
    /// the same bits, with each lattice cell's hashes reused while
    /// consecutive points stay in it (NoiseBlock.cpp). Points in lattice
    /// order (a block of voxels) share the most.
    void evaluate(const double* x, const double* y, const double* z, std::size_t n, double* out) const;
    /// The 2D sum at (x[i], y[i]).
    void evaluate(const double* x, const double* y, std::size_t n, double* out) const;

    /// Upper bound of |∇| in noise units for the 3D (or 2D) evaluation.
    double lipschitz(int dimensions = 3) const;

    /// An interval holding the sum at every point of the box [lo, hi]
    /// (noise units, lo <= hi). Per octave i the basis lies within
    /// n_i(c_i) ± L_b·f_i·r (L_b the basis' gradient bound, f_i the
    /// octave's frequency, r the box's half diagonal) and within the basis'
    /// rigorous range (basisRange); for gradient noise (2D and 3D), an octave
    /// whose box lies in one lattice cell uses the mean value form instead
    /// when tighter (an interval enclosure of the gradient over the box,
    /// typically several times tighter on small boxes; proof in Noise.cpp).
    /// The shape (fBm, ridged, billow) maps each interval exactly and the
    /// weighted sum adds them; each octave is widened by 1e-6 for rounding
    /// (1e-4 in version 2). A gradient-noise fBm is also bounded as one
    /// function, with the octaves' gradient enclosures summed before their
    /// size is taken (their gradients partly cancel), and the tighter of the
    /// two forms is kept at each end.
    /// Costs one evaluation of the sum, about twice that for 2D gradient
    /// octaves that take the mean value form.
    Interval bounds(const glm::dvec3& lo, const glm::dvec3& hi) const;
    Interval bounds(const glm::dvec2& lo, const glm::dvec2& hi) const;

    const FractalOptions& options() const { return mOptions; }

private:
    double basis(std::uint64_t hashedSeed, const glm::dvec3& p) const;
    double basis(std::uint64_t hashedSeed, const glm::dvec2& p) const;
    double shape(double n) const;
    /// bounds() in 2D or 3D (FractalNoise.cpp).
    template <class Vec>
    Interval boxBounds(const Vec& lo, const Vec& hi) const;
    /// Version 2's sums (NoiseLanes32.cpp), z == nullptr for 2D; the scalar
    /// operator()s call it for one point, so block and scalar are one path.
    void evaluateVersion2(const double* x, const double* y, const double* z, std::size_t n, double* out) const;

    struct Octave
    {
        std::uint64_t seed; ///< derived per octave (not yet hashed)
        double frequency;
        double weight; ///< amplitude / sum of amplitudes
        double offset[3];
    };
    FractalOptions mOptions;
    int mCount = 0;
    Octave mOctaves[MAX_OCTAVES];
};

/// A rigorous range of one basis (before the fractal shape), noise units;
/// ±infinity where none is proven. Gradient noise is zero at every lattice
/// point and L-Lipschitz, so |n| <= L·√d/2 (the farthest a point gets from
/// its nearest lattice point); value noise interpolates lattice values in
/// [−1, 1] with convex weights; cellular F1 is at least 0 and at most the
/// distance to the own cell's feature point, <= 0.7·√d. Simplex and F2:
/// unbounded here.
Interval basisRange(NoiseType type, int dimensions);

/// Domain warp: w(p) = p + amplitude · (f1(p), f2(p), f3(p)), three
/// independent fractal sums, all in the caller's units (e.g. noise units).
/// The Jacobian of w is at most 1 + amplitude·√3·L_f in norm, which is the
/// factor a warped field's gradient bound grows by (lipschitz()).
class DomainWarp
{
public:
    DomainWarp(std::uint64_t seed, const FractalOptions& options, double amplitude);

    glm::dvec3 operator()(const glm::dvec3& p) const;
    /// Bound of ‖∂w/∂p‖.
    double lipschitz() const;

private:
    FractalNoise mX, mY, mZ;
    double mAmplitude;
};

} // namespace strata::terrain
